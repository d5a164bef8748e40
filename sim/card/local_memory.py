"""Memory back end on ``rtl.interfaces.LocalBus`` for PCI target benches.

Two dword arrays, space 0 (the I/O BAR) and space 1 (the memory BAR).  Each
request waits a programmable number of clocks (``latency``) and is then
answered with ``ready`` (the transfer happens at that clock edge) or, with
probability ``retry_rate``, with ``retry`` (nothing happens).  All random
choices come from one seeded generator, so a bench is reproducible.

Writes to space 1 follow ``LocalBus.room``: the memory promises to take a
number of them (``room``: always, or as a policy grants), raises ``room``
while it has promised ``LocalBus.ROOM_PLACES`` or more, and never answers
``retry`` to a promised write; only a write that comes while nothing is
promised can be refused.

A request that the target withdraws before it is answered (for instance
after it stopped the PCI transaction on the latency rules) is counted in
``abandoned`` and has no effect.  Misuse of the bus (read and write at once,
an unaligned or out-of-range address) raises ``ValueError``.
"""
import random

from myhdl import Signal, always, block, instance, now

from rtl.interfaces import LocalBus

ROOM_PLACES = LocalBus.ROOM_PLACES

NOT_READY_DATA = 0xBAD0BAD0  # rdata while not ready: a target that samples it shows up


class LocalMemory:
    """State of the back end.

    io_bytes / mem_bytes: sizes of the two spaces; latency: clocks a request
    waits before its answer: an int, a (low, high) range drawn per request,
    or a function ``(rng, space, addr, is_write) -> int``; retry_rate:
    probability that a request is answered with retry; seed: of the
    generator; schedule: optional function ``(number, space, addr,
    is_write) -> (latency, retry)`` that overrides both for request
    ``number`` (0, 1, ... in order of appearance).  room: the writes to
    space 1 the memory promises to take: None, every one (``retry`` and the
    retry of a schedule then only reach reads and space 0); or a function
    ``(rng, clock, promised) -> promised`` called at every rising edge (after
    that edge's transfer) with its own seeded generator, the edge count and
    the writes still promised, returning the new promise, which may not be
    smaller.  ``promised`` is that count (None: unbounded), ``space1_writes``
    counts the space-1 writes taken.  ``log`` lists every transfer as (time,
    space, addr, be, 'r'/'w', data).
    """

    def __init__(self, io_bytes=64, mem_bytes=4096, latency=0, retry_rate=0.0, seed=1,
                 schedule=None, room=None):
        if io_bytes % 4 or mem_bytes % 4 or io_bytes <= 0 or mem_bytes <= 0:
            raise ValueError("space sizes must be positive multiples of 4 bytes")
        if not 0.0 <= retry_rate <= 1.0:
            raise ValueError(f"retry_rate must be within 0..1, not {retry_rate}")
        self.spaces = [[0] * (io_bytes // 4), [0] * (mem_bytes // 4)]
        self.latency = latency
        self.retry_rate = retry_rate
        self.rng = random.Random(seed)
        self.log = []
        self.schedule = schedule
        self.requests = 0
        self.retries = 0
        self.abandoned = 0
        self.room = room
        self.room_rng = random.Random(f"room {seed}")
        self.promised = None if room is None else 0
        self.space1_writes = 0
        self.edges = 0

    def read(self, space, addr):
        """Dword at byte offset ``addr`` of ``space`` (no bus traffic)."""
        return self.spaces[space][self._index(space, addr)]

    def write(self, space, addr, value, be=0xF):
        """Merge ``value`` under byte enables ``be`` (no bus traffic)."""
        index = self._index(space, addr)
        mask = sum(0xFF << (8 * b) for b in range(4) if be >> b & 1)
        self.spaces[space][index] = (self.spaces[space][index] & ~mask) | (value & mask)

    def _index(self, space, addr):
        if addr & 3:
            raise ValueError(f"local address {addr:#x} is not dword aligned")
        if not 0 <= addr < 4 * len(self.spaces[space]):
            raise ValueError(f"local address {addr:#x} outside space {space}")
        return addr // 4

    def plan(self, space, addr, is_write):
        """(latency, retry) of a new request."""
        number = self.requests
        self.requests += 1
        if self.schedule is not None:
            wait, retry = self.schedule(number, space, addr, is_write)
        else:
            if callable(self.latency):
                wait = self.latency(self.rng, space, addr, is_write)
            elif isinstance(self.latency, tuple):
                wait = self.rng.randint(*self.latency)
            else:
                wait = self.latency
            retry = self.retry_rate > 0 and self.rng.random() < self.retry_rate
        return wait, retry and not self.promises(space, is_write)

    def promises(self, space, is_write):
        """Whether a write to ``space`` is promised (so it must be taken)."""
        return is_write and space == 1 and (self.promised is None or self.promised > 0)

    def took(self, space, is_write):
        """Account for a transfer: a space-1 write uses one promised place."""
        if is_write and space == 1:
            self.space1_writes += 1
            if self.promised:
                self.promised -= 1

    def grant(self):
        """The promise after a rising edge out of reset: the policy's choice."""
        self.edges += 1
        if self.room is not None:
            promised = self.room(self.room_rng, self.edges, self.promised)
            if promised < self.promised:
                raise ValueError(f"local memory: room policy took back a promise "
                                 f"({self.promised} -> {promised}) at edge {self.edges}")
            self.promised = promised

    def shows_room(self):
        """``LocalBus.room`` for the present promise."""
        return self.promised is None or self.promised >= ROOM_PLACES


@block
def local_memory(clock, reset, local, memory):
    """Serve ``local`` (a LocalBus) from ``memory`` (a LocalMemory).

    clock, reset: the card's clock and reset.  ``ready``/``retry`` are
    combinational from the request once it has waited its latency, so a
    latency of 0 answers in the clock the request appears.

        clock   _/~\\_/~\\_/~\\_/~\\_
        re      __/~~~~~~~~~~~\\___      latency 1 for A0, 0 for A1
        addr    --< A0      >< A1>--
        ready   ________/~~~~~~~~\\___
        rdata   --------< D0 >< D1>--
    """
    # "since": when the request took its present value (changes in the same
    # time step are one request settling through delta cycles, not a new
    # one); "waited": rising edges it has been waiting; "tick" wakes the
    # answer process up after every edge.
    current = {"key": None, "plan": None, "since": None, "waited": 0}
    tick = Signal(bool(0))
    request_signals = (local.we, local.re, local.space, local.addr, local.be, local.wdata, tick)

    def request_key():
        if not (local.we.val or local.re.val):
            return None
        return (int(local.space.val), int(local.addr.val), int(local.be.val),
                bool(local.we.val), int(local.wdata.val) if local.we.val else None)

    def follow(key):
        if key == current["key"]:
            return
        if current["since"] == now():
            if current["plan"] is not None:  # undo the draw for a passing value
                memory.rng.setstate(current["rng"])
                memory.requests -= 1
        else:
            if current["key"] is not None:
                memory.abandoned += 1
            current["waited"] = 0
        current["plan"] = None
        current["key"], current["since"] = key, now()

    @instance
    def answer():
        while True:
            key = request_key()
            follow(key)
            if key is not None and current["plan"] is None:
                current["rng"] = memory.rng.getstate()
                current["plan"] = memory.plan(key[0], key[1], key[3])
            wait, retry = current["plan"] or (0, False)
            due = key is not None and current["waited"] >= wait
            local.ready.next = due and not retry
            local.retry.next = due and retry
            readable = due and not retry and not key[3] and _in_range(memory, key)
            local.rdata.next = memory.read(key[0], key[1]) if readable else NOT_READY_DATA
            local.room.next = memory.shows_room()   # changes only at the edges (step)
            yield request_signals

    @always(clock.posedge, reset.negedge)
    def step():
        key = current["key"]
        if reset.val == reset.active or key is None:
            current.update(key=None, plan=None, since=None, waited=0)
        elif local.ready.val or local.retry.val:
            check(key)
            transfer(key)
            current.update(key=None, plan=None, since=None, waited=0)
        else:
            check(key)
            current["waited"] += 1
        if reset.val != reset.active:
            memory.grant()
            if key is not None and current["plan"] is not None and memory.promises(key[0], key[3]):
                current["plan"] = (current["plan"][0], False)   # promised now: it will be taken
        tick.next = not tick

    def check(key):
        if local.we.val and local.re.val:
            raise ValueError(f"local bus: read and write requested together at {now()}")
        if bool(local.write.val) != bool(local.we.val):
            raise ValueError(f"local bus: write = {int(local.write.val)} disagrees with the request at {now()}")
        if local.retry.val and key[3] and key[0] == 1 and local.room.val:
            raise ValueError(f"local memory: a space-1 write refused while room was shown at {now()}")
        memory._index(key[0], key[1])

    def transfer(key):
        space, addr, be, is_write, data = key
        if local.retry.val:
            memory.retries += 1
            return
        if is_write:
            memory.write(space, addr, data, be)
        else:
            data = memory.read(space, addr)
        memory.took(space, is_write)
        memory.log.append((now(), space, addr, be, "w" if is_write else "r", data))

    return answer, step


def _in_range(memory, key):
    space, addr = key[0], key[1]
    return not addr & 3 and addr < 4 * len(memory.spaces[space])
