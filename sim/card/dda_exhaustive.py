"""Every move of a narrow DDA build against the golden model, on Verilator.

At the narrowest coordinate width (``NARROW_WIDTH`` = 6 bits: -32..31) every
legal arc can be run: every start point, every end point the set-up accepts
(``models.dda_plan.plan_arc``: within one step of the start radius, not beyond
the radius reached on the last axis crossing), both directions; and every
line.  ``NarrowDda`` drives the Verilated ``dda_arc`` with ``advance`` held
high (an iteration every two clocks, the fastest the port allows) and reads
the STEP/DIR edges the harness records; ``check_move`` compares them with
the model's iterations (``models.dda_model.iterate``):

* every step on the clock of its iteration, with its direction, nothing else
  (so the move ends exactly at its end point and never steps past it);
* the move over (``busy`` low, ``ready`` high) within ``END_CLOCKS`` of its
  last iteration, no error;
* a refused arc (the candidates the rule rejects near the circle, and the
  centre) gives ``error`` and no step.

The set-up's clocks are the same for every arc (``setup_clocks``), so the
offset from the ``start`` edge to the first iteration is one constant per
kind of move, measured once on a move of each kind; every move must keep it.

    python -m bench.dda_exhaustive_figures      # the whole run, with its figures
"""
import time
from dataclasses import dataclass, field

from models.dda_build import DDA_MIN_WIDTH, DEFAULT_VARIANTS, PRECISE
from models.dda_model import ArcCommand, LineCommand, iterate
from models.dda_plan import plan_arc
from rtl.convert import build_dir, convert_narrow_dda
from sim.backends.verilator.build import build_model
from sim.backends.verilator.model import VerilatedModel

NARROW_WIDTH = DDA_MIN_WIDTH
# clocks after the last iteration's edge by which the run must be idle again
END_CLOCKS = 4
PINS = ("steps_step_x", "steps_dir_x", "steps_step_y", "steps_dir_y")
STEP_X, DIR_X, STEP_Y, DIR_Y = (1 << bit for bit in range(4))



def _points_by_square(coord_width):
    low, high = -(1 << (coord_width - 1)), 1 << (coord_width - 1)
    squares = {}
    for x in range(low, high):
        for y in range(low, high):
            squares.setdefault(x * x + y * y, []).append((x, y))
    return squares


def arc_candidates(coord_width=NARROW_WIDTH, margin=2, starts=None):
    """(xs, ys, xe, ye) for every start point (of ``starts`` if given) and every
    end point whose squared radius is within 2m + 1 + ``margin`` of the start's
    (m = max(|xs|, |ys|)): the legal ends and the nearest refused ones.  Start
    or end at the centre included."""
    squares = _points_by_square(coord_width)
    ordered = sorted(squares)
    for start_square in ordered:
        for xs, ys in squares[start_square]:
            if starts is not None and (xs, ys) not in starts:
                continue
            m = max(abs(xs), abs(ys))
            low, high = start_square - (2 * m - 1) - margin, start_square + 2 * m + 1 + margin
            for end_square in ordered:
                if end_square > high:
                    break
                if end_square >= low:
                    for xe, ye in squares[end_square]:
                        yield xs, ys, xe, ye


def every_arc(coord_width=NARROW_WIDTH, variants=DEFAULT_VARIANTS, starts=None, **fields):
    """(command, accepted) for every candidate arc in both directions (from
    ``starts`` only, if given; ``fields``: variant, lambda_shift, acc_bits;
    the precise mode by default)."""
    fields.setdefault("variant", PRECISE)
    for xs, ys, xe, ye in arc_candidates(coord_width, starts=starts):
        for ccw in (True, False):
            command = ArcCommand(xs, ys, xe, ye, ccw, **fields)
            try:
                plan_arc(command, coord_width, variants)
            except ValueError:
                yield command, False
            else:
                yield command, True


def every_line(coord_width=NARROW_WIDTH):
    low, high = -(1 << (coord_width - 1)), 1 << (coord_width - 1)
    for dx in range(low, high):
        for dy in range(low, high):
            yield LineCommand(dx, dy)


def expected_steps(path):
    """[(iteration, pin state)] of the model's iterations that step."""
    events = []
    for index, step in enumerate(path.steps):
        if step.step_x or step.step_y:
            state = 0
            if step.step_x:
                state |= STEP_X | (DIR_X if step.dir_x else 0)
            if step.step_y:
                state |= STEP_Y | (DIR_Y if step.dir_y else 0)
            events.append((index, state))
    return events


def step_clocks(clocks, states, first, last):
    """[(clock after ``first``, pin state)] of every clock with a STEP high, from the
    recorded edges (``clocks``, ``states``: pin changes only) up to clock ``last``:
    a state with STEP high lasts until the next edge, one step for each clock."""
    ends = [int(clock) for clock in clocks[1:]] + [last + 1]
    return [(clock - first, int(state) & 0xF) for start, state, end in zip(clocks, states, ends)
            if state & (STEP_X | STEP_Y) for clock in range(int(start), end)]


def narrow_model(verilog, top, pins, **held):
    """The Verilated narrow ``top`` of ``verilog``, its ``pins`` recorded, out of reset with
    ``cmd_advance`` and the ports ``held`` set, no edge kept yet."""
    model = VerilatedModel(build_model([verilog], top))
    model.bind_clock("clock")
    model.bind_pins(pins)
    model["reset"] = 0
    model.tick(2)
    model["reset"] = 1
    model["cmd_advance"] = 1
    for name, value in held.items():
        model[name] = value
    model.tick(2)
    model.take_edges()
    return model


class NarrowDda:
    """The Verilated narrow ``dda_arc``, one move at a time."""

    def __init__(self, verilog):
        self.model = narrow_model(verilog, "dda_arc", PINS)
        self.width = self.model.ports["cmd_xs"][1]

    def _coordinate(self, value):
        return value & ((1 << self.width) - 1)

    def start(self, command):
        """Put ``command`` on the port and give it a ``start`` clock; the clock count then."""
        model = self.model
        line = isinstance(command, LineCommand)
        model["cmd_line"] = int(line)
        if line:
            model["cmd_xe"], model["cmd_ye"] = self._coordinate(command.dx), self._coordinate(command.dy)
        else:
            for name in ("xs", "ys", "xe", "ye"):
                model[f"cmd_{name}"] = self._coordinate(getattr(command, name))
            model["cmd_ccw"] = int(command.ccw)
            model["cmd_variant"] = command.variant
            model["cmd_lambda_shift"] = command.lambda_shift
            model["cmd_acc_bits"] = command.acc_bits
        model["cmd_start"] = 1
        model.tick()
        model["cmd_start"] = 0
        return model.clocks

    def run(self, command, clocks):
        """Start ``command`` and run ``clocks`` clocks after the ``start`` edge;
        ([(clock after that edge, pin state)] of the edges with a step, busy, ready)."""
        first = self.start(command)
        self.model.tick(clocks)
        return self._steps(first), bool(self.model["cmd_busy"]), bool(self.model["cmd_ready"])

    def run_refused(self, command, clocks):
        """As ``run``, clock by clock, also telling whether ``error`` came."""
        first = self.start(command)
        error = False
        for _ in range(clocks):
            self.model.tick()
            error |= bool(self.model["cmd_error"])
        return self._steps(first), bool(self.model["cmd_busy"]), bool(self.model["cmd_ready"]), error

    def _steps(self, first):
        clocks, states = self.model.take_edges()
        return step_clocks(clocks, states, first, self.model.clocks)

    def offset(self, command):
        """Clocks from the ``start`` edge to the edge of iteration 0 of ``command``
        (which must step), measured against the model; the run is idle again after."""
        path = iterate(command, self.width)
        expected = expected_steps(path)
        steps, _, ready = self.run(command, 4 * self.width + 40 + 2 * len(path.steps))
        if not (steps and expected and ready):
            raise ValueError(f"{command} does not step or does not end: no offset from it")
        return steps[0][0] - 2 * expected[0][0]

    def close(self):
        self.model.close()


@dataclass
class Tally:
    """What an exhaustive run did."""

    moves: int = 0
    refused: int = 0
    iterations: int = 0
    steps: int = 0
    seconds: float = 0.0
    offsets: dict = field(default_factory=dict)   # "line"/"arc": clocks from start to iteration 0
    mismatches: list = field(default_factory=list)


def check_move(dda, command, tally, accepted=True, keep=20):
    """Run one move on ``dda`` and compare it with the model; mismatches go to ``tally``."""
    if not accepted:
        steps, busy, ready, error = dda.run_refused(command, 4 * dda.width + 40)
        tally.refused += 1
        if steps or busy or not ready or not error:
            _mismatch(tally, keep, command, f"refused move: steps {steps[:3]}, busy {busy}, error {error}")
        return
    kind = "line" if isinstance(command, LineCommand) else "arc"
    offset = tally.offsets[kind]
    path = iterate(command, dda.width)
    expected = expected_steps(path)
    steps, busy, ready = dda.run(command, offset + 2 * len(path.steps) + END_CLOCKS)
    tally.moves += 1
    tally.iterations += len(path.steps)
    tally.steps += len(expected)
    want = [(offset + 2 * index, state) for index, state in expected]
    got = [(clock, _masked(state)) for clock, state in steps]
    if got != want or busy or not ready:
        first = next((i for i, (a, b) in enumerate(zip(got, want)) if a != b), min(len(got), len(want)))
        _mismatch(tally, keep, command, f"step {first}: RTL {got[first:first + 2]}, model "
                  f"{want[first:first + 2]}; {len(got)} of {len(want)} steps; busy {busy}, ready {ready}")


def _masked(state):
    # a DIR line counts only with its STEP
    return state & ((STEP_X | DIR_X) * bool(state & STEP_X) | (STEP_Y | DIR_Y) * bool(state & STEP_Y))


def _mismatch(tally, keep, command, text):
    if len(tally.mismatches) < keep:
        tally.mismatches.append(f"{command}: {text}")
    else:
        tally.mismatches.append("...")


def run_all(dda, moves, tally=None):
    """Check every (command, accepted) of ``moves`` on ``dda``; the ``Tally``."""
    tally = tally or Tally()
    # one move of each kind that steps in its first iteration gives the offsets
    tally.offsets.setdefault("line", dda.offset(LineCommand(1, 1)))
    tally.offsets.setdefault("arc", dda.offset(ArcCommand(2, 0, 0, 2)))
    start = time.monotonic()
    for command, accepted in moves:
        check_move(dda, command, tally, accepted)
    tally.seconds += time.monotonic() - start
    return tally


def narrow_dda(coord_width=NARROW_WIDTH, variants=DEFAULT_VARIANTS):
    """A ``NarrowDda`` of a fresh ``coord_width`` build (converted under build/)."""
    folder = build_dir("dda_narrow", f"w{coord_width}")
    return NarrowDda(convert_narrow_dda(folder, coord_width, variants))
