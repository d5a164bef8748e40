"""Machine jobs for the end-to-end bench: random command streams, the host's
way of streaming them through the FIFO, and the checks of what came out.

``random_job(seed, segments)`` draws LINE and ARC moves (precise arcs between
lattice points of one circle) with SET (feed rate, ramp), DWELL and MARK
between them.  ``streaming_scenario`` is what host software does with a job
longer than the FIFO: burst as many words as there is room for (STATUS
FIFO_LEVEL), then sleep until the LOW_WATER interrupt; every MARK is waited
for, its tag and the position read back.  ``expected_steps`` and
``check_pin_timing`` judge the pins against ``models.dda_model`` and the timing
rules of ``models.card_model.PulseOutModel`` (STEP width, DIR set-up and hold).
"""
import random
from dataclasses import dataclass, field, replace

import numpy as np

from models import instructions as isa
from models import registers as regmap
from models.commands import command_words
from models.dda_model import ArcCommand, LineCommand, iterate, plan_arc
from sim.card.card_bench import PIN_BITS
from sim.card.card_e2e import io_read, io_write, read_position, wait_inta

COORD_WIDTH = 24
# Lattice points of the circle of radius 5 (scaled by the radius factor).
CIRCLE5 = [(5, 0), (4, 3), (3, 4), (0, 5), (-3, 4), (-4, 3), (-5, 0), (-4, -3), (-3, -4), (0, -5), (3, -4),
           (4, -3)]


@dataclass
class Job:
    """Words to stream, and per MARK tag the position the model says the card
    is at when it is reached; ``moves``: the LINE / ARC commands in order."""

    words: list = field(default_factory=list)
    marks: dict = field(default_factory=dict)
    moves: list = field(default_factory=list)
    position: tuple = (0, 0)


def _random_move(rng, max_line, max_scale):
    if rng.random() < 0.6:
        while True:
            dx, dy = rng.randint(-max_line, max_line), rng.randint(-max_line, max_line)
            if (dx, dy) != (0, 0):
                return LineCommand(dx, dy)
    while True:
        scale = rng.randint(1, max_scale)
        start, end = rng.sample(CIRCLE5, 2)
        arc = ArcCommand(scale * start[0], scale * start[1], scale * end[0], scale * end[1], ccw=rng.random() < 0.5)
        try:
            plan_arc(arc, COORD_WIDTH)
        except ValueError:  # the DDA would refuse it: draw again
            continue
        return arc



def random_job(seed, segments, max_line=40, max_scale=8, feeds=(regmap.RATE_MAX, regmap.RATE_MAX),
               dwell=0, mark_every=50, mark_dwell=2000):
    """A job of ``segments`` moves: SET FEED_RATE (log-uniform in ``feeds``)
    now and then, BLEND at random, DWELL up to ``dwell`` clocks now and then,
    a MARK after every ``mark_every`` moves and at the end, each followed by
    a DWELL of ``mark_dwell`` clocks: the card stands still at the MARK's
    position while the host reads it back."""
    rng = random.Random(seed)
    job = Job()
    x, y = 0, 0
    low, high = np.log(feeds[0]), np.log(feeds[1])
    for index in range(segments):
        if rng.random() < 0.05:
            job.words += isa.encode("SET", int(round(np.exp(rng.uniform(low, high)))), INDEX=0)
        if dwell and rng.random() < 0.02:
            job.words += isa.encode("DWELL", rng.randint(1, dwell))
        move = _random_move(rng, max_line, max_scale)
        job.words += command_words(replace(move, blend=rng.random() < 0.5))
        job.moves.append(move)
        dx, dy = (move.dx, move.dy) if isinstance(move, LineCommand) else (move.xe - move.xs, move.ye - move.ys)
        x, y = x + dx, y + dy
        if (index + 1) % mark_every == 0 or index == segments - 1:
            tag = len(job.marks) + 1
            job.words += isa.encode("MARK", TAG=tag & 0xFFFF) + isa.encode("DWELL", mark_dwell)
            job.marks[tag & 0xFFFF] = (x, y)
    job.position = (x, y)
    return job


LONGEST_WAIT = 10 ** 9  # clocks between two interrupts before a job counts as stuck (minutes on Verilator)


def streaming_scenario(job, fifo_depth, results, low_water=None, limit=LONGEST_WAIT):
    """Stream ``job`` into the FIFO as host software would (see the module
    docstring); ``results`` gets ``marks`` [(tag, MARK_TAG read, position)],
    ``position``, ``status``, ``bursts`` (the host's Results)."""
    low_water = fifo_depth // 4 if low_water is None else low_water
    enables = regmap.field_of("INT_ENABLE", LOW_WATER=1, MARK=1, ERROR=1)

    def scenario(bench, target, out):
        yield from io_write(bench, target, "LOW_WATER", low_water)
        yield from io_write(bench, target, "INT_ENABLE", enables)
        yield from io_write(bench, target, "CONTROL", 1)
        results.update(marks=[], bursts=[])
        sent = 0
        while sent < len(job.words) or len(results["marks"]) < len(job.marks):
            if sent < len(job.words):
                status = yield from io_read(bench, target, "STATUS")
                room = fifo_depth - regmap.field_value("STATUS", "FIFO_LEVEL", status)
                chunk = job.words[sent:sent + min(room, 1024)]
                if chunk:
                    burst = yield from bench.host.mem_write(target.mem, chunk)
                    results["bursts"].append(burst)
                    sent += len(burst.data)
            yield from wait_inta(bench, target, limit)
            pending = yield from io_read(bench, target, "INT_STATUS")
            if regmap.field_value("INT_STATUS", "ERROR", pending):
                results["status"] = yield from io_read(bench, target, "STATUS")
                raise AssertionError(f"the card stopped with error {results['status']:#x}")
            if regmap.field_value("INT_STATUS", "MARK", pending):
                tag = yield from io_read(bench, target, "MARK_TAG")
                position = yield from read_position(bench, target)
                results["marks"].append((tag, position))
            yield from io_write(bench, target, "INT_STATUS", pending)
        results["status"] = yield from io_read(bench, target, "STATUS")
        results["position"] = yield from read_position(bench, target)

    return scenario


def _step(sx, sy, dx, dy):
    """(x stepped, y stepped, x up or None, y up or None): a DIR pin counts where its axis steps."""
    return bool(sx), bool(sy), bool(dx) if sx else None, bool(dy) if sy else None


def expected_steps(moves):
    """Every STEP rise of the chained model paths, as ``_step``."""
    return [_step(s.step_x, s.step_y, s.dir_x, s.dir_y) for move in moves
            for s in iterate(move, COORD_WIDTH).steps if s.step_x or s.step_y]


def rise_steps(log):
    """The pins' STEP rises, as ``_step``."""
    return [_step(sx, sy, dx, dy) for _, sx, sy, dx, dy in log.rises]


def check_pin_timing(edges, width=1, setup=1, hold=1, space=None):
    """Every STEP pulse exactly ``width`` clocks high and at least ``space``
    (STEP_SPACE; None: ``width``) low; DIR changes only while STEP is low, ``hold`` clocks or more after a
    fall and ``setup`` or more before a rise (``PulseOutModel``'s rules).
    ``edges``: a PinLog's (clock, state); returns the first violation or None."""
    space = width if space is None else space
    last_rise, last_fall, last_dir = {}, {}, {}
    state = 0
    for clock, new in edges:
        for axis in ("x", "y"):
            step, direction = PIN_BITS[f"step_{axis}"], PIN_BITS[f"dir_{axis}"]
            if (new ^ state) & direction:
                if state & step or new & step:
                    return f"DIR {axis} changed with STEP high at clock {clock}"
                if clock - last_fall.get(axis, -(1 << 40)) < hold:
                    return f"DIR {axis} changed {clock - last_fall[axis]} clocks after STEP fell at clock {clock}"
                last_dir[axis] = clock
            if new & step and not state & step:
                if clock - last_fall.get(axis, -(1 << 40)) < space:
                    return f"STEP {axis} low only {clock - last_fall[axis]} clocks before clock {clock}"
                if clock - last_dir.get(axis, -(1 << 40)) < setup:
                    return f"STEP {axis} rose {clock - last_dir[axis]} clocks after DIR at clock {clock}"
                last_rise[axis] = clock
            if state & step and not new & step:
                if clock - last_rise[axis] != width:
                    return f"STEP {axis} high {clock - last_rise[axis]} clocks (not {width}) at clock {clock}"
                last_fall[axis] = clock
        state = new
    return None
