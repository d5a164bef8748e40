"""End to end: the behavioural PCI host drives the whole card (``rtl/card.py``:
``pci_slave`` + registers, FIFO, sequencer, pulse outputs, DDA) with the
protocol monitor watching every clock.

The host enumerates the card, sizes and places its BARs, programs registers
over I/O, bursts commands into the FIFO over memory, waits for INTA#, reads
position and status back.  The STEP/DIR pins are captured and the path is
rebuilt from them; golden values come from ``sim.dda_model`` (paths, V_arc)
and the register table.  The same bench runs on the MyHDL card (``rtl/card.py``,
split PCI ports) and on the generated top level in Icarus: ``gen/top.v`` as
committed for the default configuration (``$DDA_CARD_GEN/top.v`` if set), a
fresh conversion for a small FIFO, with its PCI pads (iCE40 ``SB_IO`` cells,
yosys's cell model) on the same bus model through ``sim/top_harness.py``.
The split-port card already has the pads' I/O-register timing, so both show
the bus the same, clock for clock.
"""
import re

import pytest
from myhdl import always, block

from rtl import instructions as isa
from rtl import registers as regmap
from rtl.card import card, card_ports
from rtl.interfaces import MotorPins
from rtl.top import PARAMETERS
from sim.card_bench import PinLog, command_words, expected_path, pin_capture, write_motion_view
from sim.dda_model import ArcCommand, LineCommand, iterate, metrics, v_arc
from sim.pci_bench import TARGET_DEVICE, WAVE_GROUPS, PciBench
from sim.paths import GEN
from sim.pci_host import Termination
from sim.top_harness import TopHarness, convert_top, generated_top, top_on_bus
from sim.waves import Waveform

DEVICE = 0
SMALL_FIFO = 16
DEFAULT_FIFO = PARAMETERS["fifo_depth"][1]


class CardUnderTest:
    """The card as a PciBench target, plus what the scenario needs to see:
    ``kind`` "myhdl" (``rtl.card``) or "verilog" (``top.v`` in Icarus);
    ``samples`` gets the bus of every clock (values and drivers)."""

    def __init__(self, kind, fifo_depth):
        self.kind, self.fifo_depth = kind, fifo_depth
        self.log = PinLog()
        self.samples = []
        self.io = self.mem = None

    def __call__(self, bench):
        if self.kind == "verilog":
            top = generated_top() if self.fifo_depth == DEFAULT_FIFO else convert_top(fifo_depth=self.fifo_depth)
            harness = TopHarness(top, idsel_bit=16 + TARGET_DEVICE)
            agent, motor = harness.card, MotorPins()
            core = (top_on_bus, (bench.clock, bench.reset, bench.host.agent, harness, motor))
        elif self.kind == "myhdl":
            ports = card_ports(fifo_depth=self.fifo_depth)
            ports["clock"], ports["reset"] = bench.clock, bench.reset
            agent, motor = ports["pci"], ports["pins"]
            core = (card, (), dict(ports, fifo_depth=self.fifo_depth))
        else:
            raise ValueError(f"unknown card kind {self.kind!r}: use 'myhdl' or 'verilog'")
        capture = (pin_capture, (bench.clock, motor, self.log))
        return agent, [core, capture, (bus_record, (bench, self.samples))]


@block
def bus_record(bench, samples):
    """Append the segment's sample (values and drivers) at every rising edge."""

    @always(bench.clock.posedge)
    def record():
        samples.append(bench.segment.sample())

    return record


def run_card(kind, scenario, name, fifo_depth=SMALL_FIFO):
    target = CardUnderTest(kind, fifo_depth)
    bench = PciBench(target=target, host_options=dict(max_retries=1 << 20))
    out = {}

    def wrapped(b):
        devices = yield from b.host.enumerate_bus(devices=[DEVICE])
        out["device"] = devices[0]
        bars = {("io" if bar["io"] else "mem"): bar for bar in devices[0].bars}
        target.io, target.mem = bars["io"]["base"], bars["mem"]["base"]
        out["bars"] = bars
        yield from scenario(b, target, out)

    vcd = bench.run(wrapped, f"{name}_{kind}")
    wave = Waveform(vcd)
    write_motion_view(vcd, WAVE_GROUPS, wave)
    return out, target.log, wave, bench


def io_write(bench, target, name, value):
    result = yield from bench.host.io_write(target.io + regmap.offset(name), value & 0xFFFFFFFF)
    assert result.complete, f"I/O write of {name} ended {result.termination}"


def io_read(bench, target, name):
    result = yield from bench.host.io_read(target.io + regmap.offset(name))
    assert result.complete, f"I/O read of {name} ended {result.termination}"
    return result.value


def wait_inta(bench, limit=200000):
    """Clocks until INTA# is low on the bus."""
    for clocks in range(limit):
        if not bool(bench.segment.lines.inta):
            return clocks
        yield bench.clock.posedge
    raise AssertionError("INTA# never asserted")


def program(bench, target, feed=regmap.RATE_MAX, control=1, interrupts=("DONE",)):
    yield from io_write(bench, target, "FEED_RATE", feed)
    yield from io_write(bench, target, "INT_ENABLE",
                        regmap.field_of("INT_ENABLE", **{name: 1 for name in interrupts}))
    yield from io_write(bench, target, "CONTROL", control)


def finish(bench, target, out):
    """Wait for INTA#, then read status and position; acknowledge."""
    out["inta_clocks"] = yield from wait_inta(bench)
    out["status"] = yield from io_read(bench, target, "STATUS")
    out["int_status"] = yield from io_read(bench, target, "INT_STATUS")
    x = yield from io_read(bench, target, "POS_X")
    y = yield from io_read(bench, target, "POS_Y")
    out["position"] = (regmap.field_value("POS_X", "STEPS", x), regmap.field_value("POS_Y", "STEPS", y))
    yield from io_write(bench, target, "INT_STATUS", out["int_status"])


def motion_scenario(commands, feed=regmap.RATE_MAX):
    words = [w for c in commands for w in command_words(c)]

    def scenario(bench, target, out):
        yield from program(bench, target, feed)
        out["burst"] = yield from bench.host.mem_write(target.mem, words)
        yield from finish(bench, target, out)

    return scenario


ARC = ArcCommand(40, 0, 0, 40, ccw=True)
CHAIN = [LineCommand(6, 2), LineCommand(5, 7), LineCommand(3, 4), ArcCommand(0, 12, -12, 0)]


@pytest.mark.parametrize("kind", ["myhdl", "verilog"])
def test_enumerate_program_arc(kind):
    out, log, _, _ = run_card(kind, motion_scenario([ARC]), "card_e2e_arc", DEFAULT_FIFO)
    device = out["device"]
    assert (device.vendor_id, device.device_id, device.interrupt_pin) == (0x1234, 0xDDA0, 1)
    assert out["bars"]["io"]["size"] == 1 << regmap.IO_BAR_BITS
    assert out["bars"]["mem"]["size"] == 4096
    wanted = expected_path([ARC])
    assert log.path() == wanted
    # positions count from 0: the arc's displacement from its start point
    assert out["position"] == wanted[-1] == (ARC.xe - ARC.xs, ARC.ye - ARC.ys)
    rebuilt = [(x + ARC.xs, y + ARC.ys) for x, y in log.path()]
    assert rebuilt[-1] == (ARC.xe, ARC.ye)
    model_v_arc = metrics(iterate(ARC)).v_arc
    assert v_arc(rebuilt, 40) == pytest.approx(model_v_arc, rel=1e-12)
    assert regmap.field_value("STATUS", "BUSY", out["status"]) == 0
    assert regmap.field_value("INT_STATUS", "DONE", out["int_status"]) == 1


def header_constants():
    """Every ``#define NAME 0x...u`` / ``NAME 123u`` of ``gen/dda_card.h``."""
    text = (GEN / "dda_card.h").read_text()
    found = re.findall(r"^#define (\w+) (0x[0-9A-F]+|\d+)u\b", text, re.M)
    return {name: int(value, 0) for name, value in found}


@pytest.mark.parametrize("kind", ["myhdl", "verilog"])
def test_after_reset_every_register_reads_as_documented(kind):
    """Before any write, every register reads the reset value of the table
    (``docs/registers.md``, ``DDA_<NAME>_RESET``), the offsets between them
    read 0, and configuration space holds the identity and BAR sizes that
    ``gen/dda_card.h`` gives host software."""
    reads = {}

    def scenario(bench, target, out):
        for offset in range(0, 1 << regmap.IO_BAR_BITS, regmap.WORD_BYTES):
            result = yield from bench.host.io_read(target.io + offset)
            assert result.complete, f"I/O read of {offset:#x} ended {result.termination}"
            reads[offset] = result.value
        out["subsystem"] = (yield from bench.host.config_read(DEVICE, 0x2C)).value

    out, _, _, _ = run_card(kind, scenario, "card_e2e_reset", DEFAULT_FIFO)
    for reg in regmap.REGISTERS:
        value = reads.pop(reg.offset)
        assert value == reg.reset, f"{reg.name} reads {value:#x}, the table says {reg.reset:#x}"
    assert set(reads.values()) == {0}, "an unlisted offset does not read 0"
    header, device, bars = header_constants(), out["device"], out["bars"]
    assert {reg.name: header[f"DDA_{reg.name}_RESET"] for reg in regmap.REGISTERS} == {
        reg.name: reg.reset for reg in regmap.REGISTERS}
    assert (device.vendor_id, device.device_id, device.revision_id, device.class_code) == (
        header["DDA_PCI_VENDOR_ID"], header["DDA_PCI_DEVICE_ID"], header["DDA_PCI_REVISION_ID"],
        header["DDA_PCI_CLASS_CODE"])
    assert out["subsystem"] == header["DDA_PCI_SUBSYSTEM_ID"] << 16 | header["DDA_PCI_SUBSYSTEM_VENDOR_ID"]
    assert (bars["io"]["size"], bars["mem"]["size"]) == (header["DDA_BAR0_SIZE"], header["DDA_BAR1_SIZE"])


def test_top_level_pins_match_the_split_port_card_clock_for_clock():
    """The pads' I/O registers replace the card's boundary flip-flops: the top
    in Icarus and the MyHDL card put the same values on every line, with the
    same drivers, on every clock (the golden run is the MyHDL card, which the
    other tests check against the models and the monitor)."""
    scenario = motion_scenario([LineCommand(5, 3)])
    samples = {}
    for kind in ("myhdl", "verilog"):
        _, log, _, bench = run_card(kind, scenario, "card_e2e_bus", DEFAULT_FIFO)
        assert log.path() == expected_path([LineCommand(5, 3)])
        samples[kind] = [(s.time, s.values, s.drivers) for s in bench.target.samples]
    card_run, top_run = samples["myhdl"], samples["verilog"]
    assert len(card_run) == len(top_run) > 100
    for clock, (card_sample, top_sample) in enumerate(zip(card_run, top_run)):
        assert top_sample == card_sample, f"clock {clock}: top {top_sample} != card {card_sample}"


def test_chained_segments_no_gap_between_lines():
    out, log, _, _ = run_card("myhdl", motion_scenario(CHAIN), "card_e2e_chain")
    assert log.path() == expected_path(CHAIN)
    assert out["position"] == expected_path(CHAIN)[-1]
    line_rises = sum(max(abs(c.dx), abs(c.dy)) for c in CHAIN[:3])
    gaps = log.gaps()[:line_rises - 1]
    # one iteration per clock, two clocks per pulse (width 1): the three lines leave
    # the pins as one uninterrupted pulse train, no idle clock at the boundaries
    assert set(gaps) == {2}, gaps


@pytest.mark.parametrize("kind", ["myhdl", pytest.param("verilog", marks=pytest.mark.slow)])
def test_direct_pulse_mode(kind):
    def scenario(bench, target, out):
        yield from io_write(bench, target, "PULSE_PERIOD_X", 5)
        yield from io_write(bench, target, "PULSE_PERIOD_Y", 9)
        yield from program(bench, target, control=regmap.field_of("CONTROL", ENABLE=1, MODE=1))
        yield from io_write(bench, target, "PULSE_COUNT_X", 7)
        yield from io_write(bench, target, "PULSE_COUNT_Y", -4)
        yield from finish(bench, target, out)

    out, log, _, _ = run_card(kind, scenario, "card_e2e_direct")
    assert out["position"] == (7, -4)
    assert sum(r[1] for r in log.rises) == 7 and sum(r[2] for r in log.rises) == 4


def test_long_burst_fills_fifo_nothing_lost():
    commands = [LineCommand(3 - (i % 7), (i % 5) - 2) for i in range(30)]
    commands = [c if (c.dx, c.dy) != (0, 0) else LineCommand(1, 1) for c in commands]
    words = [w for c in commands for w in command_words(c)]

    def scenario(bench, target, out):
        yield from program(bench, target, feed=regmap.RATE_ONE // 64)
        out["burst"] = yield from bench.host.mem_write(target.mem, words)
        yield from finish(bench, target, out)

    out, log, _, _ = run_card("myhdl", scenario, "card_e2e_full")
    assert len(words) > 2 * SMALL_FIFO
    stops = [t.termination for t in out["burst"].transactions]
    assert any(t in (Termination.RETRY, Termination.DISCONNECT) for t in stops), "the FIFO never filled"
    assert out["burst"].complete and len(out["burst"].data) == len(words)
    assert log.path() == expected_path(commands)
    assert out["position"] == expected_path(commands)[-1]


@pytest.mark.parametrize("kind", ["myhdl", pytest.param("verilog", marks=pytest.mark.slow)])
def test_malformed_command_error_interrupt(kind):
    bad = [0x1 << isa.OPCODE_LSB | 0x80, 0, 0]  # LINE with a reserved header bit
    good = command_words(LineCommand(5, 3))

    def scenario(bench, target, out):
        yield from program(bench, target, interrupts=("ERROR",))
        yield from bench.host.mem_write(target.mem, good + bad + good)
        yield from finish(bench, target, out)

    out, log, _, _ = run_card(kind, scenario, "card_e2e_error")
    assert regmap.field_value("STATUS", "ERROR", out["status"]) == isa.ERROR_CODE["RESERVED_BITS"]
    assert regmap.field_value("INT_STATUS", "ERROR", out["int_status"]) == 1
    assert out["position"] == (5, 3) and log.path()[-1] == (5, 3)


def test_soft_reset_mid_motion():
    def scenario(bench, target, out):
        yield from program(bench, target, feed=regmap.RATE_ONE // 4)
        yield from bench.host.mem_write(target.mem, command_words(LineCommand(300, 200)))
        yield from bench.clocks(300)
        yield from io_write(bench, target, "COMMAND", regmap.field_of("COMMAND", SOFT_RESET=1))
        yield from bench.clocks(20)
        out["status"] = yield from io_read(bench, target, "STATUS")
        out["rises"] = len(target.log.rises)
        yield from bench.clocks(200)
        out["rises_later"] = len(target.log.rises)
        x = yield from io_read(bench, target, "POS_X")
        out["x"] = regmap.field_value("POS_X", "STEPS", x)

    out, log, _, _ = run_card("myhdl", scenario, "card_e2e_soft_reset")
    assert regmap.field_value("STATUS", "BUSY", out["status"]) == 0
    assert 0 < out["rises"] == out["rises_later"]
    assert out["x"] == log.path()[-1][0] and 0 < out["x"] < 300
