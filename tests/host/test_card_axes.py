"""The card API on every axis of a three-axis simulated card: direct pulses
through each axis's registers, every position read at one instant, an axis
the card lacks or a value out of range refused before anything is written.

Expectations come from the documented behaviour (docs/registers.md: a
PULSE_COUNT write of n gives |n| pulses in its sign's direction, POS counts
the steps that left the pins, a POS_X read captures the other axes) and the
X/Y pin log, never from the API."""
import pytest

from host.card import Card
from host.transports.simulated import SimTransport
from models import registers as regmap

# one worker builds and opens the three-axis card for the module (two would both wait on one build)
pytestmark = pytest.mark.xdist_group("card_axes")


@pytest.fixture(scope="module")
def transport():
    with SimTransport("verilator", axes=3) as opened:
        yield opened


@pytest.fixture
def card(transport):
    card = Card(transport)
    card.stop()
    card.write("COMMAND", regmap.field_of("COMMAND", CLEAR_POSITION=1))
    yield card
    card.stop()


def test_direct_pulses_on_every_axis_and_all_positions_at_one_instant(card, transport):
    assert card.identity.axes == 3
    before = len(transport.pins.rises)
    card.direct(2, -6, period=5)
    card.direct(0, 3, period=4)
    transport.sleep(200 / card.identity.clock_hz)
    assert [card.pulses_left(axis) for axis in range(3)] == [0, 0, 0]
    assert card.positions() == (3, 0, -6)
    rises = transport.pins.rises[before:]   # (clock, X stepped, Y stepped, DIR X, DIR Y)
    assert sum(x for _, x, _, _, _ in rises) == 3 and not any(y for _, _, y, _, _ in rises)
    assert card.field("CONTROL", "MODE") == 1
    assert card.axis_read("PULSE_PERIOD", 2) == 5 and card.read("PULSE_PERIOD_X") == 4


@pytest.mark.parametrize("call, text", [
    (lambda card: card.direct(3, 1), "3 axes"),
    (lambda card: card.direct(2, 1 << 23), "PULSE_COUNT_Z"),
    (lambda card: card.direct(2, 1, period=0), "PULSE_PERIOD_Z"),
    (lambda card: card.axis_write("POS", 2, 1), "read only"),
    (lambda card: card.axis_read("POS", -1), "3 axes"),
])
def test_bad_axes_and_values_are_refused_before_anything_is_written(card, call, text):
    before = card.read("CONTROL"), card.axis_read("PULSE_PERIOD", 2), card.axis_read("PULSE_COUNT", 2)
    with pytest.raises(ValueError, match=text):
        call(card)
    assert (card.read("CONTROL"), card.axis_read("PULSE_PERIOD", 2), card.axis_read("PULSE_COUNT", 2)) == before
