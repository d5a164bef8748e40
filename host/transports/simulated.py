"""The simulated card as a ``Transport``: MyHDL, Icarus or Verilator.

``SimTransport(kind)`` opens a ``sim.card.card_session.CardSession``: the card
is reset and enumerated by the behavioural PCI host (``sim.pci.master``),
with the protocol checker on every bus clock, and each call below runs one
access to its end.  Simulated time passes only inside calls; ``now()`` is
the card's clocks over ``clock_hz`` (the clock the card is built for, as
CLOCK_HZ reads).  ``pins`` is the STEP/DIR log (``sim.card.card_bench.PinLog``);
``machine`` the simulated machine on the card's inputs (``SimTransport(...,
machine=config)``, a ``models.sim_machine.MachineConfig``; docs/machine.md,
"Simulated machine"): ``press_estop``, ``release_estop``, ``stall(axis)``,
``state()``.
"""
import math

from host.transports.base import SIM_KINDS, Transport, TransportError
from models.parameters import AXES, CLOCK_HZ, ENCODERS
from sim.backends.verilator.model import Stop
from sim.card.card_e2e import DEFAULT_FIFO
from sim.card.card_session import AccessError, CardSession


class SimTransport(Transport):
    """The card of ``kind`` (``myhdl``, ``icarus``, ``verilator``) with
    ``fifo_depth`` words of FIFO; ``monitor``: the protocol checker on
    Verilator (always on for the others); ``clock_hz``: the Verilator card is
    built for it (its CLOCK_HZ reads it), the others for the default;
    ``machine``: a ``MachineConfig``, the simulated machine on the inputs;
    ``axes``: the card's build (``python -m rtl.top --axes N``: STEP/DIR of N axes
    on ``pins``, BUILD.AXES = N); ``encoders``: a build with encoders
    (``--encoders``, BUILD.ENCODERS = 1; Verilator and MyHDL), whose inputs the
    machine's motors drive."""

    def __init__(self, kind, fifo_depth=DEFAULT_FIFO, clock_hz=CLOCK_HZ.default, monitor=True, machine=None,
                 axes=AXES.default, encoders=ENCODERS.default):
        if kind not in SIM_KINDS:
            raise ValueError(f"unknown simulator {kind!r}: use one of {', '.join(SIM_KINDS)}")
        self.name = f"simulated card ({kind})"
        self.kind = kind
        self.clock_hz = clock_hz
        clock = dict(clock_hz=clock_hz) if kind == "verilator" else {}
        if encoders and kind == "icarus":
            raise ValueError("a card with encoders is simulated on verilator or myhdl, not icarus")
        self.session = CardSession(kind, fifo_depth, monitor=monitor, machine=machine, axes=axes, encoders=encoders,
                                   **clock)
        self.machine = self.session.machine
        self.device = self.session.device
        self.io_size = self.session.bars["io"]["size"]
        self.mem_size = self.session.bars["mem"]["size"]
        self._start = self.session.clocks

    def _access(self, method, *args):
        try:
            return method(*args)
        except AccessError as error:
            raise TransportError(str(error)) from None

    def read(self, offset, size=4):
        return self._access(self.session.read, offset, size)

    def write(self, offset, value, size=4):
        self._access(self.session.write, offset, value, size)

    def fifo_write(self, words):
        """All of ``words`` as one burst (resumed after a disconnect); a FIFO
        that stays full past the host's retry budget is a TransportError
        saying how many words were taken."""
        self._access(self.session.fifo_write, words)

    def mem_read(self, offset, count=1):
        return self._access(self.session.mem_read, offset, count)

    def config_read(self, register, size=4):
        return self._access(self.session.config_read, register, size)

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

    def encoder_changes(self):
        """The encoder pins the simulated machine's motors drove (Verilator, MyHDL): [(clock, word)] of every
        change so far (``SimMachine.encoder_pins``'s word, set after the rising edge ``clock``)."""
        if self.machine is None:
            raise ValueError("the encoder pins are recorded by the simulated machine: open the card with one")
        return self.machine.encoder_changes()

    def close(self):
        self.session.close()
