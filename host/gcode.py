"""G-code front end: a program's lines -> ``geometry`` primitives in millimetres (degrees for A, B, C).

Supported: G0, G1 (X, Y, Z, A, B, C: lines through every axis named),
G2/G3 in the plane G17 (XY, offsets I and J), G18 (ZX, K and I) or G19 (YZ,
J and K) (centre format; radius format R, negative R for the longer arc; the
axes outside the plane that move make a helix; P, a whole number of turns,
P1 the default), G4 P (seconds), G20/G21 (linear axes only: A, B, C stay in
degrees), G90/G91, G90.1/G91.1, F (units per minute), M2/M30 (the end: lines
after it are not read), N (ignored), comments.  The modal state starts as
LinuxCNC's: G17 G21 G90 G91.1, no motion mode, no feed, at 0 on every axis.
Every refusal names the line (``ProgramError``); ``parse(..., axes=N)``
refuses, at its line, every word of an axis a card with N axes does not have
and every arc in a plane it cannot turn in.

The points have as many axes as the program names (``geometry``): an XY
program gives (x, y) points, exactly as a two-axis program always did.  An
arc of P turns is one ``Arc`` per turn (the card runs one ARC per turn).

Arcs are checked as LinuxCNC checks them: a centre-format arc is refused when
its start and end radii differ by more than 0.5 mm, or by more than 0.005 mm
and more than 0.1 % of the start radius; a radius-format arc cannot be a
full circle, and its radius must reach half the chord.
"""
import math
from dataclasses import dataclass, replace

from host.errors import ProgramError
from host.gcode_words import read_lines
from host.geometry import SAME_POINT, TAU, Arc, Dwell, Line
from models.axes import AXIS_NAMES, MAX_AXES, PLANES, ROTARY_NAMES, names

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
AXIS_WORDS = AXIS_NAMES
OFFSET_WORDS = ("I", "J", "K")  # centre offsets along X, Y, Z
ARC_WORDS = OFFSET_WORDS + ("R",)
KNOWN_WORDS = set("GMNFRP") | set(AXIS_WORDS) | set(OFFSET_WORDS)
REFUSED_AXES = set("UVW")


@dataclass(frozen=True)
class State:
    motion: int = None      # 0, 10, 20, 30 (tenths), None until a motion word
    absolute: bool = True   # G90
    arc_absolute: bool = False  # G90.1
    scale: float = 1.0      # mm per program unit of a linear axis (G21: 1, G20: 25.4)
    feed: float = None      # mm/min
    plane: int = 17         # G17, G18, G19
    position: tuple = (0.0,) * MAX_AXES


def parse(text, name="<program>", axes=MAX_AXES):
    """The primitives of G-code program ``text`` (``name`` labels errors) for a
    card with ``axes`` axes (X, Y, ... in order)."""
    state, drawing, used = State(), [], 2
    for where, line_words in read_lines(text, name):
        if not line_words:
            continue
        state, items, ended, needed = _line(state, line_words, where, axes)
        drawing += items
        used = max(used, needed)
        if ended:
            break
    return [_trimmed(item, used) for item in drawing]


def _trimmed(item, axes):
    """``item`` with points of ``axes`` axes (the program never named the others: they stay 0)."""
    if isinstance(item, Dwell):
        return item
    return replace(item, start=item.start[:axes], end=item.end[:axes])


def _needed(values, state, where, axes):
    """The axes this line needs (one past the highest); ProgramError past the card's ``axes``."""
    needed = [AXIS_WORDS.index(letter) + 1 for letter in AXIS_WORDS if letter in values]
    for letter in AXIS_WORDS:
        if letter in values and AXIS_WORDS.index(letter) >= axes:
            raise ProgramError(where, f"axis {letter}: the card has {axes} axes ({names(range(axes))})")
    if state.motion in (20, 30) and (any(k in values for k in AXIS_WORDS + ARC_WORDS)):
        plane = PLANES[state.plane]
        if max(plane) >= axes:
            raise ProgramError(where, f"an arc in G{state.plane} ({names(plane)}) needs axis "
                                      f"{AXIS_WORDS[max(plane)]}: the card has {axes} axes ({names(range(axes))})")
        needed.append(max(plane) + 1)
    return max(needed, default=2)


def _line(state, line_words, where, axes):
    """(new state, primitives, program ended, axes needed) of one line."""
    codes, values = _sort_words(line_words, where)
    if "plane" in codes:
        state = replace(state, plane=codes["plane"] // 10)
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
    needed = _needed(values, state, where, axes)
    items = []
    if "dwell" in codes:
        items.append(_dwell(values, where))
    elif "P" in values and state.motion not in (20, 30):
        raise ProgramError(where, "P without G4 (seconds) or G2/G3 (turns)")
    moving = any(k in values for k in AXIS_WORDS + ARC_WORDS)
    if moving and "dwell" in codes:
        raise ProgramError(where, "G4 cannot share a line with a move")
    if moving or codes.get("motion") in (20, 30):
        state, moves = _move(state, values, where)
        items += moves
    return state, items, "M" in values, needed


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
            raise ProgramError(where, f"axis {letter}: the card's axes are {', '.join(AXIS_WORDS)}")
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
    """The end point of a move in mm (degrees for A, B, C), every axis."""
    point = []
    for letter, current in zip(AXIS_WORDS, state.position):
        scale = 1.0 if letter in ROTARY_NAMES else state.scale
        if letter not in values:
            point.append(current)
        elif state.absolute:
            point.append(values[letter] * scale)
        else:
            point.append(current + values[letter] * scale)
    return tuple(point)


def _move(state, values, where):
    """(new state, primitives) of a move."""
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
        moves = [Line(state.position, end, None, where)]
    elif motion == 10:
        moves = [Line(state.position, end, state.feed, where)]
    else:
        moves = _arc(state, values, end, motion == 30, where)
    return replace(state, position=end), moves


def _arc(state, values, end, ccw, where):
    """The primitives of an arc: one per turn."""
    start, scale, plane = state.position, state.scale, PLANES[state.plane]
    u, v = plane
    offsets = OFFSET_WORDS[u], OFFSET_WORDS[v]
    stray = [k for k in OFFSET_WORDS if k in values and k not in offsets]
    if stray:
        raise ProgramError(where, f"{stray[0]} is not an offset of the G{state.plane} plane "
                                  f"({names(plane)}): use {offsets[0]} and {offsets[1]}")
    ends = (start[u], start[v]), (end[u], end[v])
    if "R" in values:
        if any(k in values for k in offsets):
            raise ProgramError(where, f"an arc takes R or {offsets[0]}/{offsets[1]}, not both")
        if not any(AXIS_WORDS[k] in values for k in plane):
            raise ProgramError(where, f"a radius-format arc needs an end point ({AXIS_WORDS[u]} or "
                                      f"{AXIS_WORDS[v]})")
        centre = _radius_centre(*ends, values["R"] * scale, ccw, where)
    else:
        if not any(k in values for k in offsets):
            raise ProgramError(where, f"G{2 if not ccw else 3} needs {offsets[0]}/{offsets[1]} (centre) "
                                      "or R (radius)")
        if state.arc_absolute:
            if not all(k in values for k in offsets):
                raise ProgramError(where, f"with G90.1 the centre needs both {offsets[0]} and {offsets[1]}")
            centre = values[offsets[0]] * scale, values[offsets[1]] * scale
        else:
            centre = (ends[0][0] + values.get(offsets[0], 0.0) * scale,
                      ends[0][1] + values.get(offsets[1], 0.0) * scale)
        _check_radii(*ends, centre, where)
    return _turns(Arc(start, end, centre, ccw, state.feed, where, plane), _turn_count(values, where))


def _turn_count(values, where):
    if "P" not in values:
        return 1
    turns = values["P"]
    if turns != int(turns) or turns < 1:
        raise ProgramError(where, f"P{turns:g}: the turns of an arc are a whole number, at least 1")
    return int(turns)


def _turns(arc, turns):
    """``arc`` with ``turns - 1`` more full turns, as one ``Arc`` per turn: the
    radius and the helix change linearly over the whole angle."""
    if turns == 1:
        return [arc]
    total = arc.sweep + TAU * (turns - 1)
    r0, r1 = arc.start_radius, arc.end_radius
    su, sv = arc.in_plane(arc.start)
    cu, cv = arc.centre
    u, v = arc.plane
    points = [arc.start]
    for turn in range(1, turns):
        fraction = TAU * turn / total
        ratio = (r0 + (r1 - r0) * fraction) / r0
        point = [s + (e - s) * fraction for s, e in zip(arc.start, arc.end)]
        point[u], point[v] = cu + (su - cu) * ratio, cv + (sv - cv) * ratio
        points.append(tuple(point))
    points.append(arc.end)
    return [replace(arc, start=a, end=b) for a, b in zip(points, points[1:])]


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
