"""Overfill bench of the whole card: the host writes more into the command
FIFO than it can hold while the queue is stopped, and reads registers
between the bursts.

The promise under test (``docs/instructions.md``): every dword the bus
completed is stored, in order, none twice and none extra; the host resumes
where the card stopped it; a register access never waits behind the FIFO
(it completes without retry within PCI's 16-clock initial latency).

The stored words are made visible on the pins by executing them: the
stream is LINE commands along X with alternating sign and seeded lengths,
so each command is one run of STEP_X pulses between DIR_X changes and the
pins give back the executed command sequence exactly
(``sim/card/fifo_scoreboard.py``).
``STATUS.FIFO_LEVEL`` read while the queue is stopped gives the exact count
stored.  On the MyHDL card the FIFO's own write port is recorded as well,
word for word (``taken``); the generated top level in Icarus shows only its
pins.

A run (``Overfill``) stops the queue (``CONTROL.ENABLE`` = 0, or an error
command of each kind, or a long DWELL at the head of the queue), writes
``factor`` times the FIFO depth in linear bursts of 1..``max_burst`` dwords
with random IRDY# waits, then resumes (enable, ``CLEAR_ERROR``,
``SOFT_RESET``, or the DWELL's end), sends what the card did not take, and
waits until everything ran.  ``soak`` runs the same checks with the queue
stopped and started at random times.
"""
import random
from collections import Counter
from dataclasses import dataclass, field

from models import instructions as isa
from models import registers as regmap
from rtl.card import MEM_BAR_BITS
from sim.card.fifo_scoreboard import LINE_WORDS, run_bench, x_lines
from sim.pci.host import HostError, Termination, random_waits

INITIAL_LATENCY = 16        # PCI: TRDY# (or STOP#) by the 16th clock after the address phase
WINDOW_DWORDS = 1 << (MEM_BAR_BITS - 2)
# commands that stop the queue with each error (the values of sim/card/test_regs_fifo.py)
BAD_COMMANDS = {
    "BAD_OPCODE": [0xF << isa.OPCODE_LSB],
    "RESERVED_BITS": [isa.encode("LINE", 1, 1)[0] | 1 << 7, 1, 1],   # bit 7: no field of LINE
    "RANGE": isa.encode("LINE", 1 << 23, 0),
    "DDA_REJECTED": isa.encode("ARC", 10, 0, 0, 20, CCW=1, VARIANT=3),
}
STOPS = ("disabled", "dwell", *BAD_COMMANDS)
RESUMES = ("enable", "clear_error", "soft_reset", "dwell_end")
READ_REGISTERS = ("STATUS", "INT_STATUS", "CONTROL")


@dataclass
class Overfill:
    """One overfill run: how the queue is stopped (``stop``, one of
    ``STOPS``) and resumed (``resume``, one of ``RESUMES``), the FIFO depth,
    the rounds (stop, overfill, resume, run), the dwords offered in each
    stopped stretch (``factor`` times the depth), the longest burst (every
    burst that long with ``fixed_bursts``), the longest LINE, the DWELL's
    clocks and the seed."""

    stop: str = "disabled"
    resume: str = "enable"
    fifo_depth: int = 16
    rounds: int = 1
    factor: float = 3
    max_burst: int = 256
    fixed_bursts: bool = False
    max_line: int = 4
    dwell: int = 2000
    seed: int = 1

    def __post_init__(self):
        if self.stop not in STOPS:
            raise ValueError(f"unknown stop {self.stop!r}: use one of {', '.join(STOPS)}")
        if self.resume not in RESUMES:
            raise ValueError(f"unknown resume {self.resume!r}: use one of {', '.join(RESUMES)}")

    @property
    def held(self):
        """Words of the stream the instruction register takes beside the FIFO
        while the queue is stopped: the first LINE, unless an error stopped
        the fetch."""
        return LINE_WORDS if self.stop in ("disabled", "dwell") else 0


@dataclass
class RegisterAccess:
    """A register access and what the card held then: ``full`` (the card
    refused part of the host's last burst) and ``stopped`` (the queue
    did not run)."""

    name: str
    result: object
    stopped: bool
    full: bool

    @property
    def clocks(self):
        """Clocks from the address phase to the edge that sampled TRDY# (None: never)."""
        return self.result.transactions[0].first_trdy_clock

    @property
    def prompt(self):
        """One bus transaction, no retry, TRDY# within the initial latency."""
        return (len(self.result.transactions) == 1 and self.result.termination is Termination.NORMAL
                and self.result.complete and self.clocks is not None and self.clocks <= INITIAL_LATENCY)


@dataclass
class Stretch:
    """One stopped stretch: the stream's dwords the bus completed in it
    (``taken``), STATUS.FIFO_LEVEL at its end, and after a resume that
    empties the FIFO, STATUS.FIFO_LEVEL read next (else None)."""

    taken: int
    level: int
    level_after: int = None


@dataclass
class OverfillRun:
    """What a run saw.  ``completed``: every dword the bus completed into
    BAR1, in order (from the host's transaction records); ``taken``: the
    words the FIFO took (MyHDL card only, else None); ``commands``: the
    signed LINE lengths the host queued, in the order they must run once
    each; ``runs``: the signed runs of STEP_X pulses on the pins;
    ``stretches``: one ``Stretch`` per round; ``accesses``: every register
    access; ``endings``: how the memory-write transactions ended (counts by
    ``Termination``); ``offered``, ``bursts``, ``clocks``: totals."""

    completed: list = field(default_factory=list)
    taken: list = None
    commands: list = field(default_factory=list)
    runs: list = field(default_factory=list)
    stretches: list = field(default_factory=list)
    accesses: list = field(default_factory=list)
    endings: Counter = field(default_factory=Counter)
    bursts: int = 0
    offered: int = 0
    clocks: int = 0

    def worst_clocks(self, stopped=None, full=None):
        """Longest register access (clocks to TRDY#) among those matching."""
        chosen = [a.clocks for a in self.accesses
                  if (stopped is None or a.stopped == stopped) and (full is None or a.full == full)]
        return max(chosen) if chosen else None

    @property
    def executed(self):
        """FIFO words executed as LINE commands (one run of pulses each)."""
        return LINE_WORDS * len(self.runs)


class _Host:
    """The scenario's view of the card: register accesses checked and
    recorded, bursts into the FIFO window."""

    def __init__(self, bench, io, mem, run, rng, max_burst, fixed_bursts=False):
        self.bench, self.host, self.io, self.mem = bench, bench.host, io, mem
        self.run, self.rng, self.max_burst, self.fixed_bursts = run, rng, max_burst, fixed_bursts
        self.waits = random_waits(rng.randrange(1 << 30), max_waits=3, probability=0.3)
        self.stopped = False
        self.full = False

    def register(self, name, value=None):
        """Read (``value`` None) or write a register: one transaction, no
        retry, TRDY# within the initial latency; the value read."""
        address = self.io + regmap.offset(name)
        try:
            if value is None:
                result = yield from self.host.io_read(address, max_retries=0)
            else:
                result = yield from self.host.io_write(address, value & 0xFFFFFFFF, max_retries=0)
        except HostError as error:
            raise AssertionError(f"{name} {'read' if value is None else 'write'} with the FIFO "
                                 f"{'full' if self.full else 'not full'}: {error}") from None
        access = RegisterAccess(name, result, self.stopped, self.full)
        self.run.accesses.append(access)
        if not access.prompt:
            raise AssertionError(
                f"{name} {'read' if value is None else 'write'} with the FIFO "
                f"{'full' if self.full else 'not full'}: "
                f"{[t.termination.value for t in result.transactions]}, TRDY# at clock {access.clocks}")
        return result.value if value is None else None

    def read_any(self):
        """One of the registers a driver polls, at random."""
        return (yield from self.register(self.rng.choice(READ_REGISTERS)))

    def burst(self, words, retries):
        """Write ``words`` as one access at a random place in the window,
        with random IRDY# waits (giving up after ``retries`` retries in a
        row, as the host's ``HostError`` says); the count the bus completed."""
        start = 0 if self.fixed_bursts else self.rng.randrange(WINDOW_DWORDS - len(words) + 1)
        try:
            result = yield from self.host.mem_write(self.mem + 4 * start, words, irdy_waits=self.waits,
                                                    max_retries=retries)
            transactions = result.transactions
        except HostError as error:
            transactions = error.transactions
        moved = 0
        for transaction in transactions:
            self.run.completed.extend(transaction.data)
            self.run.endings[transaction.termination] += 1
            moved += len(transaction.data)
        self.run.bursts += 1
        self.run.offered += len(words)
        self.full = moved < len(words)
        return moved

    def burst_length(self):
        """1..max_burst, short ones as often as long ones (or max_burst)."""
        if self.fixed_bursts:
            return self.max_burst
        return self.rng.randint(1, self.rng.choice((4, 32, self.max_burst)))

    def send(self, stream, cursor, offered_limit=None, retries=3):
        """Burst ``stream`` from ``cursor`` (each burst given up after
        ``retries`` retries, a register read after each) until it is all
        sent or ``offered_limit`` dwords were offered; the new cursor."""
        offered = 0
        while cursor < len(stream) and (offered_limit is None or offered < offered_limit):
            length = min(self.burst_length(), len(stream) - cursor)
            cursor += yield from self.burst(stream[cursor:cursor + length], retries)
            offered += length
            yield from self.read_any()
        return cursor

    def wait_idle(self, limit=20000):
        """Poll STATUS (every few clocks) until BUSY falls."""
        for _ in range(limit):
            status = yield from self.register("STATUS")
            if not regmap.field_value("STATUS", "BUSY", status):
                return status
            yield from self.bench.clocks(20)
        raise AssertionError("the card stayed busy")

    def wait_error(self, limit=1000):
        """Poll STATUS until ERROR is set; the code."""
        for _ in range(limit):
            status = yield from self.register("STATUS")
            code = regmap.field_value("STATUS", "ERROR", status)
            if code:
                return code
        raise AssertionError("no error")

    def level(self):
        status = yield from self.register("STATUS")
        return regmap.field_value("STATUS", "FIFO_LEVEL", status)


def _stop(card, case):
    """Stop the queue as ``case`` says (the FIFO is empty and the card idle)."""
    card.stopped = True
    if case.stop == "disabled":
        yield from card.register("CONTROL", 0)
        return
    yield from card.register("CONTROL", regmap.field_of("CONTROL", ENABLE=1))
    head = isa.encode("DWELL", case.dwell) if case.stop == "dwell" else BAD_COMMANDS[case.stop]
    moved = yield from card.burst(head, retries=0)
    if moved != len(head):
        raise AssertionError(f"an empty FIFO took {moved} of {len(head)} words")
    if case.stop != "dwell":
        code = yield from card.wait_error()
        if code != isa.ERROR_CODE[case.stop]:
            raise AssertionError(f"STATUS.ERROR {code}, not {case.stop}")


def _resume(card, case):
    """Let the queue run again; whether that dropped the words it held."""
    card.stopped = False
    if case.resume == "enable":
        yield from card.register("CONTROL", regmap.field_of("CONTROL", ENABLE=1))
        return False
    if case.resume == "clear_error":
        yield from card.register("COMMAND", regmap.field_of("COMMAND", CLEAR_ERROR=1))
        return case.stop == "BAD_OPCODE"
    if case.resume == "soft_reset":
        yield from card.register("COMMAND", regmap.field_of("COMMAND", SOFT_RESET=1))
        yield from card.register("CONTROL", regmap.field_of("CONTROL", ENABLE=1))
        return True
    return False   # dwell_end: the queue runs on once the DWELL is over


def overfill(case, run):
    """The scenario of ``case`` (an ``Overfill``), recording into ``run``
    (an ``OverfillRun``): in each round the queue is stopped with the FIFO
    empty, the host offers ``factor`` times the depth (a burst given up
    after one retry), reads FIFO_LEVEL, resumes (sending again what a
    resume dropped, as a host does from its own record), sends the rest of
    the round's commands and waits until the card is idle."""
    rng = random.Random(case.seed)

    def scenario(bench, io, mem):
        card = _Host(bench, io, mem, run, rng, case.max_burst, case.fixed_bursts)
        yield from card.register("FEED_RATE", regmap.RATE_MAX)
        round_words = LINE_WORDS * -(-int((case.factor + 1) * case.fifo_depth) // LINE_WORDS)
        run.commands, stream = x_lines(rng, case.rounds * round_words, case.max_line)
        for start in range(0, len(stream), round_words):
            words = stream[start:start + round_words]
            yield from _stop(card, case)
            cursor = yield from card.send(words, 0, case.factor * case.fifo_depth, retries=1)
            stretch = Stretch(cursor, (yield from card.level()))
            run.stretches.append(stretch)
            if (yield from _resume(card, case)):
                stretch.level_after = yield from card.level()
                cursor = 0
            yield from card.send(words, cursor)
            yield from card.wait_idle()

    return scenario


def soak(seed, fifo_depth, steps):
    """Random soak: bursts (given up after 0..3 retries), register reads,
    CONTROL.ENABLE toggled and idle stretches at random times, DWELLs of up
    to 200 clocks among the LINEs; then the rest is sent with the queue
    running.  Returns (scenario, run) for ``run_bench``."""
    rng = random.Random(seed)
    run = OverfillRun()

    def scenario(bench, io, mem):
        card = _Host(bench, io, mem, run, rng, 64)
        yield from card.register("FEED_RATE", regmap.RATE_MAX)
        run.commands, lines = x_lines(rng, 8 * steps + 4 * fifo_depth, 3)
        stream = []
        for index in range(len(run.commands)):
            stream += lines[LINE_WORDS * index:LINE_WORDS * (index + 1)]
            if rng.random() < 0.05:
                stream += isa.encode("DWELL", rng.randint(0, 200))
        yield from card.register("CONTROL", regmap.field_of("CONTROL", ENABLE=1))
        cursor = 0
        for _ in range(steps):
            action = rng.choices(("burst", "read", "toggle", "idle"), (6, 3, 1, 1))[0]
            if action == "burst" and cursor < len(stream):
                length = min(card.burst_length(), len(stream) - cursor)
                cursor += yield from card.burst(stream[cursor:cursor + length], rng.randint(0, 3))
            elif action == "toggle":
                card.stopped = not card.stopped
                yield from card.register("CONTROL", regmap.field_of("CONTROL", ENABLE=int(not card.stopped)))
            elif action == "idle":
                yield from bench.clocks(rng.randint(1, 300))
            else:
                yield from card.read_any()
        card.stopped = False
        yield from card.register("CONTROL", regmap.field_of("CONTROL", ENABLE=1))
        card.max_burst = 256
        yield from card.send(stream, cursor)
        yield from card.wait_idle()

    return scenario, run


def run_overfill(kind, case, trace=None):
    """Run ``case`` (an ``Overfill``) on ``kind``; the ``OverfillRun``.  ``trace`` as
    ``sim.backends.waves.run_traced`` takes it."""
    run = OverfillRun()
    name = f"overfill_{case.stop}_{case.resume}_{case.fifo_depth}_{kind}"
    return run_bench(kind, case.fifo_depth, overfill(case, run), run, name, trace)
