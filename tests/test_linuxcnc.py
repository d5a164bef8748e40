"""LinuxCNC with the dda_card driver on the simulated card, end to end.

The card server (``host.cardserver``) runs the Verilator card built to
report 1 MHz in CLOCK_HZ; the driver advances it by one servo period of
card clocks per period (lock-step), so the driver's timing math runs as on
a real card.  LinuxCNC runs headless as an ordinary user; ``sampler``
records the commanded joint positions and the card clock every period.
The pins' position keep_ahead - 1 periods after a period's end (the
queue's delay, docs/linuxcnc.md) must be within one step of that period's command, and
equal to it wherever the command stands still.
"""
import fcntl
import json
import os
import pwd
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from host.sysfs import find_card
from host.transport import TransportError
from rtl import registers as regmap
from tests.linuxcnc_compare import deviations, pin_positions, queued_position, read_samples

ROOT = Path(__file__).resolve().parent.parent
USER = "dda-cnc"
CLOCK_HZ = 1_000_000
SCALE = 100.0
KEEP_AHEAD = 4
DELAY_PERIODS = KEEP_AHEAD - 1  # the period's command is done at the end of period k + keep_ahead - 1
PERIOD_CLOCKS = CLOCK_HZ // 1000
STEP_CYCLE_CLOCKS = 4  # STEPLEN + STEPSPACE of the sample configuration (2000 + 2000 ns) at CLOCK_HZ
# The kill test's watchdog: the card's queue (keep_ahead - 1 periods of steps left after the
# last ADVANCE, each period's steps at its start) outlasts it by more than a period, wherever
# in its period the driver died (its last WATCHDOG write before or after that ADVANCE).
WATCHDOG_NS = 1_500_000
WATCHDOG_CLOCKS = WATCHDOG_NS * CLOCK_HZ // 1_000_000_000
WATCHDOG_SLACK = 3  # docs/machine.md: the stop comes TIMEOUT clocks after the write reaches WATCHDOG, within 3
FREE_RUN = 20 * PERIOD_CLOCKS  # clocks the card runs on its own once LinuxCNC is gone
KILL_AFTER = 1.5  # s into lcnc_kill.ngc (a 3.4 s rapid)


def _missing():
    if not shutil.which("halcompile") or not shutil.which("linuxcnc"):
        return "LinuxCNC (linuxcnc-uspace, linuxcnc-uspace-dev) is not installed"
    try:
        pwd.getpwnam(USER)
    except KeyError:
        return f"the ordinary user {USER} LinuxCNC runs as does not exist"
    if not os.path.exists("/usr/lib/linuxcnc/modules/dda_card.so"):
        return "dda_card is not installed (halcompile --install linuxcnc/dda_card.c)"
    return None


pytestmark = [pytest.mark.linuxcnc, pytest.mark.skipif(_missing() is not None, reason=str(_missing()))]

LOCK = "/tmp/dda-card-linuxcnc.lock"


@pytest.fixture
def linuxcnc_alone():
    """LinuxCNC runs once per host (fixed lock file and shared memory): one test at a time."""
    with open(LOCK, "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        yield


def _as_user(command, cwd, timeout):
    home = pwd.getpwnam(USER).pw_dir
    return subprocess.run(["runuser", "-u", USER, "--", "env", "-i", f"HOME={home}", "PATH=/usr/bin:/bin",
                           "LANG=C.UTF-8", *command], cwd=cwd, capture_output=True, text=True, timeout=timeout)


def _run_folder():
    run = Path(tempfile.mkdtemp(prefix="dda-lcnc-"))
    run.chmod(0o777)  # LinuxCNC's user writes here
    return run


RECORD_HAL = """loadrt sampler depth=16384 cfg=ffussubbs
addf sampler.0 servo-thread
net x-pos-cmd => sampler.0.pin.0
net y-pos-cmd => sampler.0.pin.1
net card-clock dda-card.0.clock => sampler.0.pin.2
net x-counts dda-card.0.stepgen.00.counts => sampler.0.pin.3
net fifo-level dda-card.0.fifo-level => sampler.0.pin.4
net underruns dda-card.0.underruns => sampler.0.pin.5
net x-enable => sampler.0.pin.6
net drive-enable => sampler.0.pin.7
net drift-trim dda-card.0.drift-trim => sampler.0.pin.8
loadusr ./record.sh {samples}
"""


def _configure(run):
    config = ROOT / "linuxcnc" / "config"
    for name in ("dda_xy.ini", "dda_xy.hal", "dda_xy.var"):
        shutil.copy(config / name, run / name)
    hal = (run / "dda_xy.hal").read_text()
    assert "\nloadrt dda_card\n" in hal
    driver = f"\nloadrt dda_card sim={run}/card.sock keep_ahead={KEEP_AHEAD}\n"
    (run / "dda_xy.hal").write_text(hal.replace("\nloadrt dda_card\n", driver))
    ini = (run / "dda_xy.ini").read_text()
    ini = ini.replace("DISPLAY = axis", f"DISPLAY = {ROOT}/linuxcnc/headless.py")
    ini = ini.replace("HALFILE = dda_xy.hal", "HALFILE = dda_xy.hal\nHALFILE = record.hal")
    (run / "dda_xy.ini").write_text(ini)
    (run / "record.hal").write_text(RECORD_HAL.format(samples=run / "samples.txt"))
    (run / "record.sh").write_text('#!/bin/sh\nexec halsampler -t > "$1"\n')
    (run / "record.sh").chmod(0o755)
    for program in (ROOT / "tests" / "gcode").glob("lcnc_*.ngc"):
        shutil.copy(program, run / program.name)
    for path in run.iterdir():
        path.chmod(0o777 if path.suffix == ".sh" else 0o666)


def test_without_a_card_the_driver_says_what_the_host_software_says(linuxcnc_alone):
    """The real-card path on a machine without the card: rtapi_pci finds none, and the
    driver refuses to load with the words of host/sysfs.py."""
    try:
        find_card()
    except TransportError as error:
        expected = str(error)
    else:
        pytest.skip("a DDA card is in this machine")
    run = _run_folder()
    (run / "card.hal").write_text("loadrt dda_card\n")
    (run / "card.hal").chmod(0o666)
    result = _as_user(["halrun", "-f", str(run / "card.hal")], run, 120)
    assert result.returncode != 0
    assert f"dda_card: {expected}" in result.stdout + result.stderr
    shutil.rmtree(run, ignore_errors=True)


def _server(run, *options):
    server = subprocess.Popen([sys.executable, "-m", "host.cardserver", "--socket", str(run / "card.sock"),
                               "--log", str(run / "card.json"), "--clock-hz", str(CLOCK_HZ), *options],
                              cwd=ROOT, stdout=subprocess.PIPE, stderr=open(run / "server.err", "w"), text=True)
    assert "listening" in server.stdout.readline()
    return server


def _run(run, jobs, *server_options):
    """LinuxCNC on the card server for ``jobs`` (headless.py's arguments); (samples, pins, record)."""
    server = _server(run, *server_options)
    try:
        lcnc = _as_user(["linuxcnc", "-r", str(run / "dda_xy.ini"), *jobs], run, 300)
        assert lcnc.returncode == 0, lcnc.stdout[-3000:] + lcnc.stderr[-3000:]
        server.wait(timeout=60)
    finally:
        server.kill()
    record = json.loads((run / "card.json").read_text())
    return read_samples(run / "samples.txt"), pin_positions(run / "card.json"), record


def _run_and_kill(run, program, seconds):
    """LinuxCNC on ``program``, SIGKILLed (its whole process group: launcher, realtime,
    task, display) ``seconds`` after the program started; the card server runs the card
    on its own for FREE_RUN clocks once the driver's socket closes.  The card's record."""
    server = _server(run, "--free-run", str(FREE_RUN))
    home = pwd.getpwnam(USER).pw_dir
    lcnc = subprocess.Popen(["runuser", "-u", USER, "--", "env", "-i", f"HOME={home}", "PATH=/usr/bin:/bin",
                             "LANG=C.UTF-8", "linuxcnc", "-r", str(run / "dda_xy.ini"), str(program)],
                            cwd=run, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True)
    try:
        output = []
        for line in lcnc.stdout:  # the launcher's and headless.py's output
            output.append(line)
            if "headless:" in line and "running" in line:
                break
        else:
            pytest.fail("the program never ran:\n" + "".join(output[-40:]))
        time.sleep(seconds)
        _kill_linuxcnc(lcnc)
        lcnc.wait(timeout=30)
        assert server.wait(timeout=60) == 0, "the card server did not see the driver go"
    finally:
        server.kill()
        _clean_up_after_kill(lcnc)
    return json.loads((run / "card.json").read_text())


def _linuxcnc_processes():
    """{pid: name} of LinuxCNC's user and rtapi_app (setuid root, it runs as root): this
    test's LinuxCNC (the lock runs one LinuxCNC at a time)."""
    listing = subprocess.run(["ps", "-U", USER, "-C", "rtapi_app", "-o", "pid=,comm="],
                             capture_output=True, text=True).stdout
    return {int(pid): name for pid, name in (line.split(None, 1) for line in listing.splitlines())}


def _kill_linuxcnc(lcnc):
    """SIGKILL the realtime process first (it runs the driver), then the launcher's process
    group and what left it (rtapi_app and the NML server start sessions of their own)."""
    realtime = [pid for pid, name in _linuxcnc_processes().items() if name == "rtapi_app"]
    for pid in realtime:
        _sigkill(os.kill, pid)
    _sigkill(os.killpg, lcnc.pid)
    for pid in _linuxcnc_processes():
        _sigkill(os.kill, pid)


def _sigkill(kill, pid):
    try:
        kill(pid, signal.SIGKILL)
    except ProcessLookupError:  # gone meanwhile
        pass


def _clean_up_after_kill(lcnc):
    """What the killed LinuxCNC left: processes, the launcher's lock, shared memory
    (the realtime's by halrun -U, the NML segments of its user, unattached)."""
    if lcnc.poll() is None:
        _kill_linuxcnc(lcnc)
    _as_user(["halrun", "-U"], "/", 60)
    _as_user(["sh", "-c", "ipcs -m | awk '$3 == \"%s\" && $6 == 0 {print $2}' | xargs -r -n1 ipcrm -m" % USER],
             "/", 60)
    Path("/tmp/linuxcnc.lock").unlink(missing_ok=True)


def test_gcode_path_from_the_pins(linuxcnc_alone):
    run = _run_folder()
    _configure(run)
    started = time.monotonic()
    samples, pins, record = _run(run, [str(run / "lcnc_path.ngc"), f"{run / 'lcnc_stop.ngc'}@1.5"])
    rises = record["rises"]
    assert len(samples) > 1000 and len(pins[0]) > 1000
    deviation = deviations(samples, pins, SCALE, DELAY_PERIODS * PERIOD_CLOCKS)
    worst = max(max(abs(dx), abs(dy)) for dx, dy in deviation)
    assert worst <= 1.0, f"the pins left the commanded path by {worst:.3f} steps"
    standstills = 0
    for k in range(1, len(samples) - DELAY_PERIODS - 1):
        if samples[k][:2] == samples[k - 1][:2] == samples[k + 1][:2]:
            x_cmd, y_cmd = samples[k][:2]
            dx, dy = deviation[k]
            assert abs(dx) <= 0.5 and abs(dy) <= 0.5, f"at rest at period {k} the pins are off by ({dx}, {dy})"
            standstills += 1
    assert standstills > 100
    for axis in (1, 2):
        clocks = [r[0] for r in rises if r[axis]]
        closest = min(b - a for a, b in zip(clocks, clocks[1:]))
        assert closest >= STEP_CYCLE_CLOCKS, f"steps {closest} clocks apart, under steplen + stepspace"
    assert samples[-1][:2] != (0.0, 0.0), "the second program was to be stopped before its end at (0, 0)"
    assert not any(s[7] for s in samples), "the drift loop trimmed a card that does not drift"
    drive = record["drive"]  # on with the machine, off at its end; every step in between
    assert [level for _, level in drive] == [0, 1, 0], drive
    assert drive[1][0] < rises[0][0] and rises[-1][0] < drive[2][0]
    running = [s for s in samples if s[3] > 0]
    levels = [s[3] for s in running[1:]]
    underruns = samples[-1][4]
    assert underruns == 0
    print(f"\nLinuxCNC: {len(samples)} servo periods recorded, {len(pins[0])} steps, largest deviation "
          f"{worst:.3f} steps, FIFO level {min(levels)}..{max(levels)} words, {underruns} underruns, "
          f"{time.monotonic() - started:.0f} s")
    shutil.rmtree(run, ignore_errors=True)


def test_estop_from_linuxcnc_stops_the_card_at_once(linuxcnc_alone):
    """E-stop mid-move: the driver sees enable and drive-enable fall (LinuxCNC's E-stop
    chain, the sample HAL) and soft-resets the card and clears MACHINE_CONTROL.DRIVE_ENABLE:
    the card's DRIVE_ENABLE pin, high while the program ran, is low from within the period
    after the one E-stop reached the HAL, and no step comes after it, though the queue held more."""
    run = _run_folder()
    _configure(run)
    samples, pins, record = _run(run, [f"{run / 'lcnc_stop.ngc'}@1.5:estop"])
    rises = record["rises"]
    on = [k for k, sample in enumerate(samples) if sample[5] and sample[6]]
    assert on and on[-1] < len(samples) - 1, "the machine was never on, or never stopped"
    stop = on[-1] + 1  # the first period with enable or drive-enable low
    moving = [s[0] for s in samples[stop - 20:stop]]
    assert len(set(moving)) > 1, "E-stop came when the machine was not moving"
    assert rises[-1][0] <= samples[stop][2], "steps came after the period E-stop reached the driver"
    drive = record["drive"]
    assert [level for _, level in drive][-2:] == [1, 0], f"DRIVE_ENABLE did not go high, then low: {drive}"
    raised, fell = drive[-2][0], drive[-1][0]
    assert raised < rises[0][0], "steps before DRIVE_ENABLE rose"
    # amp-enable and motion-enabled (drive-enable) fall in the same period, which the driver acts on
    assert samples[stop - 1][2] < fell <= samples[stop][2]
    assert rises[-1][0] <= fell, "a step after DRIVE_ENABLE fell"
    queued = abs(samples[stop - 1][0] * SCALE - pins[1][-1])
    print(f"\nE-stop: DRIVE_ENABLE low {fell - samples[stop - 1][2]} clocks after the start of the period "
          f"E-stop reached the HAL, last step {fell - rises[-1][0]} clocks before; the card stopped "
          f"{queued:.1f} steps short of the command")
    shutil.rmtree(run, ignore_errors=True)


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
    run = _run_folder()
    _configure(run)
    with open(run / "record.hal", "a") as hal:
        hal.write(f"setp dda-card.0.watchdog.timeout-ns {WATCHDOG_NS}\n")
    started = time.monotonic()
    record = _run_and_kill(run, run / "lcnc_kill.ngc", KILL_AFTER)
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
setp dda-card.0.watchdog.timeout-ns 500000
setp dda-card.0.stepgen.00.enable 1
setp dda-card.0.stepgen.01.enable 1
setp dda-card.0.drive-enable 1
start
loadusr -w sleep 0.3
{show}
setp dda-card.0.watchdog.timeout-ns 5000000
setp dda-card.0.watchdog.has-bit 0
loadusr -w sleep 0.2
getp dda-card.0.error
setp dda-card.0.stepgen.00.enable 0
loadusr -w sleep 0.2
setp dda-card.0.stepgen.00.enable 1
loadusr -w sleep 0.3
{show}
"""
SHOWN = ("watchdog.has-bit", "error", "error-code", "stop-reason")


def test_watchdog_has_bit_holds_the_card_until_written_false(linuxcnc_alone):
    """A watchdog shorter than the servo period bites in the first period (lock-step: the
    card runs a whole period after each write): has-bit, error -3, stop-reason 2, the
    card's DRIVE_ENABLE low.  Writing has-bit false alone does not restart (error stays
    until enable falls); after enable falls and rises with a 5 ms watchdog the queue runs,
    the card released (COMMAND.CLEAR_STOP) and DRIVE_ENABLE high again."""
    run = _run_folder()
    show = "\n".join(f"getp dda-card.0.{pin}" for pin in SHOWN)
    (run / "has_bit.hal").write_text(HAS_BIT_HAL.format(socket=run / "card.sock", show=show))
    (run / "has_bit.hal").chmod(0o666)
    server = _server(run)
    try:
        result = _as_user(["halrun", "-f", str(run / "has_bit.hal")], run, 120)
        assert result.returncode == 0, result.stdout[-2000:] + result.stderr[-2000:]
        server.wait(timeout=60)
    finally:
        server.kill()
    values = [line for line in result.stdout.split() if line in ("TRUE", "FALSE") or line.lstrip("-").isdigit()]
    stopped, held, running = dict(zip(SHOWN, values[:4])), values[4], dict(zip(SHOWN, values[5:]))
    assert stopped == {"watchdog.has-bit": "TRUE", "error": "TRUE", "error-code": "-3", "stop-reason": "2"}
    assert "the card stopped the machine: its watchdog" in result.stdout + result.stderr
    assert held == "TRUE", "has-bit written false restarted the card without enable falling"
    assert running == {"watchdog.has-bit": "FALSE", "error": "FALSE", "error-code": "0", "stop-reason": "0"}
    record = json.loads((run / "card.json").read_text())
    levels = [level for _, level in record["drive"]]
    assert levels == [0, 1, 0, 1, 0], f"DRIVE_ENABLE: on, the watchdog's stop, on again, unload: {record['drive']}"
    first_stop = record["drive"][2][0]
    assert first_stop <= PERIOD_CLOCKS + 100, "the 0.5 ms watchdog did not stop the card in its first period"
    shutil.rmtree(run, ignore_errors=True)


@pytest.mark.parametrize("ppm", [2000, -2000])
def test_clock_drift_is_trimmed_from_the_fifo_level(linuxcnc_alone, ppm):
    """The card's clock ``ppm`` fast or slow against the servo periods (card server
    --ppm; 2000 ppm drains or fills the queue by a period in half a second): the
    driver's DWELL trims (drift-trim) keep the card clocks queued within a period and
    a half of where they started, the FIFO level bounded, no underrun, the pins at
    the command at the end."""
    run = _run_folder()
    _configure(run)
    samples, pins, record = _run(run, [str(run / "lcnc_path.ngc")], "--ppm", str(ppm))
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
