"""Golden model of the DDA's moves over N axes (docs/axes.md), in plain Python.

* ``Follower``: axes moving by given displacements over a given number of
  iterations, by the line rule: threshold T, every accumulator loaded with
  ``T // 2``, integrand ``|d_i|``; axis i steps in an iteration when
  ``acc_i + |d_i| >= T`` and it has steps left (then ``acc_i -= T``).  After
  k iterations axis i is at ``floor((T // 2 + k |d_i|) / T)`` steps from its
  start, within half a step of ``k d_i / T``, and at ``|d_i|`` after T.
* The N-axis line: a ``Follower`` with ``T = max_i |d_i|`` (the major axis
  steps every iteration; all axes end on iteration T).  On X and Y alone it
  steps exactly as the two-axis ``LineIterator``.
* The helix: the arc runs in its plane with the two-axis arc DDA
  (``ArcIterator``, every variant, unchanged); the HELIX axes are an
  ``AreaFollower`` (``models/helix_area.py``) over the arc's AREA W (the
  area it sweeps, ``arc_area``), stepped in the same iterations as the arc:
  within half a step of the area swept, within one step of the ideal helix
  at the same angle.
* ``MoveIterator``: one iteration of any move (``LineCommand``,
  ``AxesLineCommand``, ``ArcCommand`` with plane and helix) as a step and a
  direction per axis (``AxesStep``); ``iterate_axes`` runs a move to its end.
  A move ends when the arc (if any) and every axis have ended, so a wrong
  AREA still ends every axis on its end point (the helix then leads or lags
  the arc).

``check_move`` holds the card's RANGE rules of the N-axis form
(``check_pulse`` those of a PULSE's axes); the iterators apply it, and ``plan_arc`` (``models/dda_plan.py``) the arc's own.
``iterations_left_bound`` (``models/dda_model.py``) bounds the iterations a
``MoveIterator`` has left: the largest count of steps an axis has left.
"""
from dataclasses import dataclass, field, replace

from models.axes import AXIS_NAMES, MAX_AXES, XY, names
from models.dda_build import ALL_VARIANTS
from models.dda_model import ArcIterator, iterations_left_bound, run_to_end  # noqa: F401
from models.dda_plan import ArcCommand, AxesLineCommand, LineCommand, check_width
from models.helix_area import AreaFollower, arc_area, area_increment, area_width


@dataclass(frozen=True)
class AxesStep:
    """One iteration's output: a step and a direction (1: positive) per axis.
    An axis that does not step reports the direction it would take (1 when it
    does not move at all); the pins keep theirs until it steps."""
    steps: tuple
    dirs: tuple


class Follower:
    """Axes moving by ``deltas`` (steps, indexed by axis) in ``threshold`` iterations: the line rule."""

    def __init__(self, deltas, threshold):
        self.deltas = tuple(deltas)
        self.threshold = threshold
        self.acc = [threshold // 2] * len(self.deltas)
        self.left = [abs(d) for d in self.deltas]
        self.dirs = tuple(d >= 0 for d in self.deltas)

    @property
    def finished(self):
        return not any(self.left)

    def step(self):
        """One iteration: the tuple of steps (bool per axis)."""
        steps = []
        for axis, delta in enumerate(self.deltas):
            total = self.acc[axis] + abs(delta)
            stepping = total >= self.threshold and self.left[axis] > 0
            self.acc[axis] = total - self.threshold * stepping
            self.left[axis] -= stepping
            steps.append(stepping)
        return tuple(steps)


def _padded(values, axes):
    values = tuple(values)
    return values + (0,) * (axes - len(values))


def _moving(values):
    return tuple(axis for axis, value in enumerate(values) if value)


def needed_axes(command):
    """The number of axes a card needs for ``command``: one past its highest axis, at least 2."""
    if isinstance(command, LineCommand):
        return 2
    if isinstance(command, AxesLineCommand):
        return max((2,) + tuple(axis + 1 for axis in _moving(command.deltas)))
    # a card of two axes turns arcs in X, Y only (its area, docs/axes.md): (Y, X) needs three
    reversed_xy = 3 if tuple(command.plane) == XY[::-1] else 2
    return max((reversed_xy,) + tuple(axis + 1 for axis in command.plane + _moving(command.helix)))


def check_move(command, axes=MAX_AXES, coord_width=24):
    """``command`` if a card with ``axes`` axes and ``coord_width``-bit
    coordinates takes it (the RANGE rules of docs/axes.md); ValueError else."""
    if isinstance(command, LineCommand):
        deltas = command.deltas
    elif isinstance(command, AxesLineCommand):
        deltas = command.deltas
    elif isinstance(command, ArcCommand):
        _check_arc_axes(command, axes, coord_width)
        return command
    else:
        raise ValueError(f"not a DDA move: {command!r}")
    _check_axes(deltas, axes, "LINE")
    for axis, delta in enumerate(deltas):
        check_width(delta, coord_width, f"D{AXIS_NAMES[axis]}")
    return command


def check_pulse(counts, axes=MAX_AXES):
    """The counts of a PULSE (by axis, ``models.commands.PulseCommand.counts``) if a card
    with ``axes`` axes takes them: every axis with a count is one of the card's, whatever
    the mask, on two axes as on more (RANGE, docs/axes.md); ValueError else."""
    _check_axes(counts, axes, "PULSE")
    return counts


def _check_axes(values, axes, what):
    if len(values) > MAX_AXES:
        raise ValueError(f"{what}: {len(values)} axes given, there are at most {MAX_AXES}")
    beyond = [axis for axis in _moving(values) if axis >= axes]
    if beyond:
        raise ValueError(f"{what}: axis {names(beyond)} is not on a card with {axes} axes ({names(range(axes))})")


def _check_arc_axes(command, axes, coord_width):
    u, v = command.plane
    if u == v or not (0 <= u < axes and 0 <= v < axes):
        raise ValueError(f"ARC: plane {command.plane} is not two different axes of the card's {axes}")
    if axes == 2 and (u, v) != XY:
        raise ValueError(f"ARC: plane {command.plane}: a card of two axes turns arcs in X, Y only")
    _check_axes(command.helix, axes, "ARC helix")
    helix = _moving(command.helix)
    if u in helix or v in helix:
        raise ValueError(f"ARC: a helix axis ({names(helix)}) is an axis of the plane ({names((u, v))})")
    for axis in helix:
        check_width(command.helix[axis], coord_width, f"D{AXIS_NAMES[axis]}")
    largest = (1 << area_width(coord_width)) - 1
    if helix and not (isinstance(command.area, int) and 1 <= command.area <= largest):
        raise ValueError(f"ARC: a helix needs its AREA, 1..{largest}, not {command.area!r}")


class MoveIterator:
    """Iterations of any move on a card with ``axes`` axes (default: as many as it needs)."""

    def __init__(self, command, axes=None, coord_width=24, variants=ALL_VARIANTS, **options):
        self.command = command
        self.axes = needed_axes(command) if axes is None else axes
        check_move(command, self.axes, coord_width)
        self.arc = None
        self.plane = XY
        if isinstance(command, ArcCommand):
            self.arc = ArcIterator(command, coord_width, variants=variants, **options)
            self.plane = command.plane
            deltas = _padded(command.helix, self.axes)
            self.follower = AreaFollower(deltas, command.area or 0, coord_width)
        else:
            if options:
                raise ValueError(f"options {sorted(options)} apply to arcs only")
            deltas = _padded(command.deltas, self.axes)
            self.follower = Follower(deltas, max(abs(d) for d in deltas))

    @property
    def finished(self):
        return (self.arc is None or self.arc.finished) and self.follower.finished

    @property
    def quadrant(self):
        return 0 if self.arc is None else self.arc.quadrant

    def step(self):
        """One iteration; its ``AxesStep``."""
        if self.finished:
            raise RuntimeError("move already finished")
        arc_step = swept = None
        if self.arc is not None and not self.arc.finished:
            u_before, v_before = self.arc.x, self.arc.y
            arc_step = self.arc.step()
            swept = area_increment(u_before, v_before, arc_step.step_x, arc_step.step_y)
        if self.follower.finished:
            steps = [False] * self.axes
        elif self.arc is not None:
            steps = list(self.follower.step(swept or 0, arc_step is not None))
        else:
            steps = list(self.follower.step())
        dirs = list(self.follower.dirs)
        if arc_step is not None:
            u, v = self.plane
            steps[u], steps[v] = arc_step.step_x, arc_step.step_y
            dirs[u], dirs[v] = arc_step.dir_x, arc_step.dir_y
        return AxesStep(tuple(steps), tuple(dirs))

    def steps_left(self):
        """The steps each axis still makes (a tuple indexed by axis)."""
        left = list(self.follower.left)
        if self.arc is not None:
            u, v = self.plane
            left[u], left[v] = self.arc.steps_left()
        return tuple(left)


def with_area(command, coord_width=24, variants=ALL_VARIANTS):
    """``command`` with its AREA set to W when it has a helix (as the card needs it)."""
    if not command.helix_axes:
        return command
    return replace(command, area=arc_area(command, coord_width, variants).total)


@dataclass
class AxesPath:
    """Every iteration of a move over N axes and the points it visits."""
    start: tuple
    steps: list = field(default_factory=list)

    def points(self):
        """The start point and the point after each iteration that steps an axis."""
        here = list(self.start)
        result = [tuple(here)]
        for step in self.steps:
            if any(step.steps):
                for axis, stepping in enumerate(step.steps):
                    here[axis] += (1 if step.dirs[axis] else -1) * stepping
                result.append(tuple(here))
        return result

    def positions(self):
        """The point after every iteration (stepping or not), the start first."""
        here = list(self.start)
        result = [tuple(here)]
        for step in self.steps:
            for axis, stepping in enumerate(step.steps):
                here[axis] += (1 if step.dirs[axis] else -1) * stepping
            result.append(tuple(here))
        return result

    @property
    def end(self):
        return self.points()[-1]


def move_start(command, axes):
    """Where a move starts in its own coordinates: an arc's start relative to its
    centre on the plane's axes (0 elsewhere), a line at the origin."""
    start = [0] * axes
    if isinstance(command, ArcCommand):
        u, v = command.plane
        start[u], start[v] = command.xs, command.ys
    return tuple(start)


def iterate_axes(command, axes=None, coord_width=24, max_iterations=None, **options):
    """Run ``command`` to its end on a card with ``axes`` axes; its ``AxesPath``
    (``options``: ``MoveIterator``'s)."""
    iterator = MoveIterator(command, axes, coord_width, **options)
    return run_to_end(iterator, AxesPath(move_start(command, iterator.axes)), max_iterations or 1 << (coord_width + 12))
