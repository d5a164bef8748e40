"""The drawing as primitives in millimetres: the front ends write it, the planner reads it.

Points are tuples indexed by axis (``models/axes.py``: X, Y, Z, A, B, C; A,
B and C in degrees), as long as the drawing needs: an XY drawing has (x, y)
points, a program that names Z has (x, y, z) points, and so on.

* ``Line``: a straight move, fed or rapid.
* ``Arc``: in ``plane`` (u, v) (``models.axes.PLANES``; (0, 1): X, Y) about
  ``centre`` (its (u, v) coordinates) from ``start`` to ``end`` in the
  direction ``ccw`` (from +u towards +v); ``start == end`` in the plane is a
  full circle.  When the start and end radii differ (a centre-format G-code
  arc within LinuxCNC's tolerance) the path is the spiral whose radius
  changes linearly with the angle, as LinuxCNC runs it.  Every other axis
  that differs between start and end moves linearly with the angle: a helix.
* ``Dwell``: a pause in seconds.

An arc's measures (radii, angles, sweep, rise, length) are worked out once
(``cached_property``: the primitives are frozen).

Lengths, for the feed, follow RS274/NGC: along X, Y and Z when any of them
moves (a rotary axis then just arrives with them), else along the rotary
axes in degrees.  Distances (the deviation) are Euclidean over every axis,
degrees counted as millimetres.

Moves carry their feed (mm/min; ``None`` for rapid moves) and ``where``, the
source line (``part.ngc:12``) or element (``drawing.svg#c1``) for errors.
The functions here are the ideal geometry the planner's result is measured
against.
"""
import math
from dataclasses import dataclass
from functools import cached_property

from models.axes import AXIS_NAMES, ROTARY_NAMES, XY

TAU = 2 * math.pi
SAME_POINT = 1e-9  # mm: start and end closer than this are the same point
LINEAR_AXES = AXIS_NAMES.index(ROTARY_NAMES[0])  # X, Y, Z; the axes after them are rotary


def path_length(deltas):
    """RS274/NGC's length of a move by ``deltas``: along X, Y, Z if any moves, else along the rotary axes."""
    linear = deltas[:LINEAR_AXES]
    if any(linear) or len(deltas) <= LINEAR_AXES:
        return math.hypot(*linear)
    return math.hypot(*deltas[LINEAR_AXES:])


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
        if len(self.start) == 2:
            return math.dist(self.start, self.end)
        return path_length(tuple(e - s for s, e in zip(self.start, self.end)))

    def point(self, fraction):
        return tuple(s + (e - s) * fraction for s, e in zip(self.start, self.end))

    def start_tangent(self):
        return _unit(*(e - s for s, e in zip(self.start, self.end)))

    end_tangent = start_tangent

    def distance(self, point):
        """Shortest distance from ``point`` to the segment."""
        deltas = [e - s for s, e in zip(self.start, self.end)]
        span = sum(d * d for d in deltas)
        along = sum((p - s) * d for p, s, d in zip(point, self.start, deltas))
        t = 0.0 if span == 0 else max(0.0, min(1.0, along / span))
        return math.dist(point, tuple(s + t * d for s, d in zip(self.start, deltas)))


@dataclass(frozen=True)
class Arc:
    start: tuple
    end: tuple
    centre: tuple  # (u, v)
    ccw: bool
    feed: float = None
    where: str = ""
    plane: tuple = XY

    rapid = False

    def in_plane(self, point):
        """(u, v) of ``point``."""
        u, v = self.plane
        return point[u], point[v]

    @cached_property
    def start_radius(self):
        return math.dist(self.in_plane(self.start), self.centre)

    @cached_property
    def end_radius(self):
        return math.dist(self.in_plane(self.end), self.centre)

    @cached_property
    def full_circle(self):
        return math.dist(self.in_plane(self.start), self.in_plane(self.end)) < SAME_POINT

    @cached_property
    def start_angle(self):
        return _angle(self.in_plane(self.start), self.centre)

    @cached_property
    def sweep(self):
        """Angle travelled, 0 < sweep <= 2 pi, in the arc's own direction."""
        if self.full_circle:
            return TAU
        turn = (_angle(self.in_plane(self.end), self.centre) - self.start_angle) * (1 if self.ccw else -1)
        return turn % TAU or TAU

    @cached_property
    def rise(self):
        """{axis: displacement} of the axes outside the plane that move (the helix)."""
        return {axis: e - s for axis, (s, e) in enumerate(zip(self.start, self.end))
                if axis not in self.plane and e != s}

    @cached_property
    def plane_length(self):
        return self.sweep * (self.start_radius + self.end_radius) / 2

    @cached_property
    def length(self):
        """Along the path for the feed: the helix's length when a linear axis rises, else the plane's."""
        linear = [d for axis, d in self.rise.items() if axis < LINEAR_AXES]
        return math.hypot(self.plane_length, *linear) if linear else self.plane_length

    def radius_at(self, angle):
        """Radius after turning ``angle`` (0..sweep) from the start."""
        return self.start_radius + (self.end_radius - self.start_radius) * angle / self.sweep

    def plane_point_at(self, angle):
        """(u, v) of the point after turning ``angle`` (0..sweep) from the start."""
        radius = self.radius_at(angle)
        theta = self.start_angle + (angle if self.ccw else -angle)
        return self.centre[0] + radius * math.cos(theta), self.centre[1] + radius * math.sin(theta)

    def point_at(self, angle):
        """The point after turning ``angle`` (0..sweep) from the start."""
        point = list(self.start)
        u, v = self.plane
        point[u], point[v] = self.plane_point_at(angle)
        for axis, rise in self.rise.items():
            point[axis] = self.start[axis] + rise * angle / self.sweep
        return tuple(point)

    def point(self, fraction):
        return self.point_at(fraction * self.sweep)

    def tangent_at(self, angle):
        theta = self.start_angle + (angle if self.ccw else -angle)
        sense = 1 if self.ccw else -1
        direction = [0.0] * len(self.start)
        u, v = self.plane
        direction[u], direction[v] = -math.sin(theta) * sense, math.cos(theta) * sense
        rise = self.rise
        if rise:  # per radian: the plane moves by its radius, the helix axes by rise / sweep
            direction = [d * self.radius_at(angle) for d in direction]
            for axis, amount in rise.items():
                direction[axis] = amount / self.sweep
        return _unit(*direction)

    def start_tangent(self):
        return self.tangent_at(0.0)

    def end_tangent(self):
        return self.tangent_at(self.sweep)

    def distance(self, point):
        """Distance from ``point`` to the arc: inside its angular span, to the
        curve (radially in the plane, plus the distance along the other axes;
        on a helix, to its nearest point near the point's angle), else to the
        nearer end point."""
        plane_point = self.in_plane(point)
        turned = (_angle(plane_point, self.centre) - self.start_angle) * (1 if self.ccw else -1) % TAU
        ends = min(math.dist(point, self.start), math.dist(point, self.end))
        if turned > self.sweep:
            return ends
        radial = abs(math.dist(plane_point, self.centre) - self.radius_at(turned))
        if len(point) == 2 and self.plane == XY:
            return min(ends, radial)
        if self.rise:
            return min(ends, math.dist(point, self.point_at(self._nearest_angle(point, turned))))
        off_plane = [p - q for axis, (p, q) in enumerate(zip(point, self.start)) if axis not in self.plane]
        return min(ends, math.hypot(radial, *off_plane))

    def _nearest_angle(self, point, angle, rounds=3):
        """The angle of the helix's point nearest ``point``, from ``angle`` (Gauss-Newton)."""
        sense = 1 if self.ccw else -1
        for _ in range(rounds):
            theta = self.start_angle + sense * angle
            slope = [0.0] * len(point)
            u, v = self.plane
            radius, growth = self.radius_at(angle), (self.end_radius - self.start_radius) / self.sweep
            slope[u] = -radius * math.sin(theta) * sense + growth * math.cos(theta)
            slope[v] = radius * math.cos(theta) * sense + growth * math.sin(theta)
            for axis, rise in self.rise.items():
                slope[axis] = rise / self.sweep
            here = self.point_at(angle)
            angle += sum((p - h) * d for p, h, d in zip(point, here, slope)) / sum(d * d for d in slope)
            angle = max(0.0, min(self.sweep, angle))
        return angle


@dataclass(frozen=True)
class Dwell:
    seconds: float
    where: str = ""


def _angle(point, centre):
    return math.atan2(point[1] - centre[1], point[0] - centre[0])


def _unit(*deltas):
    norm = math.hypot(*deltas)
    return tuple(0.0 for _ in deltas) if norm == 0 else tuple(d / norm for d in deltas)


def dimension(drawing):
    """The number of axes the points of ``drawing`` have (2 for an empty one)."""
    return max((len(item.start) for item in drawing if hasattr(item, "start")), default=2)


def turn_angle(before, after):
    """Direction change in radians (0..pi) between the end of ``before`` and the start of ``after``."""
    return math.acos(max(-1.0, min(1.0, sum(a * b for a, b in zip(before.end_tangent(), after.start_tangent())))))
