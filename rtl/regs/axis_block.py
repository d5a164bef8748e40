"""The per-axis register blocks' position snapshot: the one instant every
axis's position is read at (``models/registers.py``: ``AXIS_REGISTERS``,
``axis_offset``; X's and Y's block registers are BAR0's register words,
answering at both offsets: ``reg_word``'s ``aliases``)."""
from myhdl import Signal, always_comb, always_seq, block

from models import registers as regmap
from models.parameters import AXES
from rtl.interfaces import AxisBlock, card_reset


@block
def axis_block(clock, reset, axis_regs, *, axes):
    """Every axis's position but X's as a read of X's POS captured it.

    Ports: ``axis_regs`` (``AxisBlock`` of ``axes`` axes).  Parameter:
    ``axes`` (the build's).

    Reading X's POS (POS_X in BAR0, or X's block in BAR2) captures every
    other axis's count in ``held`` at the edge that takes the read, so POS
    of Y, Z, ... read afterwards are of that same clock; POS_Z, POS_A, ...
    (``pos_words``) read ``held``:

        clock       _/~\\_/~\\_/~\\_
        read        _/~~~\\_______     addr = POS_X's offset (either)
        positions.z ==5==X==6======
        held.z      =====X==5======   POS_Z reads 5
    """
    if axis_regs.axes != axes:
        raise ValueError(f"axis_block: an AxisBlock of {axis_regs.axes} axes, the build says {axes}")
    addr = axis_regs.addr
    pos_x, pos_x_block = regmap.offset("POS_X"), regmap.axis_offset("POS", 0)
    take = Signal(bool(0))

    @always_comb
    def snapshot_taken():
        take.next = axis_regs.read and (addr == pos_x or addr == pos_x_block)

    units = [snapshot_taken]
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
