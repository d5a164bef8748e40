"""The encoders in the whole card (a build with encoders, Verilator, read over PCI) against the golden
models, and the following-error stop's reaction (``sim/card/encoder_card_bench.py``)."""
import pytest

from models import registers as regmap
from sim.card.encoder_card_bench import REACTION_CLOCKS, compare_counts, following_error_trip

pytestmark = pytest.mark.xdist_group("encoder_card")


def _check_counts(seed, clocks, kind="verilator"):
    got, want = compare_counts(seed, clocks=clocks, kind=kind)
    assert got == want
    # the waveform reached both latches and an error on some axis: the comparison covered them
    assert want["INT_PROBE"] == 1 and want["INT_INDEX"] == 1
    assert any(value for key, value in want.items() if key[1:] == ("QUAD_ERROR",))


@pytest.mark.slow(reason="a Verilator build of the card with encoders (about a minute of CPU); the MyHDL card "
                         "run below compares the same registers in the default set")
@pytest.mark.parametrize("seed", [1, 2])
def test_counts_times_and_latches_read_over_pci_equal_the_models(seed):
    _check_counts(seed, 400)


@pytest.mark.slow(reason="ten more seeds of the comparison above: a sweep, not needed on every run")
@pytest.mark.parametrize("seed", range(3, 13))
def test_counts_times_and_latches_equal_the_models_at_more_seeds(seed):
    _check_counts(seed, 600)


def test_counts_equal_the_models_on_the_myhdl_card_too():
    # one short run of the same bench on the MyHDL card (the Verilator runs above carry the length)
    _check_counts(3, 120, kind="myhdl")


@pytest.mark.slow(reason="the Verilator card with encoders; the stop's unit is proved and compared with its "
                         "model every clock in the default set (test_encoder_units, formal following_error)")
@pytest.mark.parametrize("axis", [0, 1])
def test_a_following_error_trip_stops_the_card_naming_the_axis_within_the_stated_clocks(axis):
    clocks, reason, model_clocks = following_error_trip(axis)
    assert regmap.field_value("STOP_REASON", "REASON", reason) == regmap.STOP_REASONS.index("FOLLOWING_ERROR")
    assert regmap.field_value("STOP_REASON", "AXIS", reason) == axis
    # the card's stop one edge after the model's flag, as docs/encoders.md states it
    assert (clocks, model_clocks) == (REACTION_CLOCKS, REACTION_CLOCKS - 1)
