"""A PCI segment in plain Python: the host core, per-edge agents and the
protocol checker on one clock, with no simulator at all.

Each agent is an object with ``drive`` (``<line>_out`` / ``<line>_oe``
attributes for the lines it may drive, as ``HostDrive``) and
``step(sample)`` (called at every rising edge with the ``BusSample`` of the
clock that ended, after which ``drive`` holds its drive for the next clock):
``sim.pci.delayed_target.DelayedTarget`` is one.  The loop resolves every
line as the MyHDL bus model does (pull-ups on the control lines, AD, C/BE#
and PAR floating as ``None``, SERR# and INTA# wired-OR), feeds the checker,
steps the host core and the agents, and runs scenarios with the core's
trampoline.  Fast enough for long sweeps (tens of thousands of clocks a
second with the checker).

    bus = PythonBus(PciMaster(), {"target": DelayedTarget()})
    bus.reset()
    result = bus.run(bus.host.mem_read(0x80000000, 64))
"""
from sim.pci.checker import ProtocolChecker
from sim.pci.host_core import run_scenario
from sim.pci.lines import LINE_WIDTHS, OPEN_DRAIN, PULLED_UP, BusSample

CLOCK_PERIOD = 30


class PythonBus:
    """``host``: a ``PciMaster``; ``agents``: {name: agent}; ``checker``: a
    ``ProtocolChecker`` (default: a fresh one; None: no checking)."""

    def __init__(self, host, agents, checker="default", period=CLOCK_PERIOD):
        self.host = host
        self.core = host.core
        self.agents = dict(agents)
        if "host" in self.agents:
            raise ValueError("'host' names the host's own drive")
        self.checker = ProtocolChecker(master_parity_response=host.parity_response) \
            if checker == "default" else checker
        self.period = period
        self.time = 0
        self.edges = 0
        everyone = {"host": self.core.drive, **{name: a.drive for name, a in self.agents.items()}}
        self._ports = {line: [(name, drive, f"{line}_out", f"{line}_oe") for name, drive in everyone.items()
                              if hasattr(drive, f"{line}_oe")] for line in LINE_WIDTHS}
        self._names = {}
        self.sample = None

    def _resolve(self):
        values, drivers = {}, {}
        names_cache = self._names
        for line, ports in self._ports.items():
            names = []
            value = None
            for name, drive, out, enable in ports:
                if getattr(drive, enable):
                    names.append(name)
                    level = getattr(drive, out)
                    if line in OPEN_DRAIN:
                        value = level if value is None else value & level
                    else:
                        value = level if value is None else value | level
            if value is None and line in PULLED_UP:
                value = 1
            key = tuple(names)
            group = names_cache.get(key)
            if group is None:
                group = names_cache[key] = frozenset(names)
            values[line], drivers[line] = value, group
        return BusSample(self.time, values, drivers)

    def edge(self):
        """One rising edge: sample, check, step the host and every agent."""
        self.time += self.period
        self.edges += 1
        sample = self.sample = self._resolve()
        if self.checker is not None:
            self.checker.step(sample)
        values = sample.values
        self.core.step(self.time, values["ad"] or 0, values["par"] or 0, values["frame"],
                       values["irdy"], values["trdy"], values["devsel"], values["stop"])
        for agent in self.agents.values():
            agent.step(sample)

    def reset(self, clocks=3):
        """RST# for ``clocks`` edges (the checker sees them as reset clocks)."""
        self.core.reset(self.time)
        for _ in range(clocks):
            self.time += self.period
            self.edges += 1
            if self.checker is not None:
                self.checker.step(self._resolve(), in_reset=True)

    def run(self, scenario):
        """Run ``scenario`` (a generator of host waits) to its end; its result."""
        return run_scenario(scenario, self.edge)
