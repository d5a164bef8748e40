"""The narrowest DDA build against the golden model, move by move, on Verilator.

``sim/card/dda_exhaustive.py`` runs every legal arc and every line of the
6-bit build; the whole run (1,527,408 legal arcs in each of two variants,
about 50 minutes each at load 5)
is in the slow set (``python -m bench.dda_exhaustive_figures`` prints its figures),
the default suite runs every line and every arc up to radius 4.
"""
import itertools

import pytest

from models.dda_build import DEFAULT_VARIANTS, IMPROVED
from models.dda_model import ArcCommand, LineCommand
from models.dda_plan import plan_arc, setup_clocks
from sim.card.dda_exhaustive import (DIR_Y, NARROW_WIDTH, STEP_X, STEP_Y, check_move, every_arc, every_line, narrow_dda,
                                     run_all, step_clocks)

# one worker converts and builds the narrow DDA for the module: two would convert into the same
# folder at once and build the model twice
pytestmark = pytest.mark.xdist_group("dda_narrow")


@pytest.fixture(scope="module")
def dda():
    narrow = narrow_dda()
    yield narrow
    narrow.close()


def _small_arcs(radius, **fields):
    starts = {(x, y) for x in range(-radius, radius + 1) for y in range(-radius, radius + 1)
              if x * x + y * y <= radius * radius}
    return every_arc(starts=starts, **fields)


def test_the_first_iteration_follows_the_set_up_clocks(dda):
    """The move is handed to the run at the edge after its set-up clocks
    (docs/dda.md), and its first iteration steps at the edge after that."""
    tally = run_all(dda, [])
    assert tally.offsets == {"line": setup_clocks(NARROW_WIDTH, True) + 1,
                             "arc": setup_clocks(NARROW_WIDTH, False) + 1}


def test_every_line_equals_the_model(dda):
    tally = run_all(dda, ((command, True) for command in every_line()))
    assert tally.moves == 1 << (2 * NARROW_WIDTH)
    assert tally.mismatches == []


@pytest.mark.parametrize("variant", ["precise", "improved"])
def test_every_small_arc_equals_the_model(dda, variant):
    fields = dict(variant=IMPROVED) if variant == "improved" else {}
    tally = run_all(dda, _small_arcs(4, **fields))
    assert tally.moves > 1000 and tally.refused > 100, (tally.moves, tally.refused)
    assert tally.mismatches == []


def test_a_step_off_its_clock_is_a_mismatch(dda):
    """The check can fail: the same RTL judged with the iterations one clock late."""
    tally = run_all(dda, [])
    tally.offsets = {kind: offset + 1 for kind, offset in tally.offsets.items()}
    check_move(dda, LineCommand(5, -3), tally)
    check_move(dda, ArcCommand(3, 0, 0, 3), tally)
    assert len(tally.mismatches) == 2


def test_a_step_held_two_clocks_counts_twice():
    """The harness records pin changes only: STEP high for two clocks is two steps."""
    assert step_clocks([5, 7, 9, 10], [STEP_X, 0, STEP_Y | DIR_Y, DIR_Y], 2, 12) == \
        [(3, STEP_X), (4, STEP_X), (7, STEP_Y | DIR_Y)]
    assert step_clocks([5], [STEP_X], 2, 6) == [(3, STEP_X), (4, STEP_X)]


def test_an_accepted_arc_judged_as_refused_is_a_mismatch(dda):
    tally = run_all(dda, [])
    check_move(dda, ArcCommand(3, 0, 0, 3), tally, accepted=False)
    assert len(tally.mismatches) == 1 and "refused move" in tally.mismatches[0]


@pytest.mark.slow(reason="every legal arc of the 6-bit build, minutes on Verilator; the default suite runs every line and a sample of arcs")
@pytest.mark.parametrize("kind", ["precise", "improved", "refused"])
def test_every_arc_equals_the_model(dda, kind):
    """Every legal arc of the width (every start, every end the set-up
    accepts, both directions) steps exactly as the model, each on its
    iteration's clock, and is over within 4 clocks of its last iteration;
    every refused candidate near the circle gives error and no step."""
    fields = dict(variant=IMPROVED) if kind == "improved" else {}
    moves = every_arc(**fields)
    if kind == "refused":
        moves = ((command, False) for command, accepted in moves if not accepted)
    else:
        moves = ((command, True) for command, accepted in moves if accepted)
    tally = run_all(dda, moves)
    assert tally.mismatches == []
    assert (tally.refused if kind == "refused" else tally.moves) > 300_000


def test_the_candidates_include_every_legal_arc():
    """Every arc the set-up accepts has its end within 2m + 1 of the start's
    square (docs/dda.md), so the candidates' band holds them all: counted
    here against a brute force over every end point, for starts of a few rows."""
    low, high = -(1 << (NARROW_WIDTH - 1)), 1 << (NARROW_WIDTH - 1)
    starts = {(xs, ys) for xs in range(low, high, 3) for ys in (0, 7, -20)}
    brute = 0
    for (xs, ys), xe, ye in itertools.product(starts, range(low, high), range(low, high)):
        command = ArcCommand(xs, ys, xe, ye)
        try:
            plan_arc(command, NARROW_WIDTH, DEFAULT_VARIANTS)
        except ValueError:
            continue
        brute += 1
    listed = sum(1 for command, accepted in every_arc(starts=starts) if accepted and command.ccw)
    assert listed == brute > 0


@pytest.fixture(scope="module")
def axes_dda():
    from sim.card.dda_axes_exhaustive import narrow_axes

    narrow = narrow_axes()
    yield narrow
    narrow.close()


def test_a_sample_of_3d_lines_equals_the_model(axes_dda):
    from sim.card.dda_axes_exhaustive import run_lines, sample_lines

    tally = run_lines(axes_dda, sample_lines(4000, seed=26))
    # the start edge takes the line (it waits), the next edge loads it, the one after iterates it
    assert tally.offsets["line"] == 2
    assert tally.moves == 4000 and tally.mismatches == []


@pytest.mark.slow(reason="every 3-D line of the 6-bit build: 262,144 lines on Verilator")
def test_every_3d_line_equals_the_model(axes_dda):
    from sim.card.dda_axes_exhaustive import every_line, run_lines

    tally = run_lines(axes_dda, every_line())
    assert tally.moves == 1 << (3 * NARROW_WIDTH)
    assert tally.mismatches == []


def test_a_sample_of_helices_equals_the_model(axes_dda):
    from sim.card.dda_axes_exhaustive import run_helices, sample_helices

    tally = run_helices(axes_dda, sample_helices(400, seed=26))
    assert tally.moves == 400 and tally.mismatches == []


@pytest.mark.slow(reason="every arc of the 6-bit build with a helix, the steepest the host takes or -32: 1.5 million moves on Verilator")
def test_every_steepest_helix_equals_the_model(axes_dda):
    from sim.card.dda_axes_exhaustive import every_helix, run_helices

    tally = run_helices(axes_dda, every_helix())
    assert tally.moves > 1_000_000 and tally.mismatches == []
