"""The machine side of the whole card core, judged from its pins and registers:
E-stop mid-arc, the host watchdog, each limit in each direction.

``card_core`` runs as MyHDL and as its Verilog in Icarus.  Golden values:
paths from ``models.dda_model`` (the pins must rebuild a prefix of the
uninterrupted path, and POS_X/POS_Y must equal the pins' count), pulse
widths from STEP_WIDTH, reaction times from the rules of docs/machine.md.
"""
import random

import pytest
from myhdl import delay

from models import registers as regmap
from models.commands import command_words
from models.dda_model import ArcCommand, LineCommand
from models.machine_model import REASON
from rtl.regs.pulse_out import QUEUE_DEPTH
from sim.card.card_bench import expected_path, read_position, wait_idle
from sim.card.machine_bench import (REACTION, WIDTH, assert_exact, assert_stopped, clear_stop, drive_at, drive_low_at,
                                    field, read, run_machine, set_input, snapshot, wait_clocks, write)

MODES = [False, True]
MODE_IDS = ["myhdl", "icarus"]


def arm(driver, feed=regmap.RATE_MAX // 2):
    for name, value in (("FEED_RATE", feed), ("RAMP_STEP", 0), ("STEP_WIDTH", WIDTH), ("STEP_SPACE", WIDTH),
                        ("CONTROL", 1), ("MACHINE_CONTROL", 1), ("INT_ENABLE", regmap.field_of("INT_ENABLE", STOPPED=1))):
        yield from write(driver, name, value)


@pytest.mark.parametrize("cosim,seed", [(False, 1), (False, 2), (False, 3), (True, 4)],
                         ids=["myhdl-1", "myhdl-2", "myhdl-3", "icarus-4"])
def test_estop_mid_arc(cosim, seed):
    rng = random.Random(seed)
    arc, queued, after = ArcCommand(90, 0, -90, 0), LineCommand(40, 40), LineCommand(7, -5)
    press = rng.randint(150, 900)
    results = {}

    def scenario(driver, pins, pin_log, machine_log):
        yield from arm(driver)
        yield from driver.push_all(command_words(arc) + command_words(queued))
        yield from wait_clocks(driver, press)
        results["at"] = yield from set_input(pins, pin_log, machine_log, "estop", 1)
        yield from wait_clocks(driver, 30)
        results["stopped"] = yield from snapshot(driver)
        yield from clear_stop(driver)   # refused: the E-stop input is still active
        results["held"] = yield from read(driver, "STOP_REASON")
        yield from driver.push_all(command_words(after))   # held while stopped, dropped by CLEAR_STOP
        yield from wait_clocks(driver, 100)
        results["still"] = yield from read_position(driver)
        yield delay(1)
        pins.estop.next = 0
        yield from wait_clocks(driver, 20)
        yield from clear_stop(driver)
        results["released"] = yield from snapshot(driver)
        results["rises_before"] = len(pin_log.rises)
        yield from driver.push_all(command_words(after))
        yield from wait_idle(driver)
        results["end"] = yield from read_position(driver)

    pin_log, machine_log = run_machine(f"estop_{seed}", scenario, cosim)
    at, stopped = results["at"], results["stopped"]
    assert_stopped(stopped, "ESTOP")
    assert field("MACHINE_STATUS", "ACTIVE", stopped["MACHINE_STATUS"]) & 1
    assert field("STOP_REASON", "REASON", results["held"]) == REASON["ESTOP"]
    rises = [r[0] for r in pin_log.rises[:results["rises_before"]]]
    assert rises and rises[-1] <= at + REACTION, (rises[-3:], at)
    # DRIVE_ENABLE low REACTION clocks on, or the clock after the STEP pulse then under way fell
    low = drive_low_at(pin_log, at + REACTION)
    assert drive_at(machine_log, low - 1) and not drive_at(machine_log, low), (low, at)
    interrupted = pin_log.rises[:results["rises_before"]]
    partial = type(pin_log)(rises=interrupted, edges=[e for e in pin_log.edges if e[0] < at + 30])
    assert_exact(partial, stopped["position"], [arc])
    assert 0 < len(interrupted) < len(expected_path([arc])) - 1, "the E-stop came mid-arc"
    released = results["released"]
    assert results["still"] == released["position"] == stopped["position"], "nothing moved while stopped"
    assert field("STATUS", "FIFO_LEVEL", released["STATUS"]) == 0, "CLEAR_STOP empties the queue"
    assert field("STATUS", "STOPPED", released["STATUS"]) == 0 and released["STOP_REASON"] == 0
    assert field("MACHINE_STATUS", "DRIVE_ENABLE", released["MACHINE_STATUS"]) == 0, "CLEAR_STOP does not re-energise"
    x, y = stopped["position"]
    assert results["end"] == (x + after.dx, y + after.dy) == pin_log.path()[-1], "only the new move ran"


@pytest.mark.parametrize("cosim", MODES, ids=MODE_IDS)
def test_watchdog_expires_and_stops(cosim):
    timeout = 600
    line = LineCommand(400, 100)
    results = {}

    def scenario(driver, pins, pin_log, machine_log):
        yield from arm(driver)
        yield from write(driver, "WATCHDOG", timeout)
        results["written"] = pin_log.clock
        yield from driver.push_all(command_words(line))
        for _ in range(4):   # kept alive for a while
            yield from wait_clocks(driver, timeout // 2)
            yield from write(driver, "WATCHDOG", timeout)
            results["written"] = pin_log.clock
        results["alive"] = yield from read(driver, "STOP_REASON")
        yield from wait_clocks(driver, timeout + 40)
        results["stopped"] = yield from snapshot(driver)

    pin_log, machine_log = run_machine("watchdog", scenario, cosim)
    assert results["alive"] == 0
    stopped = results["stopped"]
    assert_stopped(stopped, "WATCHDOG")
    drop = machine_log.drive.index(False, results["written"]) + 1
    # the write reaches the register at the edge after the bus transfer: the count ends TIMEOUT clocks on
    # (within 3), DRIVE_ENABLE falls then, or the clock after the STEP pulse then under way fell
    assert any(drop == drive_low_at(pin_log, results["written"] + timeout + slack) for slack in range(-3, 4)), (
        drop, results["written"])
    assert all(rise[0] < drop for rise in pin_log.rises)
    assert_exact(pin_log, stopped["position"], [line])
    assert 0 < stopped["position"][0] < line.dx


LIMITS = {"limit_pos_x": (LineCommand(25, 3), LineCommand(-25, 3), "X+"),
          "limit_neg_x": (LineCommand(-25, -3), LineCommand(25, -3), "X-"),
          "limit_pos_y": (LineCommand(3, 25), LineCommand(3, -25), "Y+"),
          "limit_neg_y": (LineCommand(-3, -25), LineCommand(-3, 25), "Y-")}
LIMIT_BIT = {"X+": 0, "X-": 1, "Y+": 2, "Y-": 3}


@pytest.mark.parametrize("cosim", MODES, ids=MODE_IDS)
@pytest.mark.parametrize("limit", LIMITS)
def test_limit_blocks_towards_and_allows_away(limit, cosim):
    """With the limit active, a move towards it stops before its first step
    towards it; once cleared, a move away runs whole.  Then the limit trips
    mid-move: at most the steps already queued leave after the filter's delay."""
    towards, away, which = LIMITS[limit]
    if cosim and limit != "limit_pos_x":
        pytest.skip("one limit on the Verilog: the others differ only in the bit")
    results = {}

    def scenario(driver, pins, pin_log, machine_log):
        yield from arm(driver)
        yield from set_input(pins, pin_log, machine_log, limit, 1)
        yield from wait_clocks(driver, REACTION)
        yield from driver.push_all(command_words(towards))
        yield from wait_clocks(driver, 200)
        results["blocked"] = yield from snapshot(driver)
        yield from clear_stop(driver)   # allowed with a limit active: the machine is backed off
        yield from driver.push_all(command_words(away))
        yield from wait_idle(driver)
        results["away"] = yield from snapshot(driver)
        yield from set_input(pins, pin_log, machine_log, limit, 0)
        yield from wait_clocks(driver, REACTION)
        results["rises_before"] = len(pin_log.rises)
        yield from driver.push_all(command_words(LineCommand(4 * towards.dx, 4 * towards.dy)))
        yield from wait_clocks(driver, 100)
        results["at"] = yield from set_input(pins, pin_log, machine_log, limit, 1)
        yield from wait_clocks(driver, 200)
        results["tripped"] = yield from snapshot(driver)

    pin_log, machine_log = run_machine(f"limit_{limit}", scenario, cosim)
    blocked = results["blocked"]
    assert_stopped(blocked, "LIMIT")
    assert field("STOP_REASON", "LIMITS", blocked["STOP_REASON"]) == 1 << LIMIT_BIT[which]
    assert blocked["position"] == (0, 0), "no step left towards the limit"
    away_words = results["away"]
    assert away_words["STOP_REASON"] == 0 and away_words["position"] == (away.dx, away.dy)
    tripped = results["tripped"]
    assert_stopped(tripped, "LIMIT")
    late = [r for r in pin_log.rises[results["rises_before"]:] if r[0] > results["at"] + REACTION - 1]
    assert len(late) <= QUEUE_DEPTH, late
    assert tripped["position"] == pin_log.path()[-1]
    moved = [abs(tripped["position"][i] - away_words["position"][i]) for i in range(2)]
    assert 0 < max(moved) < 4 * max(abs(towards.dx), abs(towards.dy))
