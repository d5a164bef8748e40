"""Deviation of N-axis lines and helical arcs from the ideal: ``python -m bench.axes_figures``.

From the golden model (``models/dda_axes.py``; docs/axes.md quotes the
figures):

* N-axis lines (3 to 6 axes, seeded random displacements up to ``--line-steps``
  steps plus edge cases): the largest distance, on any axis after any
  iteration k, of the position from the ideal line at the same parameter,
  ``k d_i / T`` (exact rational arithmetic), and whether every axis ended on
  its end point on iteration T;
* helical arcs (seeded random: radius 20..5,000 steps, log-uniform; a quarter
  to a full turn; rise up to K steps; every variant, G17/G18/G19, both
  directions) by the ITERATIONS rule the card ran before register map 3.0
  (the helix axis a line DDA over the arc's K iterations:
  ``floor((K // 2 + k |h|) / K)`` after iteration k, computed here, no
  longer in the model): at every arc step (every iteration that moves the
  plane's point), the largest deviation of a helix axis from the ideal helix
  at the same parameter ``h k / K`` (per iteration) and at the same angle
  ``h theta_k / Theta`` (per angle), and the lag ``|k / K - theta_k / Theta| * K``
  (iterations); the per-angle figure also for the helices whose rise is at
  most K / 5 (about 0.2 step an iteration: a pitch angle up to about 11 degrees);
* the same helices by swept area, the card's rule (``models/helix_area.py``, AREA W the arc's
  ``arc_area``): at every arc step the largest deviation from ``h A_k / W``
  (per area, A_k the area swept so far), from the ideal helix at the same
  angle (per angle), and the 3-D distance from the ideal helix's point at
  that angle (the axial and the radial deviation, sqrt(a^2 + r^2)); how many
  of the helices the host's rule ``|h| max w <= W`` takes (fit), the
  figures over those and over every helix, the ITERATIONS rule's per angle
  over those that fit, and the steepest rise the rule takes
  (``W // max w``) as a fraction of K.
"""
import argparse
import math
import random
from dataclasses import replace
from fractions import Fraction

from models.axes import AXIS_NAMES, PLANES
from models.dda_axes import iterate_axes
from models.dda_build import IMPROVED, VARIANT_NAMES, WEIGHTED
from models.dda_plan import ArcCommand, AxesLineCommand, plan_arc
from models.helix_area import arc_area

GENTLE = 5  # rise at most K / GENTLE: within one step of the ideal helix at the same angle


def line_cases(rng, count, largest):
    """Edge cases and ``count`` seeded random lines per axis count 3..6."""
    cases = [(5, 0, 0), (0, 0, -7), (3, 3, 3), (-4, 4, -4, 4), (1, -1, 1, -1, 1, -1), (largest, 1, -1),
             (largest, largest - 1, -largest, 1, 0, 2), (0, 0, 0, 0, 0, 1)]
    for axes in range(3, 7):
        for _ in range(count):
            cases.append(tuple(rng.randint(-largest, largest) if rng.random() < 0.8 else 0 for _ in range(axes)))
    return cases


def line_deviation(deltas):
    """(largest |p_i(k) - k d_i / T| over axes and iterations, ended on T on its end point)."""
    path = iterate_axes(AxesLineCommand(deltas), len(deltas))
    threshold = max(abs(d) for d in deltas)
    positions = path.positions()
    if not threshold:
        return Fraction(0), positions[-1] == tuple(deltas)
    # |p - k d / T| = |p T - k d| / T, exactly
    worst = max(abs(p * threshold - k * d) for k, point in enumerate(positions) for p, d in zip(point, deltas))
    return Fraction(worst, threshold), len(path.steps) == threshold and positions[-1] == tuple(deltas)


def random_helix(rng, variant, plane, ccw, coord_width=24):
    """A seeded random helical arc the model accepts (AREA filled in), rising up to its K."""
    helix_axis = next(axis for axis in range(3) if axis not in plane)
    while True:
        radius = math.exp(rng.uniform(math.log(20), math.log(5000)))
        start = rng.uniform(0, math.tau)
        end = start + (1 if ccw else -1) * rng.uniform(math.pi / 2, math.tau)
        xs, ys = round(radius * math.cos(start)), round(radius * math.sin(start))
        xe, ye = round(radius * math.cos(end)), round(radius * math.sin(end))
        lam = rng.randrange(0, 4) if variant in (WEIGHTED, IMPROVED) else 0
        command = ArcCommand(xs, ys, xe, ye, ccw, variant, lam, 0, plane=plane)
        try:
            plan_arc(command, coord_width)
        except ValueError:
            continue
        area = arc_area(command, coord_width)
        rise = rng.choice([1, -1]) * max(1, round(area.iterations * rng.choice([rng.random(), rng.random() / GENTLE])))
        return replace_helix(command, helix_axis, rise, area.total)


def replace_helix(command, axis, rise, area):
    helix = [0, 0, 0]
    helix[axis] = rise
    return replace(command, helix=tuple(helix), area=area)


def sweep(command):
    """The arc's angle in its own direction, 0 < sweep <= 2 pi (start == end: a full circle)."""
    if (command.xs, command.ys) == (command.xe, command.ye):
        return math.tau
    turn = math.atan2(command.ye, command.xe) - math.atan2(command.ys, command.xs)
    return (turn if command.ccw else -turn) % math.tau or math.tau


def helix_deviation(command):
    """(per iteration, per angle, lag in iterations) of the ITERATIONS rule: the largest over the arc's steps."""
    axis = command.helix_axes[0]
    rise, theta = command.helix[axis], sweep(command)
    plain = iterate_axes(replace(command, helix=(), area=None), 3)
    total, sign = len(plain.steps), 1 if rise >= 0 else -1
    # the ITERATIONS rule's helix axis after iteration k, with the arc's own K
    positions = [tuple(sign * ((total // 2 + k * abs(rise)) // total) if a == axis else c for a, c in enumerate(p))
                 for k, p in enumerate(plain.positions())]
    u, v = command.plane
    sense = 1 if command.ccw else -1
    turned, last = 0.0, math.atan2(command.ys, command.xs)
    per_iteration = per_angle = lag = 0.0
    previous = positions[0]
    for k, point in enumerate(positions[1:], start=1):
        if (point[u], point[v]) == (previous[u], previous[v]):
            previous = point
            continue
        previous = point
        angle = math.atan2(point[v], point[u])
        turned += math.remainder(angle - last, math.tau) * sense
        last = angle
        fraction = turned / theta
        per_iteration = max(per_iteration, abs(point[axis] - rise * k / total))
        per_angle = max(per_angle, abs(point[axis] - rise * fraction))
        lag = max(lag, abs(k / total - fraction) * total)
    return per_iteration, per_angle, lag


def area_deviation(command):
    """(per area, per angle, 3-D, fits, steepest / K) of ``command``'s helix by swept area: the largest over
    its arc steps; steepest: the largest rise the host's rule takes, W // max w."""
    area = arc_area(command)
    path = iterate_axes(command)
    u, v = command.plane
    axis = command.helix_axes[0]
    rise, theta, sense = command.helix[axis], sweep(command), 1 if command.ccw else -1
    radius = math.hypot(command.xs, command.ys)
    turned, last, swept = 0.0, math.atan2(command.ys, command.xs), 0
    per_area = per_angle = distance = 0.0
    previous = path.start
    for point in path.positions()[1:]:
        step_u, step_v = point[u] != previous[u], point[v] != previous[v]
        swept += abs(previous[v]) * step_u + abs(previous[u]) * step_v   # |u dv - v du|
        moved, previous = step_u or step_v, point
        if not moved:
            continue
        angle = math.atan2(point[v], point[u])
        turned += math.remainder(angle - last, math.tau) * sense
        last = angle
        axial = abs(point[axis] - rise * turned / theta)
        per_area = max(per_area, abs(point[axis] - Fraction(rise * swept, area.total)))
        per_angle = max(per_angle, axial)
        distance = max(distance, math.hypot(axial, math.hypot(point[u], point[v]) - radius))
    return float(per_area), per_angle, distance, area.fits(rise), area.total // area.largest / area.iterations


def area_table(results):
    """Rows of the helix-by-area table: ``results`` [(variant, plane, ccw, area_deviation)]."""
    print(f"\nby swept area\n{'variant':<12} {'plane':<6} {'dir':<4} {'helices':>7} {'fit':>4} {'per area':>9} "
          f"{'per angle':>10} {'3-D':>7} {'angle all':>10} {'3-D all':>8} {'it angle':>9}")
    overall, total, fit = [0.0] * 6, 0, 0
    for key in dict.fromkeys(r[:3] for r in results):
        rows = [r[3] for r in results if r[:3] == key]
        fitting = [r for r in rows if r[3]]
        figures = (max((r[0] for r in fitting), default=0.0), max((r[1] for r in fitting), default=0.0),
                   max((r[2] for r in fitting), default=0.0), max(r[1] for r in rows), max(r[2] for r in rows),
                   max((r[5] for r in fitting), default=0.0))
        overall = [max(a, b) for a, b in zip(overall, figures)]
        total, fit = total + len(rows), fit + len(fitting)
        variant, code, ccw = key
        print(f"{VARIANT_NAMES[variant]:<12} G{code:<5} {'ccw' if ccw else 'cw':<4} {len(rows):>7} {len(fitting):>4} "
              + " ".join(f"{f:{w}.3f}" for f, w in zip(figures, (9, 10, 7, 10, 8, 9))))
    print(f"{'all':<12} {'':<6} {'':<4} {total:>7} {fit:>4} "
          + " ".join(f"{f:{w}.3f}" for f, w in zip(overall, (9, 10, 7, 10, 8, 9))))
    for variant in dict.fromkeys(r[0] for r in results):
        ratios = [r[3][4] for r in results if r[0] == variant]
        print(f"{VARIANT_NAMES[variant]}: the steepest rise the rule takes (W // max w): "
              f"{min(ratios):.3f} .. {max(ratios):.3f} K")
    print("\nper area: |z - h A_k / W|; per angle: |z - h theta_k / Theta|; 3-D: from the ideal helix's point at "
          "that angle; fit: |h| max w <= W (the columns before 'all' over those); it angle: per angle of the "
          "ITERATIONS rule over the same helices that fit")


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.axes_figures", description=__doc__.split("\n\n")[0])
    parser.add_argument("--lines", type=int, default=100, help="random lines per axis count (default 100)")
    parser.add_argument("--line-steps", type=int, default=3000, help="largest displacement (default 3000)")
    parser.add_argument("--helices", type=int, default=8,
                        help="random helices per variant, plane and direction (default 8)")
    parser.add_argument("--variants", default="traditional,weighted,improved,precise",
                        help="the variants whose helices are measured (default: all four)")
    parser.add_argument("--seed", type=int, default=26)
    options = parser.parse_args(argv)
    rng = random.Random(options.seed)
    cases = line_cases(rng, options.lines, options.line_steps)
    results = [line_deviation(deltas) for deltas in cases]
    print(f"N-axis lines: {len(cases)} (3..6 axes, |d| <= {options.line_steps}): max deviation from the ideal "
          f"line {float(max(r[0] for r in results)):.4f} steps; all end on iteration T on their end point: "
          f"{all(r[1] for r in results)}")
    print(f"\n{'variant':<12} {'plane':<6} {'dir':<4} {'helices':>7} {'per iter':>9} {'per angle':>10} "
          f"{'gentle':>8} {'lag (it)':>9}")
    overall = [0.0, 0.0, 0.0, 0.0]
    total = 0
    by_area = []
    chosen = [code for code, name in VARIANT_NAMES.items() if name in options.variants.split(",")]
    for variant in chosen:
        for code, plane in PLANES.items():
            for ccw in (True, False):
                rows = []
                for _ in range(options.helices):
                    command = random_helix(rng, variant, plane, ccw)
                    gentle = abs(command.helix[command.helix_axes[0]]) * GENTLE <= arc_area(command).iterations
                    rows.append((*helix_deviation(command), gentle))
                    by_area.append((variant, code, ccw, area_deviation(command) + (rows[-1][1],)))
                figures = (max(r[0] for r in rows), max(r[1] for r in rows),
                           max((r[1] for r in rows if r[3]), default=0.0), max(r[2] for r in rows))
                overall = [max(a, b) for a, b in zip(overall, figures)]
                total += len(rows)
                print(f"{VARIANT_NAMES[variant]:<12} G{code:<5} {'ccw' if ccw else 'cw':<4} {len(rows):>7} "
                      f"{figures[0]:9.3f} {figures[1]:10.3f} {figures[2]:8.3f} {figures[3]:9.3f}")
    print(f"{'all':<12} {'':<6} {'':<4} {total:>7} {overall[0]:9.3f} {overall[1]:10.3f} {overall[2]:8.3f} "
          f"{overall[3]:9.3f}")
    print(f"\nper iter: |z - h k / K|; per angle: |z - h theta_k / Theta|; gentle: per angle for rise <= K / "
          f"{GENTLE}; lag: |k / K - theta_k / Theta| * K; steps of the helix axis ({', '.join(AXIS_NAMES[:3])})")
    area_table(by_area)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
