"""Clock-by-clock bench of ``rtl/dda_arc.py`` against ``models.dda_clocked.ClockedDda``.

``dda_bench(ports, commands, record, ...)`` drives a list of commands through
the ``DdaPort`` (start pulse when ready, one after the other or overlapped, a
seeded random or alternating ``advance`` pattern, stray ``start`` pulses while
not ready) and compares every output with the model after every clock.  The device is the MyHDL block, or with ``verilog`` (a list of
files) a ``Cosimulation`` of the generated Verilog on the same ``ports``.  The moves the outputs made
are collected in ``record`` for the tests.  ``write_view(vcd)`` writes the
run's GTKWave save file.
"""
import math
import random

from myhdl import StopSimulation, block, instance

from models.dda_clocked import ClockedDda
from models.dda_model import ArcCommand, LineCommand, plan_arc
from rtl.dda_arc import dda_arc
from sim.backends.clocking import clock_source
from sim.backends.icarus import cosimulate
from sim.backends.waves import Waveform, write_gtkw

VIEW_GROUPS = {
    "command": ["cmd_start", "cmd_line", "cmd_variant", "cmd_ccw", "cmd_xs", "cmd_ys", "cmd_xe", "cmd_ye"],
    "status": ["cmd_advance", "cmd_ready", "cmd_busy", "cmd_done", "cmd_error", "cmd_quadrant",
               "cmd_blend", "cmd_stop_left"],
    "pulses": ["steps_step_x", "steps_dir_x", "steps_step_y", "steps_dir_y"],
    "setup (MyHDL only)": ["dda_setup.state", "dda_setup.step", "dda_setup.gap", "dda_setup.operand",
                           "dda_setup.root_root", "plan_radius", "plan_totals_diff", "plan_totals_max"],
    "run (MyHDL only)": ["dda_run.quadrant", "dda_run.step_mag_x", "dda_run.step_mag_y", "dda_run.target_x",
                         "dda_run.target_y", "dda_run.acc_x", "dda_run.acc_y", "dda_nearest.error_term",
                         "dda_nearest.bias_in", "dda_nearest.bias_out", "dda_left.difference",
                         "dda_run.crossings"],
}
VIEW_SIGNED = ("cmd_xs", "cmd_ys", "cmd_xe", "cmd_ye", "dda_run.acc_x", "dda_run.acc_y", "plan_totals_diff")
VIEW_DECIMAL = ("dda_run.step_mag_x", "dda_run.step_mag_y", "plan_radius", "plan_totals_max")
OUTPUTS = ("busy", "ready", "done", "error", "quadrant", "stop_left")
PULSES = ("step_x", "step_y", "dir_x", "dir_y")
HALF_PERIOD = 5


class Record:
    """What the device did: one entry per command, with the clock of each output step and
    of each iteration (``ticks``, the clocks after the edges that iterated it)."""

    def __init__(self):
        self.moves = []
        self.clocks = 0

    def begin(self, command):
        self.moves.append(dict(command=command, error=False, done=False, steps=[], ticks=[],
                               start_clock=self.clocks, done_clock=None))

    def current(self):
        return self.moves[-1]


def _drive_command(cmd, command):
    cmd.line.next = isinstance(command, LineCommand)
    cmd.blend.next = command.blend
    if isinstance(command, LineCommand):
        cmd.xe.next, cmd.ye.next = command.dx, command.dy
        return
    cmd.xs.next, cmd.ys.next = command.xs, command.ys
    cmd.xe.next, cmd.ye.next = command.xe, command.ye
    cmd.ccw.next = command.ccw
    cmd.variant.next = command.variant
    cmd.lambda_shift.next = command.lambda_shift
    cmd.acc_bits.next = command.acc_bits


def _observed(cmd, steps):
    values = {name: int(getattr(cmd, name).val) for name in OUTPUTS}
    values.update({name: int(getattr(steps, name).val) for name in PULSES})
    return values


@block
def dda_bench(ports, commands, record, *, verilog=None, seed=1, advance_rate=0.7, idle_gap=3,
              overlap=False, alternate=False):
    """Drive ``commands`` into the device and check it against the model on every clock.

    Each command starts when ``ready``; with ``overlap`` at once (set up while
    the move before it runs), otherwise ``idle_gap`` clocks after ``busy``
    fell.  ``advance`` is high with probability ``advance_rate``, or with
    ``alternate`` in every other clock (the fastest feed rate).  Stray
    ``start`` pulses while not ready must be ignored.
    """
    clock, reset, cmd, steps = ports["clock"], ports["reset"], ports["cmd"], ports["steps"]
    rng = random.Random(seed)
    model = ClockedDda(cmd.coord_width, cmd.variants)

    clock_driver = clock_source(clock, 2 * HALF_PERIOD)

    @instance
    def stimulus():
        reset.next = reset.active
        cmd.start.next = False
        cmd.advance.next = False
        yield clock.negedge
        yield clock.negedge
        reset.next = not reset.active
        pending = list(commands)
        command = None
        expected = dict(model.outputs)
        idle = idle_gap
        while pending or expected["busy"] or idle < idle_gap:
            start = False
            if pending and expected["ready"] and (overlap or (not expected["busy"] and idle >= idle_gap)):
                command = pending.pop(0)
                record.begin(command)
                _drive_command(cmd, command)
                start = True
            elif not expected["ready"]:
                start = rng.random() < 0.01
            if alternate:
                advance = record.clocks % 2 == 0
            else:
                advance = rng.random() < advance_rate
            cmd.start.next = start
            cmd.advance.next = advance
            expected = model.clock(start, advance, command)
            yield clock.negedge
            record.clocks += 1
            observed = _observed(cmd, steps)
            _compare(expected, observed, record)
            _collect(record, observed, model)
            idle = 0 if expected["busy"] else idle + 1
        raise StopSimulation()

    if verilog is None:
        device = dda_arc(**ports)
    else:
        device = cosimulate("dda_arc", ports, verilog)
    return device, clock_driver, stimulus


def _compare(expected, observed, record):
    wanted = {k: int(v) for k, v in expected.items()}
    if wanted != observed:
        move = len(record.moves) - 1
        raise AssertionError(f"clock {record.clocks}, move {move} ({record.current()['command']}): "
                             f"device {observed} != model {wanted}")


def _collect(record, observed, model):
    """File the outputs of the last edge under the moves the model says they belong to."""
    if model.step_move is not None:
        move = record.moves[model.step_move]
        move["ticks"].append(record.clocks)
        if observed["step_x"] or observed["step_y"]:
            move["steps"].append((record.clocks, observed["step_x"], observed["step_y"],
                                  observed["dir_x"], observed["dir_y"]))
    if model.done_move is not None:
        record.moves[model.done_move]["done"] = True
        record.moves[model.done_move]["done_clock"] = record.clocks
    if model.error_move is not None:
        record.moves[model.error_move]["error"] = bool(observed["error"])
        record.moves[model.error_move]["error_clock"] = record.clocks


def end_point(move):
    """Where the recorded step pulses of ``move`` lead from its start point."""
    command = move["command"]
    x, y = (0, 0) if isinstance(command, LineCommand) else (command.xs, command.ys)
    for _, step_x, step_y, dir_x, dir_y in move["steps"]:
        x += (1 if dir_x else -1) * step_x
        y += (1 if dir_y else -1) * step_y
    return x, y


def accepted(command, coord_width=24):
    try:
        plan_arc(command, coord_width)
    except ValueError:
        return False
    return True


def random_arc(rng, coord_width=24, radius=None, span=None, variant=3, ccw=None):
    """A seeded random arc that the model accepts (start and end near one circle)."""
    limit = (1 << (coord_width - 1)) - 1
    while True:
        r = radius or rng.uniform(1, limit)
        start = rng.uniform(0, 2 * math.pi)
        turn = span if span is not None else rng.uniform(0, 2 * math.pi)
        direction = rng.random() < 0.5 if ccw is None else ccw
        end = start + (turn if direction else -turn)
        xs, ys = round(r * math.cos(start)), round(r * math.sin(start))
        xe, ye = round(r * math.cos(end)), round(r * math.sin(end))
        lam = rng.randrange(0, 4) if variant in (1, 2) else 0
        command = ArcCommand(xs, ys, xe, ye, direction, variant, lam, 0)
        if accepted(command, coord_width):
            return command


def write_view(vcd, wave=None):
    """The save file of a DDA bench: command, status, pulses and (MyHDL) the
    datapath (the magnitudes each accumulator adds, |y| and |x| on an arc, the
    accumulators, the radial error term, the steps left); the whole run, the
    marker on the first command's start."""
    wave = wave or Waveform(vcd)
    starts = wave.edges("cmd_start", "1")
    return write_gtkw(vcd, VIEW_GROUPS, signed=VIEW_SIGNED, decimal=VIEW_DECIMAL, optional=True,
                      marker=starts[0] if starts else None)
