"""The dda_card driver's encoder pins (hostmot2's encoder) under halrun, on simulated cards built with
encoders whose encoder pins the card server drives on cue (``--encoder-walk``, ``--encoder-pulses``,
``--encoder-glitch``, ``--index``: ``sim/card/encoder_pins.py``), beside a card without encoders.

Golden values come from the cues (counts walked, the walk's edge spacing, the index's clock, the pulse
trains and glitches played into the golden encoder model, models/encoder_model.py), not from
the driver: a walk of N counts one edge every WALK_SPACING clocks is N counts at
CLOCK_HZ / WALK_SPACING counts per second.  docs/linuxcnc.md, "Encoders".
"""
import shutil
from collections import Counter

import pytest

from models import registers as regmap
from models.encoder_model import MODE_QUADRATURE, MODE_STEP_DIR, EncoderModel
from sim.card.card_server import parse_arguments
from sim.card.encoder_pins import WALK_SPACING, play
from tests.linuxcnc.halrun import note, run_halrun, until, write_scripts
from tests.linuxcnc.session import CLOCK_HZ, PERIOD_CLOCKS, missing, run_folder

pytestmark = [pytest.mark.linuxcnc, pytest.mark.xdist_group("linuxcnc"),
              pytest.mark.skipif(missing() is not None, reason=str(missing()))]

TWO_CARDS = """loadrt threads name1=servo-thread period1=1000000
loadrt dda_card sim={run}/card0.sock,{run}/card1.sock
addf dda-card.0.read servo-thread
addf dda-card.1.read servo-thread
addf dda-card.0.write servo-thread
addf dda-card.1.write servo-thread
start
"""
# atleast.sh PIN VALUE: wait (at most 60 s) until halcmd getp PIN prints a number >= VALUE
ATLEAST = ('#!/bin/sh\nfor i in $(seq 3000); do v=$(halcmd getp "$1"); [ "$v" -ge "$2" ] && exit 0; sleep 0.02\n'
           'done\necho "atleast: $1 is $(halcmd getp "$1"), not >= $2" >&2; exit 1\n')
# show.sh FILE PREFIX: the pins and parameters under PREFIX into FILE
SHOW = '#!/bin/sh\nhalcmd show pin "$2" > "$1.pins"; halcmd show param "$2" > "$1.params"\n'

E = "dda-card.0.encoder"
X_SCALE = 100.0        # counts per position unit (encoder.00.scale)
FAST = 3000            # X's first walk: counts up, WALK_SPACING clocks apart (90 periods)
BACK = -200            # then back
AFTER_INDEX = 100      # counts walked after the index
Y_WALK = -300          # Y, at scale 0 (forced to 1)
# card clocks (1 MHz: microseconds since the card server opened the card); a note or setp that must come
# between two cues has 70 ms of card time or more for it, however slowly halcmd runs on a loaded machine
CUES = {
    "fast": 100_000, "y walk": 200_000, "stray index": 215_000, "arm after": 230_000, "back": 300_000,
    "probe": 400_000, "index": 520_000, "after index": 560_000,
}
X_FERROR = 0.5         # X's following-error limit (position units): 50 counts at scale 100
VEL_TIMEOUT = 0.05     # s: the velocity falls to 0 this long after the last count
INDEX_WIDTH = 50       # clocks the index pulses stay high


def _server_options():
    walks = [f"0@{CUES['fast']}:{FAST}", f"0@{CUES['back']}:{BACK}", f"0@{CUES['after index']}:{AFTER_INDEX}",
             f"1@{CUES['y walk']}:{Y_WALK}"]
    indexes = [f"0@{CUES['stray index']}:{INDEX_WIDTH}", f"0@{CUES['index']}:{INDEX_WIDTH}"]
    options = ["--axes", "3", "--encoders"]
    options += [item for walk in walks for item in ("--encoder-walk", walk)]
    options += [item for index in indexes for item in ("--index", index)]
    return options + ["--probe", f"{CUES['probe']}:{INDEX_WIDTH}"]


SCRIPT = (
    "loadusr -w ./show.sh card0 dda-card.0\nloadusr -w ./show.sh card1 dda-card.1\n"
    f"setp {E}.00.scale {X_SCALE}\nsetp {E}.01.scale 0\nsetp {E}.00.vel-timeout {VEL_TIMEOUT}\n"
    # mid-walk, some periods in: the velocity of a steady walk
    + f"loadusr -w ./atleast.sh {E}.00.count {FAST // 4}\n" + note(f"{E}.00.velocity", f"{E}.00.count")
    + until(f"{E}.00.count", str(FAST)) + until(f"{E}.01.count", str(Y_WALK))
    + note(f"{E}.00.position", f"{E}.01.position", f"{E}.01.scale")
    # the stray index pulse (not armed): no latch
    + f"loadusr -w ./atleast.sh dda-card.0.clock {CUES['arm after']}\n" + note(f"{E}.00.count")
    # the probe armed for X and Z (before the walk back): each one's count at the probe edge,
    # probe-enable falls
    + f"setp {E}.00.probe-enable 1\nsetp {E}.02.probe-enable 1\n" + until(f"{E}.00.probe-enable", "FALSE")
    + note(f"{E}.00.count-latched", f"{E}.00.position-latched", f"{E}.02.probe-enable", f"{E}.02.count-latched",
           f"{E}.01.count-latched")
    # armed: the index latches, count reads 0 from the index on, index-enable falls
    + f"setp {E}.00.index-enable 1\n" + until(f"{E}.00.index-enable", "FALSE")
    + note(f"{E}.00.count", f"{E}.00.rawcounts", "dda-card.0.clock")
    + until(f"{E}.00.count", str(AFTER_INDEX)) + note(f"{E}.00.position", f"{E}.00.rawcounts")
    # reset: count and position 0 while it is TRUE, the card's count runs on
    + f"setp {E}.00.reset 1\n" + until(f"{E}.00.count", "0") + f"setp {E}.00.reset 0\n"
    + note(f"{E}.00.count", f"{E}.00.position", f"{E}.00.rawcounts")
    # long after the walks: the velocity fell to 0 (vel-timeout)
    + until(f"{E}.00.velocity", "0") + note(f"{E}.00.velocity")
    # the card's following error set at enable: X's written, Z's scale of the other sign refused (-8)
    + f"setp {E}.00.ferror-limit {X_FERROR}\nsetp {E}.02.scale -400\nsetp {E}.02.ferror-limit 0.1\n"
    + f"setp dda-card.0.stepgen.00.enable 1\n" + until("dda-card.0.error", "TRUE") + note("dda-card.0.error-code")
)


def _pins(path):
    """{name: value} of a `halcmd show pin/param` listing."""
    return {fields[-1]: fields[-2] for fields in (line.split() for line in path.read_text().splitlines())
            if len(fields) >= 4 and fields[-1].startswith("dda-card.")}


@pytest.mark.slow(reason="two card servers and 0.6 s of card time in lock-step: 9 to 15 s here; "
                         "test_encoder_index_counter_mode_and_quad_error covers the pins and the index in the default set")
def test_encoder_pins_count_velocity_index_and_reset(linuxcnc_alone):
    """A 3-axis card with encoders and a 2-axis card without, under one driver: hostmot2's encoder
    pins and parameters on every axis of the first only, and the inputs of Z on the first only;
    scale 0 forced to 1 and said; the counts walked on the pins read as count and position; the
    time-stamped velocity of a walk one edge every 30 clocks is exactly 1 MHz / 30 counts/s while the
    counts per period alternate 33 / 34; probe-enable on two axes latches each one's count at the
    probe's edge; an index pulse while index-enable is FALSE latches nothing;
    armed, the next index zeroes count at the index and drops index-enable, the card's own count
    (rawcounts) running on; reset holds count at 0; at enable the card's following error is set
    from the scales and ferror-limit, a ratio of the wrong sign refused."""
    run = run_folder()
    write_scripts(run, {"atleast.sh": ATLEAST, "show.sh": SHOW})
    output, notes, records = run_halrun(run, TWO_CARDS.format(run=run) + SCRIPT,
                                        {"card0": _server_options(), "card1": ()})
    card0 = {**_pins(run / "card0.pins"), **_pins(run / "card0.params")}
    card1 = {**_pins(run / "card1.pins"), **_pins(run / "card1.params")}
    hostmot2 = ("count", "rawcounts", "position", "velocity", "reset", "index-enable", "probe-enable",
                "count-latched", "position-latched", "quad-error", "quad-error-enable", "scale", "filter",
                "counter-mode", "index-invert", "vel-timeout", "ferror-limit")
    for axis in range(3):
        for name in hostmot2:
            assert f"{E}.{axis:02d}.{name}" in card0, f"{E}.{axis:02d}.{name} missing"
    assert not any(".encoder." in name for name in card1), "encoder pins on a card without encoders"
    assert "dda-card.0.input.home-z" in card0 and "dda-card.0.input.limit-neg-z" in card0
    assert "dda-card.1.input.home-y" in card1 and not any(name.endswith("-z") for name in card1)
    # scale 0: said, forced to 1, the position in counts
    assert "encoder.01.scale 0 is no scale" in output and notes[f"{E}.01.scale"] == ["1"]
    assert float(notes[f"{E}.01.position"][0]) == Y_WALK
    # the walk: count and position; its velocity from the card's time stamps, to halcmd's 7 digits
    assert float(notes[f"{E}.00.position"][0]) == FAST / X_SCALE
    assert 0 < int(notes[f"{E}.00.count"][0]) < FAST, "the velocity was not noted mid-walk"
    velocity = CLOCK_HZ / WALK_SPACING / X_SCALE
    assert float(notes[f"{E}.00.velocity"][0]) == pytest.approx(velocity, rel=1e-6)
    # (counts per period over the period would read 33 or 34 counts a period here, never 33.33)
    assert {PERIOD_CLOCKS * k // WALK_SPACING - PERIOD_CLOCKS * (k - 1) // WALK_SPACING for k in range(1, 31)} == {33, 34}
    # the stray index did nothing
    assert notes[f"{E}.00.count"][1] == str(FAST)
    # the probe: X's count there (after the walk back, before the index), Z's 0; Y's not asked for
    assert notes[f"{E}.00.count-latched"] == [str(FAST + BACK)]
    assert float(notes[f"{E}.00.position-latched"][0]) == (FAST + BACK) / X_SCALE
    assert notes[f"{E}.02.probe-enable"] == ["FALSE"] and notes[f"{E}.02.count-latched"] == ["0"]
    assert notes[f"{E}.01.count-latched"] == ["0"]
    # the armed index: count 0 from the index on, the card's count untouched
    assert notes[f"{E}.00.count"][2] == "0" and notes[f"{E}.00.rawcounts"][0] == str(FAST + BACK)
    assert int(notes["dda-card.0.clock"][0]) > CUES["index"] + INDEX_WIDTH
    assert float(notes[f"{E}.00.position"][1]) == AFTER_INDEX / X_SCALE
    assert notes[f"{E}.00.rawcounts"][1] == str(FAST + BACK + AFTER_INDEX)
    # reset: count 0, the card's count runs on
    assert notes[f"{E}.00.count"][3] == "0" and float(notes[f"{E}.00.position"][2]) == 0.0
    assert notes[f"{E}.00.rawcounts"][2] == str(FAST + BACK + AFTER_INDEX)
    assert notes[f"{E}.00.velocity"][1] == "0"
    assert records["card0"]["final"]["ENC_COUNT"][:2] == [FAST + BACK + AFTER_INDEX, Y_WALK & 0xFFFFFFFF]
    # the following error: X's ratio (100 counts per step at position-scale 1, 16.16) and limit written,
    # Z's refused naming its values
    writes = {(offset, value) for _, offset, value in records["card0"]["writes"]}
    assert (regmap.axis_offset("ENC_SCALE", 0), round(X_SCALE * 65536)) in writes
    assert (regmap.axis_offset("FERROR_LIMIT", 0), round(X_FERROR * X_SCALE)) in writes
    assert notes["dda-card.0.error-code"] == ["-8"] and "encoder.02: scale -400 over the stepgen's" in output
    assert not any(offset == regmap.axis_offset("ENC_SCALE", 2) for offset, _ in writes)
    # what reading the encoders costs: the requests of a period on each card (READs, WRITEs, FIFO, ADVANCE)
    requests = {name: Counter(record["requests"][50:]).most_common(1)[0][0] for name, record in records.items()}
    print(f"\nrequests a period, idle: {requests} (card0: 3 axes with encoders; card1: 2 axes without)")
    shutil.rmtree(run, ignore_errors=True)


ONE_CARD_LOADED = """loadrt threads name1=servo-thread period1=1000000
loadrt dda_card sim={run}/card.sock
addf dda-card.0.read servo-thread
addf dda-card.0.write servo-thread
"""
ONE_CARD = ONE_CARD_LOADED + "start\n"
# later.sh PIN N: wait (at most 60 s) until halcmd getp PIN prints a number >= its value now + N
LATER = ('#!/bin/sh\nt=$(( $(halcmd getp "$1") + $2 )); for i in $(seq 3000); do [ "$(halcmd getp "$1")" -ge "$t" ] '
         '&& exit 0; sleep 0.02\ndone\necho "later: $1 is $(halcmd getp "$1"), not >= $t" >&2; exit 1\n')
X_COUNTER_SCALE = 10.0  # X's counts per position unit in counter mode
TRAINS = ((5_000, 25), (10_000, -10))   # step/dir pulse trains on X (counter mode) and Y (quadrature): 25 up, 10 down
SHORT_WALK = 40         # counts walked on Y before its index
AFTER_GLITCH = 20       # counts walked on Y after its second glitch
# card clocks (1,000 a servo period): a note taken after one cue comes at least 150 ms of card time before
# the next cue it must precede, however slowly halcmd runs on a loaded machine
SHORT_CUES = {"glitch before enable": 1, "walk": 20_000, "walked": 22_000, "index": 200_000, "glitch": 400_000,
              "after glitch": 405_000, "noted": 407_000}


def _short_options():
    options = ["--encoders", "--encoder-walk", f"1@{SHORT_CUES['walk']}:{SHORT_WALK}",
               "--index", f"1@{SHORT_CUES['index']}:{INDEX_WIDTH}",
               "--encoder-glitch", f"1@{SHORT_CUES['glitch before enable']}", "--encoder-glitch", f"1@{SHORT_CUES['glitch']}",
               "--encoder-walk", f"1@{SHORT_CUES['after glitch']}:{AFTER_GLITCH}"]
    for axis in (0, 1):
        options += [item for clock, pulses in TRAINS for item in ("--encoder-pulses", f"{axis}@{clock}:{pulses}")]
    return options


def _model_counts(options, axis, clock, mode):
    """Axis ``axis``'s count at card clock ``clock`` by the golden encoder model (at the driver's filter,
    15 clocks) in ``mode``, on the pins the card server's ``options`` cue."""
    *_, pins = parse_arguments(["--socket", "unused", "--log", "unused", *options])
    model = EncoderModel()
    model.filter, model.mode = 14, mode
    play(pins.due(clock), axis, clock, model)
    return model.signed_count


def test_encoder_index_counter_mode_and_quad_error(linuxcnc_alone):
    """The default set's look at the encoders (the slow test above has the rest), a 2-axis card with
    encoders: an encoder per axis and no pin of a third.  Y (quadrature): the same step/dir pulse trains
    as X's counted by the Gray code, as the golden model counts them, then a walk; index-enable set, the
    next index zeroes count there and index-enable falls.  X in counter-mode: the trains' pulses, 25 up
    and 10 down, counted one each, position count / scale.  quad-error-enable TRUE on both after a glitch
    of Y's A and B at card clock 1: that glitch is not reported (as hostmot2, errors from before the
    enable are dropped); the glitch after it sets Y's quad-error (said once), not X's (quadrature by
    then), and Y's count does not move at it; quad-error-enable FALSE clears it, TRUE again reads FALSE."""
    run = run_folder()
    write_scripts(run, {"atleast.sh": ATLEAST, "later.sh": LATER})
    options = _short_options()
    script = ONE_CARD_LOADED.format(run=run) + (
        f"setp {E}.00.counter-mode 1\nsetp {E}.00.scale {X_COUNTER_SCALE}\n"
        # quad-error-enable rises after the glitch at clock 1 (the card's clock runs only with the thread)
        f"start\nloadusr -w ./atleast.sh dda-card.0.clock 2\n"
        f"setp {E}.00.quad-error-enable 1\nsetp {E}.01.quad-error-enable 1\n"
        f"setp {E}.01.index-enable 1\nloadusr -w ./later.sh dda-card.0.clock 2000\n"
        + note(f"{E}.00.quad-error", f"{E}.01.quad-error")
        + f"loadusr -w ./atleast.sh dda-card.0.clock {SHORT_CUES['walked']}\n"
        + note(f"{E}.01.index-enable") + until(f"{E}.01.index-enable", "FALSE")
        + note(f"{E}.01.count", f"{E}.01.rawcounts", f"{E}.00.count", f"{E}.00.position")
        # X to quadrature (its trains are over): a quadrature error could show on X too from here on
        + f"setp {E}.00.counter-mode 0\nloadusr -w ./atleast.sh dda-card.0.clock {SHORT_CUES['noted']}\n"
        + note(f"{E}.01.quad-error", f"{E}.00.quad-error", f"{E}.01.count", f"{E}.01.rawcounts")
        + f"setp {E}.01.quad-error-enable 0\n" + until(f"{E}.01.quad-error", "FALSE")
        + f"setp {E}.01.quad-error-enable 1\nloadusr -w ./later.sh dda-card.0.clock 5000\n" + note(f"{E}.01.quad-error"))
    output, notes, records = run_halrun(run, script, {"card": options})
    # golden counts: the model on the cued pins, X in step/dir, Y in quadrature
    x_counts = _model_counts(options, 0, SHORT_CUES["walk"], MODE_STEP_DIR)
    y_trains = _model_counts(options, 1, SHORT_CUES["walk"], MODE_QUADRATURE)
    y_at_index = _model_counts(options, 1, SHORT_CUES["index"], MODE_QUADRATURE)
    y_noted = _model_counts(options, 1, SHORT_CUES["noted"], MODE_QUADRATURE)
    assert x_counts == 25 - 10 and y_trains != x_counts
    assert y_at_index == y_trains + SHORT_WALK and y_noted == y_at_index + AFTER_GLITCH
    assert notes[f"{E}.01.index-enable"] == ["TRUE"], "index-enable fell before the index"
    assert notes[f"{E}.01.count"][0] == "0" and notes[f"{E}.01.rawcounts"][0] == str(y_at_index)
    assert notes[f"{E}.00.count"] == [str(x_counts)] and float(notes[f"{E}.00.position"][0]) == x_counts / X_COUNTER_SCALE
    assert f"{E}.02." not in output
    # the glitch before the enable: dropped; the one after the enable: Y's only, no count, said once
    assert notes[f"{E}.01.quad-error"][:2] == ["FALSE", "TRUE"] and notes[f"{E}.00.quad-error"] == ["FALSE", "FALSE"]
    assert notes[f"{E}.01.count"][1] == str(AFTER_GLITCH) and notes[f"{E}.01.rawcounts"][1] == str(y_noted)
    assert output.count("quadrature error") == 1
    assert "dda-card.0.encoder.01: quadrature error (A and B changed in the same sample, not counted; 1 since" in output
    # quad-error-enable FALSE cleared it; TRUE again reads FALSE, the card's flag cleared
    assert notes[f"{E}.01.quad-error"][2] == "FALSE"
    final = records["card"]["final"]
    assert final["ENC_COUNT"] == [x_counts, y_noted & 0xFFFFFFFF]
    quad_error = regmap.axis_spec("ENC_STATUS").field("QUAD_ERROR").mask
    assert [status & quad_error for status in final["ENC_STATUS"]] == [0, 0]
    shutil.rmtree(run, ignore_errors=True)


FE_STEP_SCALE = 100.0      # steps per unit (stepgen.00.position-scale)
FE_ENCODER_SCALE = 400.0   # counts per unit: 4 counts a step
FE_LIMIT = 0.2             # units: 80 counts, 20 steps
# 8 + 8 clocks a step at 1 MHz (p = 16): the card's stop, 3 clocks after the step that crossed the
# limit (docs/encoders.md: 2 to the flag, 1 to the guard), comes before the next step
FE_STEP_NS = 8000


def test_the_cards_following_error_stop_reaches_the_driver(linuxcnc_alone):
    """No motor turns X's encoder (a motor stalled from the start): X commanded 0.5 unit (50 steps, in one period),
    the card's following error passes ferror-limit (80 counts: 20 steps) and the card stops itself
    (STOP_REASON FOLLOWING_ERROR, axis 0): the driver's error -3 and stop-reason 4, the axis named,
    the steps made the limit's and the one that crossed it, not one more."""
    run = run_folder()
    script = ONE_CARD.format(run=run) + (
        f"setp dda-card.0.stepgen.00.position-scale {FE_STEP_SCALE}\nsetp {E}.00.scale {FE_ENCODER_SCALE}\n"
        f"setp {E}.00.ferror-limit {FE_LIMIT}\nsetp dda-card.0.stepgen.00.steplen {FE_STEP_NS}\n"
        f"setp dda-card.0.stepgen.00.stepspace {FE_STEP_NS}\n"
        f"setp dda-card.0.stepgen.00.enable 1\nsetp dda-card.0.drive-enable 1\n"
        + until("dda-card.0.fifo-level", "not:0") + "setp dda-card.0.stepgen.00.position-cmd 0.5\n"
        + until("dda-card.0.error", "TRUE") + note("dda-card.0.error-code", "dda-card.0.stop-reason"))
    output, notes, records = run_halrun(run, script, {"card": ("--encoders",)})
    record = records["card"]
    assert notes["dda-card.0.error-code"] == ["-3"] and notes["dda-card.0.stop-reason"] == ["4"]
    assert "a following error beyond FERROR_LIMIT" in output and "(STOP_REASON.AXIS 0)" in output
    stop, reason = record["final"]["STOP_REASON"], regmap.register("STOP_REASON")
    assert (stop & reason.field("REASON").mask) >> reason.field("REASON").lsb == regmap.STOP_REASONS.index("FOLLOWING_ERROR")
    assert (stop & reason.field("AXIS").mask) >> reason.field("AXIS").lsb == 0
    limit_steps = FE_LIMIT * FE_ENCODER_SCALE / (FE_ENCODER_SCALE / FE_STEP_SCALE)
    assert record["final"]["POS_X"] == limit_steps + 1, record["final"]
    shutil.rmtree(run, ignore_errors=True)
