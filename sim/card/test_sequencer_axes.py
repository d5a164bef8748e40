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
command's own displacements.  On the MyHDL block and its Verilog in Icarus.
"""
import random

import pytest
from myhdl import always, block

from models.commands import PulseCommand, stream_words
from models.dda_plan import AxesLineCommand, ArcCommand
from rtl.regs.sequencer import sequencer, sequencer_ports
from sim.backends.clocking import clock_source, reset_then_step
from sim.backends.icarus import convert_and_cosimulate
from sim.backends.waves import run_traced

HALF_PERIOD = 5
COORD_WIDTH = 14   # narrow: random displacements reach the coordinates' extremes
ITERATIONS = 1 << 20   # a helix's K: at least every helix displacement (the RANGE rule)


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
            commands.append(ArcCommand(low, high, high, low, helix=helix, iterations=ITERATIONS))
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
        # a word popped arrives in dout the next clock; the FIFO runs dry now and then
        if fifo.pop and words:
            fifo.dout.next = words.pop(0)
        fifo.empty.next = not words or rng.random() < 0.2

    return dut, fifo_source, clock_source(clock, 2 * HALF_PERIOD), reset_then_step(clock, reset, cycles, step)


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
@pytest.mark.parametrize("seed, axes", [(1, 3), (2, 4), (3, 6)])
def test_line_starts_with_its_largest_displacement(seed, axes, cosim):
    rng = random.Random(seed)
    ports = sequencer_ports(coord_width=COORD_WIDTH, axes=axes)
    control, dda, axes_cmd = ports["control"], ports["dda"], ports["axes_cmd"]
    commands = random_commands(rng, axes, 40)
    lines = [command.deltas for command in commands if isinstance(command, AxesLineCommand)]
    words = stream_words(commands)
    started = []
    # the DDA and the pulse outputs never keep the sequencer waiting: each move starts at the earliest
    dda.ready.next = 1

    def step(index):
        control.enable.next = 1
        assert not control.error_code, f"command refused at clock {index}"
        if dda.start and dda.line:
            deltas = lines[len(started)]
            started.append(deltas)
            assert [int(axes_cmd.delta(axis)) for axis in range(axes)] == list(deltas), f"deltas at clock {index}"
            assert int(axes_cmd.largest) == max(map(abs, deltas)), f"largest of {deltas} at clock {index}"

    run_traced(_bench(ports, cosim, words, step, 12 * len(words) + 50, rng),
               f"sequencer_axes_{seed}_{axes}_{'icarus' if cosim else 'myhdl'}")
    assert started == lines, f"{len(lines) - len(started)} lines not started: run the bench longer"
