"""The helix by swept area: golden model of a helix that follows the arc's angle (docs/axes.md).

The ITERATIONS rule (``models.dda_axes.Follower`` with threshold K) moves a
helix axis linearly with the arc's iterations, which are not uniform in
angle.  This rule moves it linearly with the area the arc sweeps about its
centre, which for a circle is proportional to the angle:

* On each iteration of the arc the plane's point (u, v) (centre-relative,
  before the iteration's step) sweeps ``w``: ``|v|`` when u alone steps,
  ``|u|`` when v alone steps, ``|u| + |v|`` on a diagonal step, 0 when
  neither steps (``area_increment``).  Every step of an arc goes the arc's
  way round (the quadrant sets both directions, docs/dda.md), so ``w`` is
  ``|u dv - v du|``: twice the area of the triangle (centre, point before,
  point after), whether taken with the coordinates before or after the
  step; and a diagonal step keeps ``|u| + |v|`` (one magnitude grows by 1,
  the other shrinks by 1), so the three readings of "both" agree.
* AREA ``W``: the sum of ``w`` over the arc's whole run (``arc_area``; the
  host counts it with the golden model, as it counts K today).
* Helix axis j (``AreaFollower``): an accumulator loaded with ``W // 2``;
  on each iteration of the arc it adds ``|h_j| w`` and steps when the sum
  reaches ``W`` and it has steps left (then ``-= W``).  After k iterations
  the axis is at ``floor((W // 2 + |h_j| A_k) / W)`` steps, ``A_k`` the
  area swept so far: within half a step of ``h_j A_k / W``, and on
  ``|h_j|`` when the arc ends.  A card forms ``|h_j| w`` without a
  multiplier from running products ``|h_j| |u|`` and ``|h_j| |v|`` (each
  ``+- |h_j|`` on a step of its coordinate).
* At most one step an iteration: when ``|h_j| max w <= W`` (``fits``, the
  host's rule: it counts ``max w`` with ``W``; a helix steeper than that
  becomes lines along it, as today's steeper than K) the sum stays below
  ``2 W``.  Whatever AREA says, a move ends: the accumulator saturates at its
  register's maximum (``acc_max``; a ``W`` too small makes the axis lag), and
  once the arc has ended the axes with steps left step on every iteration
  (a ``W`` too large), as the arc DDA's own end rule does.

Widths: ``|u|, |v| < 2^(c-1)`` for ``c``-bit coordinates, so ``w < 2^c`` and a
whole turn sweeps less than ``2 pi 2^(2c-2)``: ``W`` has at most
``area_width(c) = 2c + 1`` bits (two 32-bit words for c = 24; ``arc_area``
checks it), as has the accumulator.
"""
from dataclasses import dataclass, replace

from models.dda_build import ALL_VARIANTS
from models.dda_model import ArcIterator


def area_width(coord_width):
    """The bits of an arc's AREA (and of a helix axis's accumulator) for ``coord_width``-bit coordinates."""
    return 2 * coord_width + 1


def area_increment(u, v, step_u, step_v):
    """``w``: twice the area the plane's point (``u``, ``v``, before the step) sweeps in one iteration."""
    return abs(v) * step_u + abs(u) * step_v


@dataclass(frozen=True)
class ArcArea:
    """An arc's AREA ``total`` (``W``), its ``largest`` single-iteration ``w`` and its ``iterations`` K."""
    total: int
    largest: int
    iterations: int

    def fits(self, rise):
        """A helix axis rising ``rise`` steps steps at most once an iteration: ``|rise| max w <= W``."""
        return abs(rise) * self.largest <= self.total


def arc_area(command, coord_width=24, variants=ALL_VARIANTS):
    """The ``ArcArea`` of ``command``'s arc in its plane (``ArcIterator``, plane and helix aside)."""
    iterator = ArcIterator(replace(command, helix=(), iterations=None), coord_width, variants=variants)
    total = largest = iterations = 0
    while not iterator.finished:
        u, v = iterator.x, iterator.y
        step = iterator.step()
        w = area_increment(u, v, step.step_x, step.step_y)
        total, largest, iterations = total + w, max(largest, w), iterations + 1
    if total >> area_width(coord_width):
        raise RuntimeError(f"AREA {total} beyond its {area_width(coord_width)} bits")
    return ArcArea(total, largest, iterations)


class AreaFollower:
    """Helix axes moving by ``deltas`` (steps, indexed by axis) with the area an arc sweeps, AREA ``area``."""

    def __init__(self, deltas, area, coord_width=24):
        self.deltas = tuple(deltas)
        self.area = area
        self.acc_max = (1 << area_width(coord_width)) - 1
        self.acc = [area // 2] * len(self.deltas)
        self.left = [abs(d) for d in self.deltas]
        self.dirs = tuple(d >= 0 for d in self.deltas)

    @property
    def finished(self):
        return not any(self.left)

    def step(self, swept, arc_running=True):
        """One iteration in which the arc swept ``swept`` (``area_increment``): the tuple of steps.
        ``arc_running`` False: the arc has ended, every axis with steps left steps."""
        steps = []
        for axis, delta in enumerate(self.deltas):
            total = self.acc[axis] + abs(delta) * swept
            stepping = self.left[axis] > 0 and (total >= self.area or not arc_running)
            self.acc[axis] = min(total - self.area * stepping, self.acc_max) if arc_running else self.acc[axis]
            self.left[axis] -= stepping
            steps.append(stepping)
        return tuple(steps)
