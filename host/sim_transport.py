"""The simulated card as a ``Transport``: MyHDL, Icarus or Verilator.

``SimTransport(kind)`` opens a ``sim.card_session.CardSession``: the card is
reset and enumerated by the behavioural PCI host (``sim.pci_master``), with
the protocol checker on every bus clock, and each call below runs one
access to its end.  Simulated time passes only inside calls; ``now()`` is
the card's clocks over ``clock_hz`` (the clock the card is built for, as
CLOCK_HZ reads).  ``pins`` is the STEP/DIR log (``sim.card_bench.PinLog``).
"""
import math

from rtl.parameters import PARAMETERS
from sim.card_e2e import DEFAULT_FIFO
from sim.card_session import CardSession
from sim.pci_host_types import HostError
from sim.vlt.model import Stop

from host.transport import SIM_KINDS, Transport, TransportError, check_access, check_value


class SimTransport(Transport):
    """The card of ``kind`` (``myhdl``, ``icarus``, ``verilator``) with
    ``fifo_depth`` words of FIFO; ``monitor``: the protocol checker on
    Verilator (always on for the others); ``clock_hz``: the Verilator card is
    built for it (its CLOCK_HZ reads it), the others for the default."""

    def __init__(self, kind, fifo_depth=DEFAULT_FIFO, clock_hz=PARAMETERS["clock_hz"].default, monitor=True):
        if kind not in SIM_KINDS:
            raise ValueError(f"unknown simulator {kind!r}: use one of {', '.join(SIM_KINDS)}")
        self.name = f"simulated card ({kind})"
        self.kind = kind
        self.clock_hz = clock_hz
        clock = dict(clock_hz=clock_hz) if kind == "verilator" else {}
        self.session = CardSession(kind, fifo_depth, monitor=monitor, **clock)
        self.device = self.session.device
        self.io_size = self.session.bars["io"]["size"]
        self.mem_size = self.session.bars["mem"]["size"]
        self._start = self.session.clocks

    def _call(self, access, what):
        """Run ``access`` (a ``PciMaster`` generator) now; its complete ``Result``."""
        try:
            result = self.session.call(access)
        except HostError as error:
            raise TransportError(f"{what}: {error}") from None
        return self._complete(result, what)

    def _complete(self, result, what):
        if not result.complete:
            raise TransportError(f"{what} ended with {result.termination.value} "
                                 f"({len(result.data)} of {result.requested} data phases)")
        return result

    def read(self, offset, size=4):
        check_access(offset, size, self.io_size)
        session = self.session
        return self._call(session.host.io_read(session.io + offset, size), f"I/O read at {offset:#x}").value

    def write(self, offset, value, size=4):
        check_access(offset, size, self.io_size)
        check_value(value, size)
        session = self.session
        self._call(session.host.io_write(session.io + offset, value, size), f"I/O write at {offset:#x}")

    def fifo_write(self, words):
        """All of ``words`` as one burst (resumed after a disconnect); a FIFO
        that stays full past the host's retry budget is a TransportError
        saying how many words were taken."""
        words = list(words)
        if not words:
            return
        for word in words:
            check_value(word, 4)
        session = self.session
        try:
            result = session.call(session.host.mem_write(session.mem, words))
        except HostError as error:
            taken = sum(len(t.data) for t in error.transactions)
            raise TransportError(f"the FIFO stayed full: {taken} of {len(words)} words taken ({error})") from None
        self._complete(result, "FIFO write")

    def mem_read(self, offset, count=1):
        check_access(offset, 4, self.mem_size, "BAR1")
        session = self.session
        return self._call(session.host.mem_read(session.mem + offset, count),
                          f"memory read at {offset:#x}").data[:count]

    def config_read(self, register, size=4):
        check_access(register, size, 256, "configuration space")
        session = self.session
        result = self._call(session.host.config_read(self.device.device, register & ~3),
                            f"configuration read at {register:#x}")
        return (result.value >> (8 * (register & 3))) & ((1 << (8 * size)) - 1)

    def _clocks_for(self, seconds):
        return max(1, math.ceil(seconds * self.clock_hz))

    def wait_interrupt(self, seconds):
        _, reason = self.session.wait(self._clocks_for(seconds), inta=True)
        return reason is Stop.INTERRUPT

    def sleep(self, seconds):
        self.session.wait(self._clocks_for(seconds))

    def now(self):
        return (self.session.clocks - self._start) / self.clock_hz

    @property
    def clocks(self):
        return self.session.clocks

    @property
    def pins(self):
        return self.session.log

    def close(self):
        self.session.close()
