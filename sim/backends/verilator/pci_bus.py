"""The Verilated card on the PCI bus with no simulator in Python: the host
engine (``sim.pci.host_core``), its transactions (``sim.pci.master``) and
the protocol checker (``sim.pci.checker``) stepped once per bus clock around
one foreign call (``step_bus``: the host's drive in, the card's drive
resolved with it, the card clocked, the segment as sampled out).

``VerilatorBench(card, target)`` has the surface of ``sim.pci.bench.PciBench``
that the end-to-end scenarios use (``host``, ``checker``, ``run``).  RST# is
held for the same clocks as there, so the card's clocks line up with the
other back ends'.  A scenario may yield, besides the host's ``Request`` and
``Clocks``, a ``CardWait`` (``sim.backends.verilator.verilated_card``): it runs in compiled code while
the host is quiet (nothing queued, every line released), clock by clock with
the checker otherwise.

    per bus clock:  core.drive --> step_bus --> sample --> checker, core.step
    a quiet wait:   model.run(limit, INTA#, STEP rises)   (no Python per clock)
"""
from sim.backends.verilator.verilated_card import CardWait
from sim.backends.verilator.model import LINES, Stop
from sim.pci.bench import CLOCK_PERIOD, RESET_CLOCKS, TARGET_DEVICE
from sim.pci.checker import ProtocolChecker
from sim.pci.host_core import run_steps, scenario_steps
from sim.pci.lines import BusSample
from sim.pci.master import PciMaster

HOST_LINES = ("ad", "cbe", "par", "frame", "irdy", "perr")
_HOST_INDEX = [(LINES.index(line), f"{line}_out", f"{line}_oe") for line in HOST_LINES]
_DRIVERS = (frozenset(), frozenset({"host"}), frozenset({"target"}), frozenset({"host", "target"}))
_INTA = LINES.index("inta")
_SAMPLED = [LINES.index(line) for line in ("ad", "par", "frame", "irdy", "trdy", "devsel", "stop")]
AFTER_CLOCKS = 4  # clocks run after the scenario, as PciBench does


class VerilatorBench:
    """``card``: a ``VerilatedCard``; ``target``: the scenario's view of the
    card (its ``log`` gets the pins); ``host_options``: ``PciMaster``
    keyword arguments; ``monitor``: check every bus clock."""

    def __init__(self, card, target, host_options=None, allow_parity_errors=False, monitor=True):
        self.card, self.model, self.target = card, card.model, target
        self.host = PciMaster(**(host_options or {}))
        self.core = self.host.core
        self.bus = self.model.bus()
        self.checker = ProtocolChecker(TARGET_DEVICE, self.host.parity_response, allow_parity_errors)
        self.monitor = monitor
        self._released = True  # the drive of the clock that ended released every line

    def time(self):
        """Time of the last rising edge, in the PCI bench's units (edge n at 30 n - 15)."""
        return CLOCK_PERIOD * self.model.clocks - CLOCK_PERIOD // 2

    def clock_edge(self, in_reset=False):
        """One bus clock: the host's drive meets the card's, the edge, the checker, the host."""
        drive, bus = self.core.drive, self.bus
        released = True
        for index, out, enable in _HOST_INDEX:
            driven = getattr(drive, enable)
            bus.host_oe[index] = driven
            if driven:
                bus.host_out[index] = getattr(drive, out)
                released = False
        self.model.step_bus(bus)
        self._released = released
        values = bus.values.tolist()
        time = self.time()
        if self.monitor:
            floating, drivers = bus.floating.tolist(), bus.drivers.tolist()
            sample = BusSample(time, {line: None if floating[i] else values[i] for i, line in enumerate(LINES)},
                               {line: _DRIVERS[drivers[i]] for i, line in enumerate(LINES)})
            self.checker.step(sample, in_reset)
        if in_reset:
            self.core.reset(time)
        else:
            self.core.step(time, *(values[i] for i in _SAMPLED))

    def run(self, scenario, name=None, trace=None):
        """RST# for ``RESET_CLOCKS`` clocks, two more, ``scenario(bench)``, four
        more.  ``name``/``trace``: accepted for ``PciBench``'s call; the card's
        own waves are the model's (``VerilatedModel.trace``).  Returns None."""
        self.start()
        self.call(scenario(self))
        self.finish()
        return None

    def start(self):
        """RST# for ``RESET_CLOCKS`` clocks, then two idle clocks: the card is
        ready for ``call``."""
        model = self.model
        model["reset"] = 0
        self.core.reset(0)
        for _ in range(RESET_CLOCKS):
            self.clock_edge(in_reset=True)
        model["reset"] = 1
        for _ in range(2):
            self.clock_edge()

    def call(self, scenario):
        """Run the generator ``scenario`` (the host's transactions, ``Clocks``,
        ``CardWait``) to its end now, and return its value: one piece of a
        session that the caller drives step by step (``sim.card.card_session``)."""
        return self._trampoline(scenario)

    def finish(self):
        """Four more clocks, as ``PciBench`` runs after a scenario; the pins into the log."""
        for _ in range(AFTER_CLOCKS):
            self.clock_edge()
        self.card.collect_pins(self.target.log)

    def _trampoline(self, scenario):
        steps = scenario_steps(scenario, other=self._card_wait,
                               on_step=lambda: self.card.collect_pins(self.target.log))
        return run_steps(steps, lambda _: self.clock_edge())

    def _card_wait(self, item):
        if not isinstance(item, CardWait):
            raise TypeError(f"the scenario yielded {item!r}: the Verilator bench knows Request, Clocks "
                            "and CardWait")
        self._wait(item)
        yield from ()

    def _wait(self, wait):
        """Clock ``wait`` out: compiled while the bus is quiet, else clock by clock."""
        model, pending = self.model, wait.pending
        pending["rises"] = model.step_rises
        while wait.pending is not None:
            steps_left = pending["steps"] - (model.step_rises - pending["rises"]) if pending["steps"] else 0
            if pending["steps"] and steps_left <= 0:
                self.clock_edge()
                reason, ran = Stop.STEPS, 1
            elif self.core.quiet and self._released:
                reason, ran = model.run(pending["limit"] - pending["ran"], until_interrupt=pending["inta"],
                                        steps=steps_left)
            else:
                self.clock_edge()
                ran = 1
                reason = Stop.INTERRUPT if pending["inta"] and self.bus.values[_INTA] == 0 else Stop.LIMIT
            pending["ran"] += ran
            if reason in (Stop.INTERRUPT, Stop.STEPS) or pending["ran"] >= pending["limit"]:
                wait.finish(reason)
