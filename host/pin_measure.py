"""What came out of the STEP/DIR pins of a simulated card, measured.

* ``pin_moves(plan, check, rises)``: the pins' path cut into the plan's
  moves (each move's share of STEP rises is its count in the golden model,
  ``host.check``), so that each point is measured against the primitive
  its move came from;
* ``deviation(plan, moves)``: the largest distance of a pin point from its
  primitive (mm, steps);
* ``junction_gaps(plan, check, rises)``: the starvation measure.  At every
  junction inside a blended run (a move with BLEND followed by the next
  move) the interval between the last STEP rise of the move and the first of
  the next must not exceed the longest of the three intervals before it in
  the run plus DIR_SETUP: the rate never falls inside a blended run
  (docs/instructions.md: it only ramps up towards FEED_RATE; the decrease
  comes in the run's last move), and a step after a direction change waits
  for the set-up time, so a longer interval is a stall at the boundary,
  e.g. a FIFO that ran empty.  Junctions with no interval before them in
  the run are not measured.  With a constant rate (RAMP_STEP 0) and
  LINEs only, every interval of the run is also at most
  ``ceil(65536 / FEED_RATE)`` clocks plus DIR_SETUP (a step after a
  direction change waits for the set-up time): ``period_violations``.
"""
import math

from models.dda_model import ArcCommand, LineCommand
from models.registers import RATE_ONE

TAIL = 3  # intervals before a junction that give the run's step period there


def pin_points(rises, start=(0, 0), polarity=(0, 0)):
    """Points after each rise ((clock, sx, sy, dir x, dir y) tuples), from ``start``."""
    x, y = start
    points = [(x, y)]
    for _, sx, sy, dx, dy in rises:
        x += (1 if dx != polarity[0] else -1) * sx
        y += (1 if dy != polarity[1] else -1) * sy
        points.append((x, y))
    return points


def move_rises(check):
    """STEP rises per move, from the golden model's points (``host.check.Check``)."""
    return [len(points) - 1 for _, points in check.points]


def pin_moves(plan, check, rises):
    """[(primitive index, [(x, y) ...])] per move, from the pins (``rises`` of the job only)."""
    return pin_moves_of_points(check, pin_points(rises))


def pin_moves_of_points(check, points):
    """[(primitive index, [point ...])] per move, from the points the pins visited (the
    job's start first, then one a clock with a STEP rise; any number of axes)."""
    moves, first = [], 0
    for (primitive, _), count in zip(check.points, move_rises(check)):
        moves.append((primitive, points[first:first + count + 1]))
        first += count
    return moves


def deviation(plan, moves):
    """(mm, steps, where) of the pin point furthest from its primitive."""
    machine = plan.machine
    worst, where = 0.0, ""
    for primitive, points in moves:
        ideal = plan.drawing[primitive]
        for point in points:
            distance = ideal.distance(machine.mm(point))
            if distance > worst:
                worst, where = distance, ideal.where
    return worst, worst * max(machine.steps_per_mm), where


def _moves(plan):
    return [e for e in plan.entries if isinstance(e.command, (LineCommand, ArcCommand))]


def junction_gaps(plan, check, rises, dir_setup=1):
    """(junctions measured, [(clock, interval, allowed, where)] of those over the bound);
    ``rises``: one tuple a clock with a STEP rise, its clock first."""
    clocks = [r[0] for r in rises]
    entries = _moves(plan)
    measured, over = 0, []
    first = run_first = 0
    for number, (entry, count) in enumerate(zip(entries, move_rises(check))):
        if number == 0 or entries[number - 1].run != entry.run:
            run_first = first
        last = first + count - 1
        if entry.command.blend and number + 1 < len(entries) and last > run_first and last + 1 < len(clocks):
            before = [clocks[i + 1] - clocks[i] for i in range(max(run_first, last - TAIL), last)]
            allowed = max(before) + dir_setup
            interval = clocks[last + 1] - clocks[last]
            measured += 1
            if interval > allowed:
                over.append((clocks[last], interval, allowed, entry.where))
        first += count
    return measured, over


def period_violations(rises, feed_rate, dir_setup=1):
    """Intervals between consecutive rises longer than one iteration at
    ``feed_rate`` plus ``dir_setup`` clocks: [(clock, interval)]."""
    period = math.ceil(RATE_ONE / feed_rate) + dir_setup
    clocks = [r[0] for r in rises]
    return [(a, b - a) for a, b in zip(clocks, clocks[1:]) if b - a > period]
