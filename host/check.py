"""The planned path as the card makes it, measured against the drawing.

``check(plan)`` runs every LINE and ARC through the DDA's golden model
(``models.dda_model.iterate``, or ``models.dda_axes.iterate_axes`` for a
drawing of more than two axes: the exact step path of the card), rebuilds
the positions in steps, and measures each point's distance to the primitive
the command came from, over every axis (``geometry``: to an arc's ideal
point at the same angle, the helix's included).  It also counts iterations
per run and turns them into the job time at the planned feed rates.
"""
import math
from dataclasses import dataclass, field

from host.geometry import dimension
from models.commands import DwellCommand
from models.dda_axes import iterate_axes, move_start
from models.dda_model import ArcCommand, LineCommand, iterate
from models.dda_plan import AxesLineCommand
from models.registers import RATE_ONE


@dataclass
class Check:
    points: list = field(default_factory=list)   # [(primitive index, [(x, y, ...) steps ...])] per move
    max_deviation_mm: float = 0.0
    max_deviation_steps: float = 0.0
    worst_where: str = ""
    steps: tuple = (0, 0)          # output steps per axis
    iterations: int = 0
    end: tuple = (0, 0)
    job_seconds: float = 0.0       # at the planned FEED_RATE / ramps, plus dwells
    ideal_seconds: float = 0.0     # length / programmed feed, plus dwells


def _move_path(command, position, axes, coord_width):
    """(absolute step points, iterations, steps per axis) of one move from ``position``."""
    if axes == 2:
        path = iterate(command, coord_width)
        origin = (position[0] - command.xs, position[1] - command.ys) if isinstance(command, ArcCommand) else position
        points = [(origin[0] + x, origin[1] + y) for x, y in path.points()]
        counts = (sum(s.step_x for s in path.steps), sum(s.step_y for s in path.steps))
        return points, len(path.steps), counts
    path = iterate_axes(command, axes, coord_width)
    origin = [p - s for p, s in zip(position, move_start(command, axes))]
    points = [tuple(o + p for o, p in zip(origin, point)) for point in path.points()]
    counts = tuple(sum(s.steps[axis] for s in path.steps) for axis in range(axes))
    return points, len(path.steps), counts


def check(plan):
    """``Check`` of ``plan``; ValueError if the model refuses a command or the path
    does not end where the plan says."""
    machine = plan.machine
    result = Check()
    axes = dimension(plan.drawing)
    position = (0,) * axes
    run_iterations = [0] * len(plan.runs)
    scale = max(machine.steps_per_mm)
    steps = [0] * axes
    for entry in plan.entries:
        command = entry.command
        if isinstance(command, DwellCommand):
            result.job_seconds += command.clocks / machine.clock_hz
            continue
        if not isinstance(command, (LineCommand, AxesLineCommand, ArcCommand)):
            continue
        points, iterations, counts = _move_path(command, position, axes, machine.coord_width)
        if points[0] != position:
            raise ValueError(f"{entry.where}: command starts at {points[0]}, not at {position}")
        position = points[-1]
        run_iterations[entry.run] += iterations
        steps = [a + b for a, b in zip(steps, counts)]
        ideal = plan.drawing[entry.primitive]
        for point in points:
            deviation = ideal.distance(machine.mm(point))
            if deviation > result.max_deviation_mm:
                result.max_deviation_mm, result.worst_where = deviation, entry.where
        result.points.append((entry.primitive, points))
    if position != plan.end:
        raise ValueError(f"the path ends at {position}, the plan at {plan.end}")
    result.end = position
    result.max_deviation_steps = result.max_deviation_mm * scale
    result.steps = tuple(steps)
    result.iterations = sum(run_iterations)
    for run, iterations in zip(plan.runs, run_iterations):
        run.iterations = iterations
        result.job_seconds += run_clocks(iterations, run.feed_rate, run.ramp_start,
                                         run.ramp_step) / machine.clock_hz
    result.ideal_seconds = ideal_seconds(plan.drawing, machine)
    return result


def run_clocks(iterations, rate, start, step):
    """Clocks of ``iterations`` DDA iterations on a symmetric trapezoid: from ``start``
    up by ``step`` per iteration to ``rate``, down again at the end (a triangle when short)."""
    if step == 0 or rate <= start:
        return iterations * RATE_ONE / rate
    ramp = math.ceil((rate - start) / step)
    half = min(ramp, iterations // 2)
    clocks = 2 * sum(RATE_ONE / min(start + i * step, rate) for i in range(half))
    middle = iterations - 2 * half
    top = rate if half == ramp else min(start + half * step, rate)
    return clocks + middle * RATE_ONE / top


def ideal_seconds(drawing, machine):
    """Length over programmed feed (rapid moves at the rapid feed), plus dwells."""
    total = 0.0
    for item in drawing:
        if hasattr(item, "seconds"):
            total += item.seconds
        else:
            total += item.length / ((machine.rapid if item.rapid else item.feed) / 60)
    return total
