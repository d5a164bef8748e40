"""Every 3-D line, and helical arcs, of a narrow N-axis interpolator against the golden model, on Verilator.

The card's interpolator (``rtl/dda/dda_axes.py``) of three axes at the
narrowest coordinate width (``NARROW_WIDTH`` = 6 bits: -32..31 on each
axis) runs its lines through ``dda_linear``.  ``NarrowAxes`` drives the
Verilated ``dda_axes`` with ``advance`` held high for lines (the line unit
iterates once a clock), high every other clock for helices and reads the STEP/DIR edges the harness records;
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

Helices (``run_helices``): an arc of the precise mode in a plane of two
axes, the third moving with the area it sweeps (AREA the arc's W,
``models.helix_area.arc_area``, or a wrong one); the arc iterates every
other clock (its run takes two clocks an iteration), so iteration i is on
clock offset + 2i, the offset measured on a helix-free arc.
``every_helix``: every arc of the 6-bit build in X, Y
(``sim.card.dda_exhaustive.every_arc``, both directions) rising on Z by the
most the host's rule takes (W // max w, up to 31; counter-clockwise) or
falling by 32 (clockwise: the steepest the coordinates allow, mostly
beyond the rule, so that the remainder D goes below 0; the slow set);
``sample_helices``: seeded random arcs in every plane, random rises, a
wrong AREA one time in four (down to 1: D saturates; the default suite).
"""
import itertools
import random
from dataclasses import replace

from models.axes import PLANES
from models.dda_axes import MoveIterator
from models.dda_build import DDA_MIN_WIDTH, PRECISE
from models.dda_plan import ArcCommand, AxesLineCommand, plan_arc
from models.helix_area import arc_area
from rtl.convert import build_dir, convert_block
from sim.card.dda_exhaustive import Tally, _mismatch, every_arc, narrow_model

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
        self.model = narrow_model(verilog, "dda_axes", PINS, cmd_line=1)
        self.width = self.model.ports["axes_cmd_delta_x"][1]

    def put(self, command):
        """Put ``command`` (a line, or an arc with its plane and helix) on the ports."""
        model, ones = self.model, (1 << self.width) - 1
        line = isinstance(command, AxesLineCommand)
        model["cmd_line"] = int(line)
        deltas = command.deltas if line else tuple(command.helix) + (0,) * AXES
        for axis, delta in zip("xyz", deltas):
            model[f"axes_cmd_delta_{axis}"] = delta & ones
        if line:
            model["axes_cmd_largest"] = max(map(abs, deltas))
        if not line:
            for name in ("xs", "ys", "xe", "ye"):
                model[f"cmd_{name}"] = getattr(command, name) & ones
            model["cmd_ccw"], model["cmd_variant"] = int(command.ccw), command.variant
            model["axes_cmd_u"], model["axes_cmd_v"] = command.plane
            model["axes_cmd_area"] = command.area or 0

    def run(self, command, clocks, pace=1):
        """Start ``command`` and run ``clocks`` clocks after the ``start`` edge, ``advance`` high
        in every clock (``pace`` 1) or every other one from the first after that edge (2: an arc's
        pace, so that a helix's axes that go on alone after it keep it);
        ([(clock after that edge, pin state)] of every clock with a step, busy, ready, dones)."""
        model = self.model
        self.put(command)
        model["cmd_start"] = 1
        model["cmd_advance"] = int(pace == 1)
        model.tick()
        model["cmd_start"] = 0
        first = model.clocks
        dones = 0
        for index in range(clocks):
            model["cmd_advance"] = int(index % pace == 0)
            model.tick()
            dones += bool(model["cmd_done"])
        model["cmd_advance"] = 1
        edges, states = model.take_edges()
        ends = [int(clock) for clock in edges[1:]] + [model.clocks + 1]
        steps = [(clock - first, int(state)) for start, state, end in zip(edges, states, ends) if int(state) & STEPS
                 for clock in range(int(start), end)]
        return steps, bool(model["cmd_busy"]), bool(model["cmd_ready"]), dones

    def offset(self, command=AxesLineCommand((1, 1, 1)), pace=1):
        """Clocks from the ``start`` edge to the edge of iteration 0, measured on ``command``
        (a line of one step, or an arc that steps in its first iteration) at ``pace``."""
        steps, _, ready, _ = self.run(command, 4 * self.width + 40, pace)
        if not (steps and ready):
            raise ValueError(f"{command} does not step or does not end: no offset from it")
        return steps[0][0]

    def close(self):
        self.model.close()


def check_line(dda, command, tally, offset, keep=20, pace=1):
    """Run one line (or, ``pace`` 2, a helix) on ``dda`` and compare it with the model;
    mismatches go to ``tally``."""
    expected, iterations = expected_steps(command, dda.width)
    steps, busy, ready, dones = dda.run(command, offset + pace * iterations + END_CLOCKS, pace)
    tally.moves += 1
    tally.iterations += iterations
    tally.steps += len(expected)
    want = [(offset + pace * index, state) for index, state in expected]
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


def helix_of(arc, rise, coord_width=NARROW_WIDTH, area=None):
    """``arc`` (in a plane of two of the three axes) with the third axis rising by
    ``rise(swept)`` (``swept`` its ``ArcArea``), within the coordinates' range, and AREA
    ``area(W)`` (W the arc's own when None)."""
    swept = arc_area(arc, coord_width)
    other = next(axis for axis in range(AXES) if axis not in arc.plane)
    low, high = -(1 << (coord_width - 1)), (1 << (coord_width - 1)) - 1
    helix = tuple(max(low, min(high, rise(swept))) if axis == other else 0 for axis in range(AXES))
    return replace(arc, helix=helix, area=swept.total if area is None else area(swept.total))


def every_helix(coord_width=NARROW_WIDTH):
    """Every arc of the build in X, Y (the precise mode, both directions) with Z rising by the
    most the host's rule takes counter-clockwise and falling by 32 clockwise."""
    for command, accepted in every_arc(coord_width):
        if accepted:
            yield helix_of(command, (lambda a: a.total // a.largest) if command.ccw else (lambda a: -(1 << 5)),
                           coord_width)


def sample_helices(count, seed, coord_width=NARROW_WIDTH):
    """``count`` seeded random helices: arcs of the precise mode in the planes G17, G18, G19 and
    their reverses, the third axis rising by any amount the coordinates allow, AREA the arc's own
    three times in four, else anything from 1 to twice it."""
    rng = random.Random(seed)
    high = (1 << (coord_width - 1)) - 1
    planes = [PLANES[17], PLANES[18], PLANES[19]]
    helices = []
    while len(helices) < count:
        xs, ys = rng.randint(-high, high), rng.randint(-high, high)
        xe, ye = rng.randint(-high, high), rng.randint(-high, high)
        plane = rng.choice(planes)
        arc = ArcCommand(xs, ys, xe, ye, rng.random() < 0.5, PRECISE, plane=plane if rng.random() < 0.5 else plane[::-1])
        try:
            plan_arc(arc, coord_width)
        except ValueError:
            continue
        wrong = rng.random() < 0.25
        helices.append(helix_of(arc, lambda a: rng.randint(-high - 1, high), coord_width,
                                (lambda w: rng.randint(1, 2 * w)) if wrong else None))
    return helices


def run_helices(dda, helices):
    """Check every helix of ``helices`` on ``dda``; the ``Tally``."""
    tally = Tally()
    tally.offsets["arc"] = offset = dda.offset(ArcCommand(2, 0, 0, 2, variant=PRECISE), pace=2)
    for command in helices:
        check_line(dda, command, tally, offset, pace=2)
    return tally


def narrow_axes(coord_width=NARROW_WIDTH):
    """A ``NarrowAxes`` of a fresh three-axis ``coord_width`` build (converted under build/)."""
    from rtl.dda.dda_axes import dda_axes, dda_axes_ports

    folder = build_dir("dda_axes_narrow", f"w{coord_width}")
    return NarrowAxes(convert_block("dda_axes", dda_axes(**dda_axes_ports(AXES, coord_width=coord_width)), folder))
