"""The whole card (``card``, split PCI ports) as a Verilated model, on a PCI bench.

``VerilatedCard(verilog)`` builds (or takes from the cache) the model of
``gen/card.v`` or another ``card.v`` and binds its ports by the names MyHDL
gives them (``pci_<line>_in/_out/_oe``, ``pci_idsel_in``, ``pins_<pin>``,
``clock``, ``reset``): nothing else of the Verilog is assumed.

``sim/backends/verilator/pci_bus.py`` puts it on the PCI bus with the host engine and the
protocol checker.  ``CardWait`` is a wait a scenario asks for (clocks,
INTA#, STEP rises): run in compiled code there, counted edge by edge by
``card_waiter`` on the MyHDL and Icarus benches, ending at the same clock.
"""
import numpy as np
from myhdl import Signal, block, instance

from models import registers as regmap
from models.axes import AXIS_NAMES
from rtl.convert import GEN_DIR
from sim.backends.verilator.build import VerilatorError, build_model
from sim.backends.verilator.model import LINES, PINS, Stop, VerilatedModel
from sim.card.card_bench import PIN_BITS, PinLog

TOP = "card"


def rises(clocks, states, before=0):
    """PinLog-style rises ``(clock, x stepped, y stepped, dir x, dir y)`` from
    pin edges (``before``: the pins' state ahead of the first edge)."""
    states = np.asarray(states, dtype=np.uint16)
    previous = np.concatenate(([before], states[:-1])).astype(np.uint16)
    rose = states & ~previous
    step_x, step_y = (rose & PIN_BITS["step_x"]) != 0, (rose & PIN_BITS["step_y"]) != 0
    keep = step_x | step_y
    dir_x, dir_y = (states & PIN_BITS["dir_x"]) != 0, (states & PIN_BITS["dir_y"]) != 0
    return [(int(c), bool(sx), bool(sy), bool(dx), bool(dy)) for c, sx, sy, dx, dy in
            zip(np.asarray(clocks)[keep], step_x[keep], step_y[keep], dir_x[keep], dir_y[keep])]


class VerilatedCard:
    """The card's model with its roles bound; ``idsel_bit``: the AD line IDSEL is wired to."""

    def __init__(self, verilog=None, trace=None, idsel_bit=16):
        self.verilog = verilog or GEN_DIR / f"{TOP}.v"
        self.model = VerilatedModel(build_model([self.verilog], TOP, trace=trace))
        model = self.model
        model.bind_clock("clock")
        model.bind_pins([f"pins_{pin}" for pin in PINS])
        lines = {}
        for line in LINES:
            names = tuple(f"pci_{line}_{kind}" for kind in ("in", "out", "oe"))
            lines[line] = tuple(n if n in model.ports else None for n in names)
        if lines["ad"][0] is None:
            raise VerilatorError(f"{self.verilog} has no pci_ad_in: not the split-port card")
        model.bind_bus(lines, "pci_idsel_in", idsel_bit)
        self.lines = lines

    @property
    def axes(self):
        """The card's axes: those whose STEP pin the model has (X, Y, ...)."""
        return sum(f"pins_step_{name.lower()}" in self.model.ports for name in AXIS_NAMES)

    def start_machine(self, config):
        """The simulated machine of ``config`` (``models.sim_machine.MachineConfig``)
        on the input pins of the card's axes (its motors on the encoder inputs
        of a card built with encoders), run in the compiled clock loop; a
        configuration naming an axis the card lacks is a ValueError."""
        axes = self.axes
        config.check_axes(axes)
        encoders = [[f"pins_{pin}_{name.lower()}" for pin in ("enc_a", "enc_b", "enc_index")]
                    for name in AXIS_NAMES[:axes]]
        if config.motors and encoders[0][0] not in self.model.ports:
            raise VerilatorError("the machine's motors drive encoder inputs: the card must be built with encoders")
        self.model.start_machine(config, axes, [f"pins_{name.lower()}" for name in regmap.input_names(axes)],
                                 "pins_drive_enable", encoders)

    def collect_pins(self, log):
        """Move the edges recorded so far into ``log`` (an ``ArrayPinLog``)."""
        clocks, states = self.model.take_edges()
        if len(states):
            log.add(clocks, states)
        log.clock = self.model.clocks


class ArrayPinLog(PinLog):
    """A ``PinLog`` fed with the harness's arrays of pin edges; ``rises`` and
    ``edges`` become lists only when read (a long run need not pay for them)."""

    def __init__(self):
        super().__init__()
        self._chunks, self._state = [], 0
        self._rises, self._edges = [], []

    def add(self, clocks, states):
        self._chunks.append((clocks, states))

    def _materialize(self):
        for clocks, states in self._chunks:
            self._rises.extend(rises(clocks, states, self._state))
            self._edges.extend(zip(clocks.tolist(), states.tolist()))
            self._state = int(states[-1])
        self._chunks.clear()

    @property
    def rises(self):
        self._materialize()
        return self._rises

    @rises.setter
    def rises(self, value):  # the dataclass's own __init__ sets it
        self._rises = value

    @property
    def edges(self):
        self._materialize()
        return self._edges

    @edges.setter
    def edges(self, value):
        self._edges = value


class CardWait:
    """A wait the scenario hands to the bench: up to ``limit`` clocks, or
    fewer when INTA# is sampled low (``inta``) or ``steps`` STEP rises have
    been recorded (each judged at a rising edge on the clock before it, as a
    bus agent samples).  ``waited`` tells the clocks and ``reason`` why (a
    ``Stop``).  The scenario yields ``event``: on a MyHDL bench (``signal``)
    a Signal that toggles when the wait is over, else the wait itself, which
    ``sim.backends.verilator.pci_bus.VerilatorBench`` runs."""

    def __init__(self, signal):
        self.pending = None
        self.done = Signal(bool(0)) if signal else None
        self.waited = 0
        self.reason = None

    @property
    def event(self):
        return self if self.done is None else self.done

    def ask(self, limit, inta=False, steps=0):
        if limit < 1:
            raise ValueError(f"a wait lasts at least one clock, not {limit}")
        self.pending = dict(limit=limit, inta=inta, steps=steps, ran=0, rises=None)

    def finish(self, reason):
        self.waited, self.reason, self.pending = self.pending["ran"], reason, None
        if self.done is not None:
            self.done.next = not self.done


@block
def card_waiter(clock, wait, bench, log):
    """The same waits for a card simulated edge by edge (MyHDL, Icarus):
    INTA# as ``bench``'s segment resolves it, STEP rises from ``log`` (the
    ``PinLog`` of the pins)."""
    inta = bench.segment.lines.inta

    def rises():
        return sum(r[1] + r[2] for r in log.rises)

    @instance
    def watch():
        while True:
            yield clock.posedge
            pending = wait.pending
            if pending is None:
                continue
            if pending["rises"] is None:
                pending["rises"] = rises()
            pending["ran"] += 1
            if pending["inta"] and not inta.val:
                wait.finish(Stop.INTERRUPT)
            elif pending["steps"] and rises() - pending["rises"] >= pending["steps"]:
                wait.finish(Stop.STEPS)
            elif pending["ran"] >= pending["limit"]:
                wait.finish(Stop.LIMIT)

    return watch
