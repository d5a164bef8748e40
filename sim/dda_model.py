"""Golden model of the DDA interpolator (``rtl/dda_arc.py``), in plain Python.

Two levels:

* ``iterate(command)`` runs the interpolation one iteration at a time and
  returns the ``Path`` (the step of every iteration).  ``metrics(path)``
  measures it (V_arc of the paper's eq. 12, radial errors, sawteeth, ...).
* ``DdaMachine`` adds the clock: start / setup / run / done, the ``advance``
  enable and the registered outputs, exactly as the hardware does them; the
  benches compare it with the RTL on every clock.

Reading of the paper's section 4 (all variants work on the magnitudes of the
coordinates; the quadrant decides the signs, see ``docs/dda.md``):

* Per axis an accumulator ``A`` and a threshold ``T``.  The X axis integrates
  ``|y|``, the Y axis ``|x|``.  A weighting factor lambda = 2**-k is applied
  to the accumulation (the printed eq. 10/11 leave it out of the accumulate
  line: a typo) by raising the threshold instead: ``T = 2**(n + k)``.
* traditional (eq. 8): accumulators loaded with T/2 (eq. 7); Y is updated
  first and X integrates the new ``|y|``; overflow when ``A + i >= T`` (the
  carry out of an n-bit register); the excess is kept (``A - T``).
* weighted (eq. 10): accumulators loaded with 0; both axes use the old
  coordinates; overflow when ``A + i > T`` (strict, as printed); ``A - T``.
* improved (eq. 11): as weighted, and when exactly one axis overflows while
  the other would overflow on the next iteration (``A + 2i > T``), the other
  steps too, in advance: its accumulator goes negative (the sign bit).
* precise (the project's default): the accumulators are the time base only
  (``T`` = radius + 1, so the feed rate is the same for every radius); when
  either overflows a step is due, and the step taken is the one of X, Y or
  diagonal whose end point is closest to the circle, judged by the radial
  error term ``E = x**2 + y**2 - r**2`` kept up to date with additions
  (``(x +- 1)**2 = x**2 +- 2x + 1``).  The accumulator of each axis that steps
  loses ``T``.

End points: the arc is cut at the axis crossings into quadrant pieces; each
axis has a step counter loaded with its steps in the piece and stops when it
reaches zero; the other axis then steps on every iteration until it also
reaches zero (so an arc always ends exactly on its end point and never hangs
on a zero integrand).  On an axis crossing the outward coordinate is ``Rq``,
the integer whose square is nearest to ``xs**2 + ys**2``.
"""
import math
from dataclasses import dataclass, field

from rtl.dda_build import (ALL_VARIANTS, IMPROVED, MAX_THRESHOLD_EXTRA, PRECISE, TRADITIONAL,  # noqa: F401
                           VARIANT_NAMES, WEIGHTED, accumulator_width, left_width)

ERROR_EXTRA_BITS = 6   # radial error term width beyond coord_width


def error_term_width(coord_width):
    return coord_width + ERROR_EXTRA_BITS


def setup_clocks(coord_width, line):
    """Clocks from the ``start`` edge to the first edge that may hand the move to the run.

    A line: the latch and one clock for its threshold.  An arc: the latch, 7
    clocks of magnitude compares, the four squares (coord_width clocks each,
    the square root running beside the last two), 5 clocks for the end-point
    limits and 13 for the rounded radius, the inward-end test and the two
    step totals, all on one adder.
    """
    return 2 if line else 4 * coord_width + 26


def wrap(value, width):
    """Two's-complement wrap of ``value`` to ``width`` bits (a modbv)."""
    half = 1 << (width - 1)
    return ((value + half) % (1 << width)) - half


def nearest_root(square):
    """The integer whose square is nearest to ``square`` (ties go down)."""
    root = math.isqrt(square)
    return root + (square - root * root > root)


def departure_quadrant(x, y, ccw):
    """Quadrant 0..3 (I..IV) a point leaves when moving in direction ``ccw``.

    A point on an axis belongs to the quadrant the motion enters, e.g.
    (R, 0) is in I when counter-clockwise and in IV when clockwise.
    """
    if ccw:
        if x > 0 and y >= 0:
            return 0
        if x <= 0 and y > 0:
            return 1
        if x < 0 and y <= 0:
            return 2
        return 3
    if x >= 0 and y > 0:
        return 0
    if x < 0 and y >= 0:
        return 1
    if x <= 0 and y < 0:
        return 2
    return 3


def arrival_quadrant(x, y, ccw):
    """Quadrant a point is reached from: the departure quadrant backwards."""
    return departure_quadrant(x, y, not ccw)


def x_is_inward(quadrant, ccw):
    """True when |x| decreases in ``quadrant`` (I and III counter-clockwise)."""
    return (quadrant % 2 == 0) == ccw


def axis_directions(quadrant, ccw):
    """(dir_x, dir_y), 1 for a positive step, for an arc in ``quadrant``."""
    x_inward = x_is_inward(quadrant, ccw)
    x_right = quadrant in (0, 3)
    y_up = quadrant in (0, 1)
    return x_right != x_inward, y_up != (not x_inward)


@dataclass(frozen=True)
class ArcCommand:
    """An arc about the origin from (xs, ys) to (xe, ye); start == end is a full circle.

    ``acc_bits`` is the paper's accumulator width n (0: normalised, n = the
    bit length of the radius); ``lambda_shift`` is k, lambda = 2**-k.  Both
    only matter for the paper's variants.
    """
    xs: int
    ys: int
    xe: int
    ye: int
    ccw: bool = True
    variant: int = PRECISE
    lambda_shift: int = 0
    acc_bits: int = 0
    blend: bool = False


@dataclass(frozen=True)
class LineCommand:
    """A straight move by (dx, dy) from the current position.

    ``blend`` (both commands): the path goes on into the next move at speed, so
    the hardware's ``stop_left`` does not count down for this move.
    """
    dx: int
    dy: int
    blend: bool = False


@dataclass(frozen=True)
class ArcPlan:
    """What the hardware's setup computes from an ``ArcCommand``."""
    radius: int          # Rq
    r_squared: int       # xs**2 + ys**2
    threshold: int
    acc_init: int
    quadrant: int
    crossings: int       # quadrant pieces after the first one
    first_counts: tuple  # (x, y) steps of the first piece
    last_counts: tuple   # (x, y) steps of the last piece (if crossings > 0)


def _check_width(value, width, name):
    if not -(1 << (width - 1)) <= value < (1 << (width - 1)):
        raise ValueError(f"{name} = {value} does not fit {width}-bit signed coordinates")


def _in_out(x, y, quadrant, ccw):
    """(inward magnitude, outward magnitude) of a point in ``quadrant``."""
    if x_is_inward(quadrant, ccw):
        return abs(x), abs(y)
    return abs(y), abs(x)


def _xy(inward, outward, quadrant, ccw):
    """Per-axis (x, y) order of an (inward, outward) pair."""
    if x_is_inward(quadrant, ccw):
        return inward, outward
    return outward, inward


def arc_threshold(command, radius, coord_width):
    """Accumulator threshold T and initial load for ``command``'s variant."""
    if command.variant == PRECISE:
        threshold = radius + 1
        return threshold, threshold // 2
    if not 0 <= command.lambda_shift < 32 or not 0 <= command.acc_bits < 32:
        raise ValueError("acc_bits and lambda_shift must be in 0..31")
    n = command.acc_bits or radius.bit_length()
    if n + command.lambda_shift > coord_width + MAX_THRESHOLD_EXTRA:
        raise ValueError(f"acc_bits + lambda_shift = {n + command.lambda_shift} exceeds "
                         f"{coord_width + MAX_THRESHOLD_EXTRA} for {coord_width}-bit coordinates")
    threshold = 1 << (n + command.lambda_shift)
    return threshold, threshold // 2 if command.variant == TRADITIONAL else 0


def plan_arc(command, coord_width=24, variants=ALL_VARIANTS):
    """Check ``command`` as the hardware does and compute its setup; ValueError if rejected.

    ``variants``: the variants the card was built with (the model knows all four)."""
    if command.variant not in VARIANT_NAMES:
        raise ValueError(f"variant must be 0..3, not {command.variant}")
    if command.variant not in variants:
        raise ValueError(f"variant {VARIANT_NAMES[command.variant]} is not built into this card")
    xs, ys, xe, ye, ccw = command.xs, command.ys, command.xe, command.ye, command.ccw
    for name in ("xs", "ys", "xe", "ye"):
        _check_width(getattr(command, name), coord_width, name)
    r_squared = xs * xs + ys * ys
    if r_squared == 0:
        raise ValueError("arc start point is the centre")
    if xe == 0 and ye == 0:
        raise ValueError("arc end point is the centre")
    radius = nearest_root(r_squared)
    if radius >= 1 << (coord_width - 1):
        raise ValueError(f"radius {radius} too large for {coord_width}-bit coordinates")
    # |re - rs| <= 1 is guaranteed by -(2m - 1) <= re**2 - rs**2 <= 2m + 1 with m <= rs
    m = max(abs(xs), abs(ys))
    difference = xe * xe + ye * ye - r_squared
    if not -(2 * m - 1) <= difference <= 2 * m + 1:
        raise ValueError("arc end point is not within one step of the start radius")
    threshold, acc_init = arc_threshold(command, radius, coord_width)
    quadrant = departure_quadrant(xs, ys, ccw)
    end_quadrant = arrival_quadrant(xe, ye, ccw)
    crossings = (end_quadrant - quadrant) % 4 if ccw else (quadrant - end_quadrant) % 4
    a_s, b_s = _in_out(xs, ys, quadrant, ccw)
    a_e, b_e = _in_out(xe, ye, end_quadrant, ccw)
    if crossings == 0:
        ahead = a_e <= a_s and b_e >= b_s and (xs, ys) != (xe, ye)
        if ahead:
            first = _xy(a_s - a_e, b_e - b_s, quadrant, ccw)
            return ArcPlan(radius, r_squared, threshold, acc_init, quadrant, 0, first, (0, 0))
        crossings = 4
    if a_e > radius:
        raise ValueError("arc end point lies beyond the radius reached on the last axis crossing")
    first = _xy(a_s, radius - b_s, quadrant, ccw)
    last = _xy(radius - a_e, b_e, end_quadrant, ccw)
    return ArcPlan(radius, r_squared, threshold, acc_init, quadrant, crossings, first, last)


@dataclass(frozen=True)
class Step:
    """One iteration's output."""
    step_x: bool
    step_y: bool
    dir_x: bool
    dir_y: bool


class ArcIterator:
    """Iterations of an arc; ``step()`` performs one, ``finished`` says when to stop.

    ``initial_load`` (None: the variant's own; "half" or "zero") and
    ``end_rule`` ("counters", as the hardware; "reach": run until each
    coordinate has reached or passed its end value, without per-axis stops,
    as the paper's eq. 9 reads for the weighted and improved figures; one
    quadrant only) exist in the model only, to reproduce the paper's table.
    """

    def __init__(self, command, coord_width=24, initial_load=None, end_rule="counters",
                 variants=ALL_VARIANTS):
        self.command = command
        self.coord_width = coord_width
        plan = plan_arc(command, coord_width, variants)
        self.plan = plan
        self.threshold = plan.threshold
        load = {None: plan.acc_init, "half": plan.threshold // 2, "zero": 0}
        if initial_load not in load:
            raise ValueError(f"initial_load must be 'half' or 'zero', not {initial_load!r}")
        if end_rule not in ("counters", "reach"):
            raise ValueError(f"end_rule must be 'counters' or 'reach', not {end_rule!r}")
        if end_rule == "reach" and plan.crossings:
            raise ValueError("end_rule 'reach' handles arcs inside one quadrant only")
        self.reach = end_rule == "reach"
        self.acc_x = self.acc_y = load[initial_load]
        # the hardware holds A - bias (bias T, or T + 1 for a strict compare) so that an
        # overflow is a sign bit; it saturates that register at its maximum (the precise
        # mode never reaches it: ``_accumulate`` checks), and nothing may go below its minimum
        self.bias = plan.threshold + (command.variant in (WEIGHTED, IMPROVED))
        half = 1 << (accumulator_width(coord_width, variants) - 1)
        self.acc_max = half - 1 + self.bias
        self.acc_min = self.bias - half
        self.error_width = error_term_width(coord_width)
        self.x, self.y = command.xs, command.ys
        self.error_term = 0
        self.quadrant = plan.quadrant
        self.pieces_left = plan.crossings
        self.count_x, self.count_y = plan.first_counts
        self.finished = self._reached() if self.reach else False

    def _reached(self):
        dir_x, dir_y = axis_directions(self.quadrant, self.command.ccw)
        done_x = self.x <= self.command.xe if not dir_x else self.x >= self.command.xe
        done_y = self.y <= self.command.ye if not dir_y else self.y >= self.command.ye
        return done_x and done_y

    def _accumulate(self, acc, integrand):
        if acc + integrand > self.acc_max and self.command.variant == PRECISE:
            raise RuntimeError("precise accumulator beyond its register range")
        return min(acc + integrand, self.acc_max)

    def _keep(self, acc_x, acc_y):
        if min(acc_x, acc_y) < self.acc_min:
            raise RuntimeError("accumulator below its register range")
        self.acc_x, self.acc_y = acc_x, acc_y

    def _paper_overflows(self, mag_x, mag_y, x_inward):
        """(step_x, step_y, new acc_x, new acc_y) of the paper's variants."""
        variant, threshold = self.command.variant, self.threshold
        if variant == TRADITIONAL:
            sum_y = self._accumulate(self.acc_y, mag_x)
            over_y = sum_y >= threshold
            new_mag_y = mag_y + (over_y if x_inward else -over_y)
            sum_x = self._accumulate(self.acc_x, new_mag_y)
            over_x = sum_x >= threshold
        else:
            sum_x = self._accumulate(self.acc_x, mag_y)
            sum_y = self._accumulate(self.acc_y, mag_x)
            over_x, over_y = sum_x > threshold, sum_y > threshold
            if variant == IMPROVED:
                next_x, next_y = sum_x + mag_y > threshold, sum_y + mag_x > threshold
                if over_x and not over_y and next_y:
                    over_y = True
                elif over_y and not over_x and next_x:
                    over_x = True
        return over_x, over_y, sum_x - threshold * over_x, sum_y - threshold * over_y

    def _precise_choice(self, delta_x, delta_y):
        """X, Y or diagonal, whichever ends closest to the circle (ties: D, X, Y)."""
        error, width = self.error_term, self.error_width
        # the hardware compares the signs of sums of two candidates (docs/dda.md), in
        # coord_width + 4 bits: they must fit
        limit = 1 << (self.coord_width + 3)
        if max(abs(2 * error + delta_x + delta_y + d) for d in (delta_x, delta_y)) >= limit:
            raise RuntimeError("radial error term beyond the hardware's range")
        candidates = ((abs(wrap(error + delta_x + delta_y, width)), True, True),
                      (abs(wrap(error + delta_x, width)), True, False),
                      (abs(wrap(error + delta_y, width)), False, True))
        best = min(candidates, key=lambda c: c[0])
        return best[1], best[2]

    def _precise_overflows(self, mag_x, mag_y, delta_x, delta_y):
        threshold = self.threshold
        sum_x = self._accumulate(self.acc_x, mag_y)
        sum_y = self._accumulate(self.acc_y, mag_x)
        if sum_x >= threshold or sum_y >= threshold:
            step_x, step_y = self._precise_choice(delta_x, delta_y)
        else:
            step_x = step_y = False
        return step_x, step_y, sum_x - threshold * step_x, sum_y - threshold * step_y

    def step(self):
        """One iteration; returns its ``Step``."""
        if self.finished:
            raise RuntimeError("arc already finished")
        ccw = self.command.ccw
        x_inward = x_is_inward(self.quadrant, ccw)
        dir_x, dir_y = axis_directions(self.quadrant, ccw)
        mag_x, mag_y = abs(self.x), abs(self.y)
        delta_x = 1 - 2 * mag_x if x_inward else 1 + 2 * mag_x
        delta_y = 1 + 2 * mag_y if x_inward else 1 - 2 * mag_y
        tail = not self.reach and (self.count_x == 0 or self.count_y == 0)
        if tail:
            step_x, step_y = self.count_x != 0, self.count_y != 0
        else:
            if self.command.variant == PRECISE:
                step_x, step_y, acc_x, acc_y = self._precise_overflows(mag_x, mag_y, delta_x, delta_y)
            else:
                step_x, step_y, acc_x, acc_y = self._paper_overflows(mag_x, mag_y, x_inward)
            self._keep(acc_x, acc_y)
        self.error_term = wrap(self.error_term + delta_x * step_x + delta_y * step_y,
                               self.error_width)
        self.x += (1 if dir_x else -1) * step_x
        self.y += (1 if dir_y else -1) * step_y
        if self.reach:
            self.finished = self._reached()
        else:
            self._count(step_x, step_y)
        return Step(step_x, step_y, dir_x, dir_y)

    def _count(self, step_x, step_y):
        self.count_x -= step_x
        self.count_y -= step_y
        if self.count_x or self.count_y:
            return
        if self.pieces_left == 0:
            self.finished = True
            return
        self.quadrant = (self.quadrant + (1 if self.command.ccw else -1)) % 4
        self.pieces_left -= 1
        radius = self.plan.radius
        self.count_x, self.count_y = self.plan.last_counts if self.pieces_left == 0 else (radius, radius)

    def steps_left(self):
        """(x, y): the steps each axis still makes, over all remaining quadrant pieces."""
        x, y = self.count_x, self.count_y
        if self.pieces_left:
            middle = (self.pieces_left - 1) * self.plan.radius
            x += middle + self.plan.last_counts[0]
            y += middle + self.plan.last_counts[1]
        return x, y


class LineIterator:
    """Iterations of a line: Bresenham-like DDA normalised to the major axis.

    Threshold ``T = max(|dx|, |dy|)``, accumulators loaded with ``T // 2``,
    integrands ``|dx|`` and ``|dy|``: the major axis steps on every iteration,
    the minor one evenly spaced; exactly |dx| and |dy| steps.  A line reports
    quadrant 0.
    """

    def __init__(self, command, coord_width=24):
        for name in ("dx", "dy"):
            _check_width(getattr(command, name), coord_width, name)
        self.command = command
        self.threshold = max(abs(command.dx), abs(command.dy))
        self.acc_x = self.acc_y = self.threshold // 2
        self.count_x, self.count_y = abs(command.dx), abs(command.dy)
        self.dir_x, self.dir_y = command.dx >= 0, command.dy >= 0
        self.quadrant = 0
        self.x = self.y = 0
        self.finished = self.threshold == 0

    def step(self):
        if self.finished:
            raise RuntimeError("line already finished")
        threshold = self.threshold
        sum_x = self.acc_x + abs(self.command.dx)
        sum_y = self.acc_y + abs(self.command.dy)
        step_x = sum_x >= threshold and self.count_x > 0
        step_y = sum_y >= threshold and self.count_y > 0
        self.acc_x = sum_x - threshold * step_x
        self.acc_y = sum_y - threshold * step_y
        self.count_x -= step_x
        self.count_y -= step_y
        self.x += (1 if self.dir_x else -1) * step_x
        self.y += (1 if self.dir_y else -1) * step_y
        self.finished = self.count_x == 0 and self.count_y == 0
        return Step(step_x, step_y, self.dir_x, self.dir_y)

    def steps_left(self):
        """(x, y): the steps each axis still makes."""
        return self.count_x, self.count_y


def iterations_left_bound(iterator):
    """A lower bound of the iterations ``iterator`` still runs: an iteration steps
    each axis at most once, so at least the larger of the axes' remaining steps."""
    return max(iterator.steps_left())


def iterator_for(command, coord_width=24, variants=ALL_VARIANTS, **options):
    if isinstance(command, LineCommand):
        if options:
            raise ValueError(f"options {sorted(options)} apply to arcs only")
        return LineIterator(command, coord_width)
    if isinstance(command, ArcCommand):
        return ArcIterator(command, coord_width, variants=variants, **options)
    raise ValueError(f"not a DDA command: {command!r}")


@dataclass
class Path:
    """Every iteration of a move and the points it visits."""
    start: tuple
    steps: list = field(default_factory=list)

    def points(self):
        """Start point and the point after each output step (a diagonal is one step)."""
        x, y = self.start
        result = [(x, y)]
        for step in self.steps:
            if step.step_x or step.step_y:
                x += (1 if step.dir_x else -1) * step.step_x
                y += (1 if step.dir_y else -1) * step.step_y
                result.append((x, y))
        return result

    @property
    def end(self):
        return self.points()[-1]


def iterate(command, coord_width=24, max_iterations=None, **options):
    """Run ``command`` to its end; the ``Path``.  ValueError if rejected."""
    iterator = iterator_for(command, coord_width, **options)
    start = (command.xs, command.ys) if isinstance(command, ArcCommand) else (0, 0)
    path = Path(start)
    limit = max_iterations or 1 << (coord_width + 12)
    while not iterator.finished:
        if len(path.steps) >= limit:
            raise RuntimeError(f"no end after {limit} iterations")
        path.steps.append(iterator.step())
    return path


@dataclass(frozen=True)
class Metrics:
    v_arc: float           # eq. 12 over the start point and every step point
    max_radial_error: float
    rms_radial_error: float
    sawteeth: int          # X step then Y step (or Y then X) where a diagonal would do
    iterations: int
    output_steps: int
    diagonal_steps: int
    interval_min: int      # iterations between successive output steps
    interval_max: int
    interval_cv: float     # their standard deviation / mean (feed-rate uniformity)


def count_sawteeth(steps):
    """Adjacent single-axis output steps on different axes."""
    kinds = [(s.step_x, s.step_y) for s in steps if s.step_x or s.step_y]
    return sum(1 for a, b in zip(kinds, kinds[1:])
               if a in ((True, False), (False, True)) and b in ((True, False), (False, True)) and a != b)


def radial_errors(points, radius):
    return [math.hypot(x, y) - radius for x, y in points]


def v_arc(points, radius):
    """The paper's eq. 12: sum of squared radial errors over (m - 1), m points."""
    if len(points) < 2:
        raise ValueError("V_arc needs at least two points")
    return sum(e * e for e in radial_errors(points, radius)) / (len(points) - 1)


def metrics(path, radius=None):
    """``Metrics`` of an arc ``path``; ``radius`` defaults to the start radius."""
    points = path.points()
    if radius is None:
        radius = math.hypot(*path.start)
    errors = radial_errors(points, radius)
    moves = [i for i, s in enumerate(path.steps) if s.step_x or s.step_y]
    intervals = [b - a for a, b in zip(moves, moves[1:])] or [0]
    mean = sum(intervals) / len(intervals)
    spread = math.sqrt(sum((i - mean) ** 2 for i in intervals) / len(intervals))
    return Metrics(
        v_arc=v_arc(points, radius),
        max_radial_error=max(abs(e) for e in errors),
        rms_radial_error=math.sqrt(sum(e * e for e in errors) / len(errors)),
        sawteeth=count_sawteeth(path.steps),
        iterations=len(path.steps),
        output_steps=len(moves),
        diagonal_steps=sum(1 for s in path.steps if s.step_x and s.step_y),
        interval_min=min(intervals),
        interval_max=max(intervals),
        interval_cv=spread / mean if mean else 0.0,
    )


# The paper's figures 6, 7 and 10: quarter arc (100, 0) -> (0, 100), CCW, step 1.
PAPER_ARC = dict(xs=100, ys=0, xe=0, ye=100, ccw=True)
PAPER_V_ARC = {TRADITIONAL: 15.6304, WEIGHTED: 0.4223, IMPROVED: 0.4051}


def paper_configuration(variant):
    """(command, model options) that reproduce the paper's V_arc for ``variant``."""
    if variant == TRADITIONAL:
        return ArcCommand(**PAPER_ARC, variant=TRADITIONAL, acc_bits=6), {}
    if variant in (WEIGHTED, IMPROVED):
        return ArcCommand(**PAPER_ARC, variant=variant, acc_bits=7, lambda_shift=3), {"end_rule": "reach"}
    raise ValueError(f"the paper has no figure for variant {variant}")


class DdaMachine:
    """Clock-level model of ``rtl/dda_arc.py``: call ``clock()`` once per rising edge.

    ``clock(start, advance, command)`` takes the inputs sampled at the edge
    (``command``: the ``ArcCommand``/``LineCommand`` on the cmd lines, read
    when ``start`` is taken) and returns the registered outputs after it.

    Two stages, as in the hardware.  The setup stage takes a ``start`` while
    it is free (``ready``), counts the setup clocks and then offers the
    checked move.  An iteration takes two clocks: at the edge of its
    ``advance`` it makes its step outputs (and ``done`` with the last one);
    at the next edge it is applied (``quadrant`` follows then) and an
    ``advance`` there is ignored.  The run takes the offered move at an edge
    where it is idle or applies its running move's last iteration, so the
    next ``advance`` already iterates the new move.  A rejected move
    (``error``) or a line of length 0 (``done``) is handed over at the same
    edges only.  ``stop_left`` after an edge is, for the running move as the
    last applied iteration (or the handover) up to that edge left it,
    ``iterations_left_bound`` minus one (not below 0): in the second clock of
    an iteration it still counts the iteration under way, so the minus one
    keeps it a lower bound at every clock; the all-ones value while no move
    runs or the running one blends.  ``busy`` falls with the last ``done``.
    Every started move gets a number (0, 1, ...); ``step_move``,
    ``done_move`` and ``error_move`` say which move the outputs of the last
    edge belong to.  ``variants``: those the card was built with (a command
    for another is rejected).
    """

    def __init__(self, coord_width=24, variants=ALL_VARIANTS):
        self.coord_width = coord_width
        self.variants = variants
        self.all_ones = (1 << left_width(coord_width)) - 1
        self.started = 0
        self.setup = None       # [command, number, setup clocks left]
        self.run = None         # (iterator, command, number)
        self.pending = False    # an iteration was taken at the last edge: applied at this one
        self.left = None        # (blend, bound - 1) of the running move as last applied
        self.step_move = self.done_move = self.error_move = None
        self.outputs = dict(busy=False, ready=True, done=False, error=False, step_x=False,
                            step_y=False, dir_x=False, dir_y=False, quadrant=0,
                            stop_left=self.all_ones)

    def _stop_left(self):
        if self.left is None or self.left[0]:
            return self.all_ones
        return max(self.left[1], 0)

    def _applied(self, iterator, command):
        self.left = (command.blend, iterations_left_bound(iterator) - 1)

    def clock(self, start, advance, command):
        out = self.outputs
        out.update(done=False, step_x=False, step_y=False)
        self.step_move = self.done_move = self.error_move = None
        was_running = self.run is not None
        finishing = False
        if self.pending:
            self.pending = False
            iterator, run_command, _ = self.run
            out["quadrant"] = iterator.quadrant
            self._applied(iterator, run_command)
            if iterator.finished:
                finishing = True
                self.run = None
                self.left = None
        elif was_running and advance:
            self._iterate()
            self.pending = True
        self._setup_edge(start, command, was_running, finishing)
        ending = self.pending and self.run[0].finished
        out.update(stop_left=self._stop_left(), ready=self.setup is None,
                   busy=self.setup is not None or (self.run is not None and not ending))
        return dict(out)

    def _iterate(self):
        """The first clock of an iteration of the running move: its outputs."""
        out = self.outputs
        iterator, _, number = self.run
        step = iterator.step()
        self.step_move = number
        out.update(step_x=step.step_x, step_y=step.step_y, dir_x=step.dir_x, dir_y=step.dir_y)
        if iterator.finished:
            self.done_move = number
            out["done"] = True

    def _setup_edge(self, start, command, was_running, finishing):
        out = self.outputs
        if self.setup is None:
            if start:
                out["error"] = False
                self.setup = [command, self.started, setup_clocks(self.coord_width,
                                                                  isinstance(command, LineCommand))]
                self.started += 1
            return
        if self.setup[2] > 1:
            self.setup[2] -= 1
            return
        if was_running and not finishing:
            return
        command, number, _ = self.setup
        self.setup = None
        try:
            iterator = iterator_for(command, self.coord_width, self.variants)
        except ValueError:
            self.error_move = number
            out["error"] = True
            return
        if iterator.finished:
            self.done_move = number
            out.update(done=True, quadrant=iterator.quadrant)
            return
        self.run = (iterator, command, number)
        out["quadrant"] = iterator.quadrant
        self._applied(iterator, command)
