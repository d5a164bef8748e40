"""The drawing as primitives in millimetres: the front ends write it, the planner reads it.

* ``Line``: a straight move, fed or rapid.
* ``Arc``: about ``centre`` from ``start`` to ``end`` in the direction ``ccw``;
  ``start == end`` is a full circle.  When the start and end radii differ
  (a centre-format G-code arc within LinuxCNC's tolerance) the path is the
  spiral whose radius changes linearly with the angle, as LinuxCNC runs it.
* ``Dwell``: a pause in seconds.

Moves carry their feed (mm/min; ``None`` for rapid moves) and ``where``, the
source line (``part.ngc:12``) or element (``drawing.svg#c1``) for errors.
The functions here are the ideal geometry the planner's result is measured
against.
"""
import math
from dataclasses import dataclass

TAU = 2 * math.pi
SAME_POINT = 1e-9  # mm: start and end closer than this are the same point


@dataclass(frozen=True)
class Line:
    start: tuple
    end: tuple
    feed: float = None  # mm/min; None: rapid
    where: str = ""

    @property
    def rapid(self):
        return self.feed is None

    @property
    def length(self):
        return math.dist(self.start, self.end)

    def point(self, fraction):
        (xs, ys), (xe, ye) = self.start, self.end
        return xs + (xe - xs) * fraction, ys + (ye - ys) * fraction

    def start_tangent(self):
        return _unit(self.end[0] - self.start[0], self.end[1] - self.start[1])

    end_tangent = start_tangent

    def distance(self, point):
        """Shortest distance from ``point`` to the segment."""
        (xs, ys), (xe, ye) = self.start, self.end
        dx, dy = xe - xs, ye - ys
        span = dx * dx + dy * dy
        t = 0.0 if span == 0 else max(0.0, min(1.0, ((point[0] - xs) * dx + (point[1] - ys) * dy) / span))
        return math.dist(point, (xs + t * dx, ys + t * dy))


@dataclass(frozen=True)
class Arc:
    start: tuple
    end: tuple
    centre: tuple
    ccw: bool
    feed: float = None
    where: str = ""

    rapid = False

    @property
    def start_radius(self):
        return math.dist(self.start, self.centre)

    @property
    def end_radius(self):
        return math.dist(self.end, self.centre)

    @property
    def full_circle(self):
        return math.dist(self.start, self.end) < SAME_POINT

    @property
    def start_angle(self):
        return _angle(self.start, self.centre)

    @property
    def sweep(self):
        """Angle travelled, 0 < sweep <= 2 pi, in the arc's own direction."""
        if self.full_circle:
            return TAU
        turn = (_angle(self.end, self.centre) - self.start_angle) * (1 if self.ccw else -1)
        return turn % TAU or TAU

    @property
    def length(self):
        return self.sweep * (self.start_radius + self.end_radius) / 2

    def radius_at(self, angle):
        """Radius after turning ``angle`` (0..sweep) from the start."""
        return self.start_radius + (self.end_radius - self.start_radius) * angle / self.sweep

    def point_at(self, angle):
        """The point after turning ``angle`` (0..sweep) from the start."""
        radius = self.radius_at(angle)
        theta = self.start_angle + (angle if self.ccw else -angle)
        return self.centre[0] + radius * math.cos(theta), self.centre[1] + radius * math.sin(theta)

    def point(self, fraction):
        return self.point_at(fraction * self.sweep)

    def tangent_at(self, angle):
        theta = self.start_angle + (angle if self.ccw else -angle)
        sense = 1 if self.ccw else -1
        return _unit(-math.sin(theta) * sense, math.cos(theta) * sense)

    def start_tangent(self):
        return self.tangent_at(0.0)

    def end_tangent(self):
        return self.tangent_at(self.sweep)

    def distance(self, point):
        """Distance from ``point`` to the arc: radial inside its angular span
        (to the spiral at that angle), else to the nearer end point."""
        turned = (_angle(point, self.centre) - self.start_angle) * (1 if self.ccw else -1) % TAU
        ends = min(math.dist(point, self.start), math.dist(point, self.end))
        if turned <= self.sweep:
            return min(ends, abs(math.dist(point, self.centre) - self.radius_at(turned)))
        return ends


@dataclass(frozen=True)
class Dwell:
    seconds: float
    where: str = ""


def _angle(point, centre):
    return math.atan2(point[1] - centre[1], point[0] - centre[0])


def _unit(dx, dy):
    norm = math.hypot(dx, dy)
    return (0.0, 0.0) if norm == 0 else (dx / norm, dy / norm)


def turn_angle(before, after):
    """Direction change in radians (0..pi) between the end of ``before`` and the start of ``after``."""
    (ax, ay), (bx, by) = before.end_tangent(), after.start_tangent()
    return math.acos(max(-1.0, min(1.0, ax * bx + ay * by)))
