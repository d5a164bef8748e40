"""Helical arcs on the card's pins against the ideal helix: ``python -m bench.helix_pins``.

A seeded set of helices (the precise mode; G17, G18 and G19, both
directions; radius 20 to ``--radius`` steps, log-uniform; a quarter to a
full turn; the rise up to K steps, a third of them gentle, up to K / 5, those
the host's rule takes, ``|h| max w <= W``, kept; AREA the arc's W,
``models.helix_area.arc_area``) is chained into
one stream and run on the simulated three-axis card (``--card``, Verilator by
default: ``sim/card/card_e2e.py``), the STEP/DIR pins captured.  The pins'
points must be the golden model's (``models.dda_axes.iterate_axes``,
chained); then, for the model's points and the pins' alike, at every point
of every helix (after every clock that steps):

* axial: the helix axis's distance from the ideal helix at the same angle,
  ``h theta / Theta`` (theta turned by the plane's point so far, Theta the
  arc's sweep);
* radial: the plane point's distance from the circle of the start's radius;
* 3-D: the distance from the ideal helix's point at that angle,
  sqrt(axial**2 + radial**2).

docs/axes.md quotes the figures.
"""
import argparse
import math
import random

from models.axes import PLANES
from models.dda_axes import iterate_axes, move_start
from models.helix_area import arc_area
from sim.card.card_bench import axes_path
from sim.card.card_e2e import motion_scenario, run_card

from bench.axes_figures import random_helix, sweep

AXES = 3


def helices(seed, per_case, radius):
    """The seeded helices: ``per_case`` of each plane and direction."""
    rng = random.Random(seed)
    chosen = []
    for plane in PLANES.values():
        for ccw in (True, False):
            while sum(1 for h in chosen if h.plane == plane and h.ccw == ccw) < per_case:
                command = random_helix(rng, 3, plane, ccw)
                swept = arc_area(command)
                if math.hypot(command.xs, command.ys) <= radius and swept.fits(max(map(abs, command.helix))):
                    chosen.append(command)
    return chosen


def steepest(command):
    """The steepest rise the host's rule takes on ``command``'s arc: W // max w."""
    swept = arc_area(command)
    return swept.total // swept.largest


def deviations(command, points):
    """(axial, radial, 3-D) largest over ``points`` (absolute, the helix's from its start on)."""
    u, v = command.plane
    axis = command.helix_axes[0]
    origin = [p - s for p, s in zip(points[0], move_start(command, AXES))]   # the centre, the helix's base
    radius = math.hypot(command.xs, command.ys)
    rise, theta, sense = command.helix[axis], sweep(command), 1 if command.ccw else -1
    turned, last = 0.0, math.atan2(command.ys, command.xs)
    worst = [0.0, 0.0, 0.0]
    for point in points[1:]:
        pu, pv = point[u] - origin[u], point[v] - origin[v]
        angle = math.atan2(pv, pu)
        turned += math.remainder(angle - last, math.tau) * sense
        last = angle
        axial = abs(point[axis] - origin[axis] - rise * turned / theta)
        radial = abs(math.hypot(pu, pv) - radius)
        worst = [max(w, f) for w, f in zip(worst, (axial, radial, math.hypot(axial, radial)))]
    return worst


def per_helix(commands, points):
    """Split the chained ``points`` at each helix's end: [(command, its points from its start)]."""
    result, index = [], 0
    for command in commands:
        count = len(iterate_axes(command, AXES).points()) - 1
        result.append((command, points[index:index + count + 1]))
        index += count
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.helix_pins", description=__doc__.split("\n\n")[0])
    parser.add_argument("--helices", type=int, default=2, help="helices per plane and direction (default 2)")
    parser.add_argument("--radius", type=int, default=300, help="largest radius in steps (default 300)")
    parser.add_argument("--card", choices=("verilator", "icarus", "myhdl"), default="verilator")
    parser.add_argument("--seed", type=int, default=26)
    options = parser.parse_args(argv)
    commands = helices(options.seed, options.helices, options.radius)
    model = axes_path(commands, AXES)
    out, log, _, _ = run_card(options.card, motion_scenario(commands), "helix_pins", axes=AXES)
    pins = log.axis_points(AXES)
    print(f"{len(commands)} helices (precise; G17, G18, G19 both ways; radius <= {options.radius}), "
          f"{len(model) - 1} points; the pins ({options.card}) equal the model's: {pins == model}")
    print(f"{'source':<7} {'plane':<6} {'dir':<4} {'radius':>7} {'rise':>6} {'W/mw':>6} {'axial':>7} {'radial':>7} "
          f"{'3-D':>7}")
    for name, path in (("model", model), ("pins", pins)):
        overall = [0.0, 0.0, 0.0]
        for command, points in per_helix(commands, path):
            figures = deviations(command, points)
            overall = [max(a, b) for a, b in zip(overall, figures)]
            plane = next(code for code, p in PLANES.items() if p == command.plane)
            rise = command.helix[command.helix_axes[0]]
            print(f"{name:<7} G{plane:<5} {'ccw' if command.ccw else 'cw':<4} "
                  f"{math.hypot(command.xs, command.ys):7.1f} {rise:6d} {steepest(command):6d} "
                  f"{figures[0]:7.3f} {figures[1]:7.3f} {figures[2]:7.3f}")
        print(f"{name:<7} {'all':<31} {overall[0]:7.3f} {overall[1]:7.3f} {overall[2]:7.3f}  (steps)")
    print("\naxial: |z - h theta / Theta|; radial: | |(u, v)| - R |; 3-D: both; W/mw: the steepest rise the "
          "host's rule takes, W // max w (docs/axes.md)")
    return 0 if pins == model else 1


if __name__ == "__main__":
    raise SystemExit(main())
