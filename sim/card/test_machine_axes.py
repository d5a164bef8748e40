"""The machine inputs of an axis beyond X and Y on a three-axis build (docs/machine.md): Z's limit
stops the card with STOP_REASON.LIMITS's Z bit, Z's inputs read in INPUT_RAW and INPUT_ACTIVE,
INPUT_POLARITY has the bits of the build's inputs only, and HOME.AXIS_INDEX homes Z on its switch.

Golden values are the documented layout, written out here, not the table's code: INPUT_RAW 0x9C,
INPUT_ACTIVE 0xA0, INPUT_POLARITY 0x6C, inputs LIMIT_POS_Z, LIMIT_NEG_Z, HOME_Z at bits 7, 8, 9 (a
three-axis card has ten inputs), STOP_REASON.LIMITS at bits 15:4 with LIMIT_POS_Z its bit 4 (word
bit 8), REASON LIMIT 3; Z's block: POS 0x180, PULSE_COUNT 0x188; HOME 0x7C with AXIS_INDEX at
bits 6:4, HOME_STATUS 0x80 (DONE bit 1, REFUSED bit 3): a homed axis reads -HOME_BACKOFF steps
from the switch's release point (towards the negative end for a switch at the positive one).
"""
import pytest

from models import registers as regmap
from sim.card.card_session import CardSession

INPUT_POLARITY, INPUT_RAW, INPUT_ACTIVE, STOP_REASON = 0x6C, 0x9C, 0xA0, 0x68
HOME, HOME_STATUS, HOME_SEEK_PERIOD, HOME_RELEASE_PERIOD, HOME_BACKOFF = 0x7C, 0x80, 0x84, 0x88, 0x8C
HOME_DONE, HOME_REFUSED = 1 << 1, 1 << 3
POS_X, POS_Z, PULSE_COUNT_Z = 0x20, 0x180, 0x188
LIMIT_POS_Z, LIMIT_NEG_Z, HOME_Z = 1 << 7, 1 << 8, 1 << 9
STOP_LIMIT_POS_Z = 3 | 1 << 8   # REASON LIMIT, LIMITS bit 4
SETTLE = 10   # clocks: synchroniser and the default filter (3 samples) take a pin in 6


def u32(value):
    return value & 0xFFFFFFFF


@pytest.fixture(params=["myhdl", "verilator"])
def three_axes(request):
    session = CardSession(request.param, axes=3)
    yield session
    session.close()


def z_position(card):
    card.read(POS_X)   # captures every other axis's position
    return card.read(POS_Z)


def test_a_z_limit_stops_a_step_towards_it_and_lets_one_away_pass(three_axes):
    card = three_axes
    card.write(regmap.offset("CONTROL"), regmap.field_of("CONTROL", MODE=1))
    card.write(regmap.offset("MACHINE_CONTROL"), regmap.field_of("MACHINE_CONTROL", DRIVE_ENABLE=1))
    card.set_input("limit_pos_z", 1)
    card.wait(SETTLE)
    assert card.read(INPUT_RAW) == card.read(INPUT_ACTIVE) == LIMIT_POS_Z
    assert regmap.field_value("MACHINE_STATUS", "ACTIVE", card.read(regmap.offset("MACHINE_STATUS"))) == 0, \
        "MACHINE_STATUS keeps X's and Y's inputs only"
    card.write(PULSE_COUNT_Z, 5)   # towards the active positive limit
    card.wait(40)
    assert card.read(STOP_REASON) == STOP_LIMIT_POS_Z
    assert regmap.field_value("STATUS", "STOPPED", card.read(regmap.offset("STATUS"))) == 1
    assert z_position(card) == 0 and card.log.rises == [], "no Z step left towards the limit"
    card.write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", CLEAR_STOP=1))
    assert card.read(STOP_REASON) == 0
    card.write(regmap.offset("MACHINE_CONTROL"), regmap.field_of("MACHINE_CONTROL", DRIVE_ENABLE=1))
    card.write(PULSE_COUNT_Z, u32(-3))   # away from it: every step passes
    card.wait(60)
    assert z_position(card) == u32(-3) and card.read(STOP_REASON) == 0


def test_z_inputs_read_raw_and_active_with_their_polarity(three_axes):
    card = three_axes
    card.write(INPUT_POLARITY, 0xFFFFFFFF)
    assert card.read(INPUT_POLARITY) == (1 << 10) - 1, "the bits of inputs a three-axis card lacks read 0"
    card.write(INPUT_POLARITY, HOME_Z | LIMIT_NEG_Z)   # Z's home and negative limit wired active low
    card.set_input("home_z", 1)
    card.set_input("limit_neg_z", 1)
    card.wait(SETTLE)
    assert card.read(INPUT_RAW) == HOME_Z | LIMIT_NEG_Z
    assert card.read(INPUT_ACTIVE) == 0
    card.set_input("home_z", 0)
    card.wait(SETTLE)
    assert card.read(INPUT_RAW) == LIMIT_NEG_Z and card.read(INPUT_ACTIVE) == HOME_Z
    assert regmap.field_value("INT_STATUS", "INPUT", card.read(regmap.offset("INT_STATUS"))) == 1, \
        "a Z input's change raises INT_STATUS.INPUT"


def test_home_axis_index_homes_z_on_its_switch_and_refuses_an_axis_the_card_lacks(three_axes):
    """Z's home switch closes from position 5 on (no bounce): the pins' Z steps move it, the
    bench drives ``home_z`` from them clock by clock."""
    card = three_axes
    # release steps far apart beside the filter's 6 clocks: the bench's switch, a clock late on one
    # simulator or the other, cannot move the release across a step
    for offset, value in ((HOME_SEEK_PERIOD, 4), (HOME_RELEASE_PERIOD, 20), (HOME_BACKOFF, 2)):
        card.write(offset, value)
    card.write(HOME, 3 << 4)   # A: a three-axis card has none
    assert card.read(HOME_STATUS) & (HOME_REFUSED | 1) == HOME_REFUSED
    card.write(HOME, 2 << 4)   # Z, switch at the positive end
    position, closed, before = 0, False, card.pin("step_z")
    for _ in range(300):
        card.wait(1)
        level = card.pin("step_z")
        if level and not before:
            position += 1 if card.pin("dir_z") else -1
        before = level
        if (position >= 5) != closed:
            closed = position >= 5
            card.set_input("home_z", closed)
    status = card.read(HOME_STATUS)
    assert status & (HOME_DONE | HOME_REFUSED | 1) == HOME_DONE, hex(status)
    assert card.read(HOME) == 2 << 4   # AXIS_INDEX 2, AXIS (its low bit) 0, NEGATIVE 0
    assert z_position(card) == u32(-2), "zeroed at the release point, then HOME_BACKOFF steps on"
    assert card.log.rises == [], "X and Y stood still"
