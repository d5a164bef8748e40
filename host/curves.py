"""Curves (Beziers, elliptical arcs) as biarcs within a tolerance, error measured.

A curve is given as ``point(u)`` and ``derivative(u)`` for u in 0..1.  A
piece [u0, u1] becomes a biarc: two circular arcs meeting with a common
tangent, leaving the curve's start along its start tangent and arriving
along its end tangent (the "equal tangent length" biarc).  The piece's error
is measured, not assumed: the largest distance from ``SAMPLES`` points of the
curve to the biarc and from ``SAMPLES`` points of each arc to the curve's
polyline through ``DENSE`` points.  A piece whose error exceeds 90 % of the
tolerance (the rest covers what peaks between the samples) is halved; a piece
shorter than the tolerance is a line.
"""
import math

from host.geometry import Arc, Line

SAMPLES = 16
DENSE = 64
SAMPLED_SHARE = 0.9  # a piece is kept at 90 % of the tolerance: the error may peak between samples
MIN_SPAN = 1e-7   # parameter span below which a piece is a line
FLAT = 1e-9       # relative: a normal offset this small is a straight line


def approximate(point, derivative, tolerance, feed, where):
    """``Line`` and ``Arc`` primitives within ``tolerance`` (mm) of the curve."""
    return _piece(point, derivative, 0.0, 1.0, tolerance, feed, where)


def _piece(point, derivative, u0, u1, tolerance, feed, where):
    p0, p1 = point(u0), point(u1)
    if math.dist(p0, p1) <= tolerance and _error([Line(p0, p1)], point, u0, u1) <= tolerance * SAMPLED_SHARE:
        return [Line(p0, p1, feed, where)] if p0 != p1 else []
    if u1 - u0 < MIN_SPAN:
        return [Line(p0, p1, feed, where)]
    candidate = biarc(p0, _tangent(point, derivative, u0, 1), p1,
                      _tangent(point, derivative, u1, -1), feed, where)
    if candidate and _error(candidate, point, u0, u1) <= tolerance * SAMPLED_SHARE:
        return candidate
    middle = (u0 + u1) / 2
    return (_piece(point, derivative, u0, middle, tolerance, feed, where)
            + _piece(point, derivative, middle, u1, tolerance, feed, where))


def _tangent(point, derivative, u, side):
    """Unit tangent at ``u``; where the derivative vanishes (a cusp, a control
    point on its end point), the direction of the nearby chord."""
    dx, dy = derivative(u)
    norm = math.hypot(dx, dy)
    if norm > 1e-12:
        return dx / norm, dy / norm
    a, b = point(u), point(min(1.0, max(0.0, u + side * 1e-6)))
    dx, dy = (b[0] - a[0]) * side, (b[1] - a[1]) * side
    norm = math.hypot(dx, dy) or 1.0
    return dx / norm, dy / norm


def biarc(p0, t0, p1, t1, feed=None, where=""):
    """Two arcs from ``p0`` (unit tangent ``t0``) to ``p1`` (unit tangent ``t1``),
    or None when the tangents allow no such pair."""
    vx, vy = p1[0] - p0[0], p1[1] - p0[1]
    tx, ty = t0[0] + t1[0], t0[1] + t1[1]
    v_t, v_v = vx * tx + vy * ty, vx * vx + vy * vy
    denominator = 2 * (1 - (t0[0] * t1[0] + t0[1] * t1[1]))
    if denominator < 1e-12:
        if v_t <= 0:
            return None
        length = v_v / (2 * v_t)
    else:
        length = (-v_t + math.sqrt(v_t * v_t + denominator * v_v)) / denominator
    if length <= 0:
        return None
    q0 = p0[0] + length * t0[0], p0[1] + length * t0[1]
    q1 = p1[0] - length * t1[0], p1[1] - length * t1[1]
    joint = (q0[0] + q1[0]) / 2, (q0[1] + q1[1]) / 2
    jx, jy = q1[0] - q0[0], q1[1] - q0[1]
    norm = math.hypot(jx, jy)
    if norm == 0:
        return None
    return [_tangent_arc(p0, t0, joint, feed, where),
            _tangent_arc(joint, (jx / norm, jy / norm), p1, feed, where)]


def _tangent_arc(start, tangent, end, feed, where):
    """The arc leaving ``start`` along ``tangent`` to ``end`` (a line if straight)."""
    wx, wy = end[0] - start[0], end[1] - start[1]
    nx, ny = -tangent[1], tangent[0]
    offset = nx * wx + ny * wy
    span = wx * wx + wy * wy
    if abs(offset) <= FLAT * span or span == 0:
        return Line(start, end, feed, where)
    radius = span / (2 * offset)
    centre = start[0] + radius * nx, start[1] + radius * ny
    return Arc(start, end, centre, radius > 0, feed, where)


def _error(primitives, point, u0, u1):
    """Largest distance between the curve on [u0, u1] and ``primitives``, both ways."""
    curve = [point(u0 + (u1 - u0) * i / SAMPLES) for i in range(SAMPLES + 1)]
    forward = max(min(p.distance(q) for p in primitives) for q in curve)
    dense = [point(u0 + (u1 - u0) * i / DENSE) for i in range(DENSE + 1)]
    chords = [Line(a, b) for a, b in zip(dense, dense[1:])]
    backward = max(min(c.distance(p.point(i / SAMPLES)) for c in chords)
                   for p in primitives for i in range(SAMPLES + 1))
    return max(forward, backward)
