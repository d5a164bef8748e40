"""The N-axis golden model (``models/dda_axes.py``) against facts that do not come from it.

Golden facts: the ideal straight line ``k d_i / T``, checked with exact
integer arithmetic (the helix, which follows the area its arc sweeps, is
``tests/models/test_helix_area.py``'s); the two-axis golden
model (``LineIterator``), which an N-axis move must repeat on its
plane; the directions of G17, G18 and G19 as RS274/NGC defines them (normals
+Z, +Y, +X, written out here, not read from ``models.axes``).
"""
import random

import pytest

from models.dda_axes import AxesStep, MoveIterator, check_move, iterate_axes, iterations_left_bound, with_area
from models.dda_model import PRECISE, TRADITIONAL, LineIterator
from models.dda_plan import ArcCommand, AxesLineCommand, LineCommand

# RS274/NGC: G17 is the XY plane seen from +Z, G18 the ZX plane seen from +Y, G19 the YZ plane seen from +X;
# G3 turns counter-clockwise as seen from there.
PLANE_CASES = {"G17": ((0, 1), (0, 0, 1)), "G18": ((2, 0), (0, 1, 0)), "G19": ((1, 2), (1, 0, 0))}


def random_line(rng, axes, largest):
    return tuple(rng.randint(-largest, largest) if rng.random() < 0.8 else 0 for _ in range(axes))


LINE_EDGES = [(0, 0, 0), (1, 0, 0), (0, 0, -1), (7, 7, 7), (-7, 7, -7, 7), (5, -4, 3, -2, 1, 0),
              (511, 1, -1), (-511, 511, 510, -1), (2, 1, 1, 1, 1, 1), (1, 2, 3, 4, 5, 6)]


def line_cases(seed, count, largest):
    rng = random.Random(seed)
    return LINE_EDGES + [random_line(rng, rng.randint(2, 6), largest) for _ in range(count)]


def check_line_against_the_ideal(deltas, coord_width=10):
    """Every axis within half a step of k d_i / T after every iteration k, all on
    their end points after iteration T and not before."""
    path = iterate_axes(AxesLineCommand(deltas), len(deltas), coord_width)
    threshold = max(abs(d) for d in deltas)
    positions = path.positions()
    assert len(path.steps) == threshold
    assert positions[-1] == tuple(deltas)
    for k, point in enumerate(positions):
        for p, d in zip(point, deltas):
            # |p - k d / T| <= 1/2, times 2T: exact
            assert 2 * abs(p * threshold - k * d) <= threshold, (deltas, k, point)
    for step in path.steps:  # the major axis steps on every iteration
        assert any(s for s, d in zip(step.steps, deltas) if abs(d) == threshold)


@pytest.mark.parametrize("deltas", line_cases(seed=1, count=30, largest=400))
def test_n_axis_line_stays_within_half_a_step_and_ends_on_iteration_t(deltas):
    check_line_against_the_ideal(deltas)


@pytest.mark.slow(reason="500 random lines of up to 20,000 steps: a sweep of the default test")
@pytest.mark.parametrize("seed", range(4))
def test_n_axis_line_sweep(seed):
    for deltas in line_cases(seed=100 + seed, count=125, largest=20_000):
        check_line_against_the_ideal(deltas, coord_width=24)


@pytest.mark.parametrize("seed", range(3))
def test_an_xy_line_steps_as_the_two_axis_line_iterator_on_every_card(seed):
    rng = random.Random(seed)
    for dx, dy in [(0, 0), (12, 11), (-1, 0), (0, 300)] + [(rng.randint(-200, 200), rng.randint(-200, 200))
                                                            for _ in range(6)]:
        two_axis = LineIterator(LineCommand(dx, dy))
        expected = []
        while not two_axis.finished:
            step = two_axis.step()
            expected.append(((step.step_x, step.step_y), (step.dir_x, step.dir_y)))
        for axes in range(2, 7):
            for command in (LineCommand(dx, dy), AxesLineCommand((dx, dy) + (0,) * (axes - 2))):
                steps = iterate_axes(command, axes).steps
                assert [(s.steps[:2], s.dirs[:2]) for s in steps] == expected, (dx, dy, axes, command)
                assert not any(any(s.steps[2:]) for s in steps)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@pytest.mark.parametrize("name", sorted(PLANE_CASES))
@pytest.mark.parametrize("ccw", [True, False])
@pytest.mark.parametrize("variant", [TRADITIONAL, PRECISE])
def test_arcs_turn_the_way_rs274ngc_says_in_every_plane(name, ccw, variant):
    plane, normal = PLANE_CASES[name]
    command = with_area(ArcCommand(40, -9, -30, 28, ccw, variant, plane=plane, helix=(0, 0, 0, 25)))
    points = [p[:3] for p in iterate_axes(command, 4).points()]  # X, Y, Z relative to the centre
    turns = [sum(n * c for n, c in zip(normal, cross(a, b))) for a, b in zip(points, points[1:])]
    sense = 1 if ccw else -1
    assert all(t * sense >= 0 for t in turns) and sum(turns) * sense > 0
    assert {p[3 - sum(plane)] for p in points} == {0}  # the third linear axis stays


@pytest.mark.parametrize("command", [
    AxesLineCommand((9, -4, 17, 0, -3)), AxesLineCommand((0, 0, 0, 0, 0, -12)), LineCommand(-6, 2),
    with_area(ArcCommand(50, 0, 0, 50, plane=(2, 0), helix=(0, 30))),
    ArcCommand(50, 0, 0, 50, plane=(2, 0), helix=(0, 30), area=8_000),   # AREA above W (4,9xx)
    ArcCommand(50, 0, 0, 50, plane=(2, 0), helix=(0, 30), area=2_000),   # below W
    ArcCommand(-20, 21, -20, 21, ccw=False, plane=(1, 2), helix=(300, 0, 0, -11), area=5_000),
])
def test_iterations_left_bound_never_overstates_and_every_axis_ends_on_its_end(command):
    iterator = MoveIterator(command, 6)
    bounds = []
    while not iterator.finished:
        bounds.append(iterations_left_bound(iterator))
        iterator.step()
    for done, bound in enumerate(bounds):
        assert bound <= len(bounds) - done
    if not isinstance(command, ArcCommand):
        assert bounds == list(range(len(bounds), 0, -1))  # a line's bound is exact
    end = iterate_axes(command, 6).end
    if isinstance(command, ArcCommand):
        u, v = command.plane
        assert (end[u], end[v]) == (command.xe, command.ye)
        assert all(end[a] == h for a, h in enumerate(command.helix) if a not in (u, v))
    else:
        assert end == tuple(command.deltas) + (0,) * (6 - len(command.deltas))


def test_a_step_reports_every_axis():
    step = MoveIterator(AxesLineCommand((3, -1, 0, 2)), 5).step()
    assert isinstance(step, AxesStep) and len(step.steps) == len(step.dirs) == 5
    assert step.dirs == (True, False, True, True, True)


@pytest.mark.parametrize("command, axes, message", [
    (AxesLineCommand((1, 2, 3)), 2, "axis Z is not on a card with 2 axes"),
    (AxesLineCommand((0, 0, 0, 0, 0, 0, 1)), 6, "at most 6"),
    (AxesLineCommand((1 << 9, 0, 0)), 3, "DX = 512 does not fit 10-bit"),
    (ArcCommand(5, 0, 0, 5, plane=(2, 2)), 3, "not two different axes"),
    (ArcCommand(5, 0, 0, 5, plane=(0, 3)), 3, "not two different axes"),
    (ArcCommand(5, 0, 0, 5, plane=(2, 0), helix=(3, 0, 0), area=40), 3, "is an axis of the plane"),
    (ArcCommand(5, 0, 0, 5, helix=(0, 0, 3)), 3, "needs its AREA"),
    (ArcCommand(5, 0, 0, 5, helix=(0, 0, 3), area=0), 3, "needs its AREA"),
    (ArcCommand(5, 0, 0, 5, helix=(0, 0, 3), area=1 << 21), 3, "needs its AREA, 1..2097151"),   # 21 bits on 10
    (ArcCommand(5, 0, 0, 5, helix=(0, 0, 0, 2), area=40), 3, "axis A is not on a card with 3 axes"),
])
def test_the_cards_range_rules(command, axes, message):
    with pytest.raises(ValueError, match=message):
        check_move(command, axes, coord_width=10)
