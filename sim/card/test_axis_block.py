"""The per-axis register blocks in BAR2 (docs/registers.md, docs/pci.md) on the
card: a three-axis build's Z axis driven and read through its block, X's and
Y's blocks the same registers as BAR0's, the positions of every axis read
at one instant, and the offsets without a register answering as every
unlisted offset does (read 0, writes ignored, the access completed).

Golden values come from the documented layout (block of axis i at 0x100 +
0x40 * i: POS +0x00, PULSE_PERIOD +0x04, PULSE_COUNT +0x08; BAR2 4 KiB), not
from the table's code: the offsets are written out here.
"""
import pytest

from models import registers as regmap
from sim.card.card_session import CardSession

POS_X_BAR0, POS_Y_BAR0, PULSE_PERIOD_X_BAR0 = 0x20, 0x24, 0x44
POS_X, PULSE_PERIOD_X, PULSE_COUNT_X = 0x100, 0x104, 0x108
POS_Y, PULSE_COUNT_Y = 0x140, 0x148
POS_Z, PULSE_PERIOD_Z, PULSE_COUNT_Z = 0x180, 0x184, 0x188
DIRECT_MODE = regmap.field_of("CONTROL", MODE=1)


def u32(value):
    return value & 0xFFFFFFFF


def step_rises(session, pin, clocks):
    """Clocks (counted from the call) at which ``step_<pin>`` rose, with ``dir_<pin>`` then."""
    rises, before = [], session.pin(f"step_{pin}")
    for clock in range(clocks):
        session.wait(1)
        level = session.pin(f"step_{pin}")
        if level and not before:
            rises.append((clock, session.pin(f"dir_{pin}")))
        before = level
    return rises


@pytest.fixture(params=["myhdl", "verilator"])
def three_axes(request):
    session = CardSession(request.param, axes=3)
    yield session
    session.close()


def test_a_pulse_count_z_write_moves_the_z_pins_and_pos_z_reads_them(three_axes):
    card = three_axes
    build = card.read(regmap.offset("BUILD"))
    assert regmap.field_value("BUILD", "AXES", build) == 3
    version = regmap.field_value("ID", "VERSION", card.read(regmap.offset("ID")))
    # the per-axis blocks came with 2.2; 3.0 holds every register 2.x had (docs/registers.md)
    assert (version >> 8, version & 0xFF) >= (2, 2)
    assert card.bars["alias"]["size"] == 4096
    card.write(regmap.offset("CONTROL"), DIRECT_MODE)
    card.write(PULSE_PERIOD_Z, 7)
    card.write(PULSE_COUNT_Z, u32(-5))
    rises = step_rises(card, "z", 60)
    assert len(rises) == 5 and {direction for _, direction in rises} == {False}   # DIR low: negative
    # PULSE_PERIOD_Z apart once under way (the first STEP waits DIR_SETUP after its DIR is set)
    assert {b[0] - a[0] for a, b in zip(rises[1:], rises[2:])} == {7}
    assert card.read(PULSE_COUNT_Z) == 0 and card.read(PULSE_PERIOD_Z) == 7
    assert card.log.rises == []                                                  # X and Y stood still
    # POS_Z holds what the last POS_X read captured: none yet since reset
    assert card.read(POS_Z) == 0
    assert card.read(POS_X_BAR0) == 0
    assert card.read(POS_Z) == u32(-5)


def test_the_offsets_without_a_register_read_0_and_ignore_writes(three_axes):
    card = three_axes
    card.write(PULSE_PERIOD_X, 9)
    empty = (0x10C, 0x13C, 0x18C, 0x1C0, 0x1C8, 0x240, 0xFFC)   # free places, A's and C's blocks, BAR2's end
    for offset in empty:
        card.write(offset, 0xFFFFFFFF)
    assert [card.read(offset) for offset in empty] == [0] * len(empty)
    assert card.read(PULSE_PERIOD_X_BAR0) == 9 and card.read(PULSE_PERIOD_Z) == 2   # its reset: untouched


def test_x_and_y_blocks_are_bar0_registers_and_positions_are_read_at_one_instant():
    card = CardSession("verilator")
    try:
        assert regmap.field_value("BUILD", "AXES", card.read(regmap.offset("BUILD"))) == 2
        card.write(regmap.offset("CONTROL"), DIRECT_MODE)
        card.write(PULSE_PERIOD_X, 3)
        assert card.read(PULSE_PERIOD_X_BAR0) == 3
        card.write(PULSE_COUNT_X, 4)
        card.write(PULSE_COUNT_Y, u32(-2))
        card.write(PULSE_COUNT_Z, 6)      # a two-axis card has no Z block: nothing moves
        card.wait(200)
        rises = card.log.rises   # (clock, X stepped, Y stepped, DIR X, DIR Y)
        assert sum(x for _, x, _, _, _ in rises) == 4 and sum(y for _, _, y, _, _ in rises) == 2
        assert card.read(POS_Y) == 0                  # no POS_X read yet: Y's snapshot is reset's
        assert card.read(POS_X) == 4
        assert (card.read(POS_Y), card.read(POS_Y_BAR0)) == (u32(-2), u32(-2))
        assert card.read(POS_Z) == 0 and card.read(PULSE_COUNT_Z) == 0
    finally:
        card.close()
