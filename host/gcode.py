"""G-code front end: a program's lines -> ``geometry`` primitives in millimetres.

Supported: G0, G1, G2/G3 (centre format I/J, radius format R, negative R for
the longer arc), G4 P (seconds), G17 (G18/G19 are refused: the card has X and
Y only), G20/G21, G90/G91, G90.1/G91.1, F (units per minute), M2/M30 (the end:
lines after it are not read), N (ignored), comments.  The modal state starts
as LinuxCNC's: G17 G21 G90 G91.1, no motion mode, no feed, at (0, 0).  Every
refusal names the line (``ProgramError``).

Arcs are checked as LinuxCNC checks them: a centre-format arc is refused when
its start and end radii differ by more than 0.5 mm, or by more than 0.005 mm
and more than 0.1 % of the start radius; a radius-format arc cannot be a
full circle, and its radius must reach half the chord.
"""
import math
from dataclasses import dataclass, replace

from host.errors import ProgramError
from host.gcode_words import read_lines
from host.geometry import SAME_POINT, Arc, Dwell, Line

MM_PER_INCH = 25.4
ARC_RADIUS_LIMIT = 0.5       # mm
ARC_RADIUS_SMALL = 0.005     # mm
ARC_RADIUS_RELATIVE = 0.001  # of the radius
HALF_CHORD_SLACK = 1e-6      # mm: R may fall short of half the chord by this (rounding in the program)

GROUPS = {  # G codes in tenths -> modal group
    0: "motion", 10: "motion", 20: "motion", 30: "motion",
    170: "plane", 180: "plane", 190: "plane",
    900: "distance", 910: "distance",
    901: "arc distance", 911: "arc distance",
    200: "units", 210: "units",
    40: "dwell",
}
M_CODES = {20: "M2", 300: "M30"}
AXIS_WORDS = ("X", "Y")
ARC_WORDS = ("I", "J", "R")
KNOWN_WORDS = set("GMNFXYIJRP")
REFUSED_AXES = set("ZABCUVW")


@dataclass(frozen=True)
class State:
    motion: int = None      # 0, 10, 20, 30 (tenths), None until a motion word
    absolute: bool = True   # G90
    arc_absolute: bool = False  # G90.1
    scale: float = 1.0      # mm per program unit (G21: 1, G20: 25.4)
    feed: float = None      # mm/min
    position: tuple = (0.0, 0.0)


def parse(text, name="<program>"):
    """The primitives of G-code program ``text`` (``name`` labels errors)."""
    state, drawing = State(), []
    for where, line_words in read_lines(text, name):
        if not line_words:
            continue
        state, items, ended = _line(state, line_words, where)
        drawing += items
        if ended:
            break
    return drawing


def _line(state, line_words, where):
    """(new state, primitives, program ended) of one line."""
    codes, values = _sort_words(line_words, where)
    for code in codes.values():
        if code == 180 or code == 190:
            raise ProgramError(where, f"G{code // 10}: only the XY plane (G17) is supported")
    if "units" in codes:
        state = replace(state, scale=MM_PER_INCH if codes["units"] == 200 else 1.0)
    if "distance" in codes:
        state = replace(state, absolute=codes["distance"] == 900)
    if "arc distance" in codes:
        state = replace(state, arc_absolute=codes["arc distance"] == 901)
    if "F" in values:
        if values["F"] <= 0:
            raise ProgramError(where, f"feed F{values['F']:g} must be positive")
        state = replace(state, feed=values["F"] * state.scale)
    if "motion" in codes:
        state = replace(state, motion=codes["motion"])
    items = []
    if "dwell" in codes:
        items.append(_dwell(values, where))
    elif "P" in values:
        raise ProgramError(where, "P without G4")
    moving = any(k in values for k in AXIS_WORDS + ARC_WORDS)
    if moving and "dwell" in codes:
        raise ProgramError(where, "G4 cannot share a line with a move")
    if moving or codes.get("motion") in (20, 30):
        state, move = _move(state, values, where)
        items.append(move)
    return state, items, "M" in values


def _sort_words(line_words, where):
    """({modal group: G code}, {letter: value}) of one line; duplicates refused."""
    codes, values = {}, {}
    for word in line_words:
        letter = word.letter
        if letter == "G":
            group = GROUPS.get(word.code)
            if group is None:
                raise ProgramError(where, f"G{word.text} is not supported")
            if group in codes:
                raise ProgramError(where, f"two {group} codes on one line")
            codes[group] = word.code
        elif letter == "M":
            if word.code not in M_CODES:
                raise ProgramError(where, f"M{word.text} is not supported (M2 and M30 are)")
            values["M"] = word.code
        elif letter == "N":
            continue
        elif letter in REFUSED_AXES:
            raise ProgramError(where, f"axis {letter}: the card drives X and Y only")
        elif letter not in KNOWN_WORDS:
            raise ProgramError(where, f"word {word} is not supported")
        elif letter in values:
            raise ProgramError(where, f"{letter} appears twice")
        else:
            values[letter] = word.value
    return codes, values


def _dwell(values, where):
    if "P" not in values:
        raise ProgramError(where, "G4 needs P (seconds)")
    if values["P"] < 0:
        raise ProgramError(where, f"G4 P{values['P']:g}: a dwell cannot be negative")
    return Dwell(values["P"], where)


def _target(state, values):
    """The end point of a move in mm."""
    x, y = state.position
    point = []
    for letter, current in zip(AXIS_WORDS, (x, y)):
        if letter not in values:
            point.append(current)
        elif state.absolute:
            point.append(values[letter] * state.scale)
        else:
            point.append(current + values[letter] * state.scale)
    return tuple(point)


def _move(state, values, where):
    motion = state.motion
    if motion is None:
        raise ProgramError(where, "a move with no motion mode (G0, G1, G2 or G3) in effect")
    arc_words = [k for k in ARC_WORDS if k in values]
    if arc_words and motion in (0, 10):
        raise ProgramError(where, f"{', '.join(arc_words)} only with G2 or G3")
    if motion != 0 and state.feed is None:
        raise ProgramError(where, f"G{motion // 10} needs a feed: no F word yet")
    end = _target(state, values)
    if motion == 0:
        move = Line(state.position, end, None, where)
    elif motion == 10:
        move = Line(state.position, end, state.feed, where)
    else:
        move = _arc(state, values, end, motion == 30, where)
    return replace(state, position=end), move


def _arc(state, values, end, ccw, where):
    start, scale = state.position, state.scale
    if "R" in values:
        if "I" in values or "J" in values:
            raise ProgramError(where, "an arc takes R or I/J, not both")
        if not any(k in values for k in AXIS_WORDS):
            raise ProgramError(where, "a radius-format arc needs an end point (X or Y)")
        centre = _radius_centre(start, end, values["R"] * scale, ccw, where)
    else:
        if "I" not in values and "J" not in values:
            raise ProgramError(where, f"G{2 if not ccw else 3} needs I/J (centre) or R (radius)")
        if state.arc_absolute:
            if "I" not in values or "J" not in values:
                raise ProgramError(where, "with G90.1 the centre needs both I and J")
            centre = values["I"] * scale, values["J"] * scale
        else:
            centre = start[0] + values.get("I", 0.0) * scale, start[1] + values.get("J", 0.0) * scale
        _check_radii(start, end, centre, where)
    return Arc(start, end, centre, ccw, state.feed, where)


def _check_radii(start, end, centre, where):
    """LinuxCNC's test of a centre-format arc."""
    start_radius, end_radius = math.dist(start, centre), math.dist(end, centre)
    if start_radius < SAME_POINT:
        raise ProgramError(where, "arc radius is zero: the centre is the start point")
    difference = abs(end_radius - start_radius)
    if difference > ARC_RADIUS_LIMIT or (difference > ARC_RADIUS_SMALL
                                         and difference > ARC_RADIUS_RELATIVE * start_radius):
        raise ProgramError(where, f"arc start radius {start_radius:.4f} mm and end radius "
                                  f"{end_radius:.4f} mm differ by {difference:.4f} mm (the limit is "
                                  f"0.5 mm, or 0.005 mm and 0.1 % of the radius)")


def _radius_centre(start, end, radius, ccw, where):
    """Centre of the arc of ``radius`` (negative: the longer way round) from ``start`` to ``end``."""
    chord = math.dist(start, end)
    if chord < SAME_POINT:
        raise ProgramError(where, "a radius-format arc cannot be a full circle (use I/J)")
    if radius == 0:
        raise ProgramError(where, "R0 is not an arc")
    half = chord / 2
    if half > abs(radius) + HALF_CHORD_SLACK:
        raise ProgramError(where, f"R{abs(radius):g} mm is shorter than half the chord "
                                  f"({half:.4f} mm)")
    height = math.sqrt(max(radius * radius - half * half, 0.0))
    ux, uy = (end[0] - start[0]) / chord, (end[1] - start[1]) / chord
    side = (1 if ccw else -1) * (1 if radius > 0 else -1)
    mid = (start[0] + end[0]) / 2, (start[1] + end[1]) / 2
    return mid[0] - uy * height * side, mid[1] + ux * height * side
