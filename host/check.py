"""The planned path as the card makes it, measured against the drawing.

``check(plan)`` runs every LINE and ARC through the DDA's golden model
(``models.dda_model.iterate``: the exact step path of the card), rebuilds the
positions in steps, and measures each point's distance to the primitive the
command came from.  It also counts iterations per run and turns them into
the job time at the planned feed rates.
"""
import math
from dataclasses import dataclass, field

from models.commands import DwellCommand
from models.dda_model import ArcCommand, LineCommand, iterate
from models.registers import RATE_ONE


@dataclass
class Check:
    points: list = field(default_factory=list)   # [(primitive index, [(x, y) steps ...])] per move
    max_deviation_mm: float = 0.0
    max_deviation_steps: float = 0.0
    worst_where: str = ""
    steps: tuple = (0, 0)          # output steps per axis
    iterations: int = 0
    end: tuple = (0, 0)
    job_seconds: float = 0.0       # at the planned FEED_RATE / ramps, plus dwells
    ideal_seconds: float = 0.0     # length / programmed feed, plus dwells


def check(plan):
    """``Check`` of ``plan``; ValueError if the model refuses a command or the path
    does not end where the plan says."""
    machine = plan.machine
    result = Check()
    position = (0, 0)
    run_iterations = [0] * len(plan.runs)
    scale = max(machine.steps_per_mm)
    steps_x = steps_y = 0
    for entry in plan.entries:
        command = entry.command
        if isinstance(command, DwellCommand):
            result.job_seconds += command.clocks / machine.clock_hz
            continue
        if not isinstance(command, (LineCommand, ArcCommand)):
            continue
        path = iterate(command, machine.coord_width)
        if isinstance(command, ArcCommand):
            centre = (position[0] - command.xs, position[1] - command.ys)
        else:
            centre = position
        points = [(centre[0] + x, centre[1] + y) for x, y in path.points()]
        if points[0] != position:
            raise ValueError(f"{entry.where}: command starts at {points[0]}, not at {position}")
        position = points[-1]
        run_iterations[entry.run] += len(path.steps)
        steps_x += sum(s.step_x for s in path.steps)
        steps_y += sum(s.step_y for s in path.steps)
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
    result.steps = (steps_x, steps_y)
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
