"""The standard PCI bench: host + target + bus model + monitor + back end.

``PciBench`` builds the pieces on one clock (30 time units = 33.3 MHz, so
times read as ns); ``run(scenario, name)`` runs ``scenario(bench)`` (a
generator that calls the host's transactions) with a VCD trace and a GTKWave
save file, the monitor watching every clock.

Targets: ``target="myhdl"`` (``rtl.pci_slave``), ``"verilog"`` (the
generated ``gen/pci_slave.v`` in Icarus), a ``VerilogTarget`` (any Verilog
PCI target, ``sim.pci.verilog_target``), or a function ``bench -> (agent, blocks)``
for any other target (the behavioural ones of the host tests, the whole
card), ``blocks`` a list of ``(block factory, args[, keyword args])`` or a
function ``bench -> list`` called once the bus model exists.

Verilog targets run in float mode (``floating=True``): an AD, C/BE# or PAR
line nobody drives reaches them as ``z``, and an X/Z detector on every line
they drive reports to the monitor (rule 19; rule 20 for X/Z the host takes
as read data).  The monitor stops at the
first violation (``monitor="stop"``) or records every one and fails the run
at its end with a summary (``monitor="record"``).
"""
from myhdl import Signal, StopSimulation, block, instance, intbv, now

from models.parameters import Build
from rtl.convert import GEN_DIR
from rtl.interfaces import card_reset
from sim.backends.clocking import clock_source
from sim.backends.icarus import flatten_ports
from sim.backends.waves import Waveform, run_traced, write_gtkw
from sim.card.local_memory import LocalMemory, local_memory
from sim.pci.bus import PciSegment, pci_segment
from sim.pci.host import MEMORY_WRITES, PciHost, pci_host, run_scenario
from sim.pci.lines import LINE_WIDTHS
from sim.pci.monitor import ProtocolChecker, pci_monitor
from sim.pci.verilog_target import TargetAgent, VerilogTarget, pci_target_cosimulation, split_pins

CLOCK_PERIOD = 30  # time units per PCI clock; 30 ns is 33.3 MHz
RESET_CLOCKS = 3
SETTLE_CLOCKS = 2  # idle clocks after RST# rises before the scenario starts
TARGET_DEVICE = 0  # IDSEL of the target on AD[16]

WAVE_GROUPS = {
    "PCI": ["clock", "reset"] + [f"bus_{line}" for line in (
        "frame", "irdy", "ad_view", "cbe", "par", "devsel", "trdy", "stop", "perr", "serr",
        "inta")],
    "target drive": [f"target_{line}_oe" for line in (
        "ad", "par", "devsel", "trdy", "stop", "perr", "serr", "inta")] + ["irq"],
    "target state (MyHDL only: the paper's states)": ["state"],
    "local bus": ["local_space", "local_addr", "local_be", "local_we", "local_re",
                  "local_wdata", "local_rdata", "local_ready", "local_retry", "local_room"],
}


class PciBench:
    """One bench.  ``build``: the ``Build`` of ``pci_slave`` (default: ``Build()``);
    ``memory``: the back end (a LocalMemory sized to the BARs by default);
    ``host_options``: PciHost keyword arguments; ``allow_parity_errors``:
    passed to the monitor; ``monitor``: "stop" or "record";
    ``settle_clocks``: idle clocks between the end of RST# and the
    scenario (default ``SETTLE_CLOCKS``, 2: enough for this card; PCI allows
    a device 2^25 clocks before its first configuration access, Trhfa, so
    a slow target may need more, or an ``enumerate_bus(settle_clocks=...)``
    that retries master-aborted reads); ``floating``: float mode of
    Verilog targets.  ``outputs``: ``{name: Signal}`` of the outputs a
    ``VerilogTarget`` names in its ``outputs``, for a scenario to watch."""

    def __init__(self, target="myhdl", build=None, memory=None, host_options=None,
                 allow_parity_errors=False, monitor="stop", settle_clocks=SETTLE_CLOCKS,
                 floating=True):
        if settle_clocks < 1:
            raise ValueError(f"settle_clocks must be >= 1, not {settle_clocks}")
        self.build = Build() if build is None else build
        self.target = target
        self.settle_clocks = settle_clocks
        self.floating = floating
        self.clock = Signal(bool(0))
        self.reset = card_reset()
        self.irq = Signal(bool(0))
        self.host = PciHost(self.clock, **(host_options or {}))
        self.ports = None
        self.memory = memory
        self.other_blocks = []
        self.outputs = {}
        if isinstance(target, VerilogTarget):
            agent = TargetAgent([line for line in LINE_WIDTHS if target.drives(line)])
            self.outputs = {name: Signal(bool(0)) if width == 1 else Signal(intbv(0)[width:])
                            for name, width in target.output_widths().items()}
        elif callable(target):
            agent, self.other_blocks = target(self)
        else:
            agent = self._slave_ports()
        self.agent = agent
        self.segment = PciSegment({"host": self.host.agent, "target": agent},
                                  idsel={"target": 16 + TARGET_DEVICE})
        self.checker = ProtocolChecker(TARGET_DEVICE, self.host.parity_response, allow_parity_errors,
                                       mode=monitor)

    def _slave_ports(self):
        from rtl.pci_slave import pci_slave_ports  # here: other targets need no RTL

        ports = pci_slave_ports(self.build.io_bar_bits, self.build.mem_bar_bits)
        ports["clock"], ports["reset"], ports["irq"] = self.clock, self.reset, self.irq
        self.ports = ports
        if self.memory is None:
            self.memory = LocalMemory(1 << self.build.io_bar_bits, 1 << self.build.mem_bar_bits)
        return ports["pci"]

    def target_blocks(self):
        """[(block factory, args)] of the target side, or a ready Cosimulation
        in place of a factory (MyHDL wants blocks created in the bench body)."""
        if isinstance(self.target, VerilogTarget):
            return [(self._target_cosimulation(self.target, self.outputs), None)]
        if callable(self.target):
            blocks = self.other_blocks
            return blocks(self) if callable(blocks) else blocks
        blocks = [(local_memory, (self.clock, self.reset, self.ports["local"], self.memory))]
        if self.target == "myhdl":
            from rtl.pci_slave import pci_slave

            return blocks + [(pci_slave, (), dict(self.ports, build=self.build))]
        if self.target == "verilog":
            return blocks + [(self._cosimulation(), None)]
        raise ValueError(f"unknown target {self.target!r}: use 'myhdl', 'verilog' or a function")

    def _cosimulation(self):
        from sim.backends.icarus import convert_module

        if self.build != Build():
            from rtl.pci_slave import pci_slave

            verilog = convert_module(pci_slave, "pci_slave", self.ports, build=self.build)
        else:
            verilog = GEN_DIR / "pci_slave.v"
            if not verilog.exists():
                raise FileNotFoundError(f"{verilog} missing: run python -m rtl.top --convert")
        target = VerilogTarget([verilog], "pci_slave", split_pins([verilog], "pci_slave"), clock="clock",
                               reset="reset", idsel="pci_idsel_in")
        others = {name: signal for name, signal in flatten_ports(self.ports).items()
                  if not name.startswith("pci_") and name not in ("clock", "reset")}
        return self._target_cosimulation(target, others)

    def _target_cosimulation(self, target, others=None):
        return pci_target_cosimulation(target, self.clock, self.reset, self.agent, self.segment,
                                       self.host.agent, 16 + TARGET_DEVICE, self.floating, others)

    def run(self, scenario, name, trace=None, background=None):
        """Run ``scenario(bench)`` to its end, ``background(bench)`` (a
        generator, e.g. an interrupt source or a reset) beside it; return the
        VCD path, or None if untraced.  ``trace``: True when the caller reads
        the VCD back, False never, None when every bench's waves are wanted
        (``sim.backends.waves.run_traced``)."""
        top = pci_testbench(self, scenario, background)
        vcd = run_traced(top, name, trace=trace)
        if vcd is not None:
            write_gtkw(vcd, self._wave_groups(vcd))
        self.checker.raise_recorded()
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
        local_rdata, local_ready, local_retry, local_room = local.rdata, local.ready, local.retry, local.room

    host_driver = pci_host(clock, reset, bench.host)
    segment = pci_segment(clock, bench.segment)
    monitor = pci_monitor(clock, reset, bench.segment, bench.checker)
    target = [] if bench.ports is None else [room_audit(clock, lines, bench.memory)]
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
        yield from bench.clocks(bench.settle_clocks)
        yield from run_scenario(bench.host, scenario(bench))
        yield from bench.clocks(4)
        raise StopSimulation()

    @instance
    def beside():
        yield from bench.clocks(RESET_CLOCKS + bench.settle_clocks)
        if background is not None:
            yield from run_scenario(bench.host, background(bench))

    return host_driver, segment, monitor, target, clock_driver, stimulus, beside


@block
def room_audit(clock, lines, memory):
    """The target acknowledges a memory-write dword only if the back end
    (``memory``, a LocalMemory) will take it: after every rising edge, the
    dwords completed on the bus and not yet written to space 1 are no more
    than the writes the memory still promises.  (The first dword of a burst
    reaches the memory a clock before it completes on the bus.)

        clock    _/~\\_/~\\_/~\\_
        count      ^       ^         phases completed (IRDY#, TRDY#, DEVSEL#)
        check        ^       ^       at the falling edge: held <= promised
    """

    @instance
    def audit():
        completed = 0
        writing = False
        frame_before = True
        while True:
            yield clock.posedge
            frame, irdy, trdy, devsel = (bool(line) for line in (lines.frame, lines.irdy, lines.trdy,
                                                                 lines.devsel))
            if not frame and frame_before:   # address phase
                writing = int(lines.cbe) in MEMORY_WRITES
            elif writing and not (irdy or trdy or devsel):
                completed += 1
            frame_before = frame
            yield clock.negedge
            held = completed - memory.space1_writes
            if memory.promised is not None and held > memory.promised:
                raise AssertionError(f"at {now()} the target holds {held} acknowledged dwords, "
                                     f"the back end promised {memory.promised}")

    return audit
