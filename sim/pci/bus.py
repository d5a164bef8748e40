"""Bus model of a 32-bit PCI segment for test benches.

Every agent on the segment (the host, a target core, a scripted agent) is an
object with ``<line>_out`` / ``<line>_oe`` Signals for the lines it may drive
and ``<line>_in`` Signals for the lines it samples (``rtl.interfaces.PciBus``
is such an object, so is ``PciAgent``).  ``PciSegment`` resolves every shared
line from all drivers:

* undriven control lines (FRAME#, IRDY#, TRDY#, DEVSEL#, STOP#, PERR#, SERR#,
  INTA#) read 1 (the system board's pull-ups);
* undriven AD, C/BE# and PAR read 0 for logic, and the segment marks them as
  floating (``<line>_driven`` low) so that the monitor and the waveform can
  tell (``ad_view`` is a tri-state copy of AD that shows ``z`` in GTKWave);
* SERR# and INTA# are wired-OR (open drain): any driver low pulls them low.

IDSEL of a target is wired to one AD line (``idsel={agent: ad_bit}``), as on a
mother board.  At every rising clock edge the segment records who drove each
line in the clock that just ended (``drivers`` of ``sample()``), which the
monitor uses for the contention and turnaround rules.
"""
from collections import deque

from myhdl import Signal, TristateSignal, always, block, instance, intbv, now

from sim.pci.lines import LINE_WIDTHS, OPEN_DRAIN, PULLED_UP, SUSTAINED_TRISTATE, BusSample, even_parity  # noqa: F401


def _line_signal(line, value):
    width = LINE_WIDTHS[line]
    return Signal(bool(value)) if width == 1 else Signal(intbv(value)[width:])


class PciAgent:
    """Drive and sample ports of a generic agent: ``<line>_out``,
    ``<line>_oe`` and ``<line>_in`` for every line, plus ``idsel_in``."""

    def __init__(self):
        for line in LINE_WIDTHS:
            idle = 1 if line in PULLED_UP else 0
            setattr(self, f"{line}_out", _line_signal(line, idle))
            setattr(self, f"{line}_oe", Signal(bool(0)))
            setattr(self, f"{line}_in", _line_signal(line, idle))
        self.idsel_in = Signal(bool(0))


class PciLines:
    """The resolved segment: one Signal per line (the logic value) and, for
    AD, C/BE# and PAR, whether anyone drives it."""

    def __init__(self):
        for line in LINE_WIDTHS:
            setattr(self, line, _line_signal(line, 1 if line in PULLED_UP else 0))
        self.ad_driven = Signal(bool(0))
        self.cbe_driven = Signal(bool(0))
        self.par_driven = Signal(bool(0))
        self.ad_view = TristateSignal(intbv(0)[32:])


class PciSegment:
    """Resolution and driver record of one PCI segment.

    ``agents`` maps a name to an agent object; ``idsel`` maps a name to the AD
    bit its IDSEL input is wired to.  ``history`` keeps the last
    ``history_depth`` samples.
    """

    def __init__(self, agents, idsel=None, history_depth=64):
        if not agents:
            raise ValueError("a PCI segment needs at least one agent")
        self.agents = dict(agents)
        self.idsel = dict(idsel or {})
        unknown = set(self.idsel) - set(self.agents)
        if unknown:
            raise ValueError(f"IDSEL given for unknown agents {sorted(unknown)}")
        for name, bit in self.idsel.items():
            if not 11 <= bit <= 31:
                raise ValueError(f"IDSEL of {name} must be wired to AD[31:11], not AD[{bit}]")
        self.lines = PciLines()
        self.history = deque(maxlen=history_depth)
        self._ports = {line: self._drive_ports(line) for line in LINE_WIDTHS}
        self.values, self.drivers = {}, {}
        self._seen = {}
        self._unknown = []          # [(Signal, lines)] of X/Z detectors
        for line in LINE_WIDTHS:
            self.update(line)

    def _drive_ports(self, line):
        ports = []
        for name, agent in self.agents.items():
            out = getattr(agent, f"{line}_out", None)
            enable = getattr(agent, f"{line}_oe", None)
            if out is not None and enable is not None:
                ports.append((name, out, enable))
        return ports

    def resolve(self, line):
        """(value, drivers) of ``line`` from the agents' current out/oe."""
        drivers = [(name, int(out.val)) for name, out, enable in self._ports[line] if enable.val]
        names = frozenset(name for name, _ in drivers)
        if line in OPEN_DRAIN:
            value = 0 if any(v == 0 for _, v in drivers) else 1
        elif drivers:
            value = 0
            for _, v in drivers:
                value |= v
        else:
            value = None
        return value, names

    def update(self, line):
        """Re-resolve ``line`` into ``values``/``drivers`` if any of its
        drivers changed; return whether it did."""
        seen = tuple((bool(enable.val), int(out.val)) for _, out, enable in self._ports[line])
        if self._seen.get(line) == seen:
            return False
        self._seen[line] = seen
        value, names = self.resolve(line)
        if value is None and line in PULLED_UP:
            value = 1
        self.values[line], self.drivers[line] = value, names
        return True

    def watch_unknown(self, report, lines):
        """Take X/Z reports into every sample: bit i of the Signal ``report``
        high means ``lines[i]`` was X or Z while driven (a four-state
        simulator's detector, e.g. the wrapper of ``sim.pci.verilog_target``)."""
        self._unknown.append((report, tuple(lines)))

    def sample(self):
        """The segment as it is now (at a rising edge: the clock that ended)."""
        unknown = frozenset()
        for report, lines in self._unknown:
            bits = int(report.val)
            if bits:
                unknown |= {line for bit, line in enumerate(lines) if bits >> bit & 1}
        return BusSample(now(), dict(self.values), dict(self.drivers), unknown)


@block
def pci_segment(clock, segment):
    """Resolve ``segment``'s lines and feed every agent's ``*_in`` ports.

    clock: the PCI clock (only used to record the drivers per clock).
    segment: a ``PciSegment``.  The resolved lines are traced under their
    own names (``frame``, ``ad_view`` ...).

        clock      _/~\\_/~\\_/~\\_
        agent oe   __/~~~~~\\_____
        line       zz< val >zzzzz    resolved the same delta cycle
        history       ^   ^   ^      one BusSample per rising edge
    """
    lines = segment.lines
    ad, cbe, par, frame, irdy, trdy, devsel, stop, perr, serr, inta = (
        getattr(lines, line) for line in LINE_WIDTHS)
    ad_view = lines.ad_view
    view = ad_view.driver()
    sensitivity = tuple(s for ports in segment._ports.values() for _, out, enable in ports
                        for s in (out, enable))  # a tuple: MyHDL would trace a list as a memory
    inputs = {line: [getattr(a, f"{line}_in") for a in segment.agents.values()
                     if hasattr(a, f"{line}_in")] for line in LINE_WIDTHS}
    idsel_inputs = [(segment.agents[name].idsel_in, bit) for name, bit in segment.idsel.items()]

    @instance
    def resolver():
        everything = True  # the first pass sets every input, later ones what changed
        while True:
            for line in LINE_WIDTHS:
                if segment.update(line) or everything:
                    _drive_line(segment, line, inputs[line])
            everything = False
            ad_value = segment.values["ad"]
            view.next = ad_value
            for port, bit in idsel_inputs:
                port.next = bool(((ad_value or 0) >> bit) & 1)
            yield sensitivity

    @always(clock.posedge)
    def recorder():
        segment.history.append(segment.sample())

    return resolver, recorder


def _drive_line(segment, line, inputs):
    value = segment.values[line]
    floating = value is None
    if floating:
        value = 0
    getattr(segment.lines, line).next = value
    for port in inputs:
        port.next = value
    driven = getattr(segment.lines, f"{line}_driven", None)
    if driven is not None:
        driven.next = not floating


@block
def scripted_agent(clock, agent, script, done=None):
    """Drive ``agent`` from a script: one dict per clock, ``{line: value}``
    drives a line, ``{line: None}`` releases it, lines not named keep their
    state.  Values change just after the rising edge that starts the clock.

    clock: the PCI clock; agent: a ``PciAgent``; script: list of dicts;
    done: optional Signal(bool) set once the script has been played.

        clock   _/~\\_/~\\_/~\\_
        line    --<s[0]><s[1]>--
    """

    @instance
    def player():
        for step in script:
            yield clock.posedge
            for line, value in step.items():
                if line not in LINE_WIDTHS:
                    raise ValueError(f"unknown PCI line {line!r} in script")
                if value is None:
                    getattr(agent, f"{line}_oe").next = False
                else:
                    getattr(agent, f"{line}_out").next = value
                    getattr(agent, f"{line}_oe").next = True
        yield clock.posedge
        if done is not None:
            done.next = True

    return player


@block
def edge_agent(clock, reset, agent, model):
    """A per-edge Python agent (``model.step(sample)``, ``model.drive``; e.g.
    ``sim.pci.delayed_target.DelayedTarget``) on ``agent``'s Signals (a
    ``PciAgent`` on a ``PciSegment``).  While RST# (``reset``, or None) is
    asserted the agent is released and not stepped.

        clock        _/~\\_/~\\_/~\\_
        agent *_in     ^   ^   ^       sampled: model.step(sample)
        agent out/oe   --< d >< d >    model.drive for the next clock
    """
    drive = model.drive
    names = [line for line in LINE_WIDTHS if hasattr(drive, f"{line}_oe")]
    ports = [(getattr(agent, f"{line}_out"), getattr(agent, f"{line}_oe"), f"{line}_out", f"{line}_oe")
             for line in names]
    inputs = [(line, getattr(agent, f"{line}_in")) for line in LINE_WIDTHS]

    @instance
    def run():
        while True:
            yield clock.posedge
            if reset is not None and reset.val == reset.active:
                for _, enable, _, _ in ports:
                    enable.next = False
                continue
            values = {line: int(port.val) for line, port in inputs}
            model.step(BusSample(now(), values, {}))
            for out, enable, out_name, enable_name in ports:
                out.next = getattr(drive, out_name)
                enable.next = getattr(drive, enable_name)

    return run
