"""The per-axis register blocks' glue: where an offset in BAR2's blocks
lands, and the one instant every axis's position is read at
(``models/registers.py``: ``AXIS_REGISTERS``, ``axis_offset``)."""
from myhdl import Signal, always_comb, always_seq, block, intbv

from models import registers as regmap
from models.parameters import AXES
from rtl.interfaces import AxisBlock, card_reset


@block
def axis_block(clock, reset, axis_regs, *, axes):
    """The offset the register words see, and the position snapshot.

    Ports: ``axis_regs`` (``AxisBlock`` of ``axes`` axes).  Parameter:
    ``axes`` (the build's).

    X's and Y's blocks hold BAR0's own registers (POS_X, PULSE_PERIOD_X,
    ...): ``reg_addr`` is their BAR0 offset there, so one ``reg_word`` and
    one side effect serve both offsets; a free place in those blocks stays
    outside BAR0 and so reaches no register (reads 0, writes ignored); every
    other offset passes as it is.  The blocks of Z, A, ... are register words
    of their own at their BAR2 offsets; the blocks of axes the build lacks
    reach none.  Reading POS_X (at either offset) captures every other axis's
    count in ``held`` at the edge that takes the read, so POS of Y, Z, ...
    read afterwards are of that same clock:

        clock       _/~\\_/~\\_/~\\_
        read        _/~~~\\_______     reg_addr = POS_X
        positions.z ==5==X==6======
        held.z      =====X==5======   POS_Z reads 5
    """
    if axis_regs.axes != axes:
        raise ValueError(f"axis_block: an AxisBlock of {axis_regs.axes} axes, the build says {axes}")
    addr, reg_addr = axis_regs.addr, axis_regs.reg_addr
    width = len(addr)
    aliases = regmap.axis_aliases()
    # X's and Y's blocks side by side: one window, its dwords looked up in a table
    window = regmap.AXIS_BLOCK_BASE
    window_bits = (regmap.AXIS_STRIDE * regmap.BAR0_AXES - 1).bit_length()
    if window % (1 << window_bits) or window >> width:
        raise ValueError("axis_block: X's and Y's blocks do not form one aligned window of the bus")
    window_tag = window >> window_bits
    table = tuple(aliases.get(window + 4 * dword, window + 4 * dword) for dword in range(1 << (window_bits - 2)))
    looked_up = Signal(intbv(0)[width:])
    pos_x_offset = regmap.offset("POS_X")
    take = Signal(bool(0))

    @always_comb
    def look_up():
        looked_up.next = table[addr[window_bits:2]]

    @always_comb
    def translate():
        if addr[width:window_bits] == window_tag:
            reg_addr.next = looked_up
        else:
            reg_addr.next = addr

    @always_comb
    def snapshot_taken():
        take.next = axis_regs.read and reg_addr == pos_x_offset

    units = [look_up, translate, snapshot_taken]
    for axis in range(1, axes):
        word = axis_regs.pos_words[axis - 2] if axis >= 2 else None
        units.append(_snapshot(clock, reset, take, axis_regs.positions.of(axis), axis_regs.held.of(axis), word))
    return units


@block
def _snapshot(clock, reset, take, live, held, word):
    """``held`` takes ``live`` when ``take``; ``word`` (if any) reads it, 32 bits."""

    @always_seq(clock.posedge, reset=reset)
    def capture():
        if take:
            held.next = live

    @always_comb
    def show():
        word.next = held[32:]

    return (capture, show) if word is not None else capture


def axis_block_ports(axes=AXES.default):
    """Fresh ports of ``axis_block`` for ``axes`` axes, on a 12-bit local bus (4 KiB BAR2)."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), axis_regs=AxisBlock(axes, regmap.REG_BAR_BITS))
