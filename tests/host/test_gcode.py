"""G-code front end: every supported word and mode, every refusal with its line.

Golden values are geometry worked out by hand from the program text (RS274NGC
/ LinuxCNC semantics), not from the parser.
"""
import math

import pytest

from host.errors import ProgramError
from host.gcode import parse
from host.geometry import Arc, Dwell, Line


def only(program):
    """The primitives of ``program``, without the leading rapid many tests use."""
    return parse(program, "t.ngc")


def close(a, b, tol=1e-9):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def test_rapid_and_feed_lines_absolute():
    drawing = only("G0 X10 Y5\nG1 X20 F300\nY15\n")
    assert drawing == [Line((0.0, 0.0), (10.0, 5.0), None, "t.ngc:1"),
                       Line((10.0, 5.0), (20.0, 5.0), 300.0, "t.ngc:2"),
                       Line((20.0, 5.0), (20.0, 15.0), 300.0, "t.ngc:3")]


def test_incremental_and_back_to_absolute():
    drawing = only("G91 G0 X10 Y5\nX1 Y1\nG90 X0 Y0\n")
    assert [d.end for d in drawing] == [(10.0, 5.0), (11.0, 6.0), (0.0, 0.0)]


def test_inches_convert_to_mm_including_feed():
    drawing = only("G20 G1 X1 Y0.5 F10\nG21 X1\n")
    assert close(drawing[0].end, (25.4, 12.7)) and drawing[0].feed == pytest.approx(254.0)
    assert close(drawing[1].end, (1.0, 12.7))


@pytest.mark.parametrize("program, ccw", [("G3", True), ("G2", False)])
def test_centre_format_quarter_arcs_both_directions(program, ccw):
    end = (0.0, 10.0) if ccw else (0.0, -10.0)
    drawing = only(f"G0 X10 Y0\n{program} X{end[0]} Y{end[1]} I-10 J0 F100\n")
    arc = drawing[1]
    assert isinstance(arc, Arc) and arc.ccw == ccw
    assert close(arc.centre, (0.0, 0.0)) and arc.sweep == pytest.approx(math.pi / 2)


def test_absolute_arc_centre_g90_1_and_back_g91_1():
    drawing = only("G0 X10 Y0\nG90.1 G3 X0 Y10 I0 J0 F100\nG91.1 G3 X-10 Y0 I0 J-10\n")
    assert close(drawing[1].centre, (0.0, 0.0))
    assert close(drawing[2].centre, (0.0, 0.0))


def test_g90_1_needs_both_i_and_j():
    with pytest.raises(ProgramError, match=r"t\.ngc:2: .*both I and J"):
        only("G0 X10\nG90.1 G3 X0 Y10 I0 F100\n")


@pytest.mark.parametrize("words, ccw, centre, sweep", [
    ("G3 X0 Y10 R10", True, (0.0, 0.0), math.pi / 2),         # short way, counter-clockwise
    ("G3 X0 Y10 R-10", True, (10.0, 10.0), 3 * math.pi / 2),  # long way
    ("G2 X0 Y10 R10", False, (10.0, 10.0), math.pi / 2),      # short way, clockwise
    ("G2 X0 Y10 R-10", False, (0.0, 0.0), 3 * math.pi / 2),
])
def test_radius_format_picks_the_centre_by_sign_and_direction(words, ccw, centre, sweep):
    arc = only(f"G0 X10 Y0\n{words} F100\n")[1]
    assert arc.ccw == ccw and close(arc.centre, centre, 1e-9)
    assert arc.sweep == pytest.approx(sweep)


def test_full_circle_with_i_j():
    arc = only("G0 X10 Y0\nG2 X10 Y0 I-10 J0 F100\n")[1]
    assert arc.full_circle and arc.sweep == pytest.approx(2 * math.pi)


def test_dwell_comments_line_numbers_and_program_end():
    drawing = only("%\nN10 G0 X1 (to the start) Y1 ; rapid\n\nG4 P1.5\n(only a comment)\nM2\nG0 X5\n%\n")
    assert drawing == [Line((0.0, 0.0), (1.0, 1.0), None, "t.ngc:2"), Dwell(1.5, "t.ngc:4")]


def test_m30_ends_too_and_g17_is_accepted():
    assert len(only("G17 G0 X1\nM30\nG0 X2\n")) == 1


def test_feed_is_modal_and_lowercase_is_read():
    drawing = only("g1 x1 f120\ng1 x2\n")
    assert [d.feed for d in drawing] == [120.0, 120.0]


@pytest.mark.parametrize("start_radius, difference, accepted", [
    (1.0, 0.0049, True),     # within 0.005 mm
    (1.0, 0.0051, False),    # over 0.005 mm and over 0.1 % (0.001 mm)
    (10.0, 0.0099, True),    # over 0.005 mm but within 0.1 % (0.01 mm)
    (10.0, 0.0101, False),
    (400.0, 0.399, True),    # 0.1 % of 400 mm is 0.4 mm
    (600.0, 0.499, True),    # within 0.1 % and within 0.5 mm
    (600.0, 0.501, False),   # within 0.1 % (0.6 mm) but over 0.5 mm
])
def test_linuxcnc_radius_mismatch_rule(start_radius, difference, accepted):
    r = start_radius
    program = f"G0 X{r}\nG3 X0 Y{r + difference:.4f} I{-r} J0 F100\n"
    if accepted:
        assert only(program)[1].end_radius == pytest.approx(r + difference)
    else:
        with pytest.raises(ProgramError, match=r"^t\.ngc:2: arc start radius"):
            only(program)


@pytest.mark.parametrize("program, line, message", [
    ("G18 G1 F10\nG2 X1 Z1 J1\n", 2, "J is not an offset of the G18 plane"),
    ("G1 F10\nG3 X1 Y1 I1 P1.5\n", 2, "whole number"),
    ("G1 X1\n", 1, "needs a feed"),
    ("X1\n", 1, "no motion mode"),
    ("G0 X1\nG1 X2 F0\n", 2, "must be positive"),
    ("G0 X1 Q2\n", 1, "word Q2 is not supported"),
    ("G0 X1 U2\n", 1, "axis U"),
    ("G28\n", 1, "G28 is not supported"),
    ("M3\n", 1, "M3 is not supported"),
    ("G0 X1 X2\n", 1, "X appears twice"),
    ("G0 G1 X1 F1\n", 1, "two motion codes"),
    ("G0 X1 @\n", 1, "cannot read '@'"),
    ("G0 X\n", 1, "word X has no number"),
    ("G0 X1 (open\n", 1, "not closed"),
    ("G0 X1 )\n", 1, "without a '('"),
    ("G4\n", 1, "G4 needs P"),
    ("G4 P-1\n", 1, "cannot be negative"),
    ("G4 P1 X1\n", 1, "cannot share a line"),
    ("G0 X1 P1\n", 1, "P without G4"),
    ("G0 X1 I1\n", 1, "only with G2 or G3"),
    ("G1 F10\nG2 X1\n", 2, "needs I/J"),
    ("G1 F10\nG2 X1 R1 I1\n", 2, "R or I/J, not both"),
    ("G1 F10\nG2 R5\n", 2, "needs an end point"),
    ("G0 X1\nG2 X1 Y0 R5 F10\n", 2, "cannot be a full circle"),
    ("G1 F10\nG2 X10 R4\n", 2, "shorter than half the chord"),
    ("G1 F10\nG2 X10 R0\n", 2, "R0 is not an arc"),
    ("G0 X1\nG2 X1 Y0 I0 J0 F10\n", 2, "radius is zero"),
    ("G0 X10\nG3 X0 Y11 I-10 J0 F10\n", 2, "differ by 1.0000 mm"),
])
def test_errors_name_their_line(program, line, message):
    with pytest.raises(ProgramError) as error:
        only(program)
    assert error.value.where == f"t.ngc:{line}"
    assert message in error.value.message
    assert str(error.value).startswith(f"t.ngc:{line}: ")
