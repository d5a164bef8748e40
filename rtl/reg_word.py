"""One function register, built from its entry in ``rtl/registers.py``."""
from myhdl import Signal, always_comb, always_seq, block, concat, intbv

from rtl.registers import Register


@block
def reg_word(clock, reset, addr, write_addr, write_now, byte_mask, wdata, set_strobe, set_index,
             set_value, hw_value, value, strobe, clamp_in, clamp_out, read_in, read_out, *, spec):
    """The register ``spec`` (a ``rtl.registers.Register``) on the I/O bus.

    Ports: ``addr`` (byte offset of reads), ``write_addr`` (of writes),
    ``write_now`` (an I/O write happens at this clock edge), ``byte_mask``
    (byte enables of the write as a bit mask), ``wdata``; ``set_strobe``/``set_index``/``set_value`` (the SET command's
    write port); ``hw_value`` (RO and WP: what reads return; W1C: bits the
    hardware sets; W1S: bits the hardware clears); ``value`` (RW/W1C/W1S:
    the register; WP: the last value written); ``strobe`` (WP: one clock per
    write); ``clamp_out`` is ``clamp_in`` or'ed with a one-clock flag raised
    when a write to this register was out of range and was clamped; the read
    data of the registers before this one comes in on ``read_in`` and leaves,
    with this register's when ``addr`` is its offset, on ``read_out`` (a
    chain of ORs, so the decoder is generated from the table; reads have no
    side effect here, and whether the bus reads at all is decided after the
    chain's end).

        clock     _/~\\_/~\\_/~\\_
        write_now _/~~~\\_______     addr = spec.offset
        value     =====X=new====
        strobe    _____/~~~\\___     (WP only)
    """
    width, offset = spec.width, spec.offset
    checked = spec.minimum is not None or spec.maximum is not None
    mine = Signal(bool(0))
    mine_write = Signal(bool(0))
    written = Signal(intbv(0)[32:] if checked else intbv(0)[width:])
    shown_wide = Signal(intbv(0)[32:])
    honoured = Signal(intbv(0)[width:])
    out_of_range = Signal(bool(0))
    clamped = Signal(bool(0))
    set_mine = set_strobe if spec.set_index is not None else Signal(bool(0))
    set_target = spec.set_index if spec.set_index is not None else 0
    stored = spec.access in ("RW", "W1C", "W1S", "WP")
    shown = value if spec.access in ("RW", "W1C", "W1S") else hw_value

    @always_comb
    def select():
        mine.next = addr == offset

    @always_comb
    def select_write():
        mine_write.next = write_addr == offset

    @always_comb
    def read_chain():
        if mine:
            read_out.next = read_in | shown_wide
        else:
            read_out.next = read_in

    @always_comb
    def clamp_chain():
        clamp_out.next = clamp_in or clamped

    @always_comb
    def clamp_pass():
        clamp_out.next = clamp_in

    span = 32 if checked else width

    @always_comb
    def merge_bytes():
        if set_mine and set_index == set_target:
            written.next = set_value[span:]
        else:
            written.next = (shown_wide[span:] & ~byte_mask[span:]) | (wdata[span:] & byte_mask[span:])

    @always_comb
    def mask_bytes():
        written.next = wdata[span:] & byte_mask[span:]

    merge = merge_bytes if spec.access == "RW" else mask_bytes  # RW: shown_wide is the register
    generators = [select, read_chain, _widen(shown, shown_wide)]
    if not stored:
        return generators + [clamp_pass]
    generators += [select_write, merge, _limit(written, honoured, out_of_range, spec)]
    generators.append(clamp_chain if spec.access in ("RW", "WP") else clamp_pass)
    generators.append(_store(clock, reset, mine_write, write_now, set_mine, set_index, set_target, written,
                             honoured, out_of_range, hw_value, value, strobe, clamped, spec))
    return generators


@block
def _widen(narrow, wide):
    """``wide`` (32 bits) is ``narrow`` zero-extended."""
    pad = len(wide) - len(narrow)

    @always_comb
    def extend():
        wide.next = concat(intbv(0)[pad:], narrow)

    @always_comb
    def copy():
        wide.next = narrow

    return extend if pad else copy


@block
def _limit(written, honoured, out_of_range, spec):
    """``honoured``: ``written`` clamped to the register's range (or cut to its width)."""
    width = spec.width
    low = spec.minimum if spec.minimum is not None else (-(1 << (width - 1)) if spec.signed else 0)
    high = spec.maximum if spec.maximum is not None else (
        (1 << (width - 1)) - 1 if spec.signed else (1 << width) - 1)
    checked = spec.minimum is not None or spec.maximum is not None
    low_bits, high_bits = low & ((1 << width) - 1), high & ((1 << width) - 1)

    if not checked:
        @always_comb
        def cut():
            honoured.next = written[width:]
        return cut

    if spec.signed:
        if (low, high) != (-(1 << (width - 1)), (1 << (width - 1)) - 1):
            raise ValueError(f"{spec.name}: a signed register clamps to its full width only")
        ones = (1 << (33 - width)) - 1

        @always_comb
        def clamp_signed():
            # in range when bits 31..width-1 are copies of the sign: no comparator needed
            if written[32:width - 1] == 0 or written[32:width - 1] == ones:
                honoured.next = written[width:]
                out_of_range.next = False
            elif written[31]:
                honoured.next = low_bits
                out_of_range.next = True
            else:
                honoured.next = high_bits
                out_of_range.next = True
        return clamp_signed

    high_top, low_top = high.bit_length(), max(low.bit_length(), 1)

    @always_comb
    def clamp_unsigned():
        # compare only the bits a bound has; any higher bit set is out of range
        out_of_range.next = True
        if written[32:low_top] == 0 and written[low_top:] < low:
            honoured.next = low_bits
        elif written[32:high_top] != 0 or written[high_top:] > high:
            honoured.next = high_bits
        else:
            honoured.next = written[width:]
            out_of_range.next = False

    @always_comb
    def clamp_unsigned_power_of_two():
        # high is 2**high_top - 1: above it exactly when a higher bit is set
        out_of_range.next = True
        if written[32:low_top] == 0 and written[low_top:] < low:
            honoured.next = low_bits
        elif written[32:high_top] != 0:
            honoured.next = high_bits
        else:
            honoured.next = written[width:]
            out_of_range.next = False

    return clamp_unsigned_power_of_two if high == (1 << high_top) - 1 else clamp_unsigned


@block
def _store(clock, reset, mine, write_now, set_mine, set_index, set_target, written, honoured,
           out_of_range, hw_value, value, strobe, clamped, spec):
    """The register's flip-flops, by access kind."""
    kind = spec.access

    @always_seq(clock.posedge, reset=reset)
    def hold_rw():
        clamped.next = False
        if (set_mine and set_index == set_target) or (write_now and mine):
            value.next = honoured
            clamped.next = out_of_range

    @always_seq(clock.posedge, reset=reset)
    def clear_on_one():
        if write_now and mine:
            value.next = (value & ~honoured) | hw_value
        else:
            value.next = value | hw_value

    @always_seq(clock.posedge, reset=reset)
    def set_on_one():
        if write_now and mine:
            value.next = (value & ~hw_value) | honoured
        else:
            value.next = value & ~hw_value

    @always_seq(clock.posedge, reset=reset)
    def pulse_on_write():
        strobe.next = False
        clamped.next = False
        if write_now and mine:
            value.next = honoured
            strobe.next = True
            clamped.next = out_of_range

    return {"RW": hold_rw, "W1C": clear_on_one, "W1S": set_on_one, "WP": pulse_on_write}[kind]


def reg_word_ports(spec):
    """Fresh ports of ``reg_word`` for ``spec``."""
    if not isinstance(spec, Register):
        raise ValueError("spec must be a rtl.registers.Register")
    width = spec.width
    return dict(clock=Signal(bool(0)), reset=None, addr=Signal(intbv(0)[16:]), write_addr=Signal(intbv(0)[16:]),
                write_now=Signal(bool(0)), byte_mask=Signal(intbv(0)[32:]),
                wdata=Signal(intbv(0)[32:]), set_strobe=Signal(bool(0)), set_index=Signal(intbv(0)[4:]),
                set_value=Signal(intbv(0)[32:]), hw_value=Signal(intbv(0)[width:]),
                value=Signal(intbv(spec.reset)[width:]), strobe=Signal(bool(0)),
                clamp_in=Signal(bool(0)), clamp_out=Signal(bool(0)), read_in=Signal(intbv(0)[32:]), read_out=Signal(intbv(0)[32:]))
