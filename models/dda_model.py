"""Golden model of the DDA interpolator (``rtl/dda_arc.py``), in plain Python.

Two levels:

* ``iterate(command)`` runs the interpolation one iteration at a time and
  returns the ``Path`` (the step of every iteration), from the checks and
  set-up of ``models/dda_plan.py`` (``plan_arc``).  ``metrics(path)``
  (``models/dda_measure.py``) measures it (V_arc of the paper's eq. 12, radial
  errors, sawteeth, ...).
* ``ClockedDda`` (``models/dda_clocked.py``) adds the clock: start / setup / run
  / done, the ``advance`` enable and the registered outputs, exactly as the
  hardware does them; the benches compare it with the RTL on every clock.

This module also offers the names of ``models/dda_plan.py`` and
``models/dda_measure.py``, so ``from models.dda_model import ...`` finds them all.

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
from dataclasses import dataclass, field

from models.dda_build import (ALL_VARIANTS, IMPROVED, PRECISE, TRADITIONAL, VARIANT_NAMES, WEIGHTED,  # noqa: F401
                              accumulator_width)
from models.dda_measure import (PAPER_ARC, PAPER_V_ARC, Metrics, count_sawteeth, metrics,  # noqa: F401
                                paper_configuration, radial_errors, v_arc)
from models.dda_plan import (ArcCommand, ArcPlan, LineCommand, arc_threshold, axis_directions,  # noqa: F401
                             check_width, error_term_width, nearest_root, plan_arc, setup_clocks, wrap, x_is_inward)


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
            check_width(getattr(command, name), coord_width, name)
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
    return run_to_end(iterator, Path(start), max_iterations or 1 << (coord_width + 12))


def run_to_end(iterator, path, limit):
    """Append ``iterator``'s steps to ``path.steps`` until it finishes; ``path``.
    RuntimeError after ``limit`` iterations without an end."""
    while not iterator.finished:
        if len(path.steps) >= limit:
            raise RuntimeError(f"no end after {limit} iterations")
        path.steps.append(iterator.step())
    return path
