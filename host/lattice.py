"""Moves onto the step lattice: LINE and ARC commands the card's DDA accepts.

Every command starts where the one before ended (an integer step position)
and ends exactly on the rounded end point of its primitive, so rounding
never accumulates.  An ARC is given relative to its centre, so the centre is
an integer point too; the card accepts it when the end lies within one step
of the start radius (``models.dda_model.plan_arc``, the card's rule, decides).

``arc_commands`` maps a circular arc or a LinuxCNC spiral:

1. the centre: of the integer points within two steps of the ideal centre,
   the one with the least offset from it plus radius mismatch at the ends
   (the most the lattice arc can stray from the ideal one);
2. a spiral whose radius changes by more than ``RADIUS_STEP`` is cut into
   equal angles, each changing the radius by at most that; the cuts are the
   lattice points next to the ideal ones whose distance from the centre is
   nearest the ideal radius;
3. each piece is one ARC if the card accepts it, it turns the intended way
   by about the intended angle, and the radius the card holds (its start's)
   stays within ``RADIUS_SLACK`` of the ideal curve's distance from the
   lattice centre along it (sampled); otherwise it is halved at the lattice
   point next to the ideal one of its middle angle, down to pieces of at
   most ``LINE_SPAN`` steps, which become LINEs.  So a start or end point that
   rounding put off the ideal radius is joined to the ideal curve by short
   pieces instead of moving the whole arc.

A radius beyond the coordinate width is refused; a line beyond it is cut
into equal parts.  Lines run through every axis of their points
(``AxesLineCommand`` when an axis other than X and Y moves); arcs are mapped
in their plane's (u, v) coordinates here, the planner adds the plane and the
helix (``host/helix.py``).
"""
import math

from host.errors import ProgramError
from models.dda_model import ArcCommand, LineCommand, plan_arc
from models.dda_plan import AxesLineCommand

RADIUS_STEP = 0.25  # steps: most radius change of one spiral piece
LINE_SPAN = 2          # steps: a piece this short is a LINE
SWEEP_SLACK = math.pi / 4  # a lattice piece may turn this much more or less than intended
RADIUS_SLACK = 0.5  # steps: a piece's radius may differ this much from the ideal curve's
RADIUS_SAMPLES = 8
MAX_DEPTH = 40


def line_commands(start, end, coord_limit):
    """LINEs from ``start`` to ``end`` (step positions, any number of axes), cut to fit ``coord_limit``."""
    deltas = [e - s for s, e in zip(start, end)]
    parts = max(1, -(-max(abs(d) for d in deltas) // coord_limit))
    commands, previous = [], (0,) * len(deltas)
    for i in range(1, parts + 1):
        here = tuple(_nearest(d * i / parts) for d in deltas)
        if here != previous:
            commands.append(line_command([a - b for a, b in zip(here, previous)]))
        previous = here
    return commands


def line_command(deltas):
    """A ``LineCommand`` when only X and Y move, else an ``AxesLineCommand``."""
    if any(deltas[2:]):
        return AxesLineCommand(tuple(deltas))
    return LineCommand(deltas[0], deltas[1])


def arc_commands(arc, start, end, scale, coord_width):
    """Commands for ``arc`` (a ``geometry.Arc`` in mm) in its plane, from the step
    position ``start`` to ``end`` (both (u, v)) with ``scale`` steps per mm on both axes."""
    ideal_centre = (arc.centre[0] * scale, arc.centre[1] * scale)
    start_radius, end_radius = arc.start_radius * scale, arc.end_radius * scale
    limit = (1 << (coord_width - 1)) - 2
    if max(start_radius, end_radius) + 2 > limit:
        raise ProgramError(arc.where, f"arc radius {max(arc.start_radius, arc.end_radius):g} mm is "
                                      f"{max(start_radius, end_radius):.0f} steps, beyond the "
                                      f"card's {coord_width}-bit coordinates ({limit} steps)")
    centre = _lattice_centre(ideal_centre, start, end, start_radius, end_radius)
    mapper = _ArcMapper(arc, centre, scale, coord_width)
    sweep = arc.sweep
    parts = max(1, math.ceil(abs(end_radius - start_radius) / RADIUS_STEP))
    if start == end and sweep > math.pi:
        # (nearly) a full circle: one ARC whose start is its end, else two halves
        whole = mapper.lattice_arc(start, end, 0.0, sweep)
        if whole is not None:
            return [whole]
        parts = max(parts, 2)
    commands, previous = [], start
    for i in range(1, parts + 1):
        here = end if i == parts else mapper.lattice_point(sweep * i / parts)
        commands += mapper.pieces(previous, here, sweep * (i - 1) / parts, sweep * i / parts, 0)
        previous = here
    return commands


def _nearest(value):
    return math.floor(value + 0.5)


def _lattice_centre(ideal, start, end, start_radius, end_radius):
    base = _nearest(ideal[0]), _nearest(ideal[1])

    def badness(candidate):
        # the lattice arc about ``candidate`` strays from the ideal one by at most
        # the centre's offset plus the larger radius mismatch at an end
        mismatch = max(abs(math.dist(start, candidate) - start_radius),
                       abs(math.dist(end, candidate) - end_radius))
        return mismatch + math.dist(candidate, ideal), mismatch

    candidates = [(base[0] + i, base[1] + j) for i in range(-2, 3) for j in range(-2, 3)]
    return min(candidates, key=badness)


class _ArcMapper:
    """Pieces of one arc about the integer ``centre``."""

    def __init__(self, arc, centre, scale, coord_width):
        self.arc, self.centre, self.scale, self.coord_width = arc, centre, scale, coord_width

    def lattice_point(self, angle):
        """Of the lattice points next to the ideal point at ``angle``, the one whose
        distance from the lattice centre is nearest the ideal point's."""
        x, y = self.arc.plane_point_at(angle)
        x, y = x * self.scale, y * self.scale
        radius = math.dist((x, y), self.centre)
        base = _nearest(x), _nearest(y)
        near = [(base[0] + i, base[1] + j) for i in (-1, 0, 1) for j in (-1, 0, 1)]
        return min(near, key=lambda p: (abs(math.dist(p, self.centre) - radius), math.dist(p, (x, y))))

    def lattice_arc(self, start, end, angle_from, angle_to):
        """The ARC from ``start`` to ``end`` if the card takes it, it turns by about
        the intended angle and its radius keeps near the ideal one."""
        cx, cy = self.centre
        command = ArcCommand(start[0] - cx, start[1] - cy, end[0] - cx, end[1] - cy, self.arc.ccw)
        try:
            plan_arc(command, self.coord_width)
        except ValueError:
            return None
        if abs(turn(command, self.arc.ccw) - (angle_to - angle_from)) > SWEEP_SLACK:
            return None
        return command if self.radius_error(start, angle_from, angle_to) <= RADIUS_SLACK else None

    def radius_error(self, start, angle_from, angle_to):
        """Largest difference, at ``RADIUS_SAMPLES`` angles of the piece, between the
        radius the card holds (the start's) and the ideal point's distance from the centre."""
        radius = math.dist(start, self.centre)
        worst = 0.0
        for i in range(RADIUS_SAMPLES + 1):
            x, y = self.arc.plane_point_at(angle_from + (angle_to - angle_from) * i / RADIUS_SAMPLES)
            worst = max(worst, abs(math.dist((x * self.scale, y * self.scale), self.centre) - radius))
        return worst

    def pieces(self, start, end, angle_from, angle_to, depth):
        if start == end:
            return []
        whole = self.lattice_arc(start, end, angle_from, angle_to)
        if whole is not None:
            return [whole]
        if max(abs(end[0] - start[0]), abs(end[1] - start[1])) <= LINE_SPAN or depth >= MAX_DEPTH:
            return [LineCommand(end[0] - start[0], end[1] - start[1])]
        middle_angle = (angle_from + angle_to) / 2
        middle = self.lattice_point(middle_angle)
        if middle in (start, end):
            return [LineCommand(end[0] - start[0], end[1] - start[1])]
        return (self.pieces(start, middle, angle_from, middle_angle, depth + 1)
                + self.pieces(middle, end, middle_angle, angle_to, depth + 1))


def turn(command, ccw):
    """Angle an ARC command turns through, in (0, 2 pi]."""
    if (command.xs, command.ys) == (command.xe, command.ye):
        return math.tau
    turn = math.atan2(command.ye, command.xe) - math.atan2(command.ys, command.xs)
    return (turn if ccw else -turn) % math.tau or math.tau
