"""More axes on the host: G17/G18/G19, helices, 3-D lines, the A axis, refusals with their
line, the commands and feeds the planner gives them, and the path the model makes of them.

Golden values are worked out by hand from the program text (RS274/NGC and
LinuxCNC: G18 is the ZX plane seen from +Y, G19 the YZ plane seen from +X,
I/J/K are offsets along X/Y/Z, P counts turns, G20 scales linear axes only,
F runs along X, Y, Z, or in degrees per minute for rotary axes alone), the
bit positions of docs/axes.md, and the two-axis DDA model.
"""
import math
import re
import subprocess
import sys

import pytest

from host.check import check
from host.errors import ProgramError
from host.gcode import parse
from host.geometry import Arc, Line
from host.machine import Machine
from host.planner import plan
from models.commands import decode_words
from models.dda_axes import iterate_axes
from models.dda_model import iterate
from models.dda_plan import ArcCommand, AxesLineCommand, LineCommand
from models.registers import RATE_ONE

CLOCK = 33_000_000
ROUNDING = math.sqrt(2) / 2
# docs/axes.md: a precise helix by area is within this many steps of the ideal helix at the same angle
HELIX_PER_ANGLE = 0.75


def sweeps(command):
    """|u dv - v du| of each step of the arc of ``command`` on the two-axis model's path: twice the area
    each step sweeps about the centre (their sum is the AREA the card needs)."""
    plain = ArcCommand(command.xs, command.ys, command.xe, command.ye, command.ccw, command.variant)
    points = iterate(plain).points()
    return [abs(a[0] * (b[1] - a[1]) - a[1] * (b[0] - a[0])) for a, b in zip(points, points[1:])]


def close(a, b, tol=1e-9):
    return len(a) == len(b) and all(abs(x - y) <= tol for x, y in zip(a, b))


def test_3d_lines_and_a_rotary_axis_that_inches_do_not_scale():
    drawing = parse("G21 G1 X1 Y2 Z3 A90 F100\nG20 Z1 A180\n", "t.ngc")
    assert drawing == [Line((0.0, 0.0, 0.0, 0.0), (1.0, 2.0, 3.0, 90.0), 100.0, "t.ngc:1"),
                       Line((1.0, 2.0, 3.0, 90.0), (1.0, 2.0, 25.4, 180.0), 100.0, "t.ngc:2")]


def test_an_xy_program_keeps_two_axis_points_and_z_adds_one():
    assert parse("G0 X1 Y2\n")[0].end == (1.0, 2.0)
    assert parse("G0 X1 Y2\nG0 Z-1\n")[0].end == (1.0, 2.0, 0.0)


@pytest.mark.parametrize("program, centre, sweep", [
    # G18, seen from +Y: counter-clockwise turns +Z towards +X, so +X towards -Z; from X10 to Z10 about
    # the origin G3 goes through -Z and -X (three quarters), G2 straight up (one quarter)
    ("G0 X10\nG18 G3 X0 Z10 I-10 K0 F100\n", (0.0, 0.0), 3 * math.pi / 2),
    ("G0 X10\nG18 G2 X0 Z10 I-10 K0 F100\n", (0.0, 0.0), math.pi / 2),
    # G19, seen from +X: counter-clockwise turns +Y towards +Z: from Y10 to Z10 is one quarter
    ("G0 Y10\nG19 G3 Y0 Z10 J-10 K0 F100\n", (0.0, 0.0), math.pi / 2),
    ("G0 Y10\nG19 G2 Y0 Z10 J-10 K0 F100\n", (0.0, 0.0), 3 * math.pi / 2),
    # radius format, the short way: G18 G2 from X10 to Z10 is the quarter about the origin
    ("G0 X10\nG18 G2 X0 Z10 R10 F100\n", (0.0, 0.0), math.pi / 2),
    ("G0 X10\nG18 G3 X0 Z10 R10 F100\n", (10.0, 10.0), math.pi / 2),  # centre (Z, X) = (10, 10)
])
def test_g18_and_g19_arcs_turn_as_rs274ngc_defines(program, centre, sweep):
    arc = parse(program, "t.ngc")[1]
    assert isinstance(arc, Arc) and arc.plane == ((2, 0) if "G18" in program else (1, 2))
    assert close(arc.centre, centre) and arc.sweep == pytest.approx(sweep)


def test_the_plane_is_modal_until_g17():
    drawing = parse("G0 X10\nG18 G2 X0 Z10 I-10 K0 F100\nG2 X10 Z0 I0 K-10\nG17 G3 X0 Y10 I-10 J0\n")
    assert [a.plane for a in drawing[1:]] == [(2, 0), (2, 0), (0, 1)]


def test_p_turns_become_one_arc_per_turn_with_the_helix_shared_by_angle():
    drawing = parse("G0 X10\nG3 X0 Y10 Z-5 I-10 J0 P2 F100\n", "t.ngc")
    first, second = drawing[1:]
    # 2.5 quarter... a full turn and a quarter: 5/2 pi in all, the full turn takes 4/5 of the rise
    assert first.full_circle and first.sweep == pytest.approx(math.tau)
    assert close(first.end, (10.0, 0.0, -4.0)) and second.sweep == pytest.approx(math.pi / 2)
    assert close(second.end, (0.0, 10.0, -5.0)) and first.where == second.where == "t.ngc:2"
    three = parse("G0 X10\nG2 X10 Y0 Z-6 I-10 J0 P3 F100\n")[1:]
    assert [round(a.end[2], 9) for a in three] == [-2.0, -4.0, -6.0] and all(a.full_circle for a in three)


@pytest.mark.parametrize("program, line, message", [
    ("G1 F10\nG3 X1 Y1 K1\n", 2, "K is not an offset of the G17 plane"),
    ("G19 G1 F10\nG3 Y1 Z1 I1\n", 2, "I is not an offset of the G19 plane"),
    ("G18 G1 F10\nG3 Y1 R2\n", 2, "needs an end point (Z or X)"),
    ("G1 F10\nG3 X1 Y1 I1 P0\n", 2, "whole number, at least 1"),
    ("G0 X1 W1\n", 1, "axis W"),
])
def test_plane_words_refused_with_their_line(program, line, message):
    with pytest.raises(ProgramError) as error:
        parse(program, "t.ngc")
    assert error.value.where == f"t.ngc:{line}" and message in error.value.message


@pytest.mark.parametrize("program, axes, line, message", [
    ("G0 X1\nG1 Y2 F10\nG1 Z1\n", 2, 3, "axis Z: the card has 2 axes (X, Y)"),
    ("G0 X1\nG18 G2 X0 I-1 F10\n", 2, 2, "needs axis Z: the card has 2 axes (X, Y)"),
    ("G0 X1 Z1\nG1 A10 F10\n", 3, 2, "axis A: the card has 3 axes (X, Y, Z)"),
    ("G0 X1\nG19 G2 Y0 Z1 R1 F10\nG0 C1\n", 5, 3, "axis C: the card has 5 axes"),
])
def test_a_program_needing_more_axes_than_the_card_has_is_refused_at_its_line(program, axes, line, message):
    with pytest.raises(ProgramError) as error:
        parse(program, "t.ngc", axes)
    assert error.value.where == f"t.ngc:{line}" and message in error.value.message


def test_the_planner_refuses_a_move_on_an_axis_the_machine_lacks():
    drawing = parse("G0 X1\nG1 Y1 F10\nG1 Z2\n", "t.ngc")
    with pytest.raises(ProgramError, match=r"t\.ngc:3: axis Z: the machine has 2 axes"):
        plan(drawing, Machine())


def decoded_moves(planned):
    """The planner's words read back (the one decoder) beside their entries."""
    commands = decode_words(planned.words())
    assert len(commands) == len(planned.entries)
    return [(e, c) for e, c in zip(planned.entries, commands) if isinstance(c, (LineCommand, AxesLineCommand,
                                                                                ArcCommand))]


def model_path(planned, axes):
    """Absolute step points of every move (decoded words through the N-axis model)."""
    position, result = (0,) * axes, []
    for entry, command in decoded_moves(planned):
        path = iterate_axes(command, axes)
        origin = [p - s for p, s in zip(position, path.start)]
        points = [tuple(o + p for o, p in zip(origin, point)) for point in path.points()]
        assert points[0] == position
        position = points[-1]
        result.append((entry, command, points))
    return result


BORE = "G0 X2 Y0 Z1\nG1 Z0 F200\nG3 X2 Y0 Z-3 I-2 J0 P3 F300\nG3 X2 Y0 I-2 J0\n"


def test_a_helical_bore_plans_to_helical_arcs_that_end_on_the_drawing():
    machine = Machine(steps_per_mm=(100.0, 100.0, 100.0))
    planned = plan(parse(BORE, "bore.ngc", 3), machine)
    moves = model_path(planned, 3)
    helical = [c for _, c, _ in moves if isinstance(c, ArcCommand) and c.helix]
    assert helical and all(c.plane == (0, 1) and c.helix_axes == (2,) for c in helical)
    for command in helical:  # AREA is the area the arc sweeps
        assert command.area == sum(sweeps(command))
    assert sum(c.helix[2] for c in helical) == -300  # three turns down 3 mm, the flat turn none
    assert moves[-1][2][-1] == (200, 0, -300) == planned.end
    result = check(planned)
    # radially half a step and the rounding onto the lattice; along Z the helix's own bound
    # (docs/axes.md) and the rounding of the pieces' ends onto the lattice
    assert result.max_deviation_steps <= math.hypot(0.5 + ROUNDING, HELIX_PER_ANGLE + 0.5)


@pytest.mark.parametrize("program, header_bits", [
    # docs/axes.md: U_AXIS bits 15:13, V_AXIS bits 19:17; G18 = (Z, X), G19 = (Y, Z)
    ("G0 X10\nG18 G3 X0 Z10 I-10 K0 F100\n", (2 << 13) | (0 << 17)),
    ("G0 Y10\nG19 G3 Y0 Z10 J-10 K0 F100\n", (1 << 13) | (2 << 17)),
])
def test_g18_and_g19_arcs_carry_their_plane_in_the_header(program, header_bits):
    planned = plan(parse(program), Machine(steps_per_mm=(100.0,) * 3))
    arcs = [w for w in planned.words() if w >> 28 == 0x2]
    assert arcs and all(w & (0x3F << 13) == header_bits for w in arcs)
    ends = model_path(planned, 3)[-1][2][-1]
    assert ends == planned.end and ends == tuple(round(v * 100) for v in parse(program)[-1].end)


def rate_units(iterations_per_second):
    return round(iterations_per_second / CLOCK * RATE_ONE)


def feed_rates(planned):
    return [e.command.value for e in planned.entries if getattr(e.command, "register", "") == "FEED_RATE"]


def test_f_runs_along_the_3d_line():
    # 3-4-12: 13 mm along the path; the major axis Z steps 2,400 times, one an iteration
    planned = plan(parse("G1 X3 Y4 Z12 F6000\n"), Machine(steps_per_mm=(200.0,) * 3))
    assert feed_rates(planned) == [rate_units(6000 / 60 / 13 * 2400)]


def test_f_runs_along_the_helix():
    # one turn of radius 10 mm rising 20 mm: the plane's 62.8 mm of 66.0 mm along the helix; the arc
    # runs about one step of its plane's length an iteration
    planned = plan(parse("G0 X10\nG3 X10 Y0 Z20 I-10 J0 F3000\n"), Machine(steps_per_mm=(100.0,) * 3))
    plane = math.tau * 10
    wanted = rate_units(3000 / 60 * plane / math.hypot(plane, 20) * 100)
    assert feed_rates(planned)[-1] in (wanted, wanted + 1, wanted - 1)


@pytest.mark.parametrize("program, iterations_per_second", [
    ("G1 A90 F36000\n", 36000 / 60 * 10),      # A alone: degrees per minute; 10 steps a degree
    ("G1 X10 A90 F600\n", 600 / 60 * 200),     # X with A: F along X, 200 steps a mm on X, the major axis
])
def test_a_rotary_axis_feed(program, iterations_per_second):
    planned = plan(parse(program), Machine(steps_per_mm=(200.0, 200.0, 200.0, 10.0)))
    assert feed_rates(planned) == [rate_units(iterations_per_second)]
    (_, command, points), = model_path(planned, 4)
    assert points[-1] == tuple(planned.end)


def test_an_xy_program_plans_the_same_words_for_every_card():
    program = "G0 X10 Y5\nG1 X20 F300\nG2 X30 Y5 I5 J0\nG3 X20 Y5 R5\nG4 P0.5\nG0 X0 Y0\n"
    words = plan(parse(program), Machine()).words()
    for axes in range(3, 7):
        assert plan(parse(program), Machine(steps_per_mm=(200.0,) * axes)).words() == words


@pytest.mark.parametrize("rise_mm", [20, 5])
def test_a_helix_steeper_than_the_card_steps_becomes_3d_lines(rise_mm):
    # radius 1 mm, 20 mm up in one turn: the Z axis would need more steps than the arc has iterations;
    # 5 mm: 1,000 steps, fewer than its 1,264 iterations but more than W / max w = 888 allows (|h| max w > W)
    machine = Machine(steps_per_mm=(200.0,) * 3)
    planned = plan(parse(f"G0 X1\nG3 X1 Y0 Z{rise_mm} I-1 J0 F300\n"), machine)
    moves = model_path(planned, 3)
    helical = [c for _, c, _ in moves if isinstance(c, ArcCommand) and c.helix]
    # the card's at-most-one-step rule, from the path's own sweeps: |h| times the largest sweep <= W
    for command in helical:
        swept = sweeps(command)
        assert max(map(abs, command.helix)) * max(swept) <= command.area == sum(swept)
    assert len(helical) < len(moves)
    assert moves[-1][2][-1] == (200, 0, 200 * rise_mm)
    # the chords' sagitta, half a step of the DDA and the rounding of their ends onto the lattice
    assert check(planned).max_deviation_mm <= machine.chord_tolerance + (0.5 + math.sqrt(3) / 2) / 200


def run_host(*args):
    from rtl.convert import ROOT
    return subprocess.run([sys.executable, "-m", "host", *map(str, args)], cwd=ROOT, capture_output=True,
                          text=True, timeout=1800)


def one_error_line(result):
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, result.stderr
    return lines[0]


def test_plan_for_a_three_axis_card_and_the_refusal_on_the_default_one(tmp_path):
    mill, words = tmp_path / "mill.ngc", tmp_path / "words.txt"
    mill.write_text("G0 X1 Y1\nG1 Z-1 F100\nG18 G2 X3 Z-1 I1 K0\nG17 G3 X3 Y1 Z-2 I-1 J0\nG0 Z0\n")
    result = run_host("plan", mill, "--axes", "3", "--words", words)
    assert result.returncode == 0, result.stderr
    assert re.search(r"^steps:\s+X \d+, Y \d+, Z \d+;", result.stdout, re.M)
    assert any(int(w, 16) >> 20 & 0x3F for w in words.read_text().split() if int(w, 16) >> 28 in (1, 2))
    words.unlink()
    refused = run_host("plan", mill, "--words", words)  # the default card: two axes
    assert refused.returncode != 0 and not words.exists()
    assert re.fullmatch(r"python -m host: error: mill\.ngc:2: axis Z: the card has 2 axes \(X, Y\)",
                        one_error_line(refused))
    bad = run_host("plan", mill, "--axes", "3", "--steps-per-mm", "200,200")
    assert bad.returncode == 2 and "2 values for 3 axes" in one_error_line(bad)


def test_run_refuses_a_helix_the_card_lacks_an_axis_for_before_anything_moves(tmp_path):
    from rtl.convert import ROOT
    mill = ROOT / "examples" / "mill.ngc"
    refused = run_host("run", mill, "--card", "verilator")  # the simulated two-axis card reports its axes
    assert refused.returncode == 1 and "streamed:" not in refused.stdout
    assert re.fullmatch(r"python -m host: error: mill\.ngc:\d+: axis Z: the card has 2 axes \(X, Y\)",
                        one_error_line(refused))
    # a helix on a card of two axes: its Z, at its line (the XY moves before it would run)
    bore = tmp_path / "bore.ngc"
    bore.write_text("G21 G90 G17\nG0 X2 Y1\nG1 X3 F300\nG3 X3 Y1 Z-1 I-0.5 J0\nM2\n")
    two = run_host("plan", bore)
    assert two.returncode != 0
    assert re.fullmatch(r"python -m host: error: bore\.ngc:4: axis Z: the card has 2 axes \(X, Y\)",
                        one_error_line(two))
    # a helix moving an axis the card lacks (A on a plan for three axes), at its line
    bore.write_text("G21 G90 G17\nG0 X2 Y1\nG3 X2 Y1 Z-1 A30 I-0.5 J0 F300\nM2\n")
    three = run_host("plan", bore, "--axes", "3")
    assert three.returncode != 0
    assert re.fullmatch(r"python -m host: error: bore\.ngc:3: axis A: the card has 3 axes \(X, Y, Z\)",
                        one_error_line(three))


@pytest.mark.slow(reason="the whole mill part (3-D lines, a helical bore, G18/G19 grooves) on the 3-axis Verilator "
                         "card through the CLI: 37 million clocks, minutes; the card's helices against the golden "
                         "path run by default in sim/card/test_card_e2e_axes.py and test_card_axes.py")
def test_the_mill_part_with_its_helical_bore_runs_on_the_three_axis_verilator_card():
    from rtl.convert import ROOT
    # fifty times the part's feeds and 50 steps/mm: about a second of card time (the path is the same)
    result = run_host("run", ROOT / "examples" / "mill.ngc", "--card", "verilator", "--axes", "3",
                      "--steps-per-mm", "50", "--feed-override", "5000", "--acceleration", "50000")
    assert result.returncode == 0, result.stdout + result.stderr
    assert re.search(r"^pins end:\s+\(0, 0, 250\) steps", result.stdout, re.M), result.stdout
    pins = re.search(r"^pins:\s+(\d+) STEP rises; the path is the golden model's; max deviation \S+ mm = (\S+) steps",
                     result.stdout, re.M)
    assert pins, result.stdout
    # docs/axes.md: lines within half a step per axis, arcs within one step, the bore's helix (a gentle one,
    # 1 mm a turn of 25 mm) within one step of the ideal (0.660 steps measured, at the bore's line)
    assert float(pins.group(2)) < 1.0


# 3-D lines and G18/G19 arcs, short and fast: a fraction of a second of card time
PART_3D = """G21 G90 G17 G91.1
G0 X1 Y1 Z0.5
G1 X2 Y1.5 Z-0.2 F3000
G1 X2 Y2 Z-0.4
G18 G2 X3 Z-0.4 I0.5 K0
G19 G3 Y3 Z-0.4 J0.5 K0
G17 G1 X1 Y1 Z0
M2
"""


@pytest.mark.slow(reason="a whole part on the 3-axis Verilator card through the CLI, about 30 s; the card's pins "
                         "against the golden path for 3-D lines and G18/G19 arcs run by default in "
                         "sim/card/test_card_e2e_axes.py and test_card_axes.py")
def test_a_3d_program_runs_on_the_three_axis_verilator_card_to_its_end_points(tmp_path):
    part = tmp_path / "part.ngc"
    part.write_text(PART_3D)
    result = run_host("run", part, "--card", "verilator", "--axes", "3", "--steps-per-mm", "100",
                      "--acceleration", "5000", "--rapid", "6000")
    assert result.returncode == 0, result.stdout + result.stderr
    # the end: X and Y from POS_X/POS_Y, every axis from the pins; the pins follow the golden model exactly
    assert re.search(r"^position:\s+\(100, 100\) steps \(POS_X, POS_Y\) \(plan: \(100, 100, 0\)\)", result.stdout, re.M)
    assert re.search(r"^pins end:\s+\(100, 100, 0\) steps", result.stdout, re.M)
    pins = re.search(r"^pins:\s+(\d+) STEP rises; the path is the golden model's; max deviation \S+ mm = (\S+) steps",
                     result.stdout, re.M)
    assert pins, result.stdout
    # docs/axes.md: every axis of a line within half a step of the ideal at the same parameter (the two
    # minor axes of a 3-D line: 0.5 * sqrt(2) from it), an arc as on the two-axis card (within one step)
    assert int(pins.group(1)) > 300 and float(pins.group(2)) < 1.0


def test_the_preview_of_a_3d_drawing_has_the_projections_and_a_3d_view(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    from matplotlib import figure

    from host.preview import draw
    planned = plan(parse("G0 X1 Y0 Z1\nG3 X1 Y0 Z0 I-1 J0 F300\nG18 G2 X3 Z0 I1 K0\n"),
                   Machine(steps_per_mm=(50.0,) * 3))
    saved = []
    monkeypatch.setattr(figure.Figure, "savefig", lambda self, path, **_: saved.append(
        [(a.get_xlabel(), a.get_ylabel(), a.name) for a in self.axes]))
    draw(planned, check(planned), tmp_path / "p.png")
    assert saved == [[("X (mm)", "Y (mm)", "rectilinear"), ("X (mm)", "Z (mm)", "rectilinear"),
                      ("Y (mm)", "Z (mm)", "rectilinear"), ("X (mm)", "Y (mm)", "3d")]]
