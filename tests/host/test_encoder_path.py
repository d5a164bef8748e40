"""The path the encoders measured (host/encoder_path.py) and ``python -m host run --encoders``: the
decoding of recorded encoder pins, the measure against the drawing and the pins with known offsets,
the options refused before the card is opened, and (slow set) runs on the Verilator card with motors."""
import json
import re

import pytest

from host import gcode
from host.check import check
from host.encoder_path import encoder_samples, measure
from host.machine import Machine
from host.planner import plan
from models.sim_machine import MachineConfig, Motor
from tests.host.test_run import EXAMPLES, figure, run_host

GRAY_UP = (0b01, 0b11, 0b10, 0b00)   # (A, B) as a word, one count up each (A leads B)
STEPS_PER_MM = 10


def test_encoder_changes_decode_into_counts_over_counts_per_step():
    # X: 3 up, 1 down at 4 counts a step; Y (bits 3, 4): 5 up at 5/2 counts a step
    changes = [(10, GRAY_UP[0]), (12, GRAY_UP[1]), (14, GRAY_UP[2]), (16, GRAY_UP[1])]
    y = 0
    for n in range(5):
        y = GRAY_UP[n % 4] << 3
        changes.append((20 + n, GRAY_UP[1] | y))
    samples = encoder_samples(changes, [(4, 1), (5, 2)])
    assert [clock for clock, _ in samples] == [10, 12, 14, 16, 20, 21, 22, 23, 24]
    assert samples[3][1] == (0.5, 0.0) and samples[-1][1] == (0.5, 2.0)
    index_only = encoder_samples([(5, 0b100)], [(1, 1)])
    assert index_only == [(5, (0.0,))], "the index bit is not a count"


def test_a_change_of_a_and_b_together_is_refused():
    with pytest.raises(ValueError, match="A and B changed together at clock 7"):
        encoder_samples([(7, 0b11)], [(1, 1)])


def _line_plan():
    machine = Machine(steps_per_mm=(STEPS_PER_MM, STEPS_PER_MM), rapid=600, acceleration=1000, start_feed=60)
    planned = plan(gcode.parse("G1 X4 F600\nG1 Y3\n", "t.ngc"), machine)
    return planned, check(planned)


def _pin_rises(model):
    """One rise every 10 clocks along the golden model's points: [(clock, point)]."""
    points = [p for _, moves in model.points for p in moves[1:]]
    return [(10 * (n + 1), point) for n, point in enumerate(points)]


@pytest.mark.parametrize("lag_rises,offset", [(0, (0, 0)), (2, (0, 0)), (0, (0.5, 0)), (0, (0, -1.5))])
def test_measure_gives_the_distance_from_the_pins_and_from_the_drawing(lag_rises, offset):
    planned, model = _line_plan()
    rises = _pin_rises(model)
    # the encoders lag ``lag_rises`` rises behind the pins and sit ``offset`` steps off them
    samples = [(clock + 1, tuple(c + o for c, o in zip(rises[max(0, n - lag_rises)][1], offset)))
               for n, (clock, _) in enumerate(rises)]
    result = measure(planned, model, samples, rises, (0, 0))
    lagged = max(sum((a - b) ** 2 for a, b in zip(rises[n][1], rises[max(0, n - lag_rises)][1])) ** 0.5
                 for n in range(len(rises)))
    expected_pins = max(lagged, sum(o * o for o in offset) ** 0.5)   # one of the two is 0 in each case
    assert result.samples == len(rises)
    assert result.pins_mm == pytest.approx(expected_pins / STEPS_PER_MM)
    # per axis, in steps: each sample against the pins' point after the rise just before it
    per_axis = tuple(max(abs(rises[max(0, n - lag_rises)][1][axis] + offset[axis] - rises[n][1][axis])
                         for n in range(len(rises))) for axis in (0, 1))
    assert result.pins_steps == pytest.approx(per_axis)
    # on the drawing's lines the pins are exact lattice points: the distance is the offset across the line
    across = {(0, 0): 0.0, (0.5, 0): 0.5, (0, -1.5): 1.5}[offset]
    assert result.drawing_mm == pytest.approx(across / STEPS_PER_MM)
    assert [primitive for primitive, _ in result.moves] == [primitive for primitive, _ in model.points]


@pytest.mark.parametrize("args, text", [
    (("--encoders", "--card", "icarus"), "--encoders runs on --card verilator or myhdl"),
    (("--encoders", "--card", "pci"), "--encoders runs on --card verilator or myhdl"),
    (("--ferror-limit", "5"), "--ferror-limit needs --encoders"),
    (("--encoders", "--ferror-limit", "-1"), "FERROR_LIMIT is a count"),
    (("--encoders", "--ferror-limit", "x"), "FERROR_LIMIT is a count"),
])
def test_bad_encoder_options_are_refused_before_the_card_is_opened(args, text):
    result = run_host("run", EXAMPLES / "part.ngc", *args, timeout=60)
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert result.returncode == 2 and len(lines) == 1 and text in lines[0], result.stderr
    assert result.stdout == ""


@pytest.mark.parametrize("command", [("run", EXAMPLES / "part.ngc"), ("info",)])
def test_a_machine_with_motors_needs_encoders(tmp_path, command):
    (tmp_path / "m.json").write_text(MachineConfig(motors={"X": Motor()}).to_json())
    result = run_host(*command, "--machine", tmp_path / "m.json", timeout=60)
    assert result.returncode == 2 and "its motors need --encoders" in result.stderr and result.stdout == ""


@pytest.mark.parametrize("axes", [(), ("--axes", "2")])
def test_a_machine_with_an_axis_the_card_lacks_is_refused_before_the_card_is_opened(tmp_path, axes):
    (tmp_path / "m.json").write_text(MachineConfig(motors={"X": Motor(), "Z": Motor()}).to_json())
    result = run_host("run", EXAMPLES / "part.ngc", "--encoders", "--machine", tmp_path / "m.json", *axes, timeout=60)
    assert result.returncode == 2 and result.stdout == ""
    assert "the machine names axes the card lacks: motor Z; the card has 2 axes (X, Y): build it with --axes 3" \
        in result.stderr


SQUARE = "G21 G90\nG1 X5 F1200\nG1 Y4\nG1 X0\nG1 Y0\n"
FAST = ("--feed-override", "100000", "--steps-per-mm", "40", "--acceleration", "2000000", "--start-feed", "60000")


@pytest.mark.slow(reason="the Verilator card with encoders (a build of its own, about a minute of CPU); the "
                         "measure is tested above, the motors in tests/models and tests/sim")
def test_run_with_encoders_reports_the_measured_path_and_previews_it(tmp_path):
    (tmp_path / "square.ngc").write_text(SQUARE)
    (tmp_path / "m.json").write_text(json.dumps({"motors": {"X": {"counts_per_step": 4, "lag": 1500},
                                                            "Y": {"counts_per_step": [5, 2], "jitter": 2}}}))
    picture = tmp_path / "measured.png"
    result = run_host("run", tmp_path / "square.ngc", "--encoders", "--machine", tmp_path / "m.json", *FAST,
                      "--ferror-limit", "400", "--preview", picture)
    assert result.returncode == 0, result.stderr
    out = result.stdout
    counts, steps = figure(out, "encoders", r"counts \((-?\d+, -?\d+)\) \(ENC_COUNT\) = \(([-\d., ]+)\) steps")
    assert counts == "0, 0" and steps == "0.000, 0.000"   # back at the start: every count came back
    samples, drawing, pins = figure(out, "measured", r"(\d+) encoder samples; max deviation from the drawing "
                                                     r"([\d.]+) mm .* from the pins ([\d.]+) mm")
    # 2 x (200 + 160) steps: 4 counts a step on X, 2.5 on Y, each counted there and back
    assert int(samples) == 2 * 200 * 4 + 2 * 160 * 5 // 2
    # X lags 1,500 clocks behind its steps, about three steps at this feed: the pins are that far ahead (0.025 mm a
    # step); the drawing is nearer (a lagging point is still on its line), within the pins' half step of it
    assert 0.025 < float(pins) < 0.5 and float(drawing) <= float(pins) + 0.0125
    assert "stop NONE" in out and picture.stat().st_size > 10_000


@pytest.mark.slow(reason="the Verilator card with encoders, as above")
def test_a_stalled_motor_stops_the_run_with_the_following_error_and_reports_it(tmp_path):
    (tmp_path / "square.ngc").write_text(SQUARE)
    (tmp_path / "m.json").write_text(json.dumps({"motors": {"X": {"stall_at": 200_000}, "Y": {}}}))
    result = run_host("run", tmp_path / "square.ngc", "--encoders", "--machine", tmp_path / "m.json", *FAST,
                      "--ferror-limit", "20")
    assert result.returncode == 1, result.stderr
    assert "FOLLOWING_ERROR" in figure(result.stdout, "stopped", r"(.*)")[0]
    assert "stop FOLLOWING_ERROR X" in result.stdout


# 3-D lines and a helix (one turn about (1, 1) mm, down 0.5 mm), short: a fraction of a second of card time
HELIX_3D = """G21 G90 G17 G91.1
G1 X1.5 Y1 Z-0.25 F1200
G3 X1.5 Y1 Z-0.75 I-0.5 J0
G1 X0.5 Y0.25 Z0
G1 X0 Y0 Z-0.25
M2
"""


def _per_axis(out):
    return [float(v) for v in re.findall(r"[XYZ] (\d+\.\d+)", figure(out, "per axis", r"(.*)")[0])]


def test_a_3d_run_with_encoders_measures_every_axis_and_ends_on_exact_counts(tmp_path):
    (tmp_path / "helix.ngc").write_text(HELIX_3D)
    (tmp_path / "m.json").write_text(json.dumps({"motors": {"X": {}, "Y": {"counts_per_step": [5, 2]},
                                                            "Z": {"counts_per_step": 3, "lag": 300}}}))
    result = run_host("run", tmp_path / "helix.ngc", "--encoders", "--axes", "3", "--machine", tmp_path / "m.json",
                      "--steps-per-mm", "40", "--ferror-limit", "60", "--acceleration", "200000", "--rapid", "6000",
                      "--feed-override", "2000")
    assert result.returncode == 0, result.stdout + result.stderr
    out = result.stdout
    assert re.search(r"^pins end:\s+\(0, 0, -10\) steps", out, re.M), out
    # -10 Z steps at 3 counts a step; X and Y back at 0
    assert figure(out, "encoders", r"counts \((-?\d+, -?\d+, -?\d+)\) \(ENC_COUNT\)") == ("0, 0, -30",)
    assert re.search(r"^counts end: exact: the pins' \(0, 0, -10\) steps x counts per step = \(0, 0, -30\)", out, re.M)
    assert "stop NONE" in out
    # every axis's steps come further apart (over 1,000 clocks at these feeds) than its motor's lag and counts
    # take (X: 4 counts 4 clocks apart, Y 3, Z 300 clocks + 3 counts): the encoders are never more than the
    # step the pins just made behind them, and they do fall behind
    per_axis = _per_axis(out)
    assert len(per_axis) == 3 and all(0 < apart <= 1.0 for apart in per_axis), out


@pytest.mark.slow(reason="the MyHDL card with encoders, three axes, through the CLI: about 50,000 clocks, a minute "
                         "of CPU; the Verilator run above checks the same report by default")
def test_a_3d_run_with_encoders_on_the_myhdl_card_measures_every_axis(tmp_path):
    (tmp_path / "short.ngc").write_text("G21 G90 G17 G91.1\nG1 X0.2 Y0.1 Z-0.1 F6000\n"
                                        "G3 X0.2 Y0.1 Z-0.2 I-0.1 J0\nG1 X0.1 Y0.05 Z-0.05\nM2\n")
    # no --machine: a motor on every axis of the card, as Motor() has them (4 counts a step)
    result = run_host("run", tmp_path / "short.ngc", "--card", "myhdl", "--encoders", "--axes", "3",
                      "--steps-per-mm", "40", "--acceleration", "2000000", "--start-feed", "60000",
                      "--feed-override", "10000", "--rapid", "600000")
    assert result.returncode == 0, result.stdout + result.stderr
    out = result.stdout
    assert re.search(r"^pins end:\s+\(4, 2, -2\) steps", out, re.M), out
    assert re.search(r"^counts end: exact: the pins' \(4, 2, -2\) steps x counts per step = \(16, 8, -8\)", out, re.M)
    assert figure(out, "encoders", r"counts \((-?\d+, -?\d+, -?\d+)\) \(ENC_COUNT\)") == ("16, 8, -8",)
    per_axis = _per_axis(out)
    assert len(per_axis) == 3 and all(0 < apart <= 1.0 for apart in per_axis), out
