"""The whole card (``card``, split PCI ports) as a Verilated model, on a PCI bench.

``VerilatedCard(verilog)`` builds (or takes from the cache) the model of
``gen/card.v`` or another ``card.v`` and binds its ports by the names MyHDL
gives them (``pci_<line>_in/_out/_oe``, ``pci_idsel_in``, ``pins_<pin>``,
``clock``, ``reset``): nothing else of the Verilog is assumed.

On a MyHDL bench (``sim/pci_bench.py``, with the behavioural host, the bus
model and the protocol monitor), ``verilated_card_on_bus`` is the card: one
foreign call per rising edge and per change of the card's inputs.  A wait
asked for through ``CardWait`` (clocks, INTA#, STEP rises) runs in compiled
code instead, between two of the bench's clocks, once the host has left the
bus: the card's clock count then runs ahead of the bench's time by the
clocks run, and the pins keep the card's clock numbers.

    bench clock  _/~\\_/~\\___________/~\\_/~\\_
    card clocks    1   2  [3 .. 4002]  4003     run(until INTA#) at edge 3
"""
import numpy as np
from myhdl import Signal, block, instance

from sim.card_bench import PIN_BITS
from sim.paths import GEN
from sim.vlt.build import VerilatorError, build_model
from sim.vlt.model import LINES, PINS, Stop, VerilatedModel

TOP = "card"


def rises(clocks, states, before=0):
    """PinLog-style rises ``(clock, x stepped, y stepped, dir x, dir y)`` from
    pin edges (``before``: the pins' state ahead of the first edge)."""
    states = np.asarray(states, dtype=np.uint8)
    previous = np.concatenate(([before], states[:-1])).astype(np.uint8)
    rose = states & ~previous
    step_x, step_y = (rose & PIN_BITS["step_x"]) != 0, (rose & PIN_BITS["step_y"]) != 0
    keep = step_x | step_y
    dir_x, dir_y = (states & PIN_BITS["dir_x"]) != 0, (states & PIN_BITS["dir_y"]) != 0
    return [(int(c), bool(sx), bool(sy), bool(dx), bool(dy)) for c, sx, sy, dx, dy in
            zip(np.asarray(clocks)[keep], step_x[keep], step_y[keep], dir_x[keep], dir_y[keep])]


class VerilatedCard:
    """The card's model with its roles bound; ``idsel_bit``: the AD line IDSEL is wired to."""

    def __init__(self, verilog=None, trace=None, idsel_bit=16):
        self.verilog = verilog or GEN / f"{TOP}.v"
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
        self.pin_state = 0

    def collect_pins(self, log):
        """Move the edges recorded so far into ``log`` (a ``PinLog``)."""
        clocks, states = self.model.take_edges()
        if len(states):
            log.rises.extend(rises(clocks, states, self.pin_state))
            log.edges.extend(zip(clocks.tolist(), states.tolist()))
            self.pin_state = int(states[-1])
        log.clock = self.model.clocks


class CardWait:
    """A wait the scenario hands to the bench: up to ``limit`` clocks, or
    fewer when INTA# is sampled low (``inta``) or ``steps`` STEP rises have
    been recorded (each judged at a rising edge on the clock before it, as a
    bus agent samples).  ``done`` toggles when it is over; ``waited`` tells
    the clocks and ``reason`` why (a ``Stop``)."""

    def __init__(self):
        self.pending = None
        self.done = Signal(bool(0))
        self.waited = 0
        self.reason = None

    def ask(self, limit, inta=False, steps=0):
        if limit < 1:
            raise ValueError(f"a wait lasts at least one clock, not {limit}")
        self.pending = dict(limit=limit, inta=inta, steps=steps, ran=0, rises=None)

    def finish(self, reason):
        self.waited, self.reason, self.pending = self.pending["ran"], reason, None
        self.done.next = not self.done


@block
def verilated_card_on_bus(clock, reset, pci, card, log, wait, host):
    """``card`` (a ``VerilatedCard``) as the target ``pci`` (``PciBus``) of a bench.

    clock, reset: the bench's; log: the ``PinLog`` the pins go to; wait: a
    ``CardWait``; host: the host's agent (a wait runs compiled only after a
    clock in which the host drove nothing).  At a rising edge the card gets
    the inputs of the clock that ended and is clocked, or runs the pending
    wait; when an input changes it settles; its outputs go to ``pci``'s
    out/oe Signals.

        clock      _/~\\_/~\\_/~\\_
        pci *_in   --< i1 >< i2 >--     set as they change, settled
        pci *_out  ----< o1 >< o2 >     after each edge and each settle
    """
    model = card.model
    in_names = ["reset", "pci_ad_in", "pci_cbe_in", "pci_par_in", "pci_frame_in", "pci_irdy_in", "pci_idsel_in"]
    in_signals = [reset] + [getattr(pci, n[len("pci_"):]) for n in in_names[1:]]
    out_names = [n for line in LINES for n in card.lines[line][1:] if n is not None]
    out_signals = [getattr(pci, n[len("pci_"):]) for n in out_names]
    port = model.io_exchange(in_names, out_names)
    values, out = port.values, port.out
    host_enables = [getattr(host, f"{line}_oe") for line in LINES]

    def exchange(tick):
        for index, signal in enumerate(in_signals):
            values[index] = int(signal.val)
        port(tick)
        for signal, value in zip(out_signals, out.tolist()):
            signal.next = value

    def run_wait():
        pending = wait.pending
        if pending["rises"] is None:
            pending["rises"] = model.step_rises
        quiet = not any(enable.val for enable in host_enables)
        steps_left = pending["steps"] - (model.step_rises - pending["rises"]) if pending["steps"] else 0
        if pending["steps"] and steps_left <= 0:
            model.tick()
            reason, ran = Stop.STEPS, 1
        else:
            limit = pending["limit"] - pending["ran"] if quiet else 1
            reason, ran = model.run(limit, until_interrupt=pending["inta"], steps=steps_left)
        pending["ran"] += ran
        if reason in (Stop.INTERRUPT, Stop.STEPS) or pending["ran"] >= pending["limit"]:
            wait.finish(reason)

    @instance
    def edges():
        while True:
            yield clock.posedge
            if wait.pending is None:
                exchange(True)
            else:
                exchange(False)
                run_wait()
                exchange(False)
            card.collect_pins(log)

    @instance
    def settle():
        while True:
            yield tuple(in_signals)
            exchange(False)

    return edges, settle


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
