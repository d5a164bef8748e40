"""Motion control of the card, judged from the STEP/DIR pins: the trapezoidal
feed-rate ramp, BLEND, chained segments with no gap, errors in a chain.

Two interpolators behind the card's registers (``rtl/regs_fifo.py``):
``contract``, ``models.card_model.DdaContractModel`` (the DDA as
``rtl.interfaces.DdaPort`` promises it: overlapped setup, ``ready``,
``stop_left``), and the card's own ``rtl/dda_arc.py`` through
``rtl/card_core.py``, as MyHDL (``rtl``) and as its Verilog co-simulated in
Icarus (``verilog``).  Golden values: paths and iterations from
``models.dda_model``, step intervals from the register settings (65536 / rate
clocks per iteration), pin timing from ``PulseOutModel`` every clock (on
the MyHDL card, whose registers it reads).
"""
from dataclasses import replace

import pytest
from myhdl import Signal, block, instance

from models import instructions as isa
from models import registers as regmap
from models.card_model import DdaContractModel
from models.commands import command_words
from models.dda_build import DEFAULT_VARIANTS
from models.dda_model import TRADITIONAL, ArcCommand, LineCommand, iterate, setup_clocks
from models.parameters import Build
from rtl.card_core import card_core, card_core_ports
from rtl.interfaces import AxesCommand, AxisPulses, DdaPort, LocalBus, MotorPins, card_reset
from rtl.regs_fifo import regs_fifo
from sim.backends.icarus import convert_and_cosimulate
from sim.backends.waves import run_traced
from sim.card.card_bench import (BUS_GROUPS, TIMING, PinLog, clock_and_pins, expected_path, pin_model_check,
                                 read_position, scenario_runner, wait_error, wait_idle, write_motion_view)
from sim.card.local_bus_driver import LocalBusDriver

COORD_WIDTH = 24
FIFO_DEPTH = 32
BUILD = Build(coord_width=COORD_WIDTH, fifo_depth=FIFO_DEPTH)
STEADY = regmap.RATE_MAX  # one iteration every other clock: a step every other clock at width 1


DDAS = ["contract", "rtl", "verilog"]
# The Icarus co-simulation of the card core (``verilog``) takes about 15 s a bench: the default
# suite runs it for the ramp and the chain; the other benches run it in the slow set.
SLOW_VERILOG = pytest.mark.slow(reason="another Icarus run of the card core; the ramp and the chain check "
                                       "its Verilog by default")
DDAS_BUT_SLOW_VERILOG = ["contract", "rtl", pytest.param("verilog", marks=SLOW_VERILOG)]


def _command_of(dda):
    """The model command on the DDA's command lines, with its BLEND bit."""
    if dda.line:
        command = LineCommand(int(dda.xe), int(dda.ye))
    else:
        command = ArcCommand(int(dda.xs), int(dda.ys), int(dda.xe), int(dda.ye), ccw=bool(dda.ccw),
                             variant=int(dda.variant), lambda_shift=int(dda.lambda_shift),
                             acc_bits=int(dda.acc_bits))
    return command, bool(dda.blend)


@block
def contract_dda(clock, core_clear, dda, steps):
    """``DdaContractModel`` on the DDA's ports: registered outputs, reset by the core's clear."""

    def fresh():
        return DdaContractModel(lambda c: iterate(c[0], COORD_WIDTH).steps, lambda c: c[1],
                                lambda c: setup_clocks(COORD_WIDTH, isinstance(c[0], LineCommand)),
                                dda.left_width)

    @instance
    def run():
        model = fresh()
        while True:
            yield clock.posedge
            if core_clear:
                model = fresh()
            else:
                model.clock(bool(dda.start), bool(dda.advance), _command_of(dda) if dda.start else None)
            dda.ready.next, dda.busy.next = model.ready, model.busy
            dda.done.next, dda.error.next = model.done, model.error
            dda.stop_left.next = model.stop_left
            steps.step_x.next, steps.step_y.next, steps.dir_x.next, steps.dir_y.next = model.steps

    return run


@block
def motion_bench(kind, scenario, log, failures):
    if kind == "contract":
        clock, reset = Signal(bool(0)), card_reset()
        local, pins, irq = LocalBus(), MotorPins(), Signal(bool(0))
        dda, steps, core_clear = DdaPort(BUILD.coord_width, BUILD.variants), AxisPulses(), Signal(bool(0))
        regs = regs_fifo(clock, reset, local, dda, AxesCommand(), steps, pins, irq, core_clear, build=BUILD)
        parts = [regs, contract_dda(clock, core_clear, dda, steps)]
    else:
        ports = card_core_ports()
        clock, reset, local, pins = ports["clock"], ports["reset"], ports["local"], ports["pins"]
        if kind == "verilog":
            regs = None   # its registers are inside Icarus: the pins are judged by the tests alone
            parts = [convert_and_cosimulate(card_core, "card_core", ports, build=BUILD)]
        else:
            core = card_core(**ports, build=BUILD)
            regs = core.subs[1]
            parts = [core]
    parts.append(clock_and_pins(clock, pins, log))
    if regs is not None:
        parts.append(pin_model_check(clock, reset, pins, regs, TIMING, failures))
    return parts, scenario_runner(clock, reset, LocalBusDriver(clock, local), scenario)


def run_motion(name, kind, scenario):
    log, failures = PinLog(), []
    vcd = run_traced(motion_bench(kind, scenario, log, failures), f"motion_{name}_{kind}")
    if vcd is not None:
        write_motion_view(vcd, BUS_GROUPS)
    assert not failures, failures[0]
    return log


def words(command, blend=False):
    return command_words(replace(command, blend=blend))


def field(name, field_name, word):
    return regmap.field_value(name, field_name, word)


def program(driver, feed, ramp_start=regmap.RATE_MAX, ramp_step=0):
    for name, value in (("FEED_RATE", feed), ("RAMP_START", ramp_start), ("RAMP_STEP", ramp_step),
                        ("CONTROL", 1)):
        yield from driver.io_write(regmap.offset(name), value)


def x_gaps(log):
    times = [rise[0] for rise in log.rises if rise[1]]
    return [b - a for a, b in zip(times, times[1:])]


RAMP = dict(feed=16384, ramp_start=2048, ramp_step=512)  # 4 clocks per iteration at speed, 32 at the ends


def _gap(rate):
    return regmap.RATE_ONE / rate


@pytest.mark.parametrize("kind", DDAS)
def test_long_line_ramps_up_and_down(kind):
    """Intervals shrink, stay at FEED_RATE, grow back; the first and the last
    are those of RAMP_START (to one clock); the deceleration mirrors the ramp up."""
    results = {}

    def scenario(driver):
        yield from program(driver, **RAMP)
        yield from driver.push_all(words(LineCommand(300, 120)))
        results["status"] = yield from wait_idle(driver)
        results["position"] = yield from read_position(driver)

    log = run_motion("ramp", kind, scenario)
    assert results["position"] == (300, 120) == log.path()[-1]
    gaps = x_gaps(log)
    assert len(gaps) == 299
    slow, fast = _gap(RAMP["ramp_start"]), _gap(RAMP["feed"])
    # the first X interval is the second iteration's: one RAMP_STEP up already
    assert abs(gaps[0] - _gap(RAMP["ramp_start"] + RAMP["ramp_step"])) <= 1, gaps[:4]
    assert abs(gaps[-1] - slow) <= 1, gaps[-4:]
    ramp = (RAMP["feed"] - RAMP["ramp_start"]) // RAMP["ramp_step"]
    low = next(i for i, g in enumerate(gaps) if g <= fast)
    high = len(gaps) - 1 - next(i for i, g in enumerate(reversed(gaps)) if g <= fast)
    assert all(b <= a + 1 for a, b in zip(gaps[:low], gaps[1:low + 1])), "not shrinking"
    assert all(abs(g - fast) <= 1 for g in gaps[low:high + 1]), "not steady at FEED_RATE"
    assert all(b >= a - 1 for a, b in zip(gaps[high:], gaps[high + 1:])), "not growing back"
    # the rounded intervals reach FEED_RATE's a little before the rate does: compare the ends
    assert low <= ramp and abs(low - (len(gaps) - 1 - high)) <= 3, (low, high, ramp)


@pytest.mark.parametrize("kind", DDAS_BUT_SLOW_VERILOG)
@pytest.mark.parametrize("blend", [True, False], ids=["blend", "stop"])
def test_blend_keeps_speed_across_the_boundary(kind, blend):
    """BLEND = 1: the intervals around the boundary stay those of FEED_RATE;
    BLEND = 0: the first segment slows down to RAMP_START before it."""
    first, second = LineCommand(150, 0), LineCommand(150, 40)

    def scenario(driver):
        yield from program(driver, **RAMP)
        yield from driver.push_all(words(first, blend=blend) + words(second))
        yield from wait_idle(driver)

    log = run_motion(f"blend_{int(blend)}", kind, scenario)
    assert log.path() == expected_path([first, second])
    gaps = x_gaps(log)
    around = gaps[first.dx - 6:first.dx + 5]
    if blend:
        assert all(abs(g - _gap(RAMP["feed"])) <= 1 for g in around), around
    else:
        assert abs(gaps[first.dx - 2] - _gap(RAMP["ramp_start"])) <= 1, around
    assert abs(gaps[-1] - _gap(RAMP["ramp_start"])) <= 1, gaps[-4:]


CHAIN = [ArcCommand(80, 0, 0, 80), ArcCommand(70, 0, 0, 70), LineCommand(-70, 80), ArcCommand(60, 0, 0, 60)]


def _model_iterations(commands):
    """For every output step of the chained model paths, the index of its iteration."""
    indices, base = [], 0
    for command in commands:
        steps = iterate(command, COORD_WIDTH).steps
        indices += [base + i for i, step in enumerate(steps) if step.step_x or step.step_y]
        base += len(steps)
    return indices


@pytest.mark.parametrize("kind", DDAS)
def test_chained_moves_lose_no_iteration(kind):
    """Arc, arc, line, arc at one iteration every other clock: every STEP rise
    is two clocks per model iteration after the one before it (no slot lost at
    a boundary), and the path is the model's, segment after segment.  All
    segments move X down and Y up (a first move sets the DIR pins that way),
    so no DIR turn shifts the pins."""
    results = {}
    prime = LineCommand(-1, 1)

    def scenario(driver):
        yield from program(driver, STEADY)
        yield from driver.push_all(words(prime))
        yield from wait_idle(driver)
        yield from driver.push_all([w for command in CHAIN for w in words(command, blend=True)])
        results["status"] = yield from wait_idle(driver)
        results["position"] = yield from read_position(driver)

    log = run_motion("chain", kind, scenario)
    wanted = expected_path([prime] + CHAIN)
    assert log.path() == wanted and results["position"] == wanted[-1]
    assert field("STATUS", "ERROR", results["status"]) == 0
    iterations = _model_iterations(CHAIN)
    rises = [rise[0] for rise in log.rises[1:]]
    assert len(rises) == len(iterations)
    slots = [(b - a) - 2 * (j - i) for a, b, i, j in zip(rises, rises[1:], iterations, iterations[1:])]
    late = [(k, s) for k, s in enumerate(slots) if s]
    assert not late, f"rises off their iteration slot (rise index, clocks): {late[:5]}"


@pytest.mark.parametrize("kind", DDAS_BUT_SLOW_VERILOG)
def test_rejected_arc_in_a_chain(kind):
    """The line before a rejected arc completes, the error is the arc's, the
    line queued after it runs once CLEAR_ERROR is written."""
    results = {}
    bad = isa.encode("ARC", 10, 0, 0, 20, CCW=1, VARIANT=3)

    def scenario(driver):
        yield from program(driver, STEADY)
        yield from driver.push_all(words(LineCommand(90, 10), blend=True) + bad + words(LineCommand(3, 4)))
        for _ in range(2000):
            status = yield from driver.io_read(regmap.offset("STATUS"))
            if field("STATUS", "ERROR", status):
                break
        results["error"] = field("STATUS", "ERROR", status)
        for _ in range(50):  # the last step of the line leaves the pins; nothing more may follow
            yield driver.clock.negedge
        results["held"] = yield from read_position(driver)
        yield from driver.io_write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", CLEAR_ERROR=1))
        yield from wait_idle(driver)
        results["after"] = yield from read_position(driver)

    run_motion("rejected", kind, scenario)
    assert results["error"] == isa.ERROR_CODE["DDA_REJECTED"]
    assert results["held"] == (90, 10)
    assert results["after"] == (93, 14)


@pytest.mark.parametrize("kind", DDAS_BUT_SLOW_VERILOG)
def test_arc_of_a_variant_not_built_is_refused(kind):
    """The default build has the improved and precise variants: an ARC asking for the
    traditional one is RANGE, nothing of it moves, the line after it runs once
    CLEAR_ERROR is written."""
    results = {}
    refused = words(ArcCommand(40, 0, 0, 40, variant=TRADITIONAL))

    def scenario(driver):
        yield from program(driver, STEADY)
        yield from driver.push_all(words(LineCommand(3, 0)) + refused + words(LineCommand(0, 2)))
        results["error"] = yield from wait_error(driver, 500)
        results["held"] = yield from read_position(driver)
        yield from driver.io_write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", CLEAR_ERROR=1))
        yield from wait_idle(driver)
        results["after"] = yield from read_position(driver)

    run_motion("unbuilt_variant", kind, scenario)
    assert TRADITIONAL not in DEFAULT_VARIANTS
    assert results["error"] == isa.ERROR_CODE["RANGE"]
    assert results["held"] == (3, 0)
    assert results["after"] == (3, 2)


@pytest.mark.parametrize("kind", DDAS_BUT_SLOW_VERILOG)
def test_bad_opcode_discards_the_fifo_on_clear(kind):
    """After BAD_OPCODE the words behind the bad header (here a LINE's operands
    and more commands) are dropped by CLEAR_ERROR, not executed; words written
    after CLEAR_ERROR run.  A MARK before the bad header is reached."""
    results = {}
    bad = [0xF << isa.OPCODE_LSB] + words(LineCommand(50, 0)) + isa.encode("MARK", TAG=9)

    def scenario(driver):
        yield from program(driver, STEADY)
        yield from driver.push_all(words(LineCommand(4, 2)) + isa.encode("MARK", TAG=7) + bad)
        for _ in range(500):
            status = yield from driver.io_read(regmap.offset("STATUS"))
            if field("STATUS", "ERROR", status):
                break
        results["error"] = field("STATUS", "ERROR", status)
        results["level"] = field("STATUS", "FIFO_LEVEL", status)
        yield from driver.io_write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", CLEAR_ERROR=1))
        # the write reaches COMMAND a clock after the transfer, its strobe acts a clock later
        for _ in range(2):
            yield driver.clock.negedge
        results["cleared"] = yield from driver.io_read(regmap.offset("STATUS"))
        yield from driver.push_all(words(LineCommand(-1, 3)))
        yield from wait_idle(driver)
        results["after"] = yield from read_position(driver)
        results["tag"] = yield from driver.io_read(regmap.offset("MARK_TAG"))

    run_motion("bad_opcode", kind, scenario)
    assert results["error"] == isa.ERROR_CODE["BAD_OPCODE"]
    assert results["level"] > 0, "the words behind the bad header should still be queued"
    assert field("STATUS", "FIFO_EMPTY", results["cleared"]) == 1
    assert field("STATUS", "ERROR", results["cleared"]) == 0
    assert results["after"] == (3, 5)
    assert results["tag"] == 7
