"""The standard PCI bench: host + target + bus model + monitor + back end.

``PciBench`` builds the pieces on one clock (30 time units = 33.3 MHz, so
times read as ns); ``run(scenario, name)`` runs ``scenario(bench)`` (a
generator that calls the host's transactions) with a VCD trace and a GTKWave
save file, the monitor watching every clock.

Targets: ``target="myhdl"`` (``rtl.pci_slave``), ``"verilog"`` (the
generated ``gen/pci_slave.v`` in Icarus), or a function ``bench -> (agent,
[(block factory, args[, keyword args])])`` for any other target (the
behavioural one of the host tests, the whole card).
"""
from myhdl import Signal, StopSimulation, block, instance

from rtl.interfaces import card_reset
from sim.local_memory import LocalMemory, local_memory
from sim.paths import GEN
from sim.pci_bus import PciSegment, pci_segment
from sim.pci_host import PciHost, pci_host, run_scenario
from sim.pci_monitor import ProtocolChecker, pci_monitor
from sim.waves import Waveform, run_traced, write_gtkw
from sim.clocking import clock_source

CLOCK_PERIOD = 30  # time units per PCI clock; 30 ns is 33.3 MHz
RESET_CLOCKS = 3
TARGET_DEVICE = 0  # IDSEL of the target on AD[16]

WAVE_GROUPS = {
    "PCI": ["clock", "reset"] + [f"bus_{line}" for line in (
        "frame", "irdy", "ad_view", "cbe", "par", "devsel", "trdy", "stop", "perr", "serr",
        "inta")],
    "target drive": [f"target_{line}_oe" for line in (
        "ad", "par", "devsel", "trdy", "stop", "perr", "serr", "inta")] + ["irq"],
    "target state (MyHDL only: the paper's states)": ["state"],
    "local bus": ["local_space", "local_addr", "local_be", "local_we", "local_re",
                  "local_wdata", "local_rdata", "local_ready", "local_retry"],
}


class PciBench:
    """One bench.  ``slave_params``: parameters of ``pci_slave``;
    ``memory``: the back end (a LocalMemory sized to the BARs by default);
    ``host_options``: PciHost keyword arguments; ``allow_parity_errors``:
    passed to the monitor."""

    def __init__(self, target="myhdl", slave_params=None, memory=None, host_options=None,
                 allow_parity_errors=False):
        self.slave_params = dict(slave_params or {})
        self.target = target
        self.clock = Signal(bool(0))
        self.reset = card_reset()
        self.irq = Signal(bool(0))
        self.host = PciHost(self.clock, **(host_options or {}))
        self.ports = None
        self.memory = memory
        self.other_blocks = []
        if callable(target):
            agent, self.other_blocks = target(self)
        else:
            agent = self._slave_ports()
        self.segment = PciSegment({"host": self.host.agent, "target": agent},
                                  idsel={"target": 16 + TARGET_DEVICE})
        self.checker = ProtocolChecker(TARGET_DEVICE, self.host.parity_response, allow_parity_errors)

    def _slave_ports(self):
        from rtl.pci_slave import pci_slave_ports  # here: other targets need no RTL

        ports = pci_slave_ports(**self.slave_params)
        ports["clock"], ports["reset"], ports["irq"] = self.clock, self.reset, self.irq
        self.ports = ports
        if self.memory is None:
            io_bytes = 1 << self.slave_params.get("io_bar_bits", 6)
            mem_bytes = 1 << self.slave_params.get("mem_bar_bits", 12)
            self.memory = LocalMemory(io_bytes, mem_bytes)
        return ports["pci"]

    def target_blocks(self):
        """[(block factory, args)] of the target side, or a ready Cosimulation
        in place of a factory (MyHDL wants blocks created in the bench body)."""
        if callable(self.target):
            return self.other_blocks
        blocks = [(local_memory, (self.clock, self.reset, self.ports["local"], self.memory))]
        if self.target == "myhdl":
            from rtl.pci_slave import pci_slave

            return blocks + [(pci_slave, (), dict(self.ports, **self.slave_params))]
        if self.target == "verilog":
            return blocks + [(self._cosimulation(), None)]
        raise ValueError(f"unknown target {self.target!r}: use 'myhdl', 'verilog' or a function")

    def _cosimulation(self):
        from sim.cosim import convert_and_cosimulate, cosimulate

        if self.slave_params:
            from rtl.pci_slave import pci_slave

            return convert_and_cosimulate(pci_slave, "pci_slave", self.ports, **self.slave_params)
        verilog = GEN / "pci_slave.v"
        if not verilog.exists():
            raise FileNotFoundError(f"{verilog} missing: run python -m rtl.top --convert")
        return cosimulate("pci_slave", self.ports, [verilog])

    def run(self, scenario, name, trace=True, background=None):
        """Run ``scenario(bench)`` to its end, ``background(bench)`` (a
        generator, e.g. an interrupt source or a reset) beside it; return the
        VCD path (or None)."""
        top = pci_testbench(self, scenario, background)
        if not trace:
            try:
                top.run_sim(quiet=1)
            finally:
                if top.sim is not None and not top.sim._finished:
                    top.quit_sim()
            return None
        vcd = run_traced(top, name)
        write_gtkw(vcd, self._wave_groups(vcd))
        return vcd

    def _wave_groups(self, vcd):
        wave = Waveform(vcd)
        groups = {}
        for group, names in WAVE_GROUPS.items():
            present = []
            for suffix in names:
                try:
                    wave.full_name(suffix)
                except KeyError:
                    continue
                present.append(suffix)
            if present:
                groups[group] = present
        return groups

    def clocks(self, count):
        """Generator: wait ``count`` rising edges."""
        for _ in range(count):
            yield self.clock.posedge


@block
def pci_testbench(bench, scenario, background=None):
    """Clock, RST# for ``RESET_CLOCKS`` clocks, host, segment, monitor,
    target and back end; stops when ``scenario`` returns (``background``
    runs beside it from the end of reset on).

        clock  _/~\\_/~\\_/~\\_/~\\_/~\\_
        RST#   __________/~~~~~~~~~~~    then the scenario runs
    """
    clock, reset = bench.clock, bench.reset
    lines = bench.segment.lines
    bus_ad, bus_ad_view, bus_cbe, bus_par = lines.ad, lines.ad_view, lines.cbe, lines.par
    bus_frame, bus_irdy, bus_trdy, bus_devsel, bus_stop = (
        lines.frame, lines.irdy, lines.trdy, lines.devsel, lines.stop)
    bus_perr, bus_serr, bus_inta = lines.perr, lines.serr, lines.inta
    # Named before any instance: MyHDL takes a bench's trace names from the
    # locals at its first instantiation.  Co-simulated ports only show so.
    if bench.ports is not None:
        pci, local, irq = bench.ports["pci"], bench.ports["local"], bench.irq
        target_ad_oe, target_par_oe, target_devsel_oe, target_trdy_oe, target_stop_oe = (
            pci.ad_oe, pci.par_oe, pci.devsel_oe, pci.trdy_oe, pci.stop_oe)
        target_perr_oe, target_serr_oe, target_inta_oe = pci.perr_oe, pci.serr_oe, pci.inta_oe
        local_space, local_addr, local_be, local_wdata, local_we, local_re = (
            local.space, local.addr, local.be, local.wdata, local.we, local.re)
        local_rdata, local_ready, local_retry = local.rdata, local.ready, local.retry

    host_driver = pci_host(clock, reset, bench.host)
    segment = pci_segment(clock, bench.segment)
    monitor = pci_monitor(clock, reset, bench.segment, bench.checker)
    target = []
    for entry in bench.target_blocks():
        factory, args = entry[0], entry[1]
        options = entry[2] if len(entry) > 2 else {}
        target.append(factory if args is None else factory(*args, **options))

    clock_driver = clock_source(clock, 2 * CLOCK_PERIOD // 2)

    @instance
    def stimulus():
        reset.next = reset.active
        # only ``yield from`` here: MyHDL would otherwise infer an edge-only
        # waiter from a plain ``yield`` and break the scenario's signal waits
        yield from bench.clocks(RESET_CLOCKS)
        reset.next = not reset.active
        yield from bench.clocks(2)
        yield from run_scenario(bench.host, scenario(bench))
        yield from bench.clocks(4)
        raise StopSimulation()

    @instance
    def beside():
        yield from bench.clocks(RESET_CLOCKS + 2)
        if background is not None:
            yield from run_scenario(bench.host, background(bench))

    return host_driver, segment, monitor, target, clock_driver, stimulus, beside
