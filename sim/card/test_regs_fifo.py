"""The card behind the PCI target (``rtl/card_core.py``: registers, FIFO, sequencer,
pulse outputs, DDA) driven over its back-end bus.

Golden values: register semantics from ``models.card_model.RegisterModel``, pin
timing from ``PulseOutModel`` (every clock), paths from ``models.dda_model``.
"""
import random

import pytest

from models import instructions as isa
from models import registers as regmap
from models.card_model import RegisterModel
from models.commands import command_words
from models.dda_model import ArcCommand, LineCommand
from sim.card.card_bench import FIFO_DEPTH, TIMING, expected_path, read_position, run_core, wait_error, wait_idle


def field(name, field_name, word):
    return regmap.field_value(name, field_name, word)


def setup_motion(driver, control=1, feed=regmap.RATE_MAX):
    yield from driver.io_write(regmap.offset("FEED_RATE"), feed)
    yield from driver.io_write(regmap.offset("CONTROL"), control)


@pytest.mark.parametrize("seed", [11, pytest.param(12, marks=pytest.mark.slow(reason="a second seed of the same walk"))])
def test_register_semantics(seed):
    rng = random.Random(seed)
    model = RegisterModel()
    # INPUT_POLARITY left out: a new polarity changes the filtered inputs, which
    # raises INT_STATUS.INPUT whenever the filter (INPUT_FILTER x INPUT_TICK
    # clocks, both written at random here) takes the new level; its events are
    # the input filter bench's to judge (sim/card/test_machine_units.py, `changed`)
    writable = [r for r in regmap.REGISTERS if r.access in ("RW",) and r.name not in ("CONTROL", "INPUT_POLARITY")]
    checks = []

    def scenario(driver):
        for reg in regmap.REGISTERS:
            if reg.access in ("RW", "W1C") or reg.name == "ID":
                word = yield from driver.io_read(reg.offset)
                checks.append((reg.name, "reset", word, reg.reset))
        for _ in range(60):
            reg = rng.choice(writable)
            data = rng.choice([rng.getrandbits(32), rng.randint(0, 300), 0, 0x10001])
            be = rng.choice([0xF, 0xF, 0x1, 0x3, 0xC, 0x0])
            yield from driver.io_write(reg.offset, data, be)
            clamped = model.write(reg.name, data, be)
            word = yield from driver.io_read(reg.offset)
            checks.append((reg.name, f"{data:#x}/{be:#x}", word, model.read(reg.name)))
            status = yield from driver.io_read(regmap.offset("INT_STATUS"))
            checks.append((reg.name, "CLAMPED", field("INT_STATUS", "CLAMPED", status), int(clamped)))
            yield from driver.io_write(regmap.offset("INT_STATUS"), status)
        cleared = yield from driver.io_read(regmap.offset("INT_STATUS"))
        checks.append(("INT_STATUS", "W1C", cleared, 0))

    run_core(f"regs_semantics_{seed}", scenario, check_pins=False)
    assert len(checks) > 100
    for name, what, got, wanted in checks:
        assert got == wanted, f"{name} {what}: read {got:#x}, model {wanted:#x}"


def _motion_scenario(commands, results, setup=None, words=None):
    def scenario(driver):
        yield from (setup or setup_motion)(driver)
        stream = words if words is not None else [w for c in commands for w in command_words(c)]
        yield from driver.push_all(stream)
        status = yield from wait_idle(driver)
        results["status"] = status
        results["position"] = yield from read_position(driver)
        results["int_status"] = yield from driver.io_read(regmap.offset("INT_STATUS"))
    return scenario


MOTIONS = {
    "lines": [LineCommand(12, 11), LineCommand(-7, 3), LineCommand(0, -9), LineCommand(20, 0)],
    "arc_quarter": [ArcCommand(30, 0, 0, 30)],
    "arc_crossing_cw": [ArcCommand(5, 14, 14, -5, ccw=False)],
    "arc_then_line": [ArcCommand(0, 10, -10, 0), LineCommand(3, -4), ArcCommand(8, 6, 6, 8, ccw=True)],
}


@pytest.mark.parametrize("name", [
    "arc_then_line", "arc_crossing_cw",
    *(pytest.param(name, marks=pytest.mark.slow(reason="lines and a quarter arc: the other two cover both kinds"))
      for name in ("arc_quarter", "lines"))])
def test_motion_matches_model(name):
    commands = MOTIONS[name]
    results = {}
    log, _ = run_core(f"regs_motion_{name}", _motion_scenario(commands, results))
    wanted = expected_path(commands)
    assert log.path() == wanted
    assert results["position"] == wanted[-1]
    assert field("STATUS", "ERROR", results["status"]) == 0
    assert field("INT_STATUS", "DONE", results["int_status"]) == 1


def test_fifo_full_retries_nothing_lost():
    commands = [LineCommand((-1) ** i * (i % 5 + 1), i % 3) for i in range(12)]
    words = [w for c in commands for w in command_words(c)]
    results = {}

    def hold_then_run(driver):
        yield from setup_motion(driver, control=0)
        accepted = yield from driver.burst(words)
        results["accepted"] = accepted
        status = yield from driver.io_read(regmap.offset("STATUS"))
        results["full_status"] = status
        yield from driver.io_write(regmap.offset("CONTROL"), 1)
        yield from driver.push_all(words[accepted:])
        yield from wait_idle(driver)
        results["position"] = yield from read_position(driver)

    log, _ = run_core("regs_fifo_full", hold_then_run)
    # the instruction register holds the first command even while CONTROL.ENABLE is 0
    assert results["accepted"] == FIFO_DEPTH + len(command_words(commands[0]))
    assert field("STATUS", "FIFO_FULL", results["full_status"]) == 1
    assert field("STATUS", "FIFO_LEVEL", results["full_status"]) == FIFO_DEPTH
    wanted = expected_path(commands)
    assert log.path() == wanted and results["position"] == wanted[-1]


MALFORMED = {  # case: (error code, words)
    "opcode": ("BAD_OPCODE", [0xF << isa.OPCODE_LSB]),
    "reserved": ("RESERVED_BITS", [isa.encode("LINE", 1, 1)[0] | 1 << 7, 1, 1]),   # bit 7: no field of LINE
    "coordinate": ("RANGE", isa.encode("LINE", 1 << 23, 0)),
    "set_index": ("RANGE", isa.encode("SET", 5, INDEX=15)),
    "off_circle": ("DDA_REJECTED", isa.encode("ARC", 10, 0, 0, 20, CCW=1, VARIANT=3)),
}


@pytest.mark.parametrize("case", [
    "coordinate", "opcode",
    *(pytest.param(case, marks=pytest.mark.slow(reason="their error codes also run end to end on MyHDL and "
                                                      "Verilator, sim/card/test_card_e2e.py"))
      for case in ("off_circle", "reserved", "set_index"))])
def test_malformed_command_stops_until_cleared(case):
    code, bad = MALFORMED[case]
    good = command_words(LineCommand(4, 2))
    results = {}

    def scenario(driver):
        yield from setup_motion(driver)
        yield from driver.io_write(regmap.offset("INT_ENABLE"), regmap.field_of("INT_ENABLE", ERROR=1))
        yield from driver.push_all(good + bad + good)
        results["error"] = yield from wait_error(driver, 200)
        results["held"] = yield from read_position(driver)
        yield from driver.io_write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", CLEAR_ERROR=1))
        yield from driver.push_all(good)
        yield from wait_idle(driver)
        results["after"] = yield from read_position(driver)

    _, wave = run_core(f"regs_malformed_{case}", scenario, trace=True)
    assert results["error"] == isa.ERROR_CODE[code]
    assert results["held"] == (4, 2)
    # BAD_OPCODE: the stream cannot be framed, CLEAR_ERROR drops the queued words;
    # any other error: the command's length is known, the next one runs
    assert results["after"] == ((8, 4) if code == "BAD_OPCODE" else (12, 6))
    assert wave.edges("irq", "1"), "INTA# request never raised"


@pytest.mark.parametrize("cosim", [
    pytest.param(False, id="myhdl", marks=pytest.mark.slow(reason="the Icarus run checks the generated Verilog; "
                                                                  "direct pulses on MyHDL run end to end")),
    pytest.param(True, id="icarus")])
def test_direct_pulse_mode(cosim):
    results = {}
    period = 7

    def scenario(driver):
        yield from driver.io_write(regmap.offset("PULSE_PERIOD_X"), period)
        yield from driver.io_write(regmap.offset("PULSE_PERIOD_Y"), 3)
        yield from driver.io_write(regmap.offset("CONTROL"), regmap.field_of("CONTROL", ENABLE=1, MODE=1))
        yield from driver.io_write(regmap.offset("PULSE_COUNT_X"), -5 & 0xFFFFFFFF)
        yield from driver.io_write(regmap.offset("PULSE_COUNT_Y"), 9)
        yield from wait_idle(driver)
        results["position"] = yield from read_position(driver)
        results["left"] = yield from driver.io_read(regmap.offset("PULSE_COUNT_X"))

    log, _ = run_core(f"regs_direct_{'icarus' if cosim else 'myhdl'}", scenario, cosim=cosim, check_pins=False)
    x_rises = [r[0] for r in log.rises if r[1]]
    assert len(x_rises) == 5 and all(not r[3] for r in log.rises if r[1])
    # both axes share one pulse timer (diagonal steps leave together), so a Y pulse
    # can shift an X pulse by up to one pulse (2 * width clocks) or a DIR set-up
    slack = 2 * TIMING["width"] + TIMING["setup"]
    gaps = [b - a for a, b in zip(x_rises, x_rises[1:])]
    assert all(abs(gap - period) <= slack for gap in gaps)
    assert abs(x_rises[-1] - x_rises[0] - 4 * period) <= slack
    assert sum(1 for r in log.rises if r[2]) == 9
    assert results["position"] == (-5, 9) and results["left"] == 0


def test_soft_reset_mid_motion():
    results = {}

    def scenario(driver):
        yield from setup_motion(driver, feed=regmap.RATE_ONE // 4)
        yield from driver.push_all(command_words(LineCommand(400, 100)) + command_words(LineCommand(5, 5)))
        for _ in range(150):
            yield driver.clock.negedge
        yield from driver.io_write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", SOFT_RESET=1))
        status = yield from wait_idle(driver, limit=50)
        results["status"] = status
        for _ in range(100):
            yield driver.clock.negedge
        results["position"] = yield from read_position(driver)
        yield from driver.push_all(command_words(LineCommand(3, -2)))
        yield from wait_idle(driver)
        results["after"] = yield from read_position(driver)

    log, _ = run_core("regs_soft_reset", scenario)
    assert field("STATUS", "FIFO_EMPTY", results["status"]) == 1
    assert 0 < results["position"][0] < 400, "the soft reset did not stop the move"
    assert results["after"] == log.path()[-1]
    assert results["after"][0] - results["position"][0] == 3


def test_stream_commands_set_mark_dwell_pulse():
    tag, dwell = 0xBEEF, 300
    stream = (isa.encode("SET", 3, INDEX=regmap.register("STEP_WIDTH").set_index)
              + command_words(LineCommand(4, 0))
              + isa.encode("DWELL", dwell)
              + isa.encode("PULSE", 3, -2)
              + isa.encode("MARK", TAG=tag)
              + isa.encode("SET", 999, INDEX=regmap.register("DIR_SETUP").set_index))
    results = {}

    def scenario(driver):
        yield from driver.io_write(regmap.offset("LOW_WATER"), 4)
        yield from setup_motion(driver)
        yield from driver.push_all(stream)
        yield from wait_idle(driver)
        for name in ("STEP_WIDTH", "DIR_SETUP", "MARK_TAG", "INT_STATUS"):
            results[name] = yield from driver.io_read(regmap.offset(name))
        results["position"] = yield from read_position(driver)

    log, wave = run_core("regs_stream", scenario, check_pins=False, trace=True)
    assert results["STEP_WIDTH"] == 3 and results["MARK_TAG"] == tag
    assert results["DIR_SETUP"] == 255, "SET is clamped like a bus write"
    events = results["INT_STATUS"]
    for name in ("MARK", "CLAMPED", "LOW_WATER", "DONE"):
        assert field("INT_STATUS", name, events) == 1, name
    assert results["position"] == (4 + 3, -2) == log.path()[-1]
    x_rises = [r[0] for r in log.rises if r[1]]
    assert dwell < x_rises[4] - x_rises[3] < dwell + 20, "DWELL did not wait its clocks after the pins"
    highs = [t for t, v in zip(*wave.changes[wave.full_name("pins_step_x")]) if v == "1"]
    lows = [t for t, v in zip(*wave.changes[wave.full_name("pins_step_x")]) if v == "0"]
    widths = {(low - high) // 10 for high, low in zip(highs, lows[1:] if lows[0] < highs[0] else lows)}
    assert widths == {3}, widths


@pytest.mark.parametrize("first, second", [
    (1, 200), *(pytest.param(*pair, marks=pytest.mark.slow(reason="more pairs of lengths of the same rule"))
                for pair in ((150, 90), (0, 120)))])
def test_back_to_back_dwells_wait_both(first, second):
    # a DWELL issued as the one before it ends waits its own clocks in full
    stream = (command_words(LineCommand(1, 0)) + isa.encode("DWELL", first) + isa.encode("DWELL", second)
              + command_words(LineCommand(1, 0)))

    def scenario(driver):
        yield from setup_motion(driver)
        yield from driver.push_all(stream)
        yield from wait_idle(driver)

    log, _ = run_core("regs_dwells", scenario, check_pins=False)
    x_rises = [r[0] for r in log.rises if r[1]]
    assert len(x_rises) == 2
    assert first + second < x_rises[1] - x_rises[0] < first + second + 20, "the DWELLs did not wait their clocks"


def test_position_snapshot_is_coherent_while_moving():
    reads = []

    def scenario(driver):
        yield from setup_motion(driver, feed=regmap.RATE_MAX)
        yield from driver.push_all(command_words(LineCommand(300, 300)))
        for _ in range(5):
            for _ in range(40):
                yield driver.clock.negedge
            x = yield from driver.io_read(regmap.offset("POS_X"))
            for _ in range(15):  # the Y axis moves on meanwhile: POS_Y must not
                yield driver.clock.negedge
            y = yield from driver.io_read(regmap.offset("POS_Y"))
            reads.append((field("POS_X", "STEPS", x), field("POS_Y", "STEPS", y)))

    run_core("regs_snapshot", scenario)
    assert all(x == y for x, y in reads), reads
    assert 0 < reads[0][0] < reads[-1][0] < 300
