"""The helix by swept area (``models/helix_area.py``) against facts that do not come from it.

Golden facts: the area the plane's point sweeps, summed here from the path's
own points as the cross product ``|u dv - v du|`` of consecutive points (not
the model's ``area_increment``); the ideal helix at the same angle,
``h theta / Theta``, with theta the angle the plane's point has turned
(``atan2`` of its integer coordinates: its rounding is some 1e-12 of a step,
far inside the bounds tested); and the floor formula of a line DDA over the
area swept, in exact integers.
"""
import math
import random
from dataclasses import replace
from fractions import Fraction

import pytest

from models.dda_axes import MoveIterator, check_move, iterate_axes
from models.dda_model import IMPROVED, PRECISE, TRADITIONAL, WEIGHTED, iterate, plan_arc
from models.dda_plan import ArcCommand
from models.helix_area import arc_area, area_width
from tests.models.random_arcs import random_arc

PLANES = {"G17": (0, 1), "G18": (2, 0), "G19": (1, 2)}
# docs/axes.md: a precise helix by area is within this many steps of the ideal helix at the
# same angle (0.58 the most measured over the 600 helices of bench.axes_figures)
PRECISE_PER_ANGLE = 0.75


def with_rise(command, rise):
    """``command`` with the one linear axis outside its plane rising ``rise``; that axis."""
    other = 3 - sum(command.plane)
    helix = [0, 0, 0]
    helix[other] = rise
    return replace(command, helix=tuple(helix)), other


def plane_sweeps(command, points):
    """The swept area (twice, |u dv - v du| of consecutive plane points) after each point."""
    u, v = command.plane
    total, result = 0, [0]
    for a, b in zip(points, points[1:]):
        total += abs(a[u] * (b[v] - a[v]) - a[v] * (b[u] - a[u]))
        result.append(total)
    return result


def ideal_sweep(command):
    if (command.xs, command.ys) == (command.xe, command.ye):
        return math.tau
    turn = math.atan2(command.ye, command.xe) - math.atan2(command.ys, command.xs)
    return (turn if command.ccw else -turn) % math.tau or math.tau


def check_helix_by_area(command, other, area):
    """The largest deviation of the helix axis from the ideal helix at the same angle, over the
    arc's steps; asserts the exact facts: the arc unchanged, the floor formula at every
    iteration (so never a step lost or two in one iteration), the end with the arc on the end."""
    path = iterate_axes(replace(command, area=area))
    plain = iterate(replace(command, helix=(), plane=(0, 1)))
    u, v = command.plane
    assert [(s.steps[u], s.steps[v], s.dirs[u], s.dirs[v]) for s in path.steps] == \
        [(s.step_x, s.step_y, s.dir_x, s.dir_y) for s in plain.steps]
    positions = path.positions()
    sweeps = plane_sweeps(command, positions)
    assert sweeps[-1] == area
    rise = command.helix[other]
    sign = 1 if rise >= 0 else -1
    for point, swept in zip(positions, sweeps):
        assert point[other] == sign * ((area // 2 + abs(rise) * swept) // area)
    assert positions[-1][other] == rise
    theta, sense = ideal_sweep(command), 1 if command.ccw else -1
    turned, last, worst = 0.0, math.atan2(command.ys, command.xs), 0.0
    for before, point in zip(positions, positions[1:]):
        if (point[u], point[v]) != (before[u], before[v]):
            angle = math.atan2(point[v], point[u])
            turned += math.remainder(angle - last, math.tau) * sense
            last = angle
            worst = max(worst, abs(point[other] - rise * turned / theta))
    return worst


@pytest.mark.parametrize("name", sorted(PLANES))
@pytest.mark.parametrize("ccw", [True, False])
def test_a_precise_helix_by_area_stays_within_a_step_of_the_ideal_helix_at_the_same_angle(name, ccw):
    rng = random.Random(f"area{name}{ccw}")
    for steep in (1.0, 1.0, None, None):   # the steepest the host's rule takes, and a random rise below it
        command = random_arc(rng, PLANES[name], ccw)
        area = arc_area(command)
        steepest = area.total // area.largest
        rise = steepest if steep else max(1, round(steepest * rng.random()))
        command, other = with_rise(command, rise * rng.choice([1, -1]))
        assert check_helix_by_area(command, other, area.total) <= PRECISE_PER_ANGLE


@pytest.mark.parametrize("variant", [TRADITIONAL, WEIGHTED, IMPROVED])
def test_every_variant_drives_the_helix_by_the_area_its_arc_sweeps(variant):
    rng = random.Random(f"area{variant}")
    for name in sorted(PLANES):
        command = random_arc(rng, PLANES[name], rng.random() < 0.5, variant)
        area = arc_area(command)
        command, other = with_rise(command, -(area.total // area.largest))
        check_helix_by_area(command, other, area.total)


@pytest.mark.slow(reason="120 random precise helices of radius 20..5,000 by area, every plane and direction: "
                         "a sweep of the default test")
@pytest.mark.parametrize("name", sorted(PLANES))
def test_helix_by_area_sweep(name):
    rng = random.Random(f"area sweep {name}")
    for ccw in (True, False):
        for _ in range(20):
            command = random_arc(rng, PLANES[name], ccw, radius=math.exp(rng.uniform(math.log(20), math.log(5000))))
            area = arc_area(command)
            rise = max(1, round(area.total // area.largest * rng.choice([1.0, rng.random()])))
            command, other = with_rise(command, rise * rng.choice([1, -1]))
            assert check_helix_by_area(command, other, area.total) <= PRECISE_PER_ANGLE


@pytest.mark.parametrize("variant", [TRADITIONAL, PRECISE])
@pytest.mark.parametrize("seed", range(3))
def test_the_area_of_an_arc_is_the_cross_product_of_its_steps_and_its_iterations_are_k(variant, seed):
    command = random_arc(random.Random(seed), PLANES["G17"], seed % 2 == 0, variant)
    points = iterate(command).points()
    steps = list(zip(points, points[1:]))
    area = arc_area(command)
    assert area.total == plane_sweeps(command, points)[-1]
    assert area.largest == max(abs(a[0] * (b[1] - a[1]) - a[1] * (b[0] - a[0])) for a, b in steps)
    # a diagonal step keeps |u| + |v|: "both" read before or after the step is the same integer
    assert all(abs(a[0]) + abs(a[1]) == abs(b[0]) + abs(b[1]) for a, b in steps if a[0] != b[0] and a[1] != b[1])
    assert area.iterations == len(iterate(command).steps)


@pytest.mark.parametrize("factor", [Fraction(1, 3), Fraction(9, 10), Fraction(11, 10), 5])
def test_a_wrong_area_still_ends_every_axis_on_its_end_point(factor):
    command = random_arc(random.Random(7), PLANES["G18"], True, radius=60)
    area = arc_area(command)
    command, other = with_rise(command, area.total // area.largest)
    wrong = int(area.total * factor)
    path = iterate_axes(replace(command, area=wrong))
    end = path.end
    assert (end[2], end[0], end[other]) == (command.xe, command.ye, command.helix[other])
    # too large: the axis lags and ends after the arc, a step every iteration
    assert len(path.steps) >= area.iterations and (factor < 1 or len(path.steps) > area.iterations)


@pytest.mark.parametrize("area", [0, 1 << area_width(10), None])
def test_the_range_rules_of_a_helix_by_area(area):
    with pytest.raises(ValueError, match="needs its AREA"):
        check_move(ArcCommand(5, 0, 0, 5, helix=(0, 0, 3), area=area), 3, coord_width=10)
    check_move(ArcCommand(5, 0, 0, 5, helix=(0, 0, 3), area=(1 << area_width(10)) - 1), 3, coord_width=10)


@pytest.mark.parametrize("variant", [TRADITIONAL, WEIGHTED, IMPROVED, PRECISE])
def test_the_largest_full_circles_of_a_6_bit_card_sweep_an_area_within_its_width(variant):
    # docs/axes.md: AREA has 2c + 1 bits; a whole turn sweeps about 2 pi R^2 with R < 2^(c-1)
    limit, checked = 1 << 5, 0
    for x in range(-limit + 1, limit):
        for y in range(-limit + 1, limit):
            command = ArcCommand(x, y, x, y, True, variant)
            if not (limit - 1) ** 2 <= x * x + y * y < limit ** 2:   # the outermost ring
                continue
            try:
                plan_arc(command, 6)
            except ValueError:
                continue
            points = iterate(command, 6).points()
            assert arc_area(command, 6).total == plane_sweeps(command, points)[-1] < 1 << area_width(6)
            checked += 1
    assert checked > 50


@pytest.mark.parametrize("seed", range(3))
def test_every_helix_axis_of_a_move_follows_the_area_on_its_own(seed):
    # a 6-axis card: the arc in G18 (Z, X), Y, A, B and C rising by different amounts
    rng = random.Random(seed)
    command = random_arc(rng, PLANES["G18"], seed % 2 == 1)
    area = arc_area(command)
    steepest = area.total // area.largest
    helix = (0, rng.randint(-steepest, steepest), 0, steepest, -rng.randint(0, steepest), -steepest)
    positions = iterate_axes(replace(command, helix=helix, area=area.total), 6).positions()
    for point, swept in zip(positions, plane_sweeps(command, positions)):
        for axis in (1, 3, 4, 5):
            rise = helix[axis]
            assert point[axis] == (1 if rise >= 0 else -1) * ((area.total // 2 + abs(rise) * swept) // area.total)
    assert positions[-1][1] == helix[1] and positions[-1][3:] == helix[3:]


@pytest.mark.parametrize("rise", [25, 31])
def test_a_remainder_far_behind_saturates_and_the_axis_still_ends(rise):
    # AREA 1 on a 6-bit card: the axis leads, stepping on every iteration while its remainder D falls
    # by |h| w - 1 an iteration, until it saturates at -2^13 (docs/axes.md)
    command = ArcCommand(20, 0, 20, 0, helix=(0, 0, rise), area=1)   # a full circle
    iterator = MoveIterator(command, 3, coord_width=6)
    floor, lowest, made = -(1 << area_width(6)), 0, 0
    while not iterator.finished:
        made += iterator.step().steps[2]
        lowest = min(lowest, iterator.follower.remainder[2])
        assert lowest >= floor
    assert made == rise and lowest == floor
