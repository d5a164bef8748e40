"""Commands of the DDA golden model and the set-up the hardware works out for an arc.

``plan_arc`` checks an ``ArcCommand`` as the hardware's check unit does and
returns its ``ArcPlan`` (rounded radius Rq, threshold, quadrant pieces); the
iterators of ``models/dda_model.py`` run from it.
"""
import math
from dataclasses import dataclass

from models.axes import XY
from models.dda_build import ALL_VARIANTS, MAX_THRESHOLD_EXTRA, PRECISE, TRADITIONAL, VARIANT_NAMES

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

    N axes (docs/axes.md): ``plane`` (u, v) names the axes the arc's x and y
    are (``models/axes.py``: (0, 1) is X, Y); ``helix`` holds a displacement
    per axis (indexed by axis, 0 for the plane's two) that moves linearly
    with the area the arc sweeps; ``area``, the arc's AREA W
    (``models.helix_area.arc_area``, ``models.dda_axes.with_area``), must be
    given with a helix.
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
    plane: tuple = XY
    helix: tuple = ()
    area: int = None

    @property
    def helix_axes(self):
        """The axes with a helix displacement not 0, ascending."""
        return tuple(axis for axis, steps in enumerate(self.helix) if steps)


@dataclass(frozen=True)
class LineCommand:
    """A straight move by (dx, dy) from the current position.

    ``blend`` (both commands): the path goes on into the next move at speed, so
    the hardware's ``stop_left`` does not count down for this move.
    """
    dx: int
    dy: int
    blend: bool = False

    @property
    def deltas(self):
        return (self.dx, self.dy)


@dataclass(frozen=True)
class AxesLineCommand:
    """A straight move by ``deltas`` (steps, indexed by axis: X, Y, Z, A, B, C;
    ``models/axes.py``) from the current position, every axis ending
    together (docs/axes.md); ``blend`` as for ``LineCommand``."""
    deltas: tuple
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


def check_width(value, width, name):
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
        check_width(getattr(command, name), coord_width, name)
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
