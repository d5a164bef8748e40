"""The PCI host's transactions and enumeration, for any simulator.

``PciMaster`` (layers 2 and 3 of the host) sits on a ``HostCore`` (layer 1,
``sim.pci.host_core``).  Its methods are generators that yield only the
core's wait objects (a ``Request``: resume when it is done; ``Clocks(n)``)
and return their result, so one scenario runs unchanged under every front
end's trampoline (``sim.pci.host.run_scenario`` for MyHDL,
``sim.pci.cocotb_bus`` for cocotb, or a loop of your own)::

    result = yield from host.mem_read(0x80000000, 16)

2. Transactions: ``config_read/config_write``, ``io_read/io_write``,
   ``mem_read/mem_write``, single or burst, byte, word or dword.  A
   disconnected burst is resumed as a new transaction at the next address,
   a retried one repeated; the ``Result`` tells the data and how every bus
   transaction ended.
3. Enumeration: ``enumerate_bus`` scans IDSEL, reads IDs and class, sizes
   BARs (write all ones, read back, restore), assigns bases, enables spaces.

Master wait states are pluggable (``irdy_waits``: an int or a function of the
data phase index), so is parity-error injection (``bad_address_parity``,
``bad_data_parity``).  The host is generic: nothing in it knows the target.

Configuration addresses are Type 0 with IDSEL of device ``d`` on AD[16+d].
"""
import random
from dataclasses import dataclass, field

from models.pci import COMMAND_INTERRUPT_DISABLE  # noqa: F401 (offered; to scenarios with the transactions)
from models.pci import COMMAND_IO, COMMAND_MEMORY, COMMAND_PARITY_RESPONSE, COMMAND_SERR_ENABLE
from sim.pci.host_core import HostCore
from sim.pci.host_types import (CONFIG_READ, CONFIG_WRITE, IO_READ, IO_WRITE, MEM_READ, MEM_WRITE, MEMORY_READS,
                                MEMORY_WRITES, Clocks, HostError, Request, Termination)

SETTLE_RETRY_CLOCKS = 8


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

    def bar(self, index):
        """The BAR of ``index`` (0..5) as enumeration found it; KeyError if it has none."""
        for bar in self.bars:
            if bar["index"] == index:
                return bar
        raise KeyError(f"device {self.device} has no BAR{index}")


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


class PciMaster:
    """A PCI master's transactions on a ``HostCore`` (``core``; a new one if
    None).

    ``irdy_waits``: default master wait states (int or function of the data
    phase index).  ``parity_response``: the master's own Parity Error
    Response (PERR# on bad read data).  ``max_retries``: retries in a row
    (per resumption point of an access) before the host gives up;
    ``max_clocks``: clocks one access may take (None: no limit); both raise
    ``HostError``.  ``finish_abandoned``: before the next access, complete a
    read given up on (a delayed transaction the target still holds).
    """

    def __init__(self, core=None, irdy_waits=0, parity_response=True, max_retries=64,
                 max_clocks=None, finish_abandoned=False):
        self.core = core or HostCore(parity_response)
        self.core.parity_response = parity_response
        self.irdy_waits = irdy_waits
        self.max_retries = max_retries
        self.max_clocks = max_clocks
        self.finish_abandoned_first = finish_abandoned
        self.abandoned = []

    @property
    def parity_response(self):
        return self.core.parity_response

    @property
    def transaction(self):
        """The bus transaction running (or the last one)."""
        return self.core.transaction

    @property
    def parity_errors_seen(self):
        return self.core.parity_errors_seen

    @staticmethod
    def clocks(count):
        """Generator: wait ``count`` rising edges (under any front end)."""
        yield Clocks(count)

    # ----- layer 2: transactions --------------------------------------------------
    def transfer(self, command, address, phases, *, resume=True, irdy_waits=None,
                 bad_address_parity=False, bad_data_parity=(), max_retries=None, max_clocks=None,
                 increment=True, size=4, offset=None):
        """Run ``phases`` ([(be, data or None)]) as one access; a generator
        returning a ``Result``.  ``increment``: a resumed burst restarts at
        the next dword (False: same address, for configuration and I/O).

        A retried transaction is repeated exactly (command, address, byte
        enables: what a delayed transaction needs to complete), at most
        ``max_retries`` times in a row: the count starts afresh whenever data
        move.  ``max_clocks`` bounds the whole access.  Either budget spent
        raises ``HostError`` with the bus transactions so far; a read given
        up that way is kept in ``abandoned`` (see ``finish_abandoned``).
        Clocks are the edges the core was stepped.
        Both default to the host's own settings."""
        if not phases:
            raise ValueError("an access needs at least one data phase")
        if not 0 <= command <= 0xF:
            raise ValueError(f"PCI command must be 0..15, not {command}")
        if self.abandoned and self.finish_abandoned_first:
            yield from self.finish_abandoned()
        waits = self.irdy_waits if irdy_waits is None else irdy_waits
        retry_budget = self.max_retries if max_retries is None else max_retries
        clock_budget = self.max_clocks if max_clocks is None else max_clocks
        offset = address & 3 if offset is None else offset
        result = Result(command, address, len(phases), offset=offset, size=size)
        first_edge = self.core.edge
        done = retries = 0
        while done < len(phases):
            start = self._resume_address(command, address, phases, done, increment)
            request = self.core.submit(Request(
                command, start, phases[done:], self._shifted(waits, done), bad_address_parity,
                frozenset(i - done for i in bad_data_parity if i >= done)))
            yield request
            transaction = request.transaction
            result.transactions.append(transaction)
            result.data.extend(transaction.data)
            done += len(transaction.data)
            if transaction.termination is Termination.MASTER_ABORT and not command & 1:
                result.data.extend([0xFFFFFFFF] * (len(phases) - done))
            if result.aborted or not resume or done == len(phases):
                break
            retries = retries + 1 if transaction.termination is Termination.RETRY else 0
            spent = self.core.edge - first_edge
            if retries > retry_budget or (clock_budget is not None and spent > clock_budget):
                self._give_up(request, result, retries if retries > retry_budget else 0, spent)
        return result

    def _give_up(self, request, result, retries, clocks):
        """Raise ``HostError`` (``retries`` in a row, or else ``clocks``, spent)."""
        if not request.command & 1:
            self.abandoned.append(request)
        budget = f"{retries} retries in a row" if retries else f"{clocks} clocks"
        transaction = result.transactions[-1]
        raise HostError(f"{transaction.command:#x} at {transaction.address:#x} gave up after {budget}"
                        f" ({len(result.data)} of {result.requested} data phases done, "
                        f"{len(result.transactions)} bus transactions)", result.transactions)

    def finish_abandoned(self, max_retries=None, max_clocks=None):
        """Repeat the reads given up on (``abandoned``, oldest first) until
        each completes its first data phase, so that a target holding one as
        a delayed transaction lets it go; the data are dropped.  Returns the
        ``Result`` of each."""
        results = []
        while self.abandoned:
            request = self.abandoned.pop(0)
            results.append((yield from self.transfer(
                request.command, request.address, request.phases[:1], irdy_waits=request.waits,
                max_retries=max_retries, max_clocks=max_clocks)))
        return results

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
                      command_bits=COMMAND_PARITY_RESPONSE | COMMAND_SERR_ENABLE, settle_clocks=0):
        """Find every function 0 on ``devices``, size and place its BARs,
        enable its spaces (plus ``command_bits``); return ``[PciDevice]``.

        ``settle_clocks``: a device still waking up from reset may not claim
        its first configuration reads (PCI gives it up to 2^25 clocks after
        RST#); a read of the IDs that master-aborts within this many clocks of
        the start of the enumeration is tried again every
        ``SETTLE_RETRY_CLOCKS`` clocks."""
        found = []
        bases = {"io": io_base, "mem": mem_base}
        start = self.core.edge
        for device in devices:
            ids = yield from self.config_read(device, 0x00)
            while ids.termination is Termination.MASTER_ABORT and self.core.edge - start < settle_clocks:
                yield Clocks(SETTLE_RETRY_CLOCKS)
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
