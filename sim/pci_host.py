"""Behavioural PCI host: a standard 32-bit PCI master for test benches.

Three layers:

1. Signal driver (the ``pci_host`` block, one process): waits for an idle bus,
   drives FRAME#, IRDY#, C/BE#, AD and PAR phase by phase, counts DEVSEL# up
   to clock 5 (master abort after that), honours TRDY# and STOP# (retry,
   disconnect with or without data, target abort), checks the parity of read
   data and drives PERR# as a master does when its Parity Error Response is
   on.  One bus transaction per request.
2. Transactions (generators, ``result = yield from host.mem_read(...)``):
   ``config_read/config_write``, ``io_read/io_write``, ``mem_read/mem_write``,
   single or burst, byte, word or dword.  A disconnected burst is resumed as
   a new transaction at the next address, a retried one repeated; the
   ``Result`` tells the data and how every bus transaction ended.
3. Enumeration: ``enumerate_bus`` scans IDSEL, reads IDs and class, sizes
   BARs (write all ones, read back, restore), assigns bases, enables spaces.

Master wait states are pluggable (``irdy_waits``: an int or a function of the
data phase index), so is parity-error injection (``bad_address_parity``,
``bad_data_parity``).  The host is generic: nothing in it knows the target.

Configuration addresses are Type 0 with IDSEL of device ``d`` on AD[16+d]
(wire the target's IDSEL with ``PciSegment(idsel={name: 16 + d})``).
"""
import enum
import random
from collections import deque
from dataclasses import dataclass, field

from myhdl import Signal, block, instance, now

from sim.pci_bus import PciAgent, even_parity

INTERRUPT_ACK = 0x0
SPECIAL_CYCLE = 0x1
IO_READ = 0x2
IO_WRITE = 0x3
MEM_READ = 0x6
MEM_WRITE = 0x7
CONFIG_READ = 0xA
CONFIG_WRITE = 0xB
MEM_READ_MULTIPLE = 0xC
DUAL_ADDRESS = 0xD
MEM_READ_LINE = 0xE
MEM_WRITE_INVALIDATE = 0xF
MEMORY_READS = (MEM_READ, MEM_READ_LINE, MEM_READ_MULTIPLE)
MEMORY_WRITES = (MEM_WRITE, MEM_WRITE_INVALIDATE)

COMMAND_IO = 1 << 0
COMMAND_MEMORY = 1 << 1
COMMAND_PARITY_RESPONSE = 1 << 6
COMMAND_SERR_ENABLE = 1 << 8
COMMAND_INTERRUPT_DISABLE = 1 << 10

MASTER_ABORT_EDGE = 4       # DEVSEL# not sampled by the 4th edge after the address: abort
TARGET_TIMEOUT_EDGES = 256  # a target that never ends a data phase stops the bench


class Termination(enum.Enum):
    NORMAL = "normal"
    RETRY = "retry"
    DISCONNECT = "disconnect"
    MASTER_ABORT = "master abort"
    TARGET_ABORT = "target abort"
    RESET = "reset"  # RST# came during the transaction


class BusReset(Exception):
    """RST# was asserted: the driver drops what it was doing."""


class HostError(RuntimeError):
    """The target left the host stuck (no TRDY#/STOP# for very long)."""


@dataclass
class BusTransaction:
    """One transaction on the bus, from FRAME# to the end of the last phase.

    ``devsel_clock`` / ``first_trdy_clock``: edges after the address edge at
    which DEVSEL# / the first TRDY# were sampled asserted (None: never).
    ``parity_errors``: indices (in ``data``) of read data with bad PAR.
    """

    command: int
    address: int
    requested: int
    data: list = field(default_factory=list)
    termination: Termination = Termination.NORMAL
    devsel_clock: int = None
    first_trdy_clock: int = None
    start: int = 0
    end: int = 0
    parity_errors: list = field(default_factory=list)


@dataclass
class Result:
    """Outcome of a layer-2 access (possibly several bus transactions).

    ``data``: dwords transferred (a read that master-aborted reads all ones,
    as a PC's host bridge returns); ``termination``: how the last bus
    transaction ended; ``complete``: every data phase was transferred.
    """

    command: int
    address: int
    requested: int
    data: list = field(default_factory=list)
    transactions: list = field(default_factory=list)
    offset: int = 0
    size: int = 4

    @property
    def termination(self):
        return self.transactions[-1].termination

    @property
    def complete(self):
        return len(self.data) >= self.requested and not self.aborted

    @property
    def aborted(self):
        return self.termination in (Termination.MASTER_ABORT, Termination.TARGET_ABORT,
                                    Termination.RESET)

    @property
    def retries(self):
        return sum(t.termination is Termination.RETRY for t in self.transactions)

    @property
    def parity_errors(self):
        return sum(len(t.parity_errors) for t in self.transactions)

    @property
    def value(self):
        """First datum, the addressed bytes only for byte and word accesses."""
        if not self.data:
            raise ValueError("no data was transferred")
        return (self.data[0] >> (8 * self.offset)) & ((1 << (8 * self.size)) - 1)


@dataclass
class PciDevice:
    """What enumeration found: ``bars`` is a list of dicts
    (index, io, size, base, prefetchable)."""

    device: int
    function: int
    vendor_id: int
    device_id: int
    class_code: int
    revision_id: int
    header_type: int
    bars: list
    interrupt_pin: int
    command: int


@dataclass
class _Request:
    command: int
    address: int
    phases: list          # [(byte enables, data or None)]
    waits: object         # phase index -> IRDY# wait states
    bad_address_parity: bool
    bad_data_parity: frozenset
    done: Signal
    transaction: BusTransaction = None


class _Run:
    """Progress of one bus transaction in the signal driver."""

    def __init__(self, request, transaction):
        self.request = request
        self.transaction = transaction
        self.write = bool(request.command & 1)
        self.index = 0          # data phase on the bus
        self.edges = 0          # rising edges since the address edge
        self.phase_edge = 0     # the edge at which the current data phase began
        self.waiting = 0        # IRDY# wait states left
        self.stop_seen = False
        self.final = False      # FRAME# is deasserted: this is the last phase


def byte_enables(address, size):
    """Active-high byte enables of a ``size``-byte access at ``address``."""
    if size not in (1, 2, 4):
        raise ValueError(f"access size must be 1, 2 or 4 bytes, not {size}")
    offset = address & 3
    if offset % size:
        raise ValueError(f"a {size}-byte access at {address:#x} is not naturally aligned")
    return ((1 << size) - 1) << offset


def io_address_bits(be):
    """AD[1:0] of an I/O access: the lowest enabled byte (0 if none)."""
    for byte in range(4):
        if be >> byte & 1:
            return byte
    return 0


def config_address(device, register, function=0):
    """Type-0 configuration address with IDSEL of ``device`` on AD[16+device]."""
    if not 0 <= device <= 15:
        raise ValueError(f"device number must be 0..15 (IDSEL on AD[31:16]), not {device}")
    if not 0 <= function <= 7:
        raise ValueError(f"function number must be 0..7, not {function}")
    if not 0 <= register <= 0xFC or register & 3:
        raise ValueError(f"configuration register must be a dword offset 0..0xFC, not {register:#x}")
    return (1 << (16 + device)) | (function << 8) | register


def random_waits(seed, max_waits=3, probability=0.3):
    """An ``irdy_waits`` function: 0 or, with ``probability``, 1..max_waits."""
    rng = random.Random(seed)

    def waits(_index):
        return rng.randint(1, max_waits) if rng.random() < probability else 0

    return waits


class PciHost:
    """A PCI master on a ``PciAgent``; instantiate ``pci_host(clock, reset,
    host)`` in the bench, call the transaction generators from a process.

    ``irdy_waits``: default master wait states (int or function of the data
    phase index).  ``parity_response``: the master's own Parity Error
    Response (PERR# on bad read data).  ``max_retries``: retries of one
    access before the host gives up and reports RETRY.
    """

    def __init__(self, clock, irdy_waits=0, parity_response=True, max_retries=64):
        self.clock = clock
        self.agent = PciAgent()
        self.irdy_waits = irdy_waits
        self.parity_response = parity_response
        self.max_retries = max_retries
        self.queue = deque()
        self.reset = None
        self.transaction = None
        self.parity_errors_seen = []
        self.edge = 0
        self._bad_par = False
        self._par_check = None
        self._perr_phase = 0
        self._idle = False
        self._idle = False

    # ----- layer 1: signal driver -------------------------------------------------
    def _drive(self, line, value):
        getattr(self.agent, f"{line}_out").next = value
        getattr(self.agent, f"{line}_oe").next = True

    def _release(self, *lines):
        for line in lines:
            getattr(self.agent, f"{line}_oe").next = False

    def _driven_low(self, line):
        return bool(getattr(self.agent, f"{line}_oe").val) and not getattr(self.agent, f"{line}_out").val

    def _sampled(self, line):
        return int(getattr(self.agent, f"{line}_in").val)

    def _tick(self):
        """Wait for the next rising edge; then do the per-clock duties:
        PAR for the AD driven in the clock that ended, read parity check,
        PERR# sequence (low one clock, high one clock, released)."""
        bad_par = self._bad_par
        if self.reset is None:
            yield self.clock.posedge
        else:
            yield self.clock.posedge, self.reset.negedge
            if self.reset.val == self.reset.active:
                self._release_all()
                raise BusReset()
        self.edge += 1
        agent = self.agent
        if agent.ad_oe.val:
            self._drive("par", even_parity(agent.ad_out.val, agent.cbe_out.val) ^ bad_par)
        else:
            self._release("par")
        error = self._check_read_parity()
        if error and self.parity_response:
            self._drive("perr", 0)
            self._perr_phase = 1
        elif self._perr_phase == 1:
            self._drive("perr", 1)
            self._perr_phase = 2
        elif self._perr_phase == 2:
            self._release("perr")
            self._perr_phase = 0
        self._idle = self._sampled("frame") == 1 and self._sampled("irdy") == 1

    def _check_read_parity(self):
        if self._par_check is None:
            return False
        ad, cbe, transaction, index = self._par_check
        self._par_check = None
        if even_parity(ad, cbe) == self._sampled("par"):
            return False
        transaction.parity_errors.append(index)
        self.parity_errors_seen.append((now(), transaction.address, index))
        return True

    def next_request(self):
        """Take the next queued request; its transaction record starts now."""
        request = self.queue.popleft()
        self.transaction = BusTransaction(request.command, request.address, len(request.phases))
        return request

    def cut_short(self):
        """The transaction RST# interrupted, marked so."""
        self.transaction.termination = Termination.RESET
        self.transaction.end = now()
        return self.transaction

    def _release_all(self):
        self._release("ad", "cbe", "par", "frame", "irdy", "perr")
        self._bad_par = False
        self._par_check = None
        self._perr_phase = 0

    def _waits_for(self, waits, index):
        count = waits(index) if callable(waits) else waits
        if count < 0:
            raise ValueError(f"IRDY# wait states must be >= 0, not {count}")
        return count

    def _start_phase(self, run):
        """Put data phase ``run.index`` on the bus; return its IRDY# wait states."""
        be, data = run.request.phases[run.index]
        self._drive("cbe", ~be & 0xF)
        if run.write:
            self._drive("ad", data)
            self._bad_par = run.index in run.request.bad_data_parity
        else:
            self._release("ad")
            self._bad_par = False
        return self._waits_for(run.request.waits, run.index)

    def _assert_irdy(self, run):
        """IRDY# now; FRAME# goes with it on the last phase or after STOP#."""
        self._drive("irdy", 0)
        if run.index == len(run.request.phases) - 1 or run.stop_seen:
            self._drive("frame", 1)
            run.final = True

    def _run(self, request):
        """Drive one bus transaction (the bus was sampled idle at the last edge)."""
        run = _Run(request, self.transaction)
        self._drive("frame", 0)
        self._drive("irdy", 1)
        self._drive("ad", request.address)
        self._drive("cbe", request.command)
        self._bad_par = request.bad_address_parity
        yield from self._tick()
        run.transaction.start = now()
        run.waiting = self._start_phase(run)
        if run.waiting == 0:
            self._assert_irdy(run)
        while True:
            yield from self._tick()
            abort = self._observe(run)
            if abort is not None:
                run.transaction.termination = abort
                if not (run.final and self._driven_low("irdy")):
                    self._drive("irdy", 0)
                    self._drive("frame", 1)
                    yield from self._tick()
                break
            if self._advance(run):
                run.transaction.termination = self._stop_kind(run.stop_seen, run.transaction)
                break
        yield from self._finish(run.transaction)
        return run.transaction

    def _observe(self, run):
        """Record DEVSEL# and TRDY# of this edge; the abort it shows, if any."""
        run.edges += 1
        transaction = run.transaction
        devsel, trdy, stop = (self._sampled(n) for n in ("devsel", "trdy", "stop"))
        if not devsel and transaction.devsel_clock is None:
            transaction.devsel_clock = run.edges
        if not trdy and transaction.first_trdy_clock is None:
            transaction.first_trdy_clock = run.edges
        claimed = transaction.devsel_clock is not None
        if claimed and devsel and not stop:
            return Termination.TARGET_ABORT
        if not claimed and run.edges >= MASTER_ABORT_EDGE:
            return Termination.MASTER_ABORT
        if run.edges - run.phase_edge > TARGET_TIMEOUT_EDGES:
            raise HostError(f"no end of data phase {run.index} within "
                            f"{run.edges - run.phase_edge} clocks at {now()}")
        return None

    def _advance(self, run):
        """Act on this edge's TRDY#/STOP#; True once the last data phase is over."""
        trdy, stop = self._sampled("trdy"), self._sampled("stop")
        claimed = run.transaction.devsel_clock is not None
        if not self._driven_low("irdy"):
            run.stop_seen = run.stop_seen or (claimed and not stop)
            run.waiting -= 1
            if run.waiting <= 0 or run.stop_seen:
                self._assert_irdy(run)
            return False
        if trdy and stop:
            return False
        if not trdy:
            self._accept(run)
            run.index += 1
            run.phase_edge = run.edges
        run.stop_seen = run.stop_seen or not stop
        if run.final:
            return True
        if run.stop_seen:
            if run.index < len(run.request.phases):
                self._start_phase(run)
            self._assert_irdy(run)
            return False
        run.waiting = self._start_phase(run)
        if run.waiting == 0:
            self._assert_irdy(run)
        else:
            self._drive("irdy", 1)
        return False

    def _accept(self, run):
        """Data phase ``run.index`` moved: keep its datum, check read parity next edge."""
        transaction = run.transaction
        if run.write:
            transaction.data.append(run.request.phases[run.index][1])
        else:
            ad = int(self.agent.ad_in.val)
            transaction.data.append(ad)
            self._par_check = (ad, int(self.agent.cbe_out.val), transaction, run.index)

    @staticmethod
    def _stop_kind(stop_seen, transaction):
        if not stop_seen:
            return Termination.NORMAL
        return Termination.DISCONNECT if transaction.data else Termination.RETRY

    def _finish(self, transaction):
        """After the last data phase: IRDY# high for a clock, then release."""
        transaction.end = now()
        self._drive("irdy", 1)
        self._drive("frame", 1)
        self._release("ad", "cbe")
        self._bad_par = False
        yield from self._tick()
        self._release("frame", "irdy")

    # ----- layer 2: transactions --------------------------------------------------
    def transfer(self, command, address, phases, *, resume=True, irdy_waits=None,
                 bad_address_parity=False, bad_data_parity=(), max_retries=None,
                 increment=True, size=4, offset=None):
        """Run ``phases`` ([(be, data or None)]) as one access; a generator
        returning a ``Result``.  ``increment``: a resumed burst restarts at
        the next dword (False: same address, for configuration and I/O)."""
        if not phases:
            raise ValueError("an access needs at least one data phase")
        if not 0 <= command <= 0xF:
            raise ValueError(f"PCI command must be 0..15, not {command}")
        waits = self.irdy_waits if irdy_waits is None else irdy_waits
        retries_left = self.max_retries if max_retries is None else max_retries
        offset = address & 3 if offset is None else offset
        result = Result(command, address, len(phases), offset=offset, size=size)
        done = 0
        while done < len(phases):
            start = self._resume_address(command, address, phases, done, increment)
            request = _Request(command, start, phases[done:], self._shifted(waits, done),
                               bad_address_parity,
                               frozenset(i - done for i in bad_data_parity if i >= done),
                               Signal(bool(0)))
            self.queue.append(request)
            yield request.done
            transaction = request.transaction
            result.transactions.append(transaction)
            result.data.extend(transaction.data)
            done += len(transaction.data)
            if transaction.termination is Termination.MASTER_ABORT and not command & 1:
                result.data.extend([0xFFFFFFFF] * (len(phases) - done))
            if result.aborted or not resume:
                break
            if transaction.termination is Termination.RETRY:
                retries_left -= 1
                if retries_left < 0:
                    break
        return result

    @staticmethod
    def _shifted(waits, done):
        if callable(waits):
            return lambda index: waits(index + done)
        return waits

    @staticmethod
    def _resume_address(command, address, phases, done, increment):
        if done == 0:
            return address
        base = (address & ~3) + (4 * done if increment else 0)
        if command in (IO_READ, IO_WRITE):
            return base | io_address_bits(phases[done][0])
        return base

    def config_read(self, device, register, *, function=0, be=0xF, count=1, **options):
        """Read ``count`` dwords of configuration space from ``register``."""
        address = config_address(device, register, function)
        return (yield from self.transfer(CONFIG_READ, address, [(be, None)] * count,
                                         increment=True, **options))

    def config_write(self, device, register, values, *, function=0, be=0xF, **options):
        """Write one value (or a list: a burst) at configuration ``register``."""
        values = values if isinstance(values, (list, tuple)) else [values]
        address = config_address(device, register, function)
        return (yield from self.transfer(CONFIG_WRITE, address, [(be, v) for v in values],
                                         **options))

    def io_read(self, address, size=4, *, be=None, count=1, **options):
        """I/O read of ``size`` bytes at byte ``address`` (AD[1:0] = address[1:0])."""
        be = byte_enables(address, size) if be is None else be
        return (yield from self.transfer(IO_READ, address, [(be, None)] * count,
                                         size=size, **options))

    def io_write(self, address, value, size=4, *, be=None, **options):
        """I/O write of ``size`` bytes (``value`` right-aligned; a list: a burst)."""
        if isinstance(value, (list, tuple)):
            be = 0xF if be is None else be
            phases = [(be, v) for v in value]
        else:
            be = byte_enables(address, size) if be is None else be
            phases = [(be, (value << 8 * (address & 3)) & 0xFFFFFFFF)]
        return (yield from self.transfer(IO_WRITE, address, phases, size=size, **options))

    def mem_read(self, address, count=1, size=4, *, command=MEM_READ, be=None, **options):
        """Memory read: a burst of ``count`` dwords, or one byte/word/dword."""
        if command not in MEMORY_READS:
            raise ValueError(f"{command:#x} is not a memory read command")
        if size != 4 and count != 1:
            raise ValueError("byte and word reads are single data phases")
        be = byte_enables(address, size) if be is None else be
        return (yield from self.transfer(command, address & ~3, [(be, None)] * count,
                                         size=size, offset=address & 3, **options))

    def mem_write(self, address, values, size=4, *, command=MEM_WRITE, be=None, **options):
        """Memory write of a dword list (a burst; ``be``: one value or a list)
        or of one byte/word (``values`` an int, right-aligned)."""
        if command not in MEMORY_WRITES:
            raise ValueError(f"{command:#x} is not a memory write command")
        if isinstance(values, (list, tuple)):
            if size != 4:
                raise ValueError("byte and word writes are single data phases")
            enables = be if isinstance(be, (list, tuple)) else [0xF if be is None else be] * len(values)
            if len(enables) != len(values):
                raise ValueError("one byte-enable value per data phase")
            phases = list(zip(enables, values))
        else:
            enable = byte_enables(address, size) if be is None else be
            phases = [(enable, (values << 8 * (address & 3)) & 0xFFFFFFFF)]
        return (yield from self.transfer(command, address & ~3, phases, size=size,
                                         offset=address & 3, **options))

    # ----- layer 3: enumeration -------------------------------------------------
    def enumerate_bus(self, devices=range(16), io_base=0x1000, mem_base=0x80000000,
                      command_bits=COMMAND_PARITY_RESPONSE | COMMAND_SERR_ENABLE):
        """Find every function 0 on ``devices``, size and place its BARs,
        enable its spaces (plus ``command_bits``); return ``[PciDevice]``."""
        found = []
        bases = {"io": io_base, "mem": mem_base}
        for device in devices:
            ids = yield from self.config_read(device, 0x00)
            if ids.aborted or ids.value & 0xFFFF == 0xFFFF:
                continue
            found.append((yield from self._configure(device, ids.value, bases, command_bits)))
        return found

    def _configure(self, device, ids, bases, command_bits):
        class_rev = (yield from self.config_read(device, 0x08)).value
        header = ((yield from self.config_read(device, 0x0C)).value >> 16) & 0xFF
        bars = []
        index = 0
        while index < 6:
            bar = yield from self._size_bar(device, index, bases)
            if bar is not None:
                bars.append(bar)
            index += 2 if bar is not None and bar.get("wide") else 1
        pin = ((yield from self.config_read(device, 0x3C)).value >> 8) & 0xFF
        command = command_bits
        if any(b["io"] for b in bars):
            command |= COMMAND_IO
        if any(not b["io"] for b in bars):
            command |= COMMAND_MEMORY
        yield from self.config_write(device, 0x04, command, be=0x3)
        return PciDevice(device, 0, ids & 0xFFFF, ids >> 16, class_rev >> 8, class_rev & 0xFF,
                         header, bars, pin, command)

    def _size_bar(self, device, index, bases):
        register = 0x10 + 4 * index
        original = (yield from self.config_read(device, register)).value
        yield from self.config_write(device, register, 0xFFFFFFFF)
        probe = (yield from self.config_read(device, register)).value
        yield from self.config_write(device, register, original)
        if probe == 0:
            return None
        io = bool(probe & 1)
        if io:
            mask = probe & 0xFFFFFFFC
            if not mask & 0xFFFF0000:
                mask |= 0xFFFF0000
        else:
            mask = probe & 0xFFFFFFF0
        size = (~mask & 0xFFFFFFFF) + 1
        kind = "io" if io else "mem"
        base = -(-bases[kind] // size) * size
        bases[kind] = base + size
        yield from self.config_write(device, register, base | (probe & (0x3 if io else 0xF)))
        wide = not io and (probe >> 1) & 3 == 2
        if wide:
            yield from self.config_write(device, register + 4, 0)
        return {"index": index, "io": io, "size": size, "base": base,
                "prefetchable": not io and bool(probe & 8), "wide": wide}


@block
def pci_host(clock, reset, host):
    """The host's signal driver: runs the queued bus transactions.

    clock: PCI clock; reset: RST# (active low ResetSignal) or None;
    host: a ``PciHost``.  Everything is released as soon as RST# falls and
    while it is low; a transaction it cuts short ends with ``RESET``.

        clock  _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        FRAME# ~~~\\_____/~~~~~~~~~~~~~
        AD     ---<ADR><D0 ><D1>-------   (write, no wait states)
        IRDY#  ~~~~~~~\\_________/~~~~~~
    """

    host.reset = reset

    @instance
    def driver():
        host._release_all()
        while True:
            try:
                yield from host._tick()
            except BusReset:
                continue
            if host.queue and host._idle:
                request = host.next_request()
                try:
                    request.transaction = yield from host._run(request)
                except BusReset:
                    request.transaction = host.cut_short()
                request.done.next = True

    return driver
