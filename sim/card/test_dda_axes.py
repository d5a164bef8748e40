"""The card's N-axis interpolator (``rtl/dda/dda_axes.py``) against the golden model.

Chains of lines over N axes and arcs in planes of any two axes (G17, G18,
G19 and the reversed pairs; X, Y on two axes), on more than two axes
helices among them (the other axes moving with the area the arc sweeps,
AREA the arc's own W mostly, a wrong one now and then so that the helix
ends before or after the arc; rises mostly within the host's rule, one
step an iteration at most, now and then steeper), each started as soon as the interpolator is
ready (the sequencer's way: set up while the move before runs), the feed's
``advance`` random but never in two clocks running.  Checked against
``models.dda_axes.MoveIterator`` run on the same commands, one after the
other: the steps and directions of every iteration that steps (in order),
the advances from the first step to the last (every iteration of the chain,
so no advance is lost between moves: no gap), ``stop_left`` of a line that
does not blend (its iterations left, exactly), ``done`` once per move with
its last step.  The same bench runs on the MyHDL block and its Verilog in
Icarus.
"""
import random
from dataclasses import replace

import pytest
from myhdl import block

from models.dda_axes import MoveIterator
from models.helix_area import arc_area
from models.dda_build import IMPROVED, PRECISE
from models.dda_plan import ArcCommand, AxesLineCommand
from rtl.dda.dda_axes import dda_axes, dda_axes_ports
from sim.backends.clocking import clock_source, reset_then_step
from sim.backends.icarus import convert_and_cosimulate
from sim.backends.waves import run_traced

HALF_PERIOD = 5
COORD_WIDTH = 14
# arcs about the centre (start, end) on circles of integer points, in the plane's (u, v); every
# move is long enough (50 iterations or more) for the next one's set-up to end before it does
ARCS = [((40, 0), (0, 40)), ((30, 40), (-40, 30)), ((-30, -40), (40, -30)), ((25, 0), (25, 0))]
MAJOR = (50, 60)   # a line's longest displacement


def random_helix(rng, arc, axes):
    """``arc`` with a helix on some of the other axes (up to W / max w steps each, the host's rule, or
    now and then up to K), AREA W the arc's own (three times in four) or off by up to a third (the
    helix ends before or after the arc)."""
    others = [axis for axis in range(axes) if axis not in arc.plane]
    swept = arc_area(arc, COORD_WIDTH)
    area = swept.total
    if rng.random() < 0.25:
        area = max(1, area + rng.randint(-area // 3, area // 3))
    steepest = swept.iterations if rng.random() < 0.2 else max(1, swept.total // swept.largest)
    helix = [0] * axes
    for axis in rng.sample(others, rng.randint(1, len(others))):
        helix[axis] = rng.choice((-1, 1)) * rng.randint(1, steepest)
    return replace(arc, helix=tuple(helix), area=area)


def random_moves(rng, axes, count, helices=False):
    """``count`` moves: lines of up to ``axes`` axes and arcs in random planes (with ``helices``
    helical mostly), random BLEND."""
    moves = []
    for index in range(count):
        blend = rng.random() < 0.5
        if index % 2:
            (xs, ys), (xe, ye) = rng.choice(ARCS)
            plane = tuple(rng.sample(range(axes), 2)) if axes > 2 else (0, 1)   # two axes: X, Y only
            arc = ArcCommand(xs, ys, xe, ye, ccw=rng.random() < 0.5, variant=rng.choice((IMPROVED, PRECISE)),
                             blend=blend, plane=plane)
            moves.append(random_helix(rng, arc, axes) if helices and rng.random() < 0.8 else arc)
        else:
            deltas = [0 if rng.random() < 0.25 else rng.randint(-MAJOR[1], MAJOR[1]) for _ in range(axes)]
            if axes == 2 or rng.random() < 0.2:
                deltas[2:] = [0] * (axes - 2)   # on X and Y alone: the two-axis card's line
            major = rng.randrange(axes if any(deltas[2:]) else 2)
            deltas[major] = rng.choice((-1, 1)) * rng.randint(*MAJOR)
            deltas = tuple(deltas)
            moves.append(AxesLineCommand(deltas, blend=blend))
    return moves


def expected(moves, axes):
    """The golden chain: [(steps, dirs of the stepping axes)] of every iteration that steps,
    the iterations from the first step to the last, and per move the iterations left after each."""
    iterations, stepping = [], []
    for move in moves:
        model = MoveIterator(move, axes=axes, coord_width=COORD_WIDTH)
        while not model.finished:
            one = model.step()
            left = max(model.steps_left()) if isinstance(move, AxesLineCommand) and not move.blend else None
            iterations.append((one, left))
    for one, left in iterations:
        if any(one.steps):
            stepping.append((one.steps, tuple(d for s, d in zip(one.steps, one.dirs) if s), left))
    marks = [index for index, (one, _) in enumerate(iterations) if any(one.steps)]
    return stepping, marks[-1] - marks[0] + 1


def drive(cmd, axes_cmd, move):
    """Put ``move`` on the command lines."""
    line = isinstance(move, AxesLineCommand)
    cmd.line.next, cmd.blend.next = line, move.blend
    if line:
        cmd.xs.next, cmd.ys.next, cmd.xe.next, cmd.ye.next = 0, 0, move.deltas[0], move.deltas[1]
        if axes_cmd.axes > 2:
            for axis, delta in enumerate(move.deltas):
                axes_cmd.delta(axis).next = delta
            axes_cmd.largest.next = max(map(abs, move.deltas))
    else:
        cmd.xs.next, cmd.ys.next, cmd.xe.next, cmd.ye.next = move.xs, move.ys, move.xe, move.ye
        cmd.ccw.next, cmd.variant.next = move.ccw, move.variant
        cmd.lambda_shift.next, cmd.acc_bits.next = move.lambda_shift, move.acc_bits
        if axes_cmd.axes > 2:
            axes_cmd.u.next, axes_cmd.v.next = move.plane
            helix = tuple(move.helix) + (0,) * axes_cmd.axes
            for axis in range(axes_cmd.axes):
                axes_cmd.delta(axis).next = helix[axis]
            axes_cmd.area.next = move.area or 0


def model_iterations(move, axes):
    """The iterations of ``move`` in the golden model."""
    model, count = MoveIterator(move, axes=axes, coord_width=COORD_WIDTH), 0
    while not model.finished:
        model.step()
        count += 1
    return count


@block
def _bench(ports, cosim, step, cycles):
    clock, reset = ports["clock"], ports["reset"]
    dut = convert_and_cosimulate(dda_axes, "dda_axes", ports) if cosim else dda_axes(**ports)
    return dut, clock_source(clock, 2 * HALF_PERIOD), reset_then_step(clock, reset, cycles, step)


def run_chain(axes, seed, count, cosim, helices=False):
    """Run ``count`` random moves on a card of ``axes`` axes; (seen, advances, dones, moves)."""
    rng = random.Random(seed)
    ports = dda_axes_ports(axes, coord_width=COORD_WIDTH)
    cmd, axes_cmd, steps = ports["cmd"], ports["axes_cmd"], ports["steps"]
    moves = random_moves(rng, axes, count, helices)
    waiting = list(moves)
    seen, state = [], {"advanced": False, "started": False, "advances": [], "dones": 0}
    all_ones = (1 << len(cmd.stop_left)) - 1

    def step(index):
        stepped = tuple(bool(steps.step(a)) for a in range(axes))
        if any(stepped):
            dirs = tuple(bool(steps.dir(a)) for a, s in enumerate(stepped) if s)
            seen.append((stepped, dirs, int(cmd.stop_left), index))
        if state["advanced"]:
            state["advances"].append((index, any(stepped)))
        state["dones"] += bool(cmd.done)
        assert not cmd.error, f"a move was rejected at clock {index}"
        start = bool(waiting) and bool(cmd.ready) and not state["started"]
        cmd.start.next = start
        if start:
            drive(cmd, axes_cmd, waiting.pop(0))
        state["started"] = start
        advance = not state["advanced"] and rng.random() < 0.7
        cmd.advance.next = advance
        state["advanced"] = advance

    # the chain's iterations at the advance's mean rate (0.41 a clock) with room, and each move's set-up
    cycles = int(sum(model_iterations(move, axes) for move in moves) / 0.35) + 150 * count + 400
    name = f"dda_axes_{axes}_{seed}{'_helix' if helices else ''}_{'icarus' if cosim else 'myhdl'}"
    run_traced(_bench(ports, cosim, step, cycles), name)
    assert not waiting, f"{len(waiting)} moves never started"
    return seen, state["advances"], state["dones"], moves, all_ones


@pytest.mark.parametrize("cosim", [False, pytest.param(True, marks=pytest.mark.slow(
    reason="the generated Verilog: the 6-bit exhaustive sample on Verilator checks it by default"))],
    ids=["myhdl", "icarus"])
@pytest.mark.parametrize("axes, seed", [(2, 1), (3, 2), pytest.param(4, 3, marks=pytest.mark.slow(
    reason="a fourth axis: the same routing and line unit as three, another 10 s a back end"))])
def test_chained_lines_and_arcs_step_as_the_golden_model(axes, seed, cosim):
    check_chain(axes, seed, cosim, helices=False)


@pytest.mark.parametrize("cosim", [False, pytest.param(True, marks=pytest.mark.slow(
    reason="the generated Verilog: the card's end-to-end helices run it on Icarus and Verilator by default"))],
    ids=["myhdl", "icarus"])
@pytest.mark.parametrize("axes, seed", [(3, 16), pytest.param(3, 14, marks=pytest.mark.slow(reason="more chains")),
                                        pytest.param(4, 6, marks=pytest.mark.slow(reason="more chains")),
                                        pytest.param(5, 7, marks=pytest.mark.slow(reason="more chains"))])
def test_chained_helices_lines_and_arcs_step_as_the_golden_model(axes, seed, cosim):
    check_chain(axes, seed, cosim, helices=True)


def check_chain(axes, seed, cosim, helices):
    """Every stepping iteration, the advances and the dones of a random chain as the golden model's."""
    seen, advances, dones, moves, all_ones = run_chain(axes, seed, 8, cosim, helices)
    golden, iterations = expected(moves, axes)
    assert [(s, d) for s, d, _, _ in seen] == [(s, d) for s, d, _ in golden]
    # a line that does not blend: stop_left is its iterations left, exactly; a blending one all ones
    for (_, _, stop_left, index), (_, _, left) in zip(seen, golden):
        if left is not None:
            assert stop_left == left, f"stop_left at clock {index}"
    first, last = seen[0][3], seen[-1][3]
    assert sum(1 for index, _ in advances if first <= index <= last) == iterations, "an advance was lost"
    assert dones == len(moves)
