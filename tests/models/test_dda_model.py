"""The DDA golden model against facts that do not come from it.

Golden values: the paper's V_arc figures (eq. 13-15), the issue's figures of
the best lattice path (V_arc 0.064, max error 0.496 step), a brute-force
search for that best path, and geometry (end points, step totals).
"""
import math
import random

import pytest

from models.dda_model import (IMPROVED, PAPER_V_ARC, PRECISE, TRADITIONAL, WEIGHTED, ArcCommand, LineCommand, Path,
                              Step, count_sawteeth, iterate, iterations_left_bound, iterator_for, metrics, nearest_root,
                              paper_configuration, plan_arc, v_arc)
from sim.card.dda_bench import random_arc


def best_lattice_path(radius):
    """Minimum sum of squared radial errors over monotone X / Y / diagonal paths
    from (R, 0) to (0, R) (dynamic programming over the whole square)."""
    inf = float("inf")
    cost = {(radius, 0): ((math.hypot(radius, 0) - radius) ** 2, 1, None)}
    for x in range(radius, -1, -1):
        for y in range(0, radius + 1):
            if (x, y) == (radius, 0):
                continue
            here = (math.hypot(x, y) - radius) ** 2
            best = (inf, 0, None)
            for px, py in ((x + 1, y), (x, y - 1), (x + 1, y - 1)):
                if (px, py) in cost and cost[(px, py)][0] + here < best[0]:
                    best = (cost[(px, py)][0] + here, cost[(px, py)][1] + 1, (px, py))
            cost[(x, y)] = best
    points, node = [], (0, radius)
    while node is not None:
        points.append(node)
        node = cost[node][2]
    return points[::-1]


def lattice_point(radius, angle):
    """The lattice point nearest to the circle close to ``angle``."""
    x, y = round(radius * math.cos(angle)), round(radius * math.sin(angle))
    near = [(x + i, y + j) for i in (-1, 0, 1) for j in (-1, 0, 1)]
    return min(near, key=lambda p: abs(math.hypot(*p) - radius))


@pytest.mark.parametrize("variant", [TRADITIONAL, WEIGHTED, IMPROVED])
def test_paper_configuration_reproduces_the_paper_within_one_percent(variant):
    command, options = paper_configuration(variant)
    measured = metrics(iterate(command, **options)).v_arc
    assert measured == pytest.approx(PAPER_V_ARC[variant], rel=0.01)


def test_improved_is_better_than_weighted_better_than_traditional():
    values = [metrics(iterate(c, **o)).v_arc for c, o in map(paper_configuration, (0, 1, 2))]
    assert values[0] > values[1] > values[2]


def test_brute_force_best_path_matches_the_issue_figures():
    points = best_lattice_path(100)
    errors = [abs(math.hypot(x, y) - 100) for x, y in points]
    assert v_arc(points, 100) == pytest.approx(0.064, abs=0.0005)
    assert max(errors) == pytest.approx(0.496, abs=0.0005)


@pytest.mark.parametrize("radius", [100, 1000, 10000, 100000])
def test_precise_mode_reaches_the_accuracy_target(radius):
    result = metrics(iterate(ArcCommand(radius, 0, 0, radius)))
    assert result.v_arc <= 0.10
    assert result.max_radial_error <= 0.75


@pytest.mark.parametrize("radius", [3, 7, 20, 41, 64])
def test_precise_mode_is_close_to_the_best_lattice_path(radius):
    best = v_arc(best_lattice_path(radius), radius)
    precise = metrics(iterate(ArcCommand(radius, 0, 0, radius))).v_arc
    assert precise <= best * 1.15 + 1e-9


def test_paper_example_8_0_to_0_8():
    path = iterate(ArcCommand(8, 0, 0, 8, variant=TRADITIONAL))
    points = path.points()
    assert points[0] == (8, 0) and points[-1] == (0, 8)
    assert sum(s.step_x for s in path.steps) == 8 and sum(s.step_y for s in path.steps) == 8
    assert all(not s.dir_x and s.dir_y for s in path.steps)


def test_line_12_11_gives_evenly_spaced_pulses():
    path = iterate(LineCommand(12, 11))
    for axis, total in (("step_x", 12), ("step_y", 11)):
        clocks = [i for i, s in enumerate(path.steps) if getattr(s, axis)]
        assert len(clocks) == total
        gaps = [b - a for a, b in zip(clocks, clocks[1:])]
        assert max(gaps) - min(gaps) <= 1
    assert path.end == (12, 11)


@pytest.mark.parametrize("dx, dy", [(0, 5), (-7, 0), (-3, -9), (100, -1), (1, 1)])
def test_lines_end_on_their_end_point(dx, dy):
    path = iterate(LineCommand(dx, dy))
    assert path.end == (dx, dy)
    assert len(path.steps) == max(abs(dx), abs(dy))


@pytest.mark.parametrize("variant", [TRADITIONAL, WEIGHTED, IMPROVED, PRECISE])
@pytest.mark.parametrize("seed", range(6))
def test_random_arcs_end_exactly_on_their_end_point(variant, seed):
    rng = random.Random(seed * 10 + variant)
    command = random_arc(rng, radius=rng.uniform(1, 300), variant=variant)
    path = iterate(command)
    assert path.end == (command.xe, command.ye)
    points = path.points()
    assert all(abs(ax - bx) <= 1 and abs(ay - by) <= 1 for (ax, ay), (bx, by) in zip(points, points[1:]))


@pytest.mark.parametrize("ccw", [True, False])
@pytest.mark.parametrize("start", [(50, 0), (0, 50), (30, 40), (-40, -30), (0, -50)])
def test_full_circle_visits_every_quadrant_and_returns(ccw, start):
    path = iterate(ArcCommand(*start, *start, ccw=ccw))
    points = path.points()
    assert points[-1] == start
    assert sum(s.step_x for s in path.steps) == 4 * 50
    # counter-clockwise means a positive signed area (shoelace)
    area = sum(ax * by - bx * ay for (ax, ay), (bx, by) in zip(points, points[1:])) / 2
    assert area == pytest.approx((1 if ccw else -1) * math.pi * 50 ** 2, rel=0.02)


@pytest.mark.parametrize("octant", range(8))
@pytest.mark.parametrize("ccw", [True, False])
def test_precise_arcs_in_every_octant_stay_near_the_circle(octant, ccw):
    angle = (octant + 0.4) * math.pi / 4
    radius = 500
    end_angle = angle + (0.5 if ccw else -0.5)
    command = ArcCommand(*lattice_point(radius, angle), *lattice_point(radius, end_angle), ccw)
    result = metrics(iterate(command))
    assert result.max_radial_error <= 0.75
    assert result.v_arc <= 0.10


@pytest.mark.parametrize("command, message", [
    (ArcCommand(100, 0, 0, 102), "within one step"),
    (ArcCommand(0, 0, 0, 1), "centre"),
    (ArcCommand(5, 0, 0, 0), "centre"),
    (ArcCommand(100, 0, 0, 100, variant=4), "variant"),
    (ArcCommand(100, 0, 0, 100, variant=WEIGHTED, acc_bits=20, lambda_shift=20), "exceeds"),
])
def test_bad_arcs_are_rejected(command, message):
    with pytest.raises(ValueError, match=message):
        plan_arc(command)


def test_radius_too_large_for_the_width_is_rejected():
    with pytest.raises(ValueError, match="too large"):
        plan_arc(ArcCommand(127, 20, 20, 127), coord_width=8)
    with pytest.raises(ValueError, match="too large"):
        plan_arc(ArcCommand(-128, 0, 0, -128), coord_width=8)
    assert plan_arc(ArcCommand(127, 0, 0, 127), coord_width=8).radius == 127


def test_end_within_one_step_is_accepted_and_reached():
    path = iterate(ArcCommand(100, 0, 0, 101))
    assert path.end == (0, 101)


def test_nearest_root():
    for square in range(1, 2000):
        root = nearest_root(square)
        assert all(abs(root * root - square) <= abs(q * q - square) for q in range(0, 50))


def test_sawtooth_count():
    x, y, d = Step(1, 0, 0, 1), Step(0, 1, 0, 1), Step(1, 1, 0, 1)
    idle = Step(0, 0, 0, 1)
    assert count_sawteeth([x, idle, y, d, y, y, x]) == 2
    assert count_sawteeth([d, d, x, x]) == 0


def test_metrics_of_a_known_path():
    path = Path((3, 0), [Step(0, 1, 0, 1), Step(0, 0, 0, 1), Step(1, 1, 0, 1)])
    result = metrics(path, radius=3)
    assert path.points() == [(3, 0), (3, 1), (2, 2)]
    expected = ((math.hypot(3, 1) - 3) ** 2 + (math.hypot(2, 2) - 3) ** 2) / 2
    assert result.v_arc == pytest.approx(expected)
    assert (result.output_steps, result.diagonal_steps, result.iterations) == (2, 1, 3)
    assert (result.interval_min, result.interval_max) == (2, 2)


def _left_along(command):
    """(bound, steps left per axis, iterations left) before every iteration of ``command``."""
    steps = iterate(command).steps
    iterator = iterator_for(command)
    rows = []
    for index in range(len(steps) + 1):
        after = steps[index:]
        rows.append((iterations_left_bound(iterator), iterator.steps_left(),
                     (sum(s.step_x for s in after), sum(s.step_y for s in after)), len(after)))
        if index < len(steps):
            iterator.step()
    return rows


STOP_CASES = [ArcCommand(100, 0, 0, 100), ArcCommand(1000, 0, 0, 1000), ArcCommand(50, 0, 50, 0),
              ArcCommand(30, 40, -40, -30, ccw=False, variant=TRADITIONAL),
              ArcCommand(-12, 5, -12, 5, ccw=False), ArcCommand(10, -1, -10, 1),
              ArcCommand(15, 1, 15, -1), ArcCommand(0, 30, 30, 0, variant=WEIGHTED, lambda_shift=1),
              LineCommand(12, -7), LineCommand(0, 9), LineCommand(-4, -4)]


def _random_stop_cases(count):
    rng = random.Random(5)
    return [random_arc(rng, radius=rng.uniform(1, 300), variant=index % 4) for index in range(count)]


@pytest.mark.parametrize("command", STOP_CASES + _random_stop_cases(12))
def test_steps_left_count_the_remaining_steps_and_bound_the_iterations(command):
    """Steps left per axis equal the steps the path still makes; the bound never exceeds
    the iterations left and reaches 0 with the last one."""
    rows = _left_along(command)
    for bound, left, made, iterations in rows:
        assert left == made
        assert bound <= iterations
    assert rows[-1][0] == 0


@pytest.mark.parametrize("command", [LineCommand(12, -7), LineCommand(-3, 40)])
def test_stop_left_of_a_line_is_exact(command):
    assert all(bound == iterations for bound, _, _, iterations in _left_along(command))


@pytest.mark.parametrize("radius", [100, 1000])
def test_stop_left_of_a_precise_quarter_arc_is_close(radius):
    # iterations run about pi/2 R (one step length per iteration), the bound R: 0.64
    rows = _left_along(ArcCommand(radius, 0, 0, radius))
    ratios = [bound / iterations for bound, _, _, iterations in rows if iterations]
    assert 0.6 <= min(ratios) and ratios[0] == pytest.approx(2 / math.pi, rel=0.02)
