"""The N-axis line (``rtl/dda/dda_linear.py``) against the golden model every clock.

Seeded random lines of three and four axes (every sign, an axis at rest,
the major axis on any of them, a line of zero length), loaded back to back
or after a gap, the feed's ``advance`` random; at every clock the steps
and directions of the iteration just made, the iterations left and
``busy`` are compared with ``models.dda_axes.MoveIterator`` run on the same
``AxesLineCommand``; the bench gives each line's largest magnitude
with its load, as the sequencer does.  The same bench runs on the MyHDL
block and on its Verilog in Icarus.
"""
import random

import pytest
from myhdl import block

from models.dda_axes import MoveIterator
from models.dda_plan import AxesLineCommand
from rtl.dda.dda_linear import dda_linear, dda_linear_ports
from sim.backends.clocking import clock_source, reset_then_step
from sim.backends.icarus import convert_and_cosimulate
from sim.backends.waves import run_traced

HALF_PERIOD = 5
COORD_WIDTH = 14   # the card's narrowest build: short lines reach the accumulators' whole range of values


def random_lines(rng, axes, count, largest):
    """``count`` lines of ``axes`` axes, each d in -largest..largest - 1 (a two's complement
    range): some axes at rest, edge cases first."""
    lines = [(0,) * axes, (largest - 1,) + (0,) * (axes - 1), (-largest,) * axes,
             tuple(largest - 1 if axis == axes - 1 else -1 for axis in range(axes))]
    while len(lines) < count:
        lines.append(tuple(0 if rng.random() < 0.2 else rng.randint(-largest, largest - 1) for _ in range(axes)))
    return lines


@block
def _bench(ports, cosim, step, cycles):
    clock, reset = ports["clock"], ports["reset"]
    if cosim:
        dut = convert_and_cosimulate(dda_linear, "dda_linear", ports)
    else:
        dut = dda_linear(**ports)
    return dut, clock_source(clock, 2 * HALF_PERIOD), reset_then_step(clock, reset, cycles, step)


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
@pytest.mark.parametrize("seed, axes, largest", [
    (1, 3, 40), (2, 4, 40),
    pytest.param(3, 6, 1 << (COORD_WIDTH - 1), marks=pytest.mark.slow(
        reason="six axes up to the coordinates' extreme |d| = 2**(W-1): about 150,000 clocks"))])
def test_lines_step_as_the_golden_model_every_clock(seed, axes, largest, cosim):
    rng = random.Random(seed)
    ports = dda_linear_ports(axes=axes, coord_width=COORD_WIDTH)
    line, steps = ports["line"], ports["steps"]
    waiting = random_lines(rng, axes, 24, largest)
    # the lines' iterations at the mean advance rate, with room for the gaps between them
    cycles = int(sum(max(map(abs, deltas)) for deltas in waiting) / 0.75 * 1.2) + 400
    state = {"model": None, "expected": (False,) * axes, "dirs": (True,) * axes, "left": 0}
    done = []

    def step(index):
        assert tuple(bool(steps.step(a)) for a in range(axes)) == state["expected"], f"steps at clock {index}"
        if state["model"] is not None:
            assert tuple(bool(steps.dir(a)) for a in range(axes)) == state["dirs"], f"dirs at clock {index}"
        assert int(line.left) == state["left"], f"iterations left at clock {index}"
        assert bool(line.busy) == (state["left"] != 0), f"busy at clock {index}"
        model = state["model"]
        finished = model is None or model.finished
        # the next line comes as soon as this one ends (no gap), or a few clocks later
        load = finished and bool(waiting) and rng.random() < 0.6
        advance = rng.random() < 0.75
        line.load.next, line.advance.next = load, advance
        state["expected"] = (False,) * axes
        if load:
            deltas = waiting.pop(0)
            for axis, delta in enumerate(deltas):
                line.magnitude(axis).next, line.positive(axis).next = abs(delta), delta >= 0
            line.largest.next = max(map(abs, deltas))
            model = state["model"] = MoveIterator(AxesLineCommand(deltas), axes=axes, coord_width=COORD_WIDTH)
            done.append(deltas)
        elif advance and not finished:
            iteration = model.step()
            state["expected"], state["dirs"] = iteration.steps, iteration.dirs
        if model is not None:
            state["left"] = max(model.steps_left())
            state["dirs"] = model.follower.dirs

    run_traced(_bench(ports, cosim, step, cycles), f"dda_linear_{seed}_{axes}_{'icarus' if cosim else 'myhdl'}")
    assert not waiting and state["model"].finished, f"{len(waiting)} lines left: run the bench longer"
    assert len(done) == 24
