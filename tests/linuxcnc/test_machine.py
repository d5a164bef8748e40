"""The dda_card driver's machine I/O and clock-drift loop under LinuxCNC, on the simulated card.

A LinuxCNC killed mid-move (the card's watchdog stops it), watchdog.has_bit
(halrun), the card's clock fast or slow against the servo periods (the
drift loop).  docs/linuxcnc.md, "The test".
"""
import json
import shutil
import time

import pytest

from models import registers as regmap
from models.sim_machine import MachineConfig, Switch
from tests.linuxcnc.compare import pin_positions, queued_position
from tests.linuxcnc.session import (CLOCK_HZ, PERIOD_CLOCKS, SCALE, as_user, card_server, configure, missing,
                                    run_and_kill, run_folder, run_linuxcnc)

# The kill test's watchdog: the card's queue (keep_ahead - 1 periods of steps left after the
# last ADVANCE, each period's steps at its start) outlasts it by more than a period, wherever
# in its period the driver died (its last WATCHDOG write before or after that ADVANCE).
WATCHDOG_NS = 1_500_000
WATCHDOG_CLOCKS = WATCHDOG_NS * CLOCK_HZ // 1_000_000_000
WATCHDOG_SLACK = 3  # docs/machine.md: the stop comes TIMEOUT clocks after the write reaches WATCHDOG, within 3
FREE_RUN = 20 * PERIOD_CLOCKS  # clocks the card runs on its own once LinuxCNC is gone
KILL_AFTER = 1.5  # s into lcnc_kill.ngc (a 3.4 s rapid)

# one LinuxCNC per host: every LinuxCNC test runs on one xdist worker, in turn
pytestmark = [pytest.mark.linuxcnc, pytest.mark.xdist_group("linuxcnc"),
              pytest.mark.skipif(missing() is not None, reason=str(missing()))]


def _field(register, name, value):
    item = regmap.register(register).field(name)
    return (value & item.mask) >> item.lsb


def test_killed_linuxcnc_is_stopped_by_the_card_watchdog(linuxcnc_alone):
    """LinuxCNC SIGKILLed mid-move: nothing advances or writes the card any more; the
    card, running on its own, makes the steps it has queued until its watchdog (last
    written in the last period the driver ran) stops it: the last STEP rise and
    DRIVE_ENABLE's fall within the watchdog's timeout (+ the documented 3 clocks) of that
    write, STOP_REASON WATCHDOG, and the pins short of what was queued.  The driver sets
    RAMP_STEP 0, so the stop has no deceleration."""
    run = run_folder()
    configure(run)
    with open(run / "record.hal", "a") as hal:
        hal.write(f"setp dda-card.0.watchdog.timeout_ns {WATCHDOG_NS}\n")
    started = time.monotonic()
    record = run_and_kill(run, run / "lcnc_kill.ngc", KILL_AFTER, FREE_RUN)
    last = record["advances"][-1][1]  # the end of the last period the driver advanced the card
    gone = record["free_run"]["start"]  # the card's clock when the driver's socket closed
    assert record["free_run"]["end"] >= gone + FREE_RUN
    rises = [r[0] for r in record["rises"]]
    assert any(last - PERIOD_CLOCKS < r <= last for r in rises), "LinuxCNC was not killed mid-move"
    drive = record["drive"]
    assert drive[-1][1] == 0 and drive[-2][1] == 1, f"DRIVE_ENABLE did not stay high, then fall: {drive}"
    fell = drive[-1][0]
    watchdog = [(clock, value) for clock, offset, value in record["writes"] if offset == regmap.offset("WATCHDOG")]
    written, value = watchdog[-1]
    assert value == WATCHDOG_CLOCKS and last - PERIOD_CLOCKS < written <= gone, "not rewritten every period"
    assert abs(fell - (written + WATCHDOG_CLOCKS)) <= WATCHDOG_SLACK
    assert rises[-1] <= fell, "a step after the watchdog stopped the card"
    after = [r for r in rises if r > last]
    assert after, "the card made none of its queued steps on its own"
    final = record["final"]
    assert _field("STOP_REASON", "REASON", final["STOP_REASON"]) == regmap.STOP_REASONS.index("WATCHDOG")
    assert _field("STATUS", "STOPPED", final["STATUS"]) == 1
    assert _field("MACHINE_STATUS", "DRIVE_ENABLE", final["MACHINE_STATUS"]) == 0
    clocks, xs, ys = pin_positions(run / "card.json")
    at_last = next((i for i in range(len(clocks) - 1, -1, -1) if clocks[i] <= last), -1)
    before = (xs[at_last], ys[at_last]) if at_last >= 0 else (0, 0)
    queued, end = queued_position(record["fifo"]), (xs[-1], ys[-1])
    for axis in (0, 1):  # a straight rapid: the pins between where they were and where the queue led
        assert min(before[axis], queued[axis]) <= end[axis] <= max(before[axis], queued[axis])
    assert end != queued, "the queue ran out before the watchdog stopped the card"
    print(f"\nwatchdog {WATCHDOG_CLOCKS} clocks: after the last advance the card made {len(after)} steps on its own, "
          f"the last {rises[-1] - last} clocks and DRIVE_ENABLE low {fell - last} clocks after it "
          f"({fell - written} after the last WATCHDOG write); "
          f"{abs(queued[0] - end[0])}, {abs(queued[1] - end[1])} steps of the queue not made; "
          f"{time.monotonic() - started:.0f} s")
    shutil.rmtree(run, ignore_errors=True)


HAS_BIT_HAL = """loadrt threads name1=servo-thread period1=1000000
loadrt dda_card sim={socket}
addf dda-card.0.read servo-thread
addf dda-card.0.write servo-thread
setp dda-card.0.watchdog.timeout_ns 500000
setp dda-card.0.stepgen.00.enable 1
setp dda-card.0.stepgen.01.enable 1
setp dda-card.0.drive-enable 1
start
loadusr -w sleep 0.3
{show}
setp dda-card.0.watchdog.timeout_ns 5000000
setp dda-card.0.watchdog.has_bit 0
loadusr -w sleep 0.2
getp dda-card.0.error
setp dda-card.0.stepgen.00.enable 0
setp dda-card.0.stepgen.01.enable 0
loadusr -w sleep 0.2
setp dda-card.0.stepgen.00.enable 1
setp dda-card.0.stepgen.01.enable 1
loadusr -w sleep 0.3
{show}
"""
SHOWN = ("watchdog.has_bit", "error", "error-code", "stop-reason")


def test_watchdog_has_bit_holds_the_card_until_written_false(linuxcnc_alone):
    """A watchdog shorter than the servo period bites in the first period (lock-step: the
    card runs a whole period after each write): has_bit, error -3, stop-reason 2, the
    card's DRIVE_ENABLE low.  Writing has_bit false alone does not restart (error stays
    until the enables fall); after they fall and rise with a 5 ms watchdog the queue runs,
    the card released (COMMAND.CLEAR_STOP) and DRIVE_ENABLE high again."""
    run = run_folder()
    show = "\n".join(f"getp dda-card.0.{pin}" for pin in SHOWN)
    (run / "has_bit.hal").write_text(HAS_BIT_HAL.format(socket=run / "card.sock", show=show))
    (run / "has_bit.hal").chmod(0o666)
    server = card_server(run)
    try:
        result = as_user(["halrun", "-f", str(run / "has_bit.hal")], run, 120)
        assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
        server.wait(timeout=60)
    finally:
        server.kill()
    values = [line for line in result.stdout.split() if line in ("TRUE", "FALSE") or line.lstrip("-").isdigit()]
    stopped, held, running = dict(zip(SHOWN, values[:4])), values[4], dict(zip(SHOWN, values[5:]))
    assert stopped == {"watchdog.has_bit": "TRUE", "error": "TRUE", "error-code": "-3", "stop-reason": "2"}
    assert "the card stopped the machine: its watchdog" in result.stdout + result.stderr
    assert held == "TRUE", "has_bit written false restarted the card without the enables falling"
    assert running == {"watchdog.has_bit": "FALSE", "error": "FALSE", "error-code": "0", "stop-reason": "0"}
    record = json.loads((run / "card.json").read_text())
    levels = [level for _, level in record["drive"]]
    assert levels == [0, 1, 0, 1, 0], f"DRIVE_ENABLE: on, the watchdog's stop, on again, unload: {record['drive']}"
    first_stop = record["drive"][2][0]
    assert first_stop <= PERIOD_CLOCKS + 100, "the 0.5 ms watchdog did not stop the card in its first period"
    shutil.rmtree(run, ignore_errors=True)


@pytest.mark.parametrize("ppm", [2000, pytest.param(-2000, marks=pytest.mark.slow(
    reason="a slow card clock: the same trim the other way, another LinuxCNC run"))])
def test_clock_drift_is_trimmed_from_the_fifo_level(linuxcnc_alone, ppm):
    """The card's clock ``ppm`` fast or slow against the servo periods (card server
    --ppm; 2000 ppm drains or fills the queue by a period in half a second): the
    driver's DWELL trims (drift-trim) keep the card clocks queued within a period and
    a half of where they started, the FIFO level bounded, no underrun, the pins at
    the command at the end."""
    run = run_folder()
    configure(run)
    samples, pins, record = run_linuxcnc(run, [str(run / "lcnc_path.ngc")], "--ppm", str(ppm))
    on = [k for k, sample in enumerate(samples) if sample[5]]
    first, last = on[0] + 1, on[-1]
    worst = trimmed = 0
    for k in range(first, last + 1):
        trimmed += samples[k][7]
        drift = samples[k][2] - samples[first - 1][2] - PERIOD_CLOCKS * (k - first + 1)
        worst = max(worst, abs(trimmed - drift))
    assert worst <= 1.5 * PERIOD_CLOCKS, f"the queue moved {worst} clocks from where it started"
    levels = [s[3] for s in samples[first + 1:last + 1]]
    assert max(levels) <= 20 and samples[-1][4] == 0
    assert (pins[1][-1], pins[2][-1]) == (round(samples[-1][0] * SCALE), round(samples[-1][1] * SCALE))
    print(f"\n{ppm:+} ppm: {last - first + 1} periods, drift {drift} clocks, trimmed {trimmed}, the queue "
          f"within {worst} clocks of its start, FIFO {min(levels)}..{max(levels)} words, no underrun")
    shutil.rmtree(run, ignore_errors=True)


# The simulated machine of the homing test: a home switch 5 mm along +X and one
# 3 mm along -Y (SCALE steps per mm), each with hysteresis and contact bounce.
HOME_SWITCHES = MachineConfig(switches={
    "HOME_X": Switch(500, positive=True, hysteresis=20, bounce=40, longest_run=5, seed=3),
    "HOME_Y": Switch(-300, positive=False, hysteresis=10, bounce=30, longest_run=4, seed=8)})
HOMING_INI = {"JOINT_0": dict(HOME_SEARCH_VEL=5, HOME_LATCH_VEL=0.5),
              "JOINT_1": dict(HOME_SEARCH_VEL=-5, HOME_LATCH_VEL=-0.5)}
HOMING_HAL = """
# the card's home inputs to LinuxCNC's homing (issue 28's simulated machine drives them)
net home-x dda-card.0.input.home-x => joint.0.home-sw-in
net home-y dda-card.0.input.home-y => joint.1.home-sw-in
"""


def test_linuxcnc_homes_on_the_simulated_machines_switches(linuxcnc_alone):
    """LinuxCNC homes both joints on their home switches (search at 5 mm/s, latch on
    the switch's closing at 0.5 mm/s), read through the driver's input.home-* pins
    from the card's filtered inputs, which the card server's simulated machine
    (--machine) drives from the axes' positions.  Homed, each joint stands at its
    HOME (0), which LinuxCNC put at the latch: the machine is within a step of where
    its switch closes, no step lost, and LinuxCNC's motor command is there."""
    run = run_folder()
    configure(run)
    ini = (run / "dda_xy.ini").read_text()
    for joint, settings in HOMING_INI.items():
        head, _, tail = ini.partition(f"[{joint}]")
        for key, value in settings.items():
            tail = tail.replace(f"{key} = 0", f"{key} = {value}", 1)
        ini = head + f"[{joint}]" + tail
    (run / "dda_xy.ini").write_text(ini)
    with open(run / "dda_xy.hal", "a") as hal:
        hal.write(HOMING_HAL)
    (run / "machine.json").write_text(HOME_SWITCHES.to_json())
    for path in ("dda_xy.ini", "dda_xy.hal", "machine.json"):
        (run / path).chmod(0o666)
    samples, pins, record = run_linuxcnc(run, [], "--machine", str(run / "machine.json"))
    machine = record["machine"]
    assert machine["lost"] == [0, 0]
    trips = [HOME_SWITCHES.switches[name].position for name in ("HOME_X", "HOME_Y")]
    assert all(abs(got - trip) <= 1 for got, trip in zip(machine["positions"], trips)), (machine, trips)
    # the pins agree with the machine (the drives were on for every step)
    assert [pins[1][-1], pins[2][-1]] == machine["positions"]
    # LinuxCNC's motor command (its joint at HOME plus the offset the latch set) is where the machine is
    assert all(abs(samples[-1][axis] * SCALE - machine["positions"][axis]) <= 1 for axis in range(2)), samples[-1]
    print(f"\nhomed: machine at {machine['positions']} steps, the switches close at {trips}")
    shutil.rmtree(run, ignore_errors=True)
