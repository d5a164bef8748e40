"""cocotb front end of the PCI host and monitor: the same host core,
transaction layer and protocol checker as the MyHDL benches, as a driver
and a monitor on a target's pins in any simulator cocotb runs.

``CocotbPciBus(dut, pins, clock, reset)`` joins the host to a target with
split PCI ports (the pin map of ``sim.pci.verilog_target``: ``{line: (in, out,
oe)}``, a ``~`` before an active-low enable, which is one bit or one per
bit of the line; ``split_pins`` builds it for the converter's
``pci_<line>_in/_out/_oe`` names).  Once per clock, at the
falling edge, when every line has settled, it reads the target's drive,
resolves each line with the host's (pull-ups on the control lines; in float
mode, the default, AD, C/BE# and PAR reach the target as ``z`` when nobody
drives them), writes the target's inputs, feeds the protocol checker the
sample (with the lines the target drove as X or Z: rules 19, 20) and steps the
host core, whose drive counts from the next rising edge.  The target's
outputs must come from its flip-flops (as PCI's timing wants), not straight
from its inputs.

    bus = CocotbPciBus(dut, split_pins(["gen/card.v"], "card"), dut.clock, dut.reset)
    bus.start()
    devices = await bus.run(bus.host.enumerate_bus(devices=[0]))

``run`` is the trampoline: host waits become cocotb waits.  A scenario
must yield only host waits; cocotb code goes between ``run`` calls.
"""
import cocotb
from cocotb.simtime import get_sim_time
from cocotb.triggers import Event, FallingEdge
from cocotb.types import Logic, LogicArray

from sim.pci.checker import ProtocolChecker
from sim.pci.host_core import CLOCK, scenario_steps
from sim.pci.lines import LINE_WIDTHS, OPEN_DRAIN, PULLED_UP, BusSample
from sim.pci.master import PciMaster


def _read(handle):
    """(value with X/Z read as 0, mask of the bits that were X/Z or other unknown)."""
    text = str(handle.value)
    if set(text) <= {"0", "1"}:
        return int(text, 2), 0
    return (int("".join(c if c in "01" else "0" for c in text), 2),
            int("".join("0" if c in "01" else "1" for c in text), 2))


def _drive(port_out, port_oe, inverted, width):
    """(value, driven, X/Z report) of a split output: one enable for the
    line, or one per bit (driven while any bit is, each bit's value only
    where it is; reported when only some bits are, or on an X/Z enable or an
    X/Z on an enabled bit)."""
    full = (1 << width) - 1
    level, level_unknown = _read(port_out)
    if port_oe is None:
        return level, True, bool(level_unknown)
    enable, enable_unknown = _read(port_oe)
    per_bit = len(port_oe) == width > 1
    mask = full if per_bit else 1
    enable = ((enable ^ mask) if inverted else enable) & ~enable_unknown   # an X/Z enable enables nothing
    if not per_bit:
        return level, bool(enable), bool(enable_unknown) or bool(enable and level_unknown)
    partial = enable not in (0, full)
    return level & enable, bool(enable), bool(enable_unknown) or partial or bool(level_unknown & enable)


class CocotbPciBus:
    """The host (``host``: a ``PciMaster``) and the checker (``checker``)
    on a cocotb DUT.  ``idsel``: the DUT's IDSEL input (a name, None: none),
    wired to AD[``idsel_bit``]; ``floating``: float mode."""

    def __init__(self, dut, pins, clock, reset, idsel=None, idsel_bit=16, floating=True, host=None,
                 checker=None, reset_active=0):
        self.dut, self.clock, self.reset = dut, clock, reset
        self.reset_active = reset_active
        self.host = host or PciMaster()
        self.core = self.host.core
        self.checker = checker or ProtocolChecker(master_parity_response=self.host.parity_response)
        self.floating = floating
        self.idsel = getattr(dut, idsel) if idsel else None
        self.idsel_bit = idsel_bit
        self.ports = {}
        for line, (in_name, out_name, oe_name) in pins.items():
            inverted = bool(oe_name) and oe_name.startswith("~")
            enable = getattr(dut, oe_name.lstrip("~")) if oe_name else None
            if enable is not None and out_name and len(enable) not in (1, LINE_WIDTHS[line]):
                raise ValueError(f"output enable {oe_name.lstrip('~')} of {line.upper()} is {len(enable)} "
                                 f"bits; give one enable (1 bit) or one per bit ({LINE_WIDTHS[line]} bits)")
            self.ports[line] = (getattr(dut, in_name) if in_name else None,
                                getattr(dut, out_name) if out_name else None, enable, inverted)
        self._completion = Event()
        self._task = None

    def start(self):
        """Start watching and driving (call once, before ``run``)."""
        self._task = cocotb.start_soon(self._clocks())
        return self._task

    async def _clocks(self):
        completed = self.core.completed
        while True:
            await FallingEdge(self.clock)
            time = get_sim_time("ns")
            in_reset = int(self.reset.value) == self.reset_active
            sample = self.resolve(time)
            self.checker.step(sample, in_reset)
            if in_reset:
                self.core.reset(time)
            else:
                values = sample.values
                self.core.step(time, values["ad"] or 0, values["par"] or 0, values["frame"],
                               values["irdy"], values["trdy"], values["devsel"], values["stop"])
            if self.core.completed != completed:
                completed = self.core.completed
                self._completion.set()

    def resolve(self, time):
        """Resolve every line, write the target's inputs; the ``BusSample``."""
        drive = self.core.drive
        values, drivers, unknown = {}, {}, set()
        for line, width in LINE_WIDTHS.items():
            names, value = [], None
            if hasattr(drive, f"{line}_oe") and getattr(drive, f"{line}_oe"):
                names.append("host")
                value = getattr(drive, f"{line}_out")
            port_in, port_out, port_oe, inverted = self.ports.get(line, (None, None, None, False))
            if port_out is not None:
                level, enable, unsure = _drive(port_out, port_oe, inverted, width)
                if unsure:
                    unknown.add(line)
                if enable:
                    names.append("target")
                    if value is None:
                        value = level
                    else:
                        value = value & level if line in OPEN_DRAIN else value | level
            if value is None and line in PULLED_UP:
                value = 1
            values[line], drivers[line] = value, frozenset(names)
            if port_in is not None:
                self._write(port_in, value, width)
        if self.idsel is not None:
            ad = values["ad"]
            self._write(self.idsel, None if ad is None else ad >> self.idsel_bit & 1, 1)
        return BusSample(time, values, drivers, frozenset(unknown))

    def _write(self, port, value, width):
        if value is None and not self.floating:
            value = 0
        if value is None:
            port.value = LogicArray("Z" * width) if width > 1 else Logic("Z")
        else:
            port.value = value

    async def run(self, scenario):
        """Run a host scenario (a generator of host waits); its result."""
        steps = scenario_steps(scenario)
        while True:
            try:
                item = next(steps)
            except StopIteration as stop:
                return stop.value
            if item is CLOCK:
                await FallingEdge(self.clock)
            else:
                self._completion.clear()
                await self._completion.wait()


def split_pins(verilog_files, top, prefix="pci_"):
    """Pin map of a module with ``<prefix><line>_in/_out/_oe`` ports."""
    from sim.pci.verilog_target import split_pins as pins_of

    return pins_of(verilog_files, top, prefix)
