"""The card server's encoder pin cues (sim/card/encoder_pins.py), played into the golden encoder model
(models/encoder_model.py) clock by clock: what a walk and an index pulse count and latch there."""
import pytest

from models.encoder_model import FILTER_MAX, EncoderModel
from sim.card.encoder_pins import WALK_SPACING, EncoderPins, parse_cue, parse_probe


def play(pins, axis, clocks, model, arm_at=None):
    """Clock ``model`` (axis ``axis``'s encoder) through ``clocks`` card clocks of ``pins``' changes."""
    letter = "xyzabc"[axis]
    level = {"a": 0, "b": 0, "index": 0}
    due = pins.due(clocks)
    for clock in range(clocks + 1):
        while due and due[0][0] == clock:
            _, name, value = due.pop(0)
            if name.endswith(f"_{letter}"):
                level[name[len("enc_"):-2]] = value
        if clock == arm_at:
            model.arm_index()
        model.clock(level["a"], level["b"], level["index"])


@pytest.mark.parametrize("walks", [[(100, 37)], [(50, 12), (400, -20)], [(10, -5), (300, 9), (700, 3)]])
@pytest.mark.parametrize("filter_setting", [2, 14, FILTER_MAX])
def test_walks_count_on_the_model_at_every_filter_the_spacing_passes(walks, filter_setting):
    """Each walk's counts, in either direction and one after another, are the model's count: every
    edge legal (no quadrature error) and WALK_SPACING clocks apart, more than the filter holds."""
    pins, model = EncoderPins(axes=2), EncoderModel()
    model.filter = filter_setting
    for clock, counts in walks:
        pins.walk(0, clock, counts)
    pins.walk(1, 0, 1000)   # another axis's pins do not reach axis 0
    end = max(clock + abs(counts) * WALK_SPACING for clock, counts in walks) + 40
    play(pins, 0, end, model)
    assert model.signed_count == sum(counts for _, counts in walks)
    assert not model.quad_error and WALK_SPACING > filter_setting + 1


def test_an_index_pulse_latches_once_armed():
    """An index pulse before the arm latches nothing; the one after it latches the count there."""
    pins, model = EncoderPins(axes=1), EncoderModel()
    pins.walk(0, 0, 10)
    pins.pulse(0, 400, 5)
    pins.walk(0, 500, 7)
    pins.pulse(0, 800, 5)
    play(pins, 0, 1000, model, arm_at=600)
    assert model.index_latch == 10 + 7 and not model.index_armed and model.signed_count == 17


@pytest.mark.parametrize("text, axes, problem", [
    ("0@100", 2, "not AXIS@CLOCK:VALUE"), ("x@1:2", 2, "not AXIS@CLOCK:VALUE"),
    ("2@100:5", 2, "axis 2 is not one of the card's 0..1"), ("0@-1:5", 2, "not negative")])
def test_a_bad_cue_is_refused_saying_why(text, axes, problem):
    with pytest.raises(ValueError, match=problem):
        parse_cue(text, axes)


def test_a_cue_read():
    assert parse_cue("1@2500:-300", 3) == (1, 2500, -300)
    with pytest.raises(ValueError, match="index pulse of 0 clocks"):
        EncoderPins(1).pulse(0, 10, 0)


def test_a_probe_cue():
    pins = EncoderPins(1)
    pins.probe(100, 3)
    assert pins.due(1000) == [(100, "probe", 1), (103, "probe", 0)]
    assert parse_probe("100:3") == (100, 3)
    with pytest.raises(ValueError, match="not CLOCK:WIDTH"):
        parse_probe("100")
