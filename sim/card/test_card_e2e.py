"""End to end: the behavioural PCI host drives the whole card (PCI target,
registers, FIFO, sequencer, pulse outputs, DDA) with the protocol monitor
watching every clock, on MyHDL, on the generated top level in Icarus and on
the generated card in Verilator (``sim/card/card_e2e.py``).

The host enumerates the card, sizes and places its BARs, programs registers
over I/O, bursts commands into the FIFO over memory, waits for INTA#, reads
position and status back.  Golden values come from ``models.dda_model``
(paths, V_arc), the register table and the instruction set; on top of that
the STEP/DIR edges of every scenario are identical, clock for clock, on the
three back ends (the MyHDL run, checked against the models, is the
reference).
"""
import functools
import re

import pytest

from models import instructions as isa
from models import registers as regmap
from models.commands import command_words
from models.dda_model import ArcCommand, LineCommand, iterate, metrics, v_arc
from rtl.convert import GEN_DIR
from sim.backends.verilator.model import Stop
from sim.card.card_bench import expected_path
from sim.card.card_e2e import (DEFAULT_FIFO, DEVICE, KINDS, SMALL_FIFO, clocks, finish, io_read, io_write,
                               motion_scenario, program, run_card, wait)
from sim.pci.host import Termination

ARC = ArcCommand(40, 0, 0, 40, ccw=True)
CHAIN = [LineCommand(6, 2), LineCommand(5, 7), LineCommand(3, 4), ArcCommand(0, 12, -12, 0)]
RAMP = dict(feed=16384, ramp_start=2048, ramp_step=512)  # 4 clocks per iteration at speed, 32 at the ends
FULL = [LineCommand(3 - (i % 7), (i % 5) - 2) for i in range(30)]
FULL = [c if (c.dx, c.dy) != (0, 0) else LineCommand(1, 1) for c in FULL]
BLEND_FIRST, BLEND_SECOND = LineCommand(150, 0), LineCommand(150, 40)
GOOD = LineCommand(5, 3)
BAD = {  # error code -> words of a command that raises it
    "BAD_OPCODE": [0xF << isa.OPCODE_LSB],
    "RESERVED_BITS": [0x1 << isa.OPCODE_LSB | 0x80, 0, 0],  # LINE with a reserved header bit
    "RANGE": isa.encode("SET", 1, INDEX=15),  # no register has SET index 15
    "DDA_REJECTED": isa.encode("ARC", 10, 0, 0, 20, CCW=1, VARIANT=3),  # end off the circle
}


def _words(command, blend=False):
    if isinstance(command, LineCommand):
        return isa.encode("LINE", command.dx, command.dy, BLEND=int(blend))
    return command_words(command)


def _error_scenario(code):
    def scenario(bench, target, out):
        yield from program(bench, target, interrupts=("ERROR",))
        yield from bench.host.mem_write(target.mem, command_words(GOOD) + BAD[code] + command_words(GOOD))
        yield from finish(bench, target, out)

    return scenario


def _direct_pulses(bench, target, out):
    yield from io_write(bench, target, "PULSE_PERIOD_X", 5)
    yield from io_write(bench, target, "PULSE_PERIOD_Y", 9)
    yield from program(bench, target, control=regmap.field_of("CONTROL", ENABLE=1, MODE=1))
    yield from io_write(bench, target, "PULSE_COUNT_X", 7)
    yield from io_write(bench, target, "PULSE_COUNT_Y", -4)
    yield from finish(bench, target, out)


def _soft_reset(bench, target, out):
    yield from program(bench, target, feed=regmap.RATE_ONE // 4)
    yield from bench.host.mem_write(target.mem, command_words(LineCommand(300, 200)))
    waited, reason = yield from wait(bench, target, steps=40)  # mid-move, on every back end alike
    assert reason is Stop.STEPS, (waited, reason)
    yield from io_write(bench, target, "COMMAND", regmap.field_of("COMMAND", SOFT_RESET=1))
    yield from clocks(bench, target, 20)
    out["status"] = yield from io_read(bench, target, "STATUS")
    out["rises"] = len(target.log.rises)
    yield from clocks(bench, target, 200)
    out["rises_later"] = len(target.log.rises)
    x = yield from io_read(bench, target, "POS_X")
    out["x"] = regmap.field_value("POS_X", "STEPS", x)


def _blend(blend):
    words = _words(BLEND_FIRST, blend) + _words(BLEND_SECOND)
    return motion_scenario([words], **RAMP)


SCENARIOS = {  # name -> (scenario, FIFO depth)
    "arc": (motion_scenario([ARC]), DEFAULT_FIFO),
    "chain": (motion_scenario(CHAIN), SMALL_FIFO),
    "ramp": (motion_scenario([LineCommand(300, 120)], **RAMP), SMALL_FIFO),
    "blend": (_blend(True), SMALL_FIFO),
    "stop": (_blend(False), SMALL_FIFO),
    "fifo_full": (motion_scenario(FULL, feed=regmap.RATE_ONE // 64), SMALL_FIFO),
    "direct_pulses": (_direct_pulses, SMALL_FIFO),
    "soft_reset": (_soft_reset, SMALL_FIFO),
    **{f"error_{code.lower()}": (_error_scenario(code), SMALL_FIFO) for code in BAD},
}


# A scenario co-simulated in Icarus takes about half a minute: the default suite runs two of
# them there (the enumeration and arc program, a chain of lines into an arc, with the
# FIFO overfilled in the slow set too); every scenario runs on MyHDL and Verilator.
ICARUS_SCENARIOS = ("arc", "chain")
SLOW_ICARUS = pytest.mark.slow(reason="another ~30 s Icarus co-simulation of a scenario the MyHDL and "
                                      "Verilator cards already run")


def on(name, kinds=KINDS):
    """``(name, kind)`` cases of scenario ``name``: Icarus beyond ICARUS_SCENARIOS in the slow set;
    each scenario's cases run on one worker, which runs its MyHDL reference once."""
    group = pytest.mark.xdist_group(f"card_e2e_{name}")
    return [pytest.param(name, kind, marks=[group] + (
        [SLOW_ICARUS] if kind == "icarus" and name not in ICARUS_SCENARIOS else []), id=f"{name}-{kind}")
        for kind in kinds]


@functools.lru_cache(maxsize=None)
def run(name, kind):
    """(out, pin log) of scenario ``name`` on ``kind``, run once per process."""
    scenario, fifo_depth = SCENARIOS[name]
    out, log, _, _ = run_card(kind, scenario, f"card_e2e_{name}", fifo_depth)
    return out, log


@pytest.mark.parametrize("name,kind", [case for name in SCENARIOS for case in on(name, KINDS[1:])])
def test_pins_identical_on_every_back_end(name, kind):
    """Every STEP/DIR edge at the same clock as on the MyHDL card."""
    _, log = run(name, kind)
    _, reference = run(name, "myhdl")
    assert log.edges, "no pin moved"
    assert log.edges == reference.edges
    assert log.rises == reference.rises


@pytest.mark.parametrize("name,kind", on("arc"))
def test_enumerate_program_arc(name, kind):
    out, log = run(name, kind)
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
    assert log.edges == run("arc", "myhdl")[1].edges


def header_constants():
    """Every ``#define NAME 0x...u`` / ``NAME 123u`` of ``gen/dda_card.h``."""
    text = (GEN_DIR / "dda_card.h").read_text()
    found = re.findall(r"^#define (\w+) (0x[0-9A-F]+|\d+)u\b", text, re.M)
    return {name: int(value, 0) for name, value in found}


@pytest.mark.parametrize("kind", KINDS)
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
        # the table's reset is gen/top.v's (Icarus); the card, MyHDL or gen/card.v, is built generic
        wanted = reg.reset if kind == "icarus" else regmap.build_word(reg, {"device": "generic"})
        assert value == wanted, f"{reg.name} reads {value:#x}, the table says {wanted:#x}"
    assert set(reads.values()) == {0}, "an unlisted offset does not read 0"
    header, device, bars = header_constants(), out["device"], out["bars"]
    assert {reg.name: header[f"DDA_{reg.name}_RESET"] for reg in regmap.REGISTERS} == {
        reg.name: reg.reset for reg in regmap.REGISTERS}
    assert (device.vendor_id, device.device_id, device.revision_id, device.class_code) == (
        header["DDA_PCI_VENDOR_ID"], header["DDA_PCI_DEVICE_ID"], header["DDA_PCI_REVISION_ID"],
        header["DDA_PCI_CLASS_CODE"])
    assert out["subsystem"] == header["DDA_PCI_SUBSYSTEM_ID"] << 16 | header["DDA_PCI_SUBSYSTEM_VENDOR_ID"]
    assert (bars["io"]["size"], bars["mem"]["size"], bars["alias"]["size"]) == (
        header["DDA_BAR0_SIZE"], header["DDA_BAR1_SIZE"], header["DDA_BAR2_SIZE"])
    assert not bars["alias"]["io"] and not bars["alias"]["prefetchable"]


def test_top_level_pins_match_the_split_port_card_clock_for_clock():
    """The pads' I/O registers replace the card's boundary flip-flops: the top
    in Icarus and the MyHDL card put the same values on every line, with the
    same drivers, on every clock (the golden run is the MyHDL card, which the
    other tests check against the models and the monitor)."""
    scenario = motion_scenario([LineCommand(5, 3)])
    samples = {}
    for kind in ("myhdl", "icarus"):
        _, log, _, bench = run_card(kind, scenario, "card_e2e_bus", DEFAULT_FIFO)
        assert log.path() == expected_path([LineCommand(5, 3)])
        samples[kind] = [(s.time, s.values, s.drivers) for s in bench.target.samples]
    card_run, top_run = samples["myhdl"], samples["icarus"]
    assert len(card_run) == len(top_run) > 100
    for clock, (card_sample, top_sample) in enumerate(zip(card_run, top_run)):
        assert top_sample == card_sample, f"clock {clock}: top {top_sample} != card {card_sample}"


@pytest.mark.parametrize("name,kind", on("chain"))
def test_chained_segments_no_gap_between_lines(name, kind):
    out, log = run(name, kind)
    assert log.path() == expected_path(CHAIN)
    assert out["position"] == expected_path(CHAIN)[-1]
    line_rises = sum(max(abs(c.dx), abs(c.dy)) for c in CHAIN[:3])
    gaps = log.gaps()[:line_rises - 1]
    # one iteration per clock, two clocks per pulse (width 1): the three lines leave
    # the pins as one uninterrupted pulse train, no idle clock at the boundaries
    assert set(gaps) == {2}, gaps


def _x_gaps(log):
    times = [rise[0] for rise in log.rises if rise[1]]
    return [b - a for a, b in zip(times, times[1:])]


def _gap(rate):
    return regmap.RATE_ONE / rate


@pytest.mark.parametrize("name,kind", on("ramp"))
def test_long_line_ramps_up_and_down(name, kind):
    """Intervals shrink, stay at FEED_RATE, grow back; the first and the last are
    those of RAMP_START (to one clock) and the deceleration mirrors the ramp up."""
    out, log = run(name, kind)
    assert out["position"] == (300, 120) == log.path()[-1]
    gaps = _x_gaps(log)
    assert len(gaps) == 299
    fast = _gap(RAMP["feed"])
    assert abs(gaps[0] - _gap(RAMP["ramp_start"] + RAMP["ramp_step"])) <= 1, gaps[:4]
    assert abs(gaps[-1] - _gap(RAMP["ramp_start"])) <= 1, gaps[-4:]
    low = next(i for i, g in enumerate(gaps) if g <= fast)
    high = len(gaps) - 1 - next(i for i, g in enumerate(reversed(gaps)) if g <= fast)
    assert all(b <= a + 1 for a, b in zip(gaps[:low], gaps[1:low + 1])), "not shrinking"
    assert all(abs(g - fast) <= 1 for g in gaps[low:high + 1]), "not steady at FEED_RATE"
    assert all(b >= a - 1 for a, b in zip(gaps[high:], gaps[high + 1:])), "not growing back"
    assert abs(low - (len(gaps) - 1 - high)) <= 3, (low, high)


@pytest.mark.parametrize("name,kind", on("blend") + on("stop"))
def test_blend_keeps_speed_across_the_boundary(name, kind):
    """BLEND = 1: the intervals around the boundary stay those of FEED_RATE;
    BLEND = 0: the first line slows down to RAMP_START before it."""
    out, log = run(name, kind)
    assert log.path() == expected_path([BLEND_FIRST, BLEND_SECOND])
    gaps = _x_gaps(log)
    around = gaps[BLEND_FIRST.dx - 6:BLEND_FIRST.dx + 5]
    if name == "blend":
        assert all(abs(g - _gap(RAMP["feed"])) <= 1 for g in around), around
    else:
        assert abs(gaps[BLEND_FIRST.dx - 2] - _gap(RAMP["ramp_start"])) <= 1, around
    assert abs(gaps[-1] - _gap(RAMP["ramp_start"])) <= 1, gaps[-4:]


@pytest.mark.parametrize("name,kind", on("fifo_full"))
def test_long_burst_fills_fifo_nothing_lost(name, kind):
    out, log = run(name, kind)
    words = sum(len(command_words(c)) for c in FULL)
    assert words > 2 * SMALL_FIFO
    stops = [t.termination for t in out["burst"].transactions]
    assert any(t in (Termination.RETRY, Termination.DISCONNECT) for t in stops), "the FIFO never filled"
    assert out["burst"].complete and len(out["burst"].data) == words
    assert log.path() == expected_path(FULL)
    assert out["position"] == expected_path(FULL)[-1]


@pytest.mark.parametrize("name,kind", on("direct_pulses"))
def test_direct_pulse_mode(name, kind):
    out, log = run(name, kind)
    assert out["position"] == (7, -4)
    assert sum(r[1] for r in log.rises) == 7 and sum(r[2] for r in log.rises) == 4


@pytest.mark.parametrize("name,kind", [case for code in BAD for case in on(f"error_{code.lower()}")])
def test_malformed_command_error_interrupt(name, kind):
    """The move before the bad command completes, the error is the bad
    command's, nothing after it runs."""
    code = name.removeprefix("error_").upper()
    out, log = run(name, kind)
    assert regmap.field_value("STATUS", "ERROR", out["status"]) == isa.ERROR_CODE[code]
    assert regmap.field_value("INT_STATUS", "ERROR", out["int_status"]) == 1
    assert out["position"] == (GOOD.dx, GOOD.dy) == log.path()[-1]


@pytest.mark.parametrize("name,kind", on("soft_reset"))
def test_soft_reset_mid_motion(name, kind):
    out, log = run(name, kind)
    assert regmap.field_value("STATUS", "BUSY", out["status"]) == 0
    assert 0 < out["rises"] == out["rises_later"]
    assert out["x"] == log.path()[-1][0] and 0 < out["x"] < 300
