"""The host's machine side on a three-axis simulated card (Verilator): limits by name from
INPUT_ACTIVE, HOME of Z through HOME.AXIS_INDEX, and an axis the card lacks refused before
anything is written (docs/machine.md)."""
import pytest

from host.card import Card
from host.homing import HomingError
from host.transports.simulated import SimTransport
from models.parameters import PARAMETERS

CLOCK_HZ = PARAMETERS["clock_hz"].default


def test_a_three_axis_card_names_z_limits_and_homes_z():
    with SimTransport("verilator", axes=3) as transport:
        card = Card(transport)
        transport.session.set_input("limit_neg_z", 1)
        transport.sleep(1e-6)
        assert card.limits() == ("LIMIT_NEG_Z",)
        assert card.machine_side()["inputs"] == ("LIMIT_NEG_Z",)
        transport.session.set_input("limit_neg_z", 0)
        home_before = card.read("HOME")
        with pytest.raises(ValueError, match="not one of X, Y, Z"):
            card.home("A")
        assert card.read("HOME") == home_before
        # no switch on Z's home input: the seek runs its 10 steps towards +Z and gives up
        with pytest.raises(HomingError, match="NOT_FOUND"):
            card.home("Z", direction="positive", seek_rate=CLOCK_HZ / 100, search=10)
        assert card.machine_side()["homing"]["AXIS"] == "Z"
        assert card.positions() == (0, 0, 10)
