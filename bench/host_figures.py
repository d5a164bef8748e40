"""Figures of the host planner: ``python -m bench.host_figures``.

* the examples (``examples/part.ngc``, ``examples/drawing.svg``) at the
  default machine (200 steps/mm, 33 MHz, 24-bit coordinates): segments,
  commands, words, steps, the largest deviation of the card's step path
  (``models.dda_model``) from the drawing, job time at the planned rates;
* seeded random LinuxCNC-accepted arcs (circles, spirals at and near the
  radius-mismatch limit, full circles) at 20 steps/mm: commands per arc and
  the largest deviation by kind;
* planning speed over 100,000 short lines.
"""
import math
import random
import time

from host import gcode, svg
from host.check import check
from host.cli import summary
from host.geometry import Arc, Line
from host.machine import Machine
from host.planner import plan
from models.dda_model import ArcCommand
from rtl.convert import ROOT

ARCS = 400


def examples():
    for name in ("part.ngc", "drawing.svg"):
        path = ROOT / "examples" / name
        started = time.process_time()
        if name.endswith(".svg"):
            drawing = svg.parse(str(path), tolerance=0.01, name=name)
        else:
            drawing = gcode.parse(path.read_text(), name)
        read = time.process_time()
        planned = plan(drawing, Machine())
        planned_at = time.process_time()
        result = check(planned)
        checked = time.process_time()
        print(f"== {name} (read {read - started:.2f} s, plan {planned_at - read:.3f} s, "
              f"model check {checked - planned_at:.2f} s of CPU)")
        for line in summary(planned, result):
            print("  " + line)


def random_arc(rng):
    radius = rng.choice([rng.uniform(0.1, 2), rng.uniform(2, 20), rng.uniform(20, 60)])
    centre = (rng.uniform(-40, 40), rng.uniform(-40, 40))
    a0 = rng.uniform(0, math.tau)
    kind = rng.choice(["circle", "spiral at the limit", "spiral below it", "full circle"])
    sweep = math.tau if kind == "full circle" else rng.uniform(0.05, math.tau - 0.01)
    ccw = rng.random() < 0.5
    end_radius = radius
    if kind.startswith("spiral"):
        limit = min(0.5, max(0.005, 0.001 * radius))
        end_radius = radius + rng.choice([-1, 1]) * limit * (0.999 if kind.endswith("limit") else rng.random())
    a1 = a0 + (sweep if ccw else -sweep)
    start = (centre[0] + radius * math.cos(a0), centre[1] + radius * math.sin(a0))
    end = start if kind == "full circle" else (centre[0] + end_radius * math.cos(a1),
                                               centre[1] + end_radius * math.sin(a1))
    return Arc(start, end, centre, ccw, 600.0, kind), kind


def arcs():
    rng = random.Random(1)
    machine = Machine(steps_per_mm=(20.0, 20.0))
    stats = {}
    for _ in range(ARCS):
        arc, kind = random_arc(rng)
        planned = plan([Line((0.0, 0.0), arc.start, None), arc], machine)
        result = check(planned)
        deviation = max(arc.distance(machine.mm(p)) * 20 for primitive, points in result.points
                        if primitive == 1 for p in points)
        commands = [e.command for e in planned.moves() if e.primitive == 1]
        entry = stats.setdefault(kind, [0, 0, 0, 0.0])
        entry[0] += 1
        entry[1] += len(commands)
        entry[2] += sum(isinstance(c, ArcCommand) for c in commands) == len(commands) == 1
        entry[3] = max(entry[3], deviation)
    print(f"== {ARCS} random LinuxCNC-accepted arcs, radius 0.1 to 60 mm, 20 steps/mm (seed 1)")
    print(f"  {'kind':<22} {'arcs':>5} {'commands/arc':>13} {'one ARC':>8} {'max deviation (steps)':>22}")
    for kind, (count, commands, single, worst) in sorted(stats.items()):
        print(f"  {kind:<22} {count:>5} {commands / count:>13.1f} {single:>8} {worst:>22.3f}")


def planning_speed():
    rng = random.Random(2)
    drawing, here = [], (0.0, 0.0)
    for number in range(100_000):
        there = (here[0] + rng.uniform(-0.3, 0.3), here[1] + rng.uniform(-0.3, 0.3))
        drawing.append(Line(here, there, 600.0, str(number)))
        here = there
    started = time.process_time()
    planned = plan(drawing, Machine())
    seconds = time.process_time() - started
    print(f"== planning 100,000 random short lines: {seconds:.2f} s of CPU, "
          f"{len(planned.entries)} commands, {len(planned.runs)} runs")


if __name__ == "__main__":
    examples()
    arcs()
    planning_speed()
