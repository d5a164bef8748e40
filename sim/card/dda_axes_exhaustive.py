"""Every 3-D line of a narrow N-axis interpolator against the golden model, on Verilator.

The card's interpolator (``rtl/dda/dda_axes.py``) of three axes at the
narrowest coordinate width (``NARROW_WIDTH`` = 6 bits: -32..31 on each
axis) runs its lines through ``dda_linear``.  ``NarrowAxes`` drives the
Verilated ``dda_axes`` with ``advance`` held high (the line unit iterates
once a clock) and reads the STEP/DIR edges the harness records;
``check_line`` compares them with the iterations of
``models.dda_axes.MoveIterator``:

* every step on the clock of its iteration, with its direction, nothing
  else (so every axis ends exactly on its end point);
* the move over (``busy`` low, ``ready`` high) within ``END_CLOCKS`` of its
  last iteration, ``done`` seen once.

The offset from the ``start`` edge to the first iteration is measured on
one line and must hold for every line.  Every line of the 6-bit build is
64**3 = 262,144 lines (the slow set); ``sample_lines`` draws a seeded
sample for the default suite.
"""
import itertools
import random

from models.dda_axes import MoveIterator
from models.dda_build import DDA_MIN_WIDTH
from models.dda_plan import AxesLineCommand
from rtl.convert import build_dir, convert_block
from sim.backends.verilator.build import build_model
from sim.backends.verilator.model import VerilatedModel
from sim.card.dda_exhaustive import Tally, _mismatch

NARROW_WIDTH = DDA_MIN_WIDTH
AXES = 3
END_CLOCKS = 4
# the pins bound, in the harness's order: STEP at bit 2i, DIR at 2i + 1 of axis i
PINS = tuple(f"steps_{kind}_{name}" for name in "xyz" for kind in ("step", "dir"))
STEPS = sum(1 << (2 * axis) for axis in range(AXES))


def every_line(coord_width=NARROW_WIDTH, axes=AXES):
    """Every line of ``axes`` axes of ``coord_width``-bit displacements."""
    values = range(-(1 << (coord_width - 1)), 1 << (coord_width - 1))
    for deltas in itertools.product(values, repeat=axes):
        yield AxesLineCommand(deltas)


def sample_lines(count, seed, coord_width=NARROW_WIDTH, axes=AXES):
    """``count`` seeded random lines, the extremes first."""
    low, high = -(1 << (coord_width - 1)), (1 << (coord_width - 1)) - 1
    rng = random.Random(seed)
    lines = [AxesLineCommand(deltas) for deltas in ((0,) * axes, (low,) * axes, (high,) * axes,
                                                    (high, low) + (1,) * (axes - 2))]
    while len(lines) < count:
        lines.append(AxesLineCommand(tuple(rng.randint(low, high) for _ in range(axes))))
    return lines


def expected_steps(command, coord_width=NARROW_WIDTH, axes=AXES):
    """([(iteration, pin state)] of the model's iterations that step, iterations)."""
    model = MoveIterator(command, axes=axes, coord_width=coord_width)
    events, index = [], 0
    while not model.finished:
        one = model.step()
        state = 0
        for axis, (step, positive) in enumerate(zip(one.steps, one.dirs)):
            if step:
                state |= (1 << (2 * axis)) | ((1 << (2 * axis + 1)) if positive else 0)
        if state:
            events.append((index, state))
        index += 1
    return events, index


def _masked(state):
    """``state`` with a DIR counted only with its STEP."""
    keep = 0
    for axis in range(AXES):
        if state >> (2 * axis) & 1:
            keep |= 3 << (2 * axis)
    return state & keep


class NarrowAxes:
    """The Verilated narrow ``dda_axes`` of three axes, one line at a time."""

    def __init__(self, verilog):
        self.model = VerilatedModel(build_model([verilog], "dda_axes"))
        self.width = self.model.ports["axes_cmd_delta_x"][1]
        self.model.bind_clock("clock")
        self.model.bind_pins(PINS)
        self.model["reset"] = 0
        self.model.tick(2)
        self.model["reset"] = 1
        self.model["cmd_advance"] = 1
        self.model["cmd_line"] = 1
        self.model.tick(2)
        self.model.take_edges()

    def run(self, command, clocks):
        """Start ``command`` and run ``clocks`` clocks after the ``start`` edge;
        ([(clock after that edge, pin state)] of every clock with a step, busy, ready, dones)."""
        model = self.model
        for axis, delta in zip("xyz", command.deltas):
            model[f"axes_cmd_delta_{axis}"] = delta & ((1 << self.width) - 1)
        model["cmd_start"] = 1
        model.tick()
        model["cmd_start"] = 0
        first = model.clocks
        dones = 0
        for _ in range(clocks):
            model.tick()
            dones += bool(model["cmd_done"])
        edges, states = model.take_edges()
        ends = [int(clock) for clock in edges[1:]] + [model.clocks + 1]
        steps = [(clock - first, int(state)) for start, state, end in zip(edges, states, ends) if int(state) & STEPS
                 for clock in range(int(start), end)]
        return steps, bool(model["cmd_busy"]), bool(model["cmd_ready"]), dones

    def offset(self):
        """Clocks from the ``start`` edge to the edge of iteration 0 (measured on a line of one step)."""
        steps, _, ready, _ = self.run(AxesLineCommand((1, 1, 1)), 12)
        if not (steps and ready):
            raise ValueError("a line of one step does not step or does not end: no offset from it")
        return steps[0][0]

    def close(self):
        self.model.close()


def check_line(dda, command, tally, offset, keep=20):
    """Run one line on ``dda`` and compare it with the model; mismatches go to ``tally``."""
    expected, iterations = expected_steps(command, dda.width)
    steps, busy, ready, dones = dda.run(command, offset + iterations + END_CLOCKS)
    tally.moves += 1
    tally.iterations += iterations
    tally.steps += len(expected)
    want = [(offset + index, state) for index, state in expected]
    got = [(clock, _masked(state)) for clock, state in steps]
    if got != want or busy or not ready or dones != 1:
        first = next((i for i, (a, b) in enumerate(zip(got, want)) if a != b), min(len(got), len(want)))
        _mismatch(tally, keep, command, f"step {first}: RTL {got[first:first + 2]}, model "
                  f"{want[first:first + 2]}; {len(got)} of {len(want)} steps; busy {busy}, ready {ready}, "
                  f"done {dones} times")


def run_lines(dda, lines):
    """Check every line of ``lines`` on ``dda``; the ``Tally``."""
    tally = Tally()
    tally.offsets["line"] = offset = dda.offset()
    for command in lines:
        check_line(dda, command, tally, offset)
    return tally


def narrow_axes(coord_width=NARROW_WIDTH):
    """A ``NarrowAxes`` of a fresh three-axis ``coord_width`` build (converted under build/)."""
    from rtl.dda.dda_axes import dda_axes, dda_axes_ports

    folder = build_dir("dda_axes_narrow", f"w{coord_width}")
    return NarrowAxes(convert_block("dda_axes", dda_axes(**dda_axes_ports(AXES, coord_width=coord_width)), folder))
