"""The sequencer of a card of more than two axes hands the N-axis interpolator
a LINE's largest |displacement| with its start.

``dda_linear`` takes a line's iteration count T = max |d_i| from
``AxesCommand.largest`` instead of comparing the axes at its load, so the
sequencer (``rtl/regs/axis_operands.py``) must have it final in the clock
of every ``dda.start``, the earliest included: the DDA is always ready here,
so every move starts in the first clock the sequencer can start it.  Seeded
streams of LINEs (any axis mask, axes at rest, the coordinates' extremes)
mixed with helical ARCs and PULSEs, whose larger operands must not leak
into the next LINE, reach it from a FIFO that runs dry at random; at every
start of a LINE, ``largest`` and each ``delta`` are compared with the
command's own displacements.  The same bench checks the helix's RANGE rules
at their edges (AREA 0, AREA at and beyond its ``area_width`` bits in
AREA_LO or AREA_HI, on a card whose AREA fits one word and on one that
needs both), which the sequencer judges on the FIFO's word as it arrives,
and that every helix started hands on its AREA.  On the MyHDL block and its
Verilog in Icarus.
"""
import random

import pytest
from myhdl import always, block

from models import instructions as isa
from models.commands import PulseCommand, stream_words
from models.dda_axes import check_move
from models.dda_plan import AxesLineCommand, ArcCommand
from models.helix_area import area_width
from rtl.regs.sequencer import sequencer, sequencer_ports
from sim.backends.clocking import clock_source, reset_then_step
from sim.backends.icarus import convert_and_cosimulate
from sim.backends.waves import run_traced

HALF_PERIOD = 5
COORD_WIDTH = 14   # narrow: random displacements reach the coordinates' extremes
AREA = (1 << 20) + 3   # a helix's AREA (any not 0 that fits is taken)


def random_commands(rng, axes, count):
    """LINEs, helical ARCs and PULSEs; the edge cases first."""
    low, high = -(1 << (COORD_WIDTH - 1)), (1 << (COORD_WIDTH - 1)) - 1
    commands = [AxesLineCommand((low,) * axes), AxesLineCommand((0,) * axes),
                AxesLineCommand((high,) + (0,) * (axes - 1)), AxesLineCommand((0,) * (axes - 1) + (-1,))]
    while len(commands) < count:
        kind = rng.random()
        if kind < 0.6:
            commands.append(AxesLineCommand(tuple(0 if rng.random() < 0.3 else rng.randint(low, high)
                                                  for _ in range(axes))))
        elif kind < 0.85:
            helix = (0, 0) + tuple(rng.randint(low, high) for _ in range(axes - 2))
            commands.append(ArcCommand(low, high, high, low, helix=helix, area=AREA))
        else:
            commands.append(PulseCommand(tuple(rng.randint(-100, 100) for _ in range(axes))))
    return commands


@block
def _bench(ports, cosim, words, step, cycles, rng):
    clock, reset, fifo = ports["clock"], ports["reset"], ports["fifo"]
    if cosim:
        dut = convert_and_cosimulate(sequencer, "sequencer", ports)
    else:
        dut = sequencer(**ports)

    @always(clock.posedge)
    def fifo_source():
        # a word popped arrives in dout the next clock; the FIFO runs dry now and then, and in the reset
        if fifo.pop and words and reset != reset.active:
            fifo.dout.next = words.pop(0)
        fifo.empty.next = not words or reset == reset.active or rng.random() < 0.2

    return dut, fifo_source, clock_source(clock, 2 * HALF_PERIOD), reset_then_step(clock, reset, cycles, step)


def run_stream(name, axes, commands, rng, cosim, coord_width=COORD_WIDTH):
    """Run ``commands`` through a sequencer of ``axes`` axes; per DDA start
    ("start", the command lines and ``axes_cmd``'s values) and per refusal
    ("refused", the error code, cleared at once), in order."""
    ports = sequencer_ports(coord_width=coord_width, axes=axes)
    control, dda, axes_cmd = ports["control"], ports["dda"], ports["axes_cmd"]
    words = stream_words(commands)
    events = []
    # the DDA and the pulse outputs never keep the sequencer waiting: each move starts at the earliest
    dda.ready.next = 1

    def step(index):
        control.enable.next = 1
        control.clear_error.next = 0
        if control.error_code and not control.clear_error:
            events.append(("refused", int(control.error_code)))
            control.clear_error.next = 1
        if dda.start:
            deltas = tuple(int(axes_cmd.delta(axis)) for axis in range(axes))
            events.append(("start", bool(dda.line), deltas, int(axes_cmd.largest), int(axes_cmd.area)))

    run_traced(_bench(ports, cosim, words, step, 12 * len(words) + 50, rng),
               f"sequencer_axes_{name}_{'icarus' if cosim else 'myhdl'}")
    return events


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
@pytest.mark.parametrize("seed, axes", [(1, 3), (2, 4), (3, 6)])
def test_line_starts_with_its_largest_displacement(seed, axes, cosim):
    rng = random.Random(seed)
    commands = random_commands(rng, axes, 40)
    events = run_stream(f"{seed}_{axes}", axes, commands, rng, cosim)
    assert [event for event in events if event[0] == "refused"] == []
    lines = [event[2:4] for event in events if event[1]]
    # the golden values: each LINE's own displacements and the largest of their magnitudes
    assert lines == [(command.deltas, max(map(abs, command.deltas))) for command in commands
                     if isinstance(command, AxesLineCommand)]


def helices_at_their_limit(axes, coord_width):
    """Helical ARCs with AREA 0, 1, at its largest, one beyond it (a bit above its
    ``area_width`` bits) and with AREA_HI's bits set, with either sign of Z's displacement."""
    bits = area_width(coord_width)
    areas = (0, 1, (1 << bits) - 1, 1 << bits, (1 << bits) + 1, 1 << 32, (1 << 63) | 5, (1 << 32) - 1)
    arcs = []
    for area in areas:
        for delta in (1, -(1 << (coord_width - 1))):
            arcs.append(ArcCommand(10, 0, 0, 10, helix=(0, 0, delta) + (0,) * (axes - 3), area=area))
    return arcs


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
@pytest.mark.parametrize("axes, coord_width", [(3, COORD_WIDTH), (4, 24)])   # AREA of 29 bits, of 49
def test_a_helix_without_an_area_or_with_one_too_wide_is_refused(axes, coord_width, cosim):
    arcs = helices_at_their_limit(axes, coord_width)
    events = run_stream(f"helix_{axes}", axes, arcs, random.Random(axes), cosim, coord_width)
    expected = []
    for arc in arcs:
        try:   # the golden rule: models.dda_axes.check_move (docs/axes.md, RANGE)
            check_move(arc, axes=axes, coord_width=coord_width)
            expected.append(("start", arc.area))
        except ValueError:
            expected.append(("refused", isa.ERROR_CODE["RANGE"]))
    assert {kind for kind, _ in expected} == {"start", "refused"}
    assert [(event[0], event[4] if event[0] == "start" else event[1]) for event in events] == expected
