"""A behavioural PCI memory target with delayed reads and posted writes.

Plain Python, stepped once per rising edge like the host core
(``step(sample)`` with a ``sim.pci.lines.BusSample``; its drive in
``drive.<line>_out`` / ``drive.<line>_oe``), so it runs under every front
end: the pure-Python loop of ``sim.pci.loop``, MyHDL (``sim.pci.bus.
edge_agent``), cocotb.  It behaves as a bridge to a slow back end does:

* memory reads are delayed transactions: the first attempt latches the
  request (command, address, byte enables) and is retried, and so are its
  repeats until it has been retried ``read_retries`` times (the first
  included), the back end has answered (``latency`` clocks, drawn at random)
  and no posted write is left; then the data go out (with
  ``read_retries=0`` and no posted write, at once): one dword and a disconnect
  without prefetch, up to ``prefetch`` dwords with it.  While a request is
  pending every other read is retried (one delayed read at a time, as PCI
  allows); a pending request nobody repeats is dropped after
  ``discard_clocks`` (PCI's discard timer);
* memory writes are posted into a FIFO of ``fifo_depth`` dwords that the back
  end drains one dword per ``latency`` clocks; the data phase that fills it
  disconnects (STOP# with TRDY#), a write that finds it full is retried;
* a data phase at ``abort_address`` is target-aborted;
* with ``config=True`` a Type-0 configuration space answers on IDSEL
  (AD[``idsel_bit``] at the address phase): IDs, Command (Memory Space
  enable), class, one 32-bit memory BAR of ``size`` bytes (then ``base`` is
  what the BAR holds, and memory is claimed only once enabled); nothing is
  claimed in the first ``wake_clocks`` clocks (a device still initialising
  after reset: master abort);
* DEVSEL# medium (sampled two edges after the address edge), no TRDY# wait
  states, PAR one clock after its AD.

``stats`` counts what it did (retries, disconnects, dwords, discarded
requests).  ``memory`` maps dword addresses to values.
"""
import random
from collections import deque

from sim.pci.lines import even_parity

MEM_READS = (0x6, 0xC, 0xE)
MEM_WRITES = (0x7, 0xF)
CONFIG_READ, CONFIG_WRITE = 0xA, 0xB
VENDOR_ID, DEVICE_ID, CLASS_CODE = 0x1234, 0xDE1A, 0x068000   # "other bridge"
TARGET_LINES = ("ad", "par", "trdy", "devsel", "stop")


class TargetDrive:
    """``<line>_out`` / ``<line>_oe`` of AD, PAR, TRDY#, DEVSEL#, STOP#."""

    __slots__ = tuple(f"{line}_{part}" for line in TARGET_LINES for part in ("out", "oe"))

    def __init__(self):
        self.release()

    def release(self):
        self.ad_out = self.par_out = 0
        self.trdy_out = self.devsel_out = self.stop_out = 1
        self.ad_oe = self.par_oe = self.trdy_oe = self.devsel_oe = self.stop_oe = False

    def control(self, devsel, trdy, stop):
        self.devsel_out, self.trdy_out, self.stop_out = devsel, trdy, stop
        self.devsel_oe = self.trdy_oe = self.stop_oe = True


class _Pending:
    """The one delayed read request: what was asked and how far it is."""

    __slots__ = ("command", "address", "be", "retries", "ready_at", "data", "idle")

    def __init__(self, command, address, be, ready_at):
        self.command, self.address, self.be = command, address, be
        self.retries = 0
        self.ready_at = ready_at
        self.data = None     # the fetched dwords once the back end answered
        self.idle = 0        # clocks since the master last asked


class DelayedTarget:
    """See the module docstring.  ``latency``: (min, max) back-end clocks;
    ``seed``: of the back-end latencies."""

    def __init__(self, base=0x80000000, size=0x10000, read_retries=2, prefetch=0, fifo_depth=8,
                 latency=(1, 8), abort_address=None, discard_clocks=1 << 15, seed=0, config=False,
                 idsel_bit=16, wake_clocks=0):
        if size & (size - 1) or size < 16:
            raise ValueError(f"size must be a power of two >= 16 bytes, not {size}")
        if read_retries < 0 or prefetch < 0 or fifo_depth < 1:
            raise ValueError("read_retries and prefetch must be >= 0, fifo_depth >= 1")
        if not 0 <= latency[0] <= latency[1]:
            raise ValueError(f"latency must be (min, max) with 0 <= min <= max, not {latency}")
        self.base, self.size = base, size
        self.read_retries, self.prefetch, self.fifo_depth = read_retries, prefetch, fifo_depth
        self.latency, self.abort_address, self.discard_clocks = latency, abort_address, discard_clocks
        self.rng = random.Random(seed)
        self.memory = {}
        self.fifo = deque()
        self.drain_at = 0
        self.pending = None
        self.drive = TargetDrive()
        self.stats = dict(retries=0, disconnects=0, target_aborts=0, read_dwords=0,
                          write_dwords=0, discarded=0)
        self.clock = 0
        self.config, self.idsel_bit, self.wake_clocks = config, idsel_bit, wake_clocks
        self.memory_enable = not config
        self._frame = 1
        self._state = "idle"
        self._command = self._address = 0
        self._data = None     # read: the dwords to serve in this transaction
        self._par_ad = None   # AD driven in the clock that ends at the next edge

    def _draw(self):
        return self.clock + self.rng.randint(*self.latency)

    # ----- back end ---------------------------------------------------------------
    def _back_end(self):
        if self.fifo and self.clock >= self.drain_at:
            address, be, value = self.fifo.popleft()
            mask = sum(0xFF << 8 * byte for byte in range(4) if be >> byte & 1)
            self.memory[address] = (self.memory.get(address, 0) & ~mask) | (value & mask)
            self.drain_at = self._draw()
        pending = self.pending
        if pending is None:
            return
        pending.idle += 1
        if pending.idle > self.discard_clocks:
            self.pending = None
            self.stats["discarded"] += 1
        elif pending.data is None and self.clock >= pending.ready_at and not self.fifo:
            pending.data = self._fetch(pending.address)

    def _fetch(self, address):
        """The dwords a read at ``address`` gets: one, or ``prefetch`` up to the end."""
        count = max(1, self.prefetch)
        return [self.memory.get(address + 4 * i, 0) for i in range(count) if self.hit(address + 4 * i)]

    def hit(self, address):
        return self.base <= address < self.base + self.size

    def _claims(self, sample):
        """Whether the address phase in ``sample`` is for this target."""
        command, address = sample.cbe, sample.ad
        if address is None or self.clock <= self.wake_clocks:
            return False
        if command in (CONFIG_READ, CONFIG_WRITE):
            return self.config and address >> self.idsel_bit & 1 and address & 3 == 0
        return command in MEM_READS + MEM_WRITES and self.memory_enable and self.hit(address)

    def _config_read(self, register):
        return {0x00: DEVICE_ID << 16 | VENDOR_ID, 0x04: 0x0200 << 16 | int(self.memory_enable) << 1,
                0x08: CLASS_CODE << 8 | 0x01, 0x10: self.base}.get(register, 0)

    def _config_write(self, register, value, be):
        if register == 0x04 and be & 1:
            self.memory_enable = bool(value & 2)
        elif register == 0x10:
            mask = sum(0xFF << 8 * byte for byte in range(4) if be >> byte & 1)
            self.base = ((self.base & ~mask) | (value & mask)) & ~(self.size - 1) & 0xFFFFFFFF

    # ----- bus ----------------------------------------------------------------------
    def step(self, sample):
        """One rising edge; ``sample`` the bus as sampled there."""
        self.clock += 1
        drive = self.drive
        if self._par_ad is not None:
            drive.par_out, drive.par_oe = even_parity(self._par_ad, sample.cbe or 0), True
        elif drive.par_oe:
            drive.par_oe = False
        self._par_ad = None
        self._back_end()
        frame, irdy = sample.frame, sample.irdy
        state = self._state
        if state == "idle":
            if self._frame == 1 and frame == 0 and self._claims(sample):
                self._command, self._address = sample.cbe, sample.ad & ~0x3
                self._state = "decode"
        elif state == "decode":      # the clock after the address: C/BE# are the byte enables
            self._first_phase(sample.cbe)
        elif state == "abort_claim":
            drive.control(1, 1, 0)
            self._state = "backoff"
        elif state == "phase":
            if irdy == 0:
                self._phase_done(sample, frame)
        elif state == "backoff":
            if frame == 1 and irdy == 0:
                self._end()
        elif state == "ending":
            drive.release()
            self._state = "idle"
        self._frame = frame
        if drive.ad_oe:
            self._par_ad = drive.ad_out

    def _first_phase(self, be):
        drive = self.drive
        if self._command in (CONFIG_READ, CONFIG_WRITE):
            drive.control(0, 0, 0)       # one data phase: disconnect with it
            if self._command == CONFIG_READ:
                drive.ad_out, drive.ad_oe = self._config_read(self._address & 0xFC), True
            self._state = "phase"
            return
        if self._address == self.abort_address:
            drive.control(0, 1, 1)       # DEVSEL# one clock, then the target abort
            self.stats["target_aborts"] += 1
            self._state = "abort_claim"
            return
        if self._command in MEM_WRITES:
            self._next_write()
            return
        drive.ad_oe = True          # a claimed read keeps AD driven to its end
        pending = self.pending
        if pending is None:
            if self.read_retries == 0 and not self.fifo:
                self._data = deque(self._fetch(self._address))
                self._next_read()
                return
            self.pending = _Pending(self._command, self._address, be, self._draw())
            self._retry(self.pending)
            return
        if (pending.command, pending.address, pending.be) != (self._command, self._address, be):
            self._retry()
            return
        pending.idle = 0
        if pending.retries < self.read_retries or pending.data is None:
            self._retry(pending)
            return
        self.pending = None
        self._data = deque(pending.data)
        self._next_read()

    def _retry(self, pending=None):
        """Retry this transaction (``pending``: it is that delayed request's repeat)."""
        self.drive.control(0, 1, 0)
        self.stats["retries"] += 1
        if pending is not None:
            pending.retries += 1
        self._state = "backoff"

    def _next_write(self):
        free = self.fifo_depth - len(self.fifo)
        if self._address == self.abort_address:
            self.drive.control(1, 1, 0)
            self.stats["target_aborts"] += 1
            self._state = "backoff"
        elif free == 0 or not self.hit(self._address):
            self.drive.control(0, 1, 0)  # retry, or disconnect without data
            self.stats["retries" if self._state == "decode" else "disconnects"] += 1
            self._state = "backoff"
        else:
            self.drive.control(0, 0, 0 if free == 1 else 1)
            self._state = "phase"

    def _next_read(self):
        drive = self.drive
        if not self._data or self._address == self.abort_address:
            drive.control(1 if self._address == self.abort_address else 0, 1, 0)
            self.stats["target_aborts" if self._address == self.abort_address else "disconnects"] += 1
            drive.ad_oe = self._address != self.abort_address
            self._state = "backoff"
            return
        drive.ad_out = self._data.popleft()
        drive.control(0, 0, 0 if not self._data else 1)
        self._state = "phase"

    def _phase_done(self, sample, frame):
        drive = self.drive
        write = self._command in MEM_WRITES
        if self._command == CONFIG_WRITE:
            self._config_write(self._address & 0xFC, sample.ad, (~sample.cbe) & 0xF)
        elif write:
            if not self.fifo:
                self.drain_at = self._draw()   # the back end takes this long for each dword
            self.fifo.append((self._address, (~sample.cbe) & 0xF, sample.ad))
            self.stats["write_dwords"] += 1
            if self.pending is not None and self.pending.address <= self._address < \
                    self.pending.address + 4 * max(1, self.prefetch):
                self.pending.data = None  # fetched before this write: fetch again
        elif self._command in MEM_READS:
            self.stats["read_dwords"] += 1
        self._address += 4
        if frame == 1:
            self._end()
        elif drive.stop_out == 0:
            drive.control(0, 1, 0)
            self.stats["disconnects"] += 1
            self._state = "backoff"
        elif write:
            self._next_write()
        else:
            self._next_read()

    def _end(self):
        drive = self.drive
        drive.control(1, 1, 1)
        drive.ad_oe = False
        self._data = None
        self._state = "ending"
