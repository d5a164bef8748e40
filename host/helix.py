"""Arcs in any plane, and helices, onto the step lattice (docs/axes.md).

``plane_arc_commands(arc, start, end, machine)`` gives the commands of a
``geometry.Arc`` from the step position ``start`` to ``end`` (every axis):

1. the plane's part is mapped as every arc is (``host.lattice.arc_commands``,
   in the plane's (u, v) coordinates): ARC pieces, and LINE pieces where
   the lattice needs them;
2. an XY arc with nothing else moving is those commands as they are (the
   two-axis commands);
3. otherwise each piece gets the plane and the share of the axes outside it:
   their value at the piece's end is the nearest step of the ideal helix at
   the angle the plane has turned there (the last piece ends on ``end``), so
   rounding never accumulates.  An ARC piece that moves a helix axis gets
   its AREA W (``models.helix_area.arc_area``: the card moves the helix axes
   with the area the arc sweeps, so with its angle); one whose helix axis
   rises more than the card can step, |h| max w > W (``ArcArea.fits``: the
   card steps a helix axis at most once an iteration, and the arc sweeps
   at most max w in one; about 0.64 to 0.71 of the arc's iterations on the
   precise mode), becomes lines through the lattice points of the ideal
   helix, each within the chord tolerance of it; a LINE piece becomes a
   line through every axis.
"""
import math
from dataclasses import replace

from host.lattice import arc_commands, line_command, line_commands, turn
from models.axes import XY
from models.dda_axes import check_move
from models.dda_plan import ArcCommand
from models.helix_area import arc_area


def plane_arc_commands(arc, start, end, machine):
    """The commands of ``arc`` from step position ``start`` to ``end`` (tuples over every axis)."""
    u, v = arc.plane
    pieces = arc_commands(arc, (start[u], start[v]), (end[u], end[v]), machine.steps_per_mm[u],
                          machine.coord_width)
    elsewhere = [axis for axis in range(len(start)) if axis not in arc.plane]
    if arc.plane == XY and all(start[axis] == end[axis] for axis in elsewhere):
        return pieces
    centre = (arc.centre[0] * machine.steps_per_mm[u], arc.centre[1] * machine.steps_per_mm[u])
    commands, here, turned, fraction = [], tuple(start), 0.0, 0.0
    for number, piece in enumerate(pieces):
        plane_step = _plane_deltas(piece)
        turned += _piece_turn(piece, (here[u] - centre[0], here[v] - centre[1]), plane_step, arc.ccw)
        reached = 1.0 if number + 1 == len(pieces) else min(turned / arc.sweep, 1.0)
        target = list(end) if number + 1 == len(pieces) else list(machine.steps(arc.point(reached)))
        target[u], target[v] = here[u] + plane_step[0], here[v] + plane_step[1]
        commands += _piece_commands(arc, piece, here, tuple(target), (fraction, reached), machine)
        here, fraction = tuple(target), reached
    return commands


def _plane_deltas(piece):
    if isinstance(piece, ArcCommand):
        return piece.xe - piece.xs, piece.ye - piece.ys
    return piece.dx, piece.dy


def _piece_turn(piece, offset, plane_step, ccw):
    """The angle a piece turns about the arc's centre (``offset``: its start from there)."""
    if isinstance(piece, ArcCommand):
        return turn(piece, ccw)
    before = math.atan2(offset[1], offset[0])
    after = math.atan2(offset[1] + plane_step[1], offset[0] + plane_step[0])
    return math.remainder(after - before, math.tau) * (1 if ccw else -1)


def _piece_commands(arc, piece, here, target, fractions, machine):
    """The commands of one plane piece from ``here`` to ``target`` with the helix's share."""
    u, v = arc.plane
    deltas = [b - a for a, b in zip(here, target)]
    if isinstance(piece, ArcCommand):
        helix = [0 if axis in arc.plane else d for axis, d in enumerate(deltas)]
        command = replace(piece, plane=arc.plane, helix=tuple(helix) if any(helix) else ())
        if any(helix):
            swept = arc_area(command, machine.coord_width)
            if not swept.fits(max(map(abs, helix))):   # steeper than the card steps: lines along the ideal helix
                return _helix_chords(arc, here, target, fractions, machine)
            command = replace(command, area=swept.total)
        return [check_move(command, machine.axes, machine.coord_width)]
    return [line_command(deltas)] if any(deltas) else []


def _helix_chords(arc, here, target, fractions, machine):
    """Lines from ``here`` to ``target`` through lattice points of the ideal helix
    between ``fractions`` of the arc's angle, each within the chord tolerance of it."""
    radius = max(arc.start_radius, arc.end_radius)
    chord = 2 * math.acos(max(-1.0, 1 - machine.chord_tolerance / radius)) if radius > 0 else math.tau
    parts = max(1, math.ceil((fractions[1] - fractions[0]) * arc.sweep / chord))
    points = [here] + [machine.steps(arc.point(fractions[0] + (fractions[1] - fractions[0]) * i / parts))
                       for i in range(1, parts)] + [target]
    return [c for a, b in zip(points, points[1:]) for c in line_commands(a, b, machine.coord_limit)]
