"""One function register, built from its entry in ``models/registers.py``."""
from myhdl import Signal, always_comb, always_seq, block, concat, intbv

from models.registers import Register
from rtl.interfaces import ReadChain, RegisterBus, RegisterWord, SetPort, card_reset


@block
def reg_word(clock, reset, bus, set_port, word, chain_in, chain_out, *, alias=None, alias_offset=0):
    """The register ``word.spec`` (a ``models.registers.Register``) on the register bus.

    Ports (``rtl/interfaces/``): ``bus`` (``RegisterBus``: ``addr`` of
    reads; ``write_addr``, ``write``, ``byte_mask`` and ``wdata`` of a
    write); ``set_port`` (``SetPort``: the SET command's write); ``word``
    (``RegisterWord``: ``hw`` is what RO and WP registers read, the bits a
    W1C register sets, the bits a W1S register clears; ``value`` the
    register, of WP the last value written; ``strobe`` one clock per WP
    write; ``hw`` of an RW register clears its fields with ``cleared`` and
    holds them at 0; its ``spec`` says which register this is); ``chain_in`` and
    ``chain_out`` (``ReadChain``): ``chain_out.clamped`` is
    ``chain_in.clamped`` or'ed with a one-clock flag raised when a write to
    this register was out of range and was clamped; the read data of the
    registers before this one comes in on ``chain_in.data`` and leaves, with
    this register's when ``bus.addr`` is its offset, on ``chain_out.data``
    (a chain of ORs, so the decoder is generated from the table; reads have
    no side effect here, and whether the bus reads at all is decided after
    the chain's end).  A register with a range keeps the written word's own
    bits (``written``, the bus's bytes merged with the register, or SET's
    value) and, of the bits above them, only whether they are all 0 (all 1
    and bit 31 too when signed, ``_above``): flags of the bus's masked data,
    the same for every register of the width, so the registers share them.
    A SET register compares the bus's word and SET's value with its bounds
    each before it chooses (``_limit_either``): the compares of SET's value
    are shared by the registers of one range.  Parameters: ``alias`` (an
    ``AliasBlock``, or None) and ``alias_offset``: the register answers at
    that offset in the block too, exactly as at its own (X's and Y's per-axis
    blocks in BAR2, ``models.registers.axis_aliases``); the block's test is
    made once for its registers (``rtl/regs/alias_block.py``).

        clock     _/~\\_/~\\_/~\\_
        bus.write _/~~~\\_______     bus.write_addr = spec.offset
        value     =====X=new====
        strobe    _____/~~~\\___     (WP only)
    """
    spec = word.spec
    width, offset = spec.width, spec.offset
    if alias is not None and not 0 <= alias_offset < alias.size:
        raise ValueError(f"{spec.name}: alias offset {alias_offset:#x} outside its {alias.size}-byte block")
    low = (alias.size - 1).bit_length() if alias is not None else 0
    in_block_read = alias.read if alias is not None else None
    in_block_write = alias.write if alias is not None else None
    checked = spec.minimum is not None or spec.maximum is not None
    mine = Signal(bool(0))
    mine_write = Signal(bool(0))
    written = Signal(intbv(0)[width:])
    # a SET register's sources: the bus's word (bytes merged with the register) and SET's value,
    # each with "its bits above the width are all 0"
    merged = Signal(intbv(0)[width:]) if spec.set_index is not None else written
    set_low = Signal(intbv(0)[width:])
    set_zero, bus_zero = Signal(bool(0)), Signal(bool(0))
    # of the written word's bits above ``width``: all 0, all 1, bit 31 (``_above``)
    zero_above, ones_above, sign = (Signal(bool(0)) for _ in range(3))
    set_selected = Signal(bool(0))
    shown_wide = Signal(intbv(0)[32:])
    honoured = Signal(intbv(0)[width:])
    out_of_range = Signal(bool(0))
    clamped = Signal(bool(0))
    set_mine = set_port.strobe if spec.set_index is not None else Signal(bool(0))
    set_target = spec.set_index if spec.set_index is not None else 0
    stored = spec.access in ("RW", "W1C", "W1S", "WP")
    shown = word.value if spec.access in ("RW", "W1C", "W1S") else word.hw

    @always_comb
    def select():
        mine.next = bus.addr == offset

    @always_comb
    def select_write():
        mine_write.next = bus.write_addr == offset

    @always_comb
    def select_either():
        mine.next = bus.addr == offset or (in_block_read and bus.addr[low:] == alias_offset)

    @always_comb
    def select_write_either():
        mine_write.next = bus.write_addr == offset or (in_block_write and bus.write_addr[low:] == alias_offset)

    @always_comb
    def read_chain():
        if mine:
            chain_out.data.next = chain_in.data | shown_wide
        else:
            chain_out.data.next = chain_in.data

    @always_comb
    def clamp_chain():
        chain_out.clamped.next = chain_in.clamped or clamped

    @always_comb
    def clamp_pass():
        chain_out.clamped.next = chain_in.clamped

    @always_comb
    def set_select():
        set_selected.next = set_mine and set_port.index == set_target

    @always_comb
    def set_or_bytes():
        if set_selected:
            written.next = set_low
        else:
            written.next = merged

    @always_comb
    def set_parts():
        set_low.next = set_port.value[width:]
        set_zero.next = set_port.value[32:width] == 0
        bus_zero.next = bus.wdata[32:width] == 0

    @always_comb
    def merge_bytes():
        merged.next = (word.value & ~bus.byte_mask[width:]) | bus.wdata[width:]

    @always_comb
    def mask_bytes():
        written.next = bus.wdata[width:]

    if spec.access != "RW":
        merge = [mask_bytes]
    elif spec.set_index is None:
        merge = [merge_bytes]
    else:
        merge = [merge_bytes, set_select, set_or_bytes, set_parts]
    generators = [select if alias is None else select_either, read_chain, zero_extend(shown, shown_wide)]
    if not stored:
        return generators + [clamp_pass]
    generators += [select_write if alias is None else select_write_either, *merge]
    if spec.set_index is not None:
        generators.append(_limit_either(set_selected, set_low, set_zero, merged, bus_zero, written, honoured,
                                        out_of_range, spec))
    else:
        generators.append(_limit(written, zero_above, ones_above, sign, honoured, out_of_range, spec))
        if checked and width < 32:
            generators.append(_above(bus, width, spec.signed, zero_above, ones_above, sign))
    generators.append(clamp_chain if spec.access in ("RW", "WP") else clamp_pass)
    generators.append(_store(clock, reset, mine_write, bus, set_mine, set_port, set_target, written, honoured,
                             out_of_range, word, clamped, spec))
    return generators


@block
def zero_extend(narrow, wide):
    """``wide`` is ``narrow`` zero-extended (or ``narrow`` itself when as wide)."""
    pad = len(wide) - len(narrow)

    @always_comb
    def extend():
        wide.next = concat(intbv(0)[pad:], narrow)

    @always_comb
    def copy():
        wide.next = narrow

    return extend if pad else copy


@block
def _above(bus, width, signed, zero_above, ones_above, sign):
    """Of a bus write's 32-bit word (its data, masked by its byte enables), bits ``width``..31:
    ``zero_above`` all 0; when ``signed``, also ``ones_above`` all 1 and ``sign`` bit 31
    (an unsigned range reads neither).  The same for every register of the width: shared."""
    ones = (1 << (32 - width)) - 1

    @always_comb
    def unsigned_flags():
        zero_above.next = bus.wdata[32:width] == 0

    @always_comb
    def signed_flags():
        zero_above.next = bus.wdata[32:width] == 0
        ones_above.next = bus.wdata[32:width] == ones
        sign.next = bus.wdata[31]

    return signed_flags if signed else unsigned_flags


@block
def _limit(written, zero_above, ones_above, sign, honoured, out_of_range, spec):
    """``honoured``: the written word clamped to the register's range (or cut
    to its width): ``written`` its low ``spec.width`` bits, ``zero_above``,
    ``ones_above`` and ``sign`` what ``_above`` says of the bits above."""
    width = spec.width
    low = spec.minimum if spec.minimum is not None else (-(1 << (width - 1)) if spec.signed else 0)
    high = spec.maximum if spec.maximum is not None else (
        (1 << (width - 1)) - 1 if spec.signed else (1 << width) - 1)
    checked = spec.minimum is not None or spec.maximum is not None
    low_bits, high_bits = low & ((1 << width) - 1), high & ((1 << width) - 1)

    if not checked or (not spec.signed and (low, high, width) == (0, (1 << 32) - 1, 32)):
        # no range, or one of every 32-bit word (ENC_SCALE, FERROR_LIMIT): nothing to clamp
        @always_comb
        def cut():
            honoured.next = written
        return cut
    if width == 32:
        raise ValueError(f"{spec.name}: a 32-bit register clamps to every 32-bit word only")

    if spec.signed:
        if (low, high) != (-(1 << (width - 1)), (1 << (width - 1)) - 1):
            raise ValueError(f"{spec.name}: a signed register clamps to its full width only")

        @always_comb
        def clamp_signed():
            # in range when bits 31..width-1 are copies of the sign: no comparator needed
            if (zero_above and not written[width - 1]) or (ones_above and written[width - 1]):
                honoured.next = written
                out_of_range.next = False
            elif sign:
                honoured.next = low_bits
                out_of_range.next = True
            else:
                honoured.next = high_bits
                out_of_range.next = True
        return clamp_signed

    below, above = Signal(bool(0)), Signal(bool(0))
    return _bounds(written, zero_above, below, above, spec), _clamp(written, below, above, honoured, out_of_range,
                                                                    low_bits, high_bits)


@block
def _limit_either(set_selected, set_low, set_zero, merged, bus_zero, written, honoured, out_of_range, spec):
    """A SET register's ``_limit``: ``written`` is ``set_low`` (SET's value, ``set_zero``
    its bits above the width all 0) while ``set_selected``, else ``merged`` (the bus's,
    ``bus_zero``); each source is compared with the bounds before the choice, so the
    compares of SET's value are shared by the registers of one range."""
    width, low, high = spec.width, spec.minimum, spec.maximum
    if spec.signed or low is None or high is None or width == 32:
        raise ValueError(f"{spec.name}: a SET register has an unsigned range narrower than 32 bits")
    below, above, set_below, set_above, bus_below, bus_above = (Signal(bool(0)) for _ in range(6))

    @always_comb
    def choose():
        if set_selected:
            below.next = set_below
            above.next = set_above
        else:
            below.next = bus_below
            above.next = bus_above

    return (_bounds(set_low, set_zero, set_below, set_above, spec),
            _bounds(merged, bus_zero, bus_below, bus_above, spec), choose,
            _clamp(written, below, above, honoured, out_of_range, low & ((1 << width) - 1), high))


@block
def _bounds(value, zero_above, below, above, spec):
    """Of a written word (``value`` its low ``spec.width`` bits, ``zero_above`` its bits above
    all 0), unsigned: ``below`` under the register's minimum, ``above`` over its maximum."""
    width = spec.width
    low = spec.minimum if spec.minimum is not None else 0
    high = spec.maximum if spec.maximum is not None else (1 << width) - 1
    # the word as an unsigned number of width + 1 bits: the top bit set when any bit above width is
    # (it is then above high, as a 32-bit word with such a bit is)
    whole = Signal(intbv(0)[width + 1:])
    top = width + 1
    high_top, low_top = high.bit_length(), max(low.bit_length(), 1)

    @always_comb
    def widen():
        whole.next = concat(not zero_above, value)

    @always_comb
    def compare():
        # compare only the bits a bound has; any higher bit set is out of range
        below.next = whole[top:low_top] == 0 and whole[low_top:] < low
        above.next = whole[top:high_top] != 0 or whole[high_top:] > high

    @always_comb
    def compare_power_of_two():
        # high is 2**high_top - 1: above it exactly when a higher bit is set
        below.next = whole[top:low_top] == 0 and whole[low_top:] < low
        above.next = whole[top:high_top] != 0

    @always_comb
    def compare_above_power_of_two():
        # low is 0 (nothing below it) and high is 2**high_top - 1: above it when a bit over
        # high_top is set, in the word or above it (the low bits are not read: no widened word)
        below.next = False
        above.next = not zero_above or value[width:high_top] != 0

    @always_comb
    def compare_above_whole_width():
        # low is 0 and high every bit of the width: above it only when a bit above the width is set
        below.next = False
        above.next = not zero_above

    @always_comb
    def compare_above():
        # low is 0: only the upper bound is compared
        below.next = False
        above.next = whole[top:high_top] != 0 or whole[high_top:] > high

    power_of_two = high == (1 << high_top) - 1
    if low == 0 and power_of_two:
        return compare_above_whole_width if high_top >= width else compare_above_power_of_two
    if low == 0:
        return widen, compare_above
    return widen, (compare_power_of_two if power_of_two else compare)


@block
def _clamp(written, below, above, honoured, out_of_range, low_bits, high_bits):
    """``honoured``: ``low_bits`` when ``below``, else ``high_bits`` when ``above``, else ``written``."""

    @always_comb
    def clamp():
        out_of_range.next = below or above
        if below:
            honoured.next = low_bits
        elif above:
            honoured.next = high_bits
        else:
            honoured.next = written

    return clamp


@block
def _store(clock, reset, mine, bus, set_mine, set_port, set_target, written, honoured, out_of_range, word, clamped,
           spec):
    """The register's flip-flops, by access kind."""
    kind = spec.access
    cleared_mask = sum(item.mask for item in spec.fields if item.cleared is not None)

    @always_seq(clock.posedge, reset=reset)
    def hold_rw():
        clamped.next = False
        if (set_mine and set_port.index == set_target) or (bus.write and mine):
            word.value.next = honoured
            clamped.next = out_of_range

    @always_seq(clock.posedge, reset=reset)
    def hold_rw_cleared():
        # the fields with ``cleared``: the hardware's hw bits clear them, a write meanwhile included
        clamped.next = False
        if (set_mine and set_port.index == set_target) or (bus.write and mine):
            word.value.next = honoured & ~(word.hw & cleared_mask)
            clamped.next = out_of_range
        else:
            word.value.next = word.value & ~(word.hw & cleared_mask)

    @always_seq(clock.posedge, reset=reset)
    def clear_on_one():
        if bus.write and mine:
            word.value.next = (word.value & ~honoured) | word.hw
        else:
            word.value.next = word.value | word.hw

    @always_seq(clock.posedge, reset=reset)
    def set_on_one():
        if bus.write and mine:
            word.value.next = (word.value & ~word.hw) | honoured
        else:
            word.value.next = word.value & ~word.hw

    @always_seq(clock.posedge, reset=reset)
    def pulse_on_write():
        word.strobe.next = False
        clamped.next = False
        if bus.write and mine:
            word.value.next = honoured
            word.strobe.next = True
            clamped.next = out_of_range

    if kind == "RW" and cleared_mask:
        return hold_rw_cleared
    return {"RW": hold_rw, "W1C": clear_on_one, "W1S": set_on_one, "WP": pulse_on_write}[kind]


def reg_word_ports(spec):
    """Fresh ports of ``reg_word`` for ``spec`` (a ``models.registers.Register``)."""
    if not isinstance(spec, Register):
        raise ValueError("spec must be a models.registers.Register")
    return dict(clock=Signal(bool(0)), reset=card_reset(), bus=RegisterBus(), set_port=SetPort(),
                word=RegisterWord(spec), chain_in=ReadChain(), chain_out=ReadChain())
