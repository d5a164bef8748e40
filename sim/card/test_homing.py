"""HOME on the whole card core, judged from its pins and registers.

A bouncing home switch (``models.homing_model.BouncingSwitch``) follows the
axis position rebuilt from the STEP/DIR pins.  Golden values come from that
model and the input filter's model (``expected_homing``): where the
position must be zeroed (the switch's release point), what POS must read,
the step spacing the HOME_* registers set.  ``card_core`` runs as MyHDL and
as its Verilog in Icarus.
"""
import pytest

from models import registers as regmap
from models.commands import command_words
from models.dda_model import LineCommand
from models.homing_model import BouncingSwitch, expected_homing
from models.machine_model import REASON
from sim.card.card_bench import read_position, wait_idle
from sim.card.homing_bench import BACKOFF, RELEASE, SAMPLES, SEEK, arm, home, homing_run, outcome, wait_homed
from sim.card.machine_bench import read, run_machine, set_input, write


def field(name, field_name, word):
    return regmap.field_value(name, field_name, word)

def gaps(rises):
    return [b[0] - a[0] for a, b in zip(rises, rises[1:])]


CASES = [(0, False, False, 1), (0, True, False, 2), (1, False, False, 3), (1, True, False, 4),
         (0, True, True, 5), (1, False, True, 6)]


@pytest.mark.parametrize("axis,negative,cosim,seed", CASES,
                         ids=[f"{'XY'[a]}{'-' if n else '+'}-{'icarus' if c else 'myhdl'}" for a, n, c, _ in CASES])
def test_home_with_bouncing_switch(axis, negative, cosim, seed):
    switch = BouncingSwitch(trip=12 + seed, negative=negative, hysteresis=seed % 3, chatter=14, longest_run=3,
                            seed=seed)
    pin_log, words = homing_run(f"home_{'xy'[axis]}{int(negative)}_{seed}", cosim, axis, negative, switch)
    expect = expected_homing(pin_log.rises, axis, switch.levels, SAMPLES, negative)
    assert outcome(words["HOME_STATUS"]) == dict(BUSY=0, DONE=1, NOT_FOUND=0, REFUSED=0, PHASE=0)
    assert field("HOME", "AXIS", words["HOME"]) == axis and field("HOME", "NEGATIVE", words["HOME"]) == negative
    assert field("INT_STATUS", "HOMED", words["INT_STATUS"]) == 1
    # the switch bounced at both changes, and the filter saw each once
    assert [closed for _, _, closed in switch.changes] == [True, False]
    assert all(sum(a != b for a, b in zip(switch.levels[c:c + 16], switch.levels[c + 1:c + 17])) >= 3
               for c, _, _ in switch.changes)
    assert switch.changes[0][1] == switch.trip_point, "the seek reached the switch"
    # zeroed exactly at the release point the switch defines; POS counts from there
    assert expect.zero_point == switch.release_point
    sense = -1 if negative else 1
    position = words["position"]
    assert position[axis] == expect.position == -sense * BACKOFF
    assert position[1 - axis] == 0 and all(not rise[2 - axis] for rise in pin_log.rises)
    # the set step rates, from the pins (the first step in a new direction leaves
    # late by the DIR change, DIR_HOLD and DIR_SETUP: DIR is positive after reset)
    assert set(gaps(expect.seek[1:])) == {SEEK}
    # every step off the switch and of the back-off at the release period, the
    # gap from the last release step to the first back-off step included
    assert len(expect.release) > 2 and len(expect.backoff) == BACKOFF
    assert gaps(expect.release[1:] + expect.backoff) == [RELEASE] * (len(expect.release) + BACKOFF - 2)
    assert expect.trip_edge < expect.release[0][0] and expect.release[-1][0] < expect.release_edge


# A filter slower than the release period (15 samples 8 clocks apart: 120
# clocks against 60): the filter sees the switch open after more steps have
# left, the spacing must not change.
SLOW_FILTER = dict(samples=15, tick=8)


# the Verilog run is slow: test_home_with_bouncing_switch checks every gap on the Verilog too
@pytest.mark.parametrize("cosim", [False, pytest.param(True, marks=pytest.mark.slow)], ids=["myhdl", "icarus"])
def test_release_and_backoff_spacing_with_a_slow_filter(cosim):
    switch = BouncingSwitch(trip=9, hysteresis=1, chatter=14, longest_run=3, seed=11)
    pin_log, words = homing_run("home_slow_filter", cosim, 0, False, switch, **SLOW_FILTER)
    expect = expected_homing(pin_log.rises, 0, switch.levels, SLOW_FILTER["samples"], False, SLOW_FILTER["tick"])
    assert outcome(words["HOME_STATUS"]) == dict(BUSY=0, DONE=1, NOT_FOUND=0, REFUSED=0, PHASE=0)
    assert words["position"] == (expect.position, 0)
    # zeroed where the filter saw the switch open, past its release point; steps
    # already requested then count from there, then HOME_BACKOFF more
    assert expect.zero_point < switch.release_point
    assert len(expect.backoff) >= BACKOFF and expect.position == -len(expect.backoff)
    assert gaps(expect.release[1:] + expect.backoff) == [RELEASE] * (len(expect.release) + len(expect.backoff) - 2)


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
def test_switch_not_found_within_search(cosim):
    switch = BouncingSwitch(trip=1000, negative=True)
    pin_log, words = homing_run("home_not_found", cosim, 0, True, switch, search=23)
    assert outcome(words["HOME_STATUS"]) == dict(BUSY=0, DONE=0, NOT_FOUND=1, REFUSED=0, PHASE=0)
    assert field("INT_STATUS", "HOMED", words["INT_STATUS"]) == 1
    assert words["position"] == (-23, 0) == pin_log.path()[-1], "23 steps, the position not zeroed"
    assert set(gaps(pin_log.rises[1:])) == {SEEK}


def test_switch_that_does_not_release_within_search():
    switch = BouncingSwitch(trip=6, hysteresis=500, chatter=10, seed=7)
    pin_log, words = homing_run("home_stuck", False, 1, False, switch, search=15)
    assert outcome(words["HOME_STATUS"]) == dict(BUSY=0, DONE=0, NOT_FOUND=1, REFUSED=0, PHASE=0)
    away = [rise for rise in pin_log.rises if not rise[4]]
    assert len(away) == 15 and set(gaps(away[1:])) == {RELEASE}
    assert words["position"] == pin_log.path()[-1] and words["position"][1] == switch.position



def test_home_refused_while_direct_pulses_run():
    """HOME while direct pulses run (CONTROL.MODE 1) is refused and every pulse
    of PULSE_COUNT comes out; once they have, a HOME homes."""
    switch = BouncingSwitch(trip=8, seed=4)
    count, period = -6, 40
    words = {}

    def scenario(driver, pins, pin_log, machine_log):
        yield from arm(driver)
        yield from write(driver, "CONTROL", regmap.field_of("CONTROL", MODE=1))
        yield from write(driver, "PULSE_PERIOD_Y", period)
        yield from write(driver, "PULSE_COUNT_Y", count & 0xFFFFFFFF)
        yield from home(driver, 0, False)
        words["during_pulses"] = yield from wait_homed(driver)
        words["left"] = yield from read(driver, "PULSE_COUNT_Y")
        yield from wait_idle(driver)
        words["pulsed"] = yield from read_position(driver)
        yield from home(driver, 0, False)
        words["after"] = yield from wait_homed(driver)

    pin_log, _ = run_machine("home_refused_direct", scenario, switches=[("x", switch)])
    assert outcome(words["during_pulses"]) == dict(BUSY=0, DONE=0, NOT_FOUND=0, REFUSED=1, PHASE=0)
    assert 0 < words["left"] < -count
    assert words["pulsed"] == (0, count)
    assert outcome(words["after"])["DONE"] == 1

@pytest.mark.parametrize("cause", ["limit_pos_x", "estop"])
def test_limit_or_estop_stops_homing(cause):
    """A stop during the seek ends homing as it ends any move: no DONE, no
    NOT_FOUND, the position exact; a HOME while stopped is refused."""
    switch = BouncingSwitch(trip=500)

    def during(driver, pins, pin_log, machine_log, words):
        for _ in range(10 * SEEK):
            yield driver.clock.negedge
        words["at"] = yield from set_input(pins, pin_log, machine_log, cause, 1)
        for _ in range(50):
            yield driver.clock.negedge
        yield from home(driver, 0, False)
        words["refused"] = yield from wait_homed(driver)

    pin_log, words = homing_run(f"home_{cause}", False, 0, False, switch, during=during)
    assert outcome(words["HOME_STATUS"]) == dict(BUSY=0, DONE=0, NOT_FOUND=0, REFUSED=1, PHASE=0)
    assert outcome(words["refused"]) == outcome(words["HOME_STATUS"])
    reason = "LIMIT" if cause.startswith("limit") else "ESTOP"
    assert field("STATUS", "STOPPED", words["STATUS"]) == 1
    assert field("STOP_REASON", "REASON", words["STOP_REASON"]) == REASON[reason]
    assert words["position"] == pin_log.path()[-1] and 5 < words["position"][0] < 15
    assert all(rise[0] <= words["at"] + SAMPLES + 3 + 4 * SEEK for rise in pin_log.rises)


def test_home_refused_while_busy():
    """HOME while a LINE runs is refused and the line runs on; a HOME while
    homing is refused and the homing it came into goes on to DONE."""
    line = LineCommand(30, -20)
    words = {}
    switch = BouncingSwitch(trip=8, seed=9)

    def scenario(driver, pins, pin_log, machine_log):
        yield from arm(driver)
        yield from write(driver, "FEED_RATE", regmap.RATE_MAX // 4)
        yield from write(driver, "CONTROL", 1)
        yield from driver.push_all(command_words(line))
        for _ in range(40):
            yield driver.clock.negedge
        yield from home(driver, 0, False)
        words["during_line"] = yield from wait_homed(driver)
        yield from wait_idle(driver)
        words["line"] = yield from read_position(driver)
        yield from write(driver, "COMMAND", regmap.field_of("COMMAND", CLEAR_POSITION=1))
        switch.position = 0
        yield from home(driver, 0, False)
        yield from home(driver, 1, True)
        for _ in range(2):   # the write reaches the register, the sequencer takes it
            yield driver.clock.negedge
        words["twice"] = yield from read(driver, "HOME_STATUS")
        words["asked"] = yield from read(driver, "HOME")
        words["end"] = yield from wait_homed(driver)
        words["position"] = yield from read_position(driver)

    run_machine("home_refused", scenario, switches=[("x", switch)])
    assert outcome(words["during_line"]) == dict(BUSY=0, DONE=0, NOT_FOUND=0, REFUSED=1, PHASE=0)
    assert words["line"] == (line.dx, line.dy)
    twice = outcome(words["twice"])
    assert twice["BUSY"] == 1 and twice["REFUSED"] == 1 and words["asked"] == 0
    assert outcome(words["end"])["DONE"] == 1
    assert words["position"] == (-BACKOFF, 0)
