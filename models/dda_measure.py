"""Measures of a DDA ``Path`` (``models/dda_model.py``): the paper's V_arc and more."""
import math
from dataclasses import dataclass

from models.dda_build import IMPROVED, TRADITIONAL, WEIGHTED
from models.dda_plan import ArcCommand


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
