"""Feed hold and the decelerated stop of the whole card core, judged from its pins.

``card_core`` runs as MyHDL and as its Verilog in Icarus.  Golden values:
paths from ``models.dda_model`` (a path held and resumed must come out on the
pins step for step as the uninterrupted one), the step times of a
decelerated stop from ``models.machine_model.paused_ticks`` (the feed rate's
ramp, ``FeedRateModel``), reasons and reactions from docs/machine.md.
"""
import random

import pytest

from models import registers as regmap
from models.commands import command_words
from models.dda_model import ArcCommand, LineCommand
from models.machine_model import paused_ticks
from sim.card.card_bench import expected_path, read_position, wait_idle
from sim.card.machine_bench import (REACTION, WIDTH, assert_exact, assert_stopped, clear_stop, drive_at, field, read,
                                    run_machine, set_input, snapshot, wait_clocks, write)

RAMP = dict(target=8192, ramp_start=1024, ramp_step=512)   # an iteration every 8 clocks at speed: the queue never fills
SETTLE = 2 * WIDTH + 4   # the last pulse leaves the pins, then the latch and DRIVE_ENABLE's flip-flop
CAUSE_SLACK = (-4, 12)  # the register write's bus latency, the guard's latch, the feed rate's clock
ITERATION = regmap.RATE_ONE // RAMP["target"]   # clocks: a limit is hit at the next step request


def arm_ramped(driver):
    for name, value in (("FEED_RATE", RAMP["target"]), ("RAMP_START", RAMP["ramp_start"]),
                        ("RAMP_STEP", RAMP["ramp_step"]), ("STEP_WIDTH", WIDTH), ("STEP_SPACE", WIDTH), ("CONTROL", 1),
                        ("MACHINE_CONTROL", regmap.field_of("MACHINE_CONTROL", DRIVE_ENABLE=1)),
                        ("INT_ENABLE", regmap.field_of("INT_ENABLE", STOPPED=1))):
        yield from write(driver, name, value)


def hold(driver, on):
    yield from write(driver, "MACHINE_CONTROL", regmap.field_of("MACHINE_CONTROL", DRIVE_ENABLE=1, HOLD=int(on)))


def wait_held(driver, limit=400):
    """Read MACHINE_STATUS until HELD; the reads it took."""
    for reads in range(limit):
        status = yield from read(driver, "MACHINE_STATUS")
        if field("MACHINE_STATUS", "HELD", status):
            return reads
    raise AssertionError("the feed never held")


def matching_pauses(rise_clocks, search):
    """(offset, pause clocks) for which ``paused_ticks`` gives the rises exactly:
    the model's clock 0 is pin clock ``offset``."""
    matches = []
    for pause_at in search:
        ticks = paused_ticks(pause_at=pause_at, **RAMP)
        offset = rise_clocks[0] - ticks[0]
        if [t + offset for t in ticks] == rise_clocks:
            matches.append((offset, pause_at))
    return matches


@pytest.mark.parametrize("cosim,seed", [(False, 1), (False, 2), (False, 3), (True, 4)],
                         ids=["myhdl-1", "myhdl-2", "myhdl-3", "icarus-4"])
def test_hold_and_resume_keep_the_path(cosim, seed):
    """Two feed holds at random clocks of a line chained with an arc: no step
    while held, and the pins' path is the uninterrupted one, step for step."""
    rng = random.Random(seed)
    commands = [LineCommand(180, 70), ArcCommand(60, 0, -60, 0), LineCommand(-40, 90)]
    holds = sorted(rng.sample(range(300, 3600), 2))
    results = {"held": []}

    def scenario(driver, pins, pin_log, machine_log):
        yield from arm_ramped(driver)
        yield from driver.push_all(sum((command_words(c) for c in commands), []))
        for at in holds:
            yield from wait_clocks(driver, max(at - pin_log.clock, 1))
            yield from hold(driver, True)
            yield from wait_held(driver)
            rises, position = len(pin_log.rises), (yield from read_position(driver))
            yield from wait_clocks(driver, rng.randint(100, 300))
            later = yield from read_position(driver)
            results["held"].append((rises, len(pin_log.rises), position, later))
            yield from hold(driver, False)
        yield from wait_idle(driver)
        results["end"] = yield from snapshot(driver)

    pin_log, machine_log = run_machine(f"hold_{seed}", scenario, cosim)
    expected = expected_path(commands)
    assert pin_log.path() == expected, "the held path differs from the uninterrupted one"
    assert results["end"]["position"] == expected[-1]
    assert results["end"]["STOP_REASON"] == 0 and all(machine_log.drive[-10:])
    for rises, later_rises, position, later in results["held"]:
        assert rises == later_rises and position == later, "a step while held"
        assert 0 < rises < len(expected) - 1, "the hold came mid-path"


def _decelerated_run(name, cosim, trip, after=None):
    """A long line at speed with a ramp; ``trip(driver, pins, pin_log, machine_log)``
    starts the stop and returns its clock, ``after(driver)`` runs once the
    card stopped.  The stop's steps and DRIVE_ENABLE are checked; (pin log,
    results: the trip's clock, the registers when stopped, the rises' clocks)."""
    line = LineCommand(1500, 400)
    results = {}

    def scenario(driver, pins, pin_log, machine_log):
        yield from arm_ramped(driver)
        yield from driver.push_all(command_words(line))
        results["at"] = yield from trip(driver, pins, pin_log, machine_log)
        yield from wait_clocks(driver, 1200)
        results["stopped"] = yield from snapshot(driver)
        results["rises"], results["until"] = len(pin_log.rises), pin_log.clock
        if after:
            yield from after(driver)

    pin_log, machine_log = run_machine(name, scenario, cosim)
    rises = pin_log.rises[:results["rises"]]
    rise_clocks = [rise[0] for rise in rises]
    stopped_log = type(pin_log)(rises=rises, edges=[e for e in pin_log.edges if e[0] <= rise_clocks[-1] + SETTLE])
    assert_exact(stopped_log, results["stopped"]["position"], [line])
    assert 0 < results["stopped"]["position"][0] < line.dx - 100, "stopped far from the path's end"
    gaps = stopped_log.gaps()
    assert gaps[-1] >= 4 * min(gaps), ("the steps slowed down before the stop", gaps[-20:])
    assert all(b >= a - 1 for a, b in zip(gaps[-12:], gaps[-11:])), ("intervals grow", gaps[-12:])
    drop = next(c for c in range(rise_clocks[0], len(machine_log.drive) + 1) if not drive_at(machine_log, c))
    assert rise_clocks[-1] < drop <= rise_clocks[-1] + SETTLE, (rise_clocks[-1], drop)
    assert not any(machine_log.drive[drop - 1:results["until"] - 1]), "DRIVE_ENABLE stays low"
    results.update(rise_clocks=rise_clocks, drop=drop)
    return pin_log, results


def assert_ramps_down_from(rise_clocks, cause, slack):
    """The rises are the model's iterations with the feed held from a clock
    within ``slack`` of the pin clock ``cause``; the steps after ``cause``."""
    search = range(cause - rise_clocks[0] - 200, cause - rise_clocks[0] + 200)
    matches = matching_pauses(rise_clocks, search)
    assert matches, "the steps do not follow the ramp"
    low, high = slack
    assert any(low <= offset + pause_at - cause <= high for offset, pause_at in matches), (matches[:3], cause)
    return sum(1 for clock in rise_clocks if clock > cause)


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
def test_watchdog_stop_decelerates(cosim):
    """The watchdog expires at speed: the steps follow the ramp down exactly
    (the model's iterations, paused from the expiry), then none; DRIVE_ENABLE
    falls after the last, reason WATCHDOG."""
    timeout = random.Random(5).randint(1500, 2500)

    def trip(driver, pins, pin_log, machine_log):
        yield from write(driver, "WATCHDOG", timeout)
        written = pin_log.clock
        yield from wait_clocks(driver, timeout)
        return written

    pin_log, results = _decelerated_run("watchdog_ramp", cosim, trip)
    assert_stopped(results["stopped"], "WATCHDOG")
    after = assert_ramps_down_from(results["rise_clocks"], results["at"] + timeout, CAUSE_SLACK)
    assert after > len(paused_ticks(pause_at=0, **RAMP)) // 2, "steps at speed, then the ramp down"


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
def test_limit_stop_decelerates_then_backs_off(cosim):
    """A limit trips at speed with a ramp set: the move decelerates along its
    path (steps towards the limit pass while it ramps down), reason LIMIT
    X+; once cleared, a move away runs whole."""
    trip_clock = random.Random(6).randint(900, 1800)

    def trip(driver, pins, pin_log, machine_log):
        yield from wait_clocks(driver, trip_clock)
        return (yield from set_input(pins, pin_log, machine_log, "limit_pos_x", 1))

    results = {}

    def back_off(driver):
        yield from clear_stop(driver)
        yield from driver.push_all(command_words(away))
        yield from wait_idle(driver)
        results["away"] = yield from snapshot(driver)

    away = LineCommand(-30, 5)
    pin_log, run = _decelerated_run("limit_ramp", cosim, trip, back_off)
    stopped = run["stopped"]
    assert_stopped(stopped, "LIMIT")
    assert field("STOP_REASON", "LIMITS", stopped["STOP_REASON"]) == 1   # LIMIT_POS_X
    active_at = run["at"] + REACTION - 1   # the filtered input is active from this clock on
    low, high = CAUSE_SLACK
    after = assert_ramps_down_from(run["rise_clocks"], active_at, (low, high + ITERATION))
    assert after > 0, "steps towards the limit while it ramps down"
    x, y = stopped["position"]
    assert results["away"]["STOP_REASON"] == 0
    assert results["away"]["position"] == (x + away.dx, y + away.dy) == pin_log.path()[-1], "the move away ran whole"
