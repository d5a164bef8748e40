"""The helix by swept area: golden model of a helix that follows the arc's angle (docs/axes.md).

The arc's iterations are not uniform in angle: a helix axis moved linearly
with them (the line rule with threshold K, the arc's iteration count: the
card's rule before AREA) strays from the helix.  This rule moves it linearly
with the area the arc sweeps about its centre, which for a circle is
proportional to the angle:

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
  host counts it with the golden model and sends it in the ARC).
* Helix axis j (``AreaFollower``), kept as the card keeps it: the
  remainder ``D`` of the way to ``W``, loaded with ``W - W // 2`` (an
  accumulator loaded with ``W // 2``); on each iteration of the arc the axis
  steps when ``|h_j| w >= D`` and it has steps left (the accumulator's sum
  reaching ``W``), and ``D`` becomes ``D - |h_j| w``, plus ``W`` if it
  stepped.  After k iterations the axis is at
  ``floor((W // 2 + |h_j| A_k) / W)`` steps, ``A_k`` the area swept so far:
  within half a step of ``h_j A_k / W``, and on ``|h_j|`` when the arc ends.
  A card forms ``|h_j| w`` without a multiplier from running products
  ``|h_j| |u|``, ``|h_j| |v|`` and their sum (each ``+- |h_j|`` on a step of
  its coordinate), and compares each with ``D`` (no adder before the
  decision).
* At most one step an iteration: when ``|h_j| max w <= W`` (``fits``, the
  host's rule: it counts ``max w`` with ``W``; a helix steeper than that
  becomes lines along it) ``D`` stays above 0.  Whatever AREA says, a move
  ends: ``D`` saturates at ``-2^area_width`` (``remainder_min``: a ``W`` too small
  makes the axis lead, stepping on every iteration until its steps are
  done), and once the arc has ended the axes with steps left step on every
  iteration (a ``W`` too large: they lag), as the arc DDA's own end rule does.

Widths: ``|u|, |v| < 2^(c-1)`` for ``c``-bit coordinates, so ``w < 2^c`` and a
whole turn sweeps less than ``2 pi 2^(2c-2)``: ``W`` has at most
``area_width(c) = 2c + 1`` bits (two 32-bit words for c = 24; ``arc_area``
checks it); ``D`` lies in ``[-2^(2c+1), W]``: ``2c + 2`` bits, signed.
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
    iterator = ArcIterator(replace(command, helix=(), area=None), coord_width, variants=variants)
    total = largest = iterations = 0
    while not iterator.finished:
        u, v = iterator.x, iterator.y
        step = iterator.step()
        w = area_increment(u, v, step.step_x, step.step_y)
        total, largest, iterations = total + w, max(largest, w), iterations + 1
    if total >> area_width(coord_width):
        raise RuntimeError(f"AREA {total} beyond its {area_width(coord_width)} bits")
    return ArcArea(total, largest, iterations)


def remainder_min(coord_width):
    """Where a helix axis's remainder ``D`` saturates: ``-2^area_width``."""
    return -(1 << area_width(coord_width))


class AreaFollower:
    """Helix axes moving by ``deltas`` (steps, indexed by axis) with the area an arc sweeps, AREA ``area``."""

    def __init__(self, deltas, area, coord_width=24):
        self.deltas = tuple(deltas)
        self.area = area
        self.floor = remainder_min(coord_width)
        self.remainder = [area - area // 2] * len(self.deltas)
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
            share = abs(delta) * swept
            stepping = self.left[axis] > 0 and (share >= self.remainder[axis] or not arc_running)
            if arc_running:
                self.remainder[axis] = max(self.remainder[axis] - share + self.area * stepping, self.floor)
            self.left[axis] -= stepping
            steps.append(stepping)
        return tuple(steps)
