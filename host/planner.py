"""Planner: ``geometry`` primitives -> the card's command stream.

Rules (docs/host.md explains them):

* Units to steps: every primitive ends on its end point rounded to the
  nearest step (``Machine.steps``); each command starts where the last one
  ended, so no rounding error is carried from one move to the next.
* Arcs onto the lattice: ``host.lattice``, in any plane and with a helix
  ``host.helix``.  When the plane's two axes' scales differ, a circle is an
  ellipse in steps: arcs become chords within ``Machine.chord_tolerance``.
* Axes: a drawing may move as many axes as the machine has (``Machine.axes``);
  a move of another axis is refused with its source line before anything
  is planned.  A move on X and Y alone is the two-axis command.
* Runs: moves joined by BLEND.  A junction blends when both moves are fed
  (or both rapid) at the same feed and the velocity jump at the corner,
  ``2 v sin(angle / 2)``, is at most the start speed (the jump the machine
  takes at every start and stop anyway).  Otherwise, and before a dwell or the
  end, the path stops.  The pieces of one primitive always blend.
* Per run, in the stream before its first move (SET waits for the motion
  before it to end, so settings change only at stops): FEED_RATE for the
  run's feed, RAMP_START for the start feed, RAMP_STEP for the acceleration
  (see ``run_settings``).
* MARK tags at stops, once at least ``Machine.mark_interval`` words have
  passed, and one at the end (a MARK waits for the motion to end, so it
  cannot sit between blended moves).
* DWELL in card clocks.
"""
import math
from dataclasses import dataclass, field, replace

from host import geometry
from host.errors import ProgramError
from host.helix import plane_arc_commands
from host.lattice import line_commands, turn
from host.machine import Machine
from models.axes import AXIS_NAMES
from models.card_model import DECEL_MARGIN
from models.commands import DwellCommand, MarkCommand, SetCommand, command_words, stream_words
from models.dda_axes import MoveIterator
from models.dda_model import ArcCommand, LineCommand
from models.dda_plan import AxesLineCommand
from models.registers import RATE_ONE

MOVES = (LineCommand, AxesLineCommand, ArcCommand)

DWELL_MAX = (1 << 32) - 1
TAG_MODULUS = 1 << 16


@dataclass(frozen=True)
class Entry:
    """One command of the stream and where it came from."""
    command: object
    where: str = ""
    primitive: int = None  # index into the drawing
    run: int = None        # index into Plan.runs (moves only)


@dataclass
class Run:
    """Moves joined by BLEND, and the settings they run with."""
    feed: float          # requested, mm/min
    rapid: bool
    mm_per_iteration: float = 0.0
    feed_rate: int = 0
    ramp_start: int = 0
    ramp_step: int = 0
    iterations: int = 0  # filled by host.check
    capped: bool = False  # FEED_RATE lowered so that the last move can slow down

    def achieved_feed(self, machine):
        """mm/min at FEED_RATE on the run's longest-stepping move."""
        return machine.iterations_per_second(self.feed_rate) * self.mm_per_iteration * 60


@dataclass
class Plan:
    machine: Machine
    drawing: list
    entries: list = field(default_factory=list)
    runs: list = field(default_factory=list)
    marks: dict = field(default_factory=dict)  # tag -> entry index
    end: tuple = (0, 0)

    def words(self):
        return stream_words(entry.command for entry in self.entries)

    def moves(self):
        return [e for e in self.entries if isinstance(e.command, MOVES)]


def plan(drawing, machine=Machine()):
    """The ``Plan`` of ``drawing`` (a list of ``geometry`` primitives) on ``machine``;
    ProgramError for a primitive that moves an axis the machine does not have."""
    drawing = fit_axes(drawing, machine)
    groups = _move_groups(drawing, machine)
    result = Plan(machine, drawing)
    position, runs, stream = (0,) * geometry.dimension(drawing), [], []
    previous = None
    for index, item in enumerate(drawing):
        if isinstance(item, geometry.Dwell):
            stream.append(("dwell", index))
            previous = None
            continue
        commands, position = groups[index]
        if not commands:
            continue
        if previous is None or not _blends(drawing[previous], item, machine):
            runs.append(Run(item.feed, item.rapid))
        stream.append(("move", index, len(runs) - 1, commands))
        previous = index
    result.end = position
    run_moves = [[] for _ in runs]
    for item in stream:
        if item[0] == "move":
            run_moves[item[2]] += item[3]
    for run, moves in zip(runs, run_moves):
        run_settings(run, moves, machine)
    result.runs = runs
    _emit(result, stream)
    return result


def fit_axes(drawing, machine):
    """``drawing`` with points of at most the machine's axes; ProgramError at the
    first primitive that moves, or puts an arc in, an axis beyond them."""
    axes = machine.axes
    if geometry.dimension(drawing) <= axes:
        return drawing
    for item in drawing:
        if isinstance(item, geometry.Dwell):
            continue
        beyond = [a for a in range(axes, len(item.start)) if item.start[a] or item.end[a]]
        beyond += [a for a in getattr(item, "plane", ()) if a >= axes]
        if beyond:
            raise ProgramError(item.where, f"axis {AXIS_NAMES[min(beyond)]}: the machine has {axes} axes "
                                           f"({machine.axis_names})")
    return [item if isinstance(item, geometry.Dwell) else replace(item, start=item.start[:axes], end=item.end[:axes])
            for item in drawing]


def _move_groups(drawing, machine):
    """{primitive index: (commands, end step position)} with the rounding carried forward."""
    groups, position = {}, (0,) * geometry.dimension(drawing)
    for index, item in enumerate(drawing):
        if isinstance(item, geometry.Dwell):
            continue
        end = machine.steps(item.end)
        if isinstance(item, geometry.Line):
            commands = line_commands(position, end, machine.coord_limit)
        elif machine.square_plane(item.plane):
            commands = plane_arc_commands(item, position, end, machine)
        else:
            commands = _chords(item, position, end, machine)
        groups[index] = ([replace(c, blend=True) for c in commands], end)
        position = end
    return groups


def _chords(arc, start, end, machine):
    """LINEs along ``arc`` whose sagitta is at most the chord tolerance."""
    radius = max(arc.start_radius, arc.end_radius)
    step = 2 * math.acos(max(-1.0, 1 - machine.chord_tolerance / radius)) if radius > 0 else math.tau
    parts = max(1, math.ceil(arc.sweep / step))
    commands, here = [], start
    for i in range(1, parts + 1):
        there = end if i == parts else machine.steps(arc.point(i / parts))
        commands += line_commands(here, there, machine.coord_limit)
        here = there
    return commands


def _feed(item, machine):
    return machine.rapid if item.rapid else item.feed


def _blends(before, after, machine):
    """The junction rule: same kind and feed, velocity jump at most the start speed."""
    if before.rapid != after.rapid or before.feed != after.feed:
        return False
    speed = _feed(after, machine) / 60
    jump = 2 * speed * math.sin(geometry.turn_angle(before, after) / 2)
    return jump <= machine.start_feed / 60


def mm_per_iteration(command, machine):
    """Path length of one DDA iteration: a LINE steps its major axis every
    iteration (the length along X, Y, Z, or the rotary axes when only they
    move: ``geometry.path_length``); a precise ARC moves about R / (R + 1)
    step per iteration in its plane, at most one, and a helix's iteration is
    longer by the helix's length over the plane's (its linear axes)."""
    scales = machine.steps_per_mm
    if isinstance(command, LineCommand):
        kx, ky = scales[0], scales[1]
        return math.hypot(command.dx / kx, command.dy / ky) / max(abs(command.dx), abs(command.dy))
    if isinstance(command, AxesLineCommand):
        mm = [d / k for d, k in zip(command.deltas, scales)]
        return geometry.path_length(mm) / max(abs(d) for d in command.deltas)
    scale = scales[command.plane[0]]
    rise = [command.helix[axis] / scales[axis] for axis in command.helix_axes if axis < geometry.LINEAR_AXES]
    if not rise:
        return 1 / scale
    plane_mm = math.hypot(command.xs, command.ys) * turn(command, command.ccw) / scale
    return math.hypot(plane_mm, *rise) / plane_mm / scale


def run_settings(run, moves, machine):
    """FEED_RATE, RAMP_START and RAMP_STEP of ``run`` (its LINE/ARC commands ``moves``).

    FEED_RATE: the run's feed on the move that goes furthest per iteration
    (elsewhere the path is slower, never faster).  RAMP_START: the start
    feed, at most FEED_RATE.  RAMP_STEP: the ramp raises the rate linearly
    with distance, so the acceleration is largest at the top speed:
    ``a = v * RAMP_STEP * f_clk / 65536``; the largest step within the
    machine's acceleration, at least 1.  When the run's last move is too short
    to slow down from FEED_RATE, FEED_RATE is lowered until it can.
    """
    run.mm_per_iteration = max(mm_per_iteration(c, machine) for c in moves)
    per_second = _feed_of(run, machine) / 60 / run.mm_per_iteration
    run.feed_rate = machine.rate_register(per_second)
    run.ramp_start = min(run.feed_rate,
                         machine.rate_register(machine.start_feed / 60 / run.mm_per_iteration))
    if run.ramp_start == run.feed_rate:
        run.ramp_step = 0
        return
    top_speed = machine.iterations_per_second(run.feed_rate) * run.mm_per_iteration
    run.ramp_step = max(1, math.floor(machine.acceleration * RATE_ONE / (top_speed * machine.clock_hz)))
    room = max(MoveIterator(moves[-1], machine.axes, machine.coord_width).steps_left()) - 1 - DECEL_MARGIN
    if math.ceil((run.feed_rate - run.ramp_start) / run.ramp_step) > room:
        run.feed_rate = max(run.ramp_start, run.ramp_start + run.ramp_step * max(room, 0))
        run.capped = True


def _feed_of(run, machine):
    return machine.rapid if run.rapid else run.feed


def _emit(result, stream):
    """Entries from the planned stream: settings, moves with BLEND, dwells, MARKs."""
    machine, entries = result.machine, result.entries
    settings = {}
    state = {"words": 0, "tag": 0}

    def add(command, where="", primitive=None, run=None):
        entries.append(Entry(command, where, primitive, run))
        state["words"] += len(command_words(command))

    def mark(force=False):
        if force or state["words"] >= machine.mark_interval:
            result.marks[state["tag"]] = len(entries)
            add(MarkCommand(state["tag"]))
            state["tag"] = (state["tag"] + 1) % TAG_MODULUS
            state["words"] = 0

    for position, item in enumerate(stream):
        if item[0] == "dwell":
            dwell = result.drawing[item[1]]
            clocks = machine.dwell_clocks(dwell.seconds)
            while clocks > 0:
                add(DwellCommand(min(clocks, DWELL_MAX)), dwell.where, item[1])
                clocks -= DWELL_MAX
            mark()
            continue
        _, index, run_index, commands = item
        run = result.runs[run_index]
        first = position == 0 or stream[position - 1][0] != "move" or stream[position - 1][2] != run_index
        if first:
            for name, value in (("RAMP_START", run.ramp_start), ("RAMP_STEP", run.ramp_step),
                                ("FEED_RATE", run.feed_rate)):
                if settings.get(name) != value:
                    add(SetCommand(name, value), result.drawing[index].where, index)
                    settings[name] = value
        last = position + 1 == len(stream) or stream[position + 1][0] != "move" \
            or stream[position + 1][2] != run_index
        where = result.drawing[index].where
        for number, command in enumerate(commands):
            if last and number + 1 == len(commands):
                command = replace(command, blend=False)
            add(command, where, index, run_index)
        if last:
            mark()
    if not entries or not isinstance(entries[-1].command, MarkCommand):
        mark(force=True)

