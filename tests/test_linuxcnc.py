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
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from host.sysfs import find_card
from host.transport import TransportError
from tests.linuxcnc_compare import deviations, pin_positions, read_samples

ROOT = Path(__file__).resolve().parent.parent
USER = "dda-cnc"
CLOCK_HZ = 1_000_000
SCALE = 100.0
KEEP_AHEAD = 4
DELAY_PERIODS = KEEP_AHEAD - 1  # the period's command is done at the end of period k + keep_ahead - 1
PERIOD_CLOCKS = CLOCK_HZ // 1000
STEP_CYCLE_CLOCKS = 4  # STEPLEN + STEPSPACE of the sample configuration (2000 + 2000 ns) at CLOCK_HZ


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


RECORD_HAL = """loadrt sampler depth=16384 cfg=ffussub
addf sampler.0 servo-thread
net x-pos-cmd => sampler.0.pin.0
net y-pos-cmd => sampler.0.pin.1
net card-clock dda-card.0.clock => sampler.0.pin.2
net x-counts dda-card.0.stepgen.00.counts => sampler.0.pin.3
net fifo-level dda-card.0.fifo-level => sampler.0.pin.4
net underruns dda-card.0.underruns => sampler.0.pin.5
net x-enable => sampler.0.pin.6
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


def _run(run, jobs):
    """LinuxCNC on the card server for ``jobs`` (headless.py's arguments); (samples, pins, rises)."""
    server = subprocess.Popen([sys.executable, "-m", "host.cardserver", "--socket", str(run / "card.sock"),
                               "--log", str(run / "card.json"), "--clock-hz", str(CLOCK_HZ)],
                              cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        assert "listening" in server.stdout.readline()
        lcnc = _as_user(["linuxcnc", "-r", str(run / "dda_xy.ini"), *jobs], run, 300)
        assert lcnc.returncode == 0, lcnc.stdout[-3000:] + lcnc.stderr[-3000:]
        server.wait(timeout=60)
    finally:
        server.kill()
    rises = json.loads((run / "card.json").read_text())["rises"]
    return read_samples(run / "samples.txt"), pin_positions(run / "card.json"), rises


def test_gcode_path_from_the_pins(linuxcnc_alone):
    run = _run_folder()
    _configure(run)
    started = time.monotonic()
    samples, pins, rises = _run(run, [str(run / "lcnc_path.ngc"), f"{run / 'lcnc_stop.ngc'}@1.5"])
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
    running = [s for s in samples if s[3] > 0]
    levels = [s[3] for s in running[1:]]
    underruns = samples[-1][4]
    assert underruns == 0
    print(f"\nLinuxCNC: {len(samples)} servo periods recorded, {len(pins[0])} steps, largest deviation "
          f"{worst:.3f} steps, FIFO level {min(levels)}..{max(levels)} words, {underruns} underruns, "
          f"{time.monotonic() - started:.0f} s")
    shutil.rmtree(run, ignore_errors=True)


def test_estop_from_linuxcnc_stops_the_card_at_once(linuxcnc_alone):
    """E-stop mid-move: the driver sees enable fall in that period and soft-resets the
    card, so no step comes after it, though the queue held more."""
    run = _run_folder()
    _configure(run)
    samples, pins, rises = _run(run, [f"{run / 'lcnc_stop.ngc'}@1.5:estop"])
    enabled = [k for k, sample in enumerate(samples) if sample[5]]
    assert enabled and enabled[-1] < len(samples) - 1, "the machine was never on, or never stopped"
    stop = enabled[-1] + 1  # the first period with enable low
    moving = [s[0] for s in samples[stop - 20:stop]]
    assert len(set(moving)) > 1, "E-stop came when the machine was not moving"
    assert rises[-1][0] <= samples[stop][2], "steps came after the period E-stop reached the driver"
    queued = abs(samples[stop - 1][0] * SCALE - pins[1][-1])
    print(f"\nE-stop: the card stopped in the period it was pressed, {queued:.1f} steps short of the command")
    shutil.rmtree(run, ignore_errors=True)
