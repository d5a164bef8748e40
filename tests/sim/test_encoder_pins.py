"""The card server's encoder pin cues (sim/card/encoder_pins.py), played into the golden encoder model
(models/encoder_model.py) clock by clock: what a walk, a pulse train, a glitch and an index pulse count
and latch there."""
import pytest

from models.encoder_model import FILTER_MAX, MODE_QUADRATURE, MODE_STEP_DIR, EncoderModel
from sim.card.card_server import parse_arguments
from sim.card.encoder_pins import WALK_SPACING, EncoderPins, parse_cue, parse_glitch, parse_probe, play


def played(pins, axis, clocks, model, arm_at=None):
    play(pins.due(clocks), axis, clocks, model, arm_at)


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
    played(pins, 0, end, model)
    assert model.signed_count == sum(counts for _, counts in walks)
    assert not model.quad_error and WALK_SPACING > filter_setting + 1


def test_an_index_pulse_latches_once_armed():
    """An index pulse before the arm latches nothing; the one after it latches the count there."""
    pins, model = EncoderPins(axes=1), EncoderModel()
    pins.walk(0, 0, 10)
    pins.pulse(0, 400, 5)
    pins.walk(0, 500, 7)
    pins.pulse(0, 800, 5)
    played(pins, 0, 1000, model, arm_at=600)
    assert model.index_latch == 10 + 7 and not model.index_armed and model.signed_count == 17


@pytest.mark.parametrize("text, axes, problem", [
    ("0@100", 2, "not AXIS@CLOCK:VALUE"), ("x@1:2", 2, "not AXIS@CLOCK:VALUE"),
    ("2@100:5", 2, "axis 2 is not one of the card's 0..1"), ("0@-1:5", 2, "not negative")])
def test_a_bad_cue_is_refused_saying_why(text, axes, problem):
    with pytest.raises(ValueError, match=problem):
        parse_cue(text, axes)


TRAINS = ((100, 25), (2000, -10))   # (clock, pulses): 25 up, then 10 down


@pytest.mark.parametrize("filter_setting", [2, 14, FILTER_MAX])
def test_pulse_trains_count_their_pulses_in_step_dir_mode(filter_setting):
    """Step/dir (hostmot2's counter mode): every pulse of a train counts one, up with B high and down
    with B low, at every filter its levels (WALK_SPACING clocks each) pass; no quadrature error."""
    pins, model = EncoderPins(axes=2), EncoderModel()
    model.filter, model.mode = filter_setting, MODE_STEP_DIR
    pins.cue(pulses=[(0, clock, counts) for clock, counts in TRAINS] + [(1, 50, 7)])
    played(pins, 0, 2000 + 10 * 2 * WALK_SPACING + 40, model)
    assert model.signed_count == 25 - 10 and not model.quad_error


def test_the_same_pulse_trains_count_by_the_gray_code_in_quadrature_mode():
    """In quadrature mode the same pins count by the Gray code (docs/encoders.md's table), not the
    pulses.  From (A, B) = 00, the up train: B rises 00 -> 01 (-1), then each pulse's A rise 01 -> 11
    (-1) and, from the second on, A's fall before it 11 -> 01 (+1): -2 in all.  The down train from 11:
    B falls 11 -> 10 (-1), each pulse A falls 10 -> 00 (-1) and rises 00 -> 10 (+1): -1.  So -3, and
    mid-train the count rocks by one with every edge of A."""
    pins, up, both = EncoderPins(axes=1), EncoderModel(), EncoderModel()
    pins.cue(pulses=[(0, clock, counts) for clock, counts in TRAINS])
    events = pins.due(10_000)
    play(events, 0, 100 + 25 * 2 * WALK_SPACING + 40, up)
    play(events, 0, 2000 + 10 * 2 * WALK_SPACING + 40, both)
    assert up.signed_count == -2 and both.signed_count == -3
    assert not both.quad_error and both.mode == MODE_QUADRATURE


def test_a_glitch_is_a_quadrature_error_on_its_axis_and_no_count():
    """A glitch changes A and B in one clock: the model's quadrature error (flag and counter), the count
    untouched; the walk after it goes on legally from the levels the glitch left; the other axis's
    pins are untouched."""
    pins = EncoderPins(axes=2)
    pins.cue(walks=[(0, 0, 10), (0, 800, 5), (1, 0, 3)], glitches=[(0, 500)])
    events = pins.due(2000)
    assert [event for event in events if event[0] == 500] == [(500, "enc_a_x", 0), (500, "enc_b_x", 0)]
    glitched, other = EncoderModel(), EncoderModel()
    play(events, 0, 1100, glitched)
    play(events, 1, 1100, other)
    assert glitched.signed_count == 15 and glitched.quad_error and glitched.error_count == 1
    assert other.signed_count == 3 and not other.quad_error


def test_the_servers_cues_are_taken_in_clock_order_and_a_bad_one_refused(tmp_path, capsys):
    """The card server's options: walks, trains and glitches of one axis are played in the order of their
    clocks whatever the order given (the glitch between the walks here); a bad glitch cue exits 2 naming it."""
    socket = str(tmp_path / "card.sock")
    *_, pins = parse_arguments(["--socket", socket, "--log", "log", "--encoders", "--encoder-walk", "0@800:5",
                                "--encoder-glitch", "0@500", "--encoder-walk", "0@0:10"])
    model = EncoderModel()
    played(pins, 0, 1100, model)
    assert model.signed_count == 15 and model.error_count == 1
    with pytest.raises(SystemExit) as exit_:
        parse_arguments(["--socket", socket, "--log", "log", "--encoders", "--encoder-glitch", "2@500"])
    assert exit_.value.code == 2 and "axis 2 is not one of the card's 0..1" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        parse_arguments(["--socket", socket, "--log", "log", "--encoder-pulses", "0@10:5"])
    assert "need --encoders" in capsys.readouterr().err


def test_a_cue_read():
    assert parse_cue("1@2500:-300", 3) == (1, 2500, -300)
    assert parse_glitch("1@2500", 2) == (1, 2500)
    with pytest.raises(ValueError, match="not AXIS@CLOCK"):
        parse_glitch("1@x", 2)
    with pytest.raises(ValueError, match="index pulse of 0 clocks"):
        EncoderPins(1).pulse(0, 10, 0)


def test_a_probe_cue():
    pins = EncoderPins(1)
    pins.probe(100, 3)
    assert pins.due(1000) == [(100, "probe", 1), (103, "probe", 0)]
    assert parse_probe("100:3") == (100, 3)
    with pytest.raises(ValueError, match="not CLOCK:WIDTH"):
        parse_probe("100")
