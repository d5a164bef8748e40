"""Running LinuxCNC with the dda_card driver on the simulated card, for the driver's tests.

The card server (``sim.card.card_server``) runs the Verilator card built to
report 1 MHz in CLOCK_HZ; the driver advances it by one servo period of
card clocks per period (lock-step).  LinuxCNC runs headless
(``linuxcnc/headless.py``) as the ordinary user ``USER``, with the sample
configuration and ``RECORD_HAL``: ``sampler`` records every period (see
``tests.linuxcnc.compare.read_samples``).  One LinuxCNC per host: tests
take ``linuxcnc_alone``.
"""
import contextlib
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

from tests.linuxcnc.compare import axis_pin_positions, pin_positions, read_axis_samples, read_samples

ROOT = Path(__file__).resolve().parents[2]
USER = "dda-cnc"
CLOCK_HZ = 1_000_000
SCALE = 100.0
KEEP_AHEAD = 4
PERIOD_CLOCKS = CLOCK_HZ // 1000


def missing():
    """Why LinuxCNC tests cannot run here, or None."""
    if not shutil.which("halcompile") or not shutil.which("linuxcnc"):
        return "LinuxCNC (linuxcnc-uspace, linuxcnc-uspace-dev) is not installed"
    try:
        pwd.getpwnam(USER)
    except KeyError:
        return f"the ordinary user {USER} LinuxCNC runs as does not exist"
    if not os.path.exists("/usr/lib/linuxcnc/modules/dda_card.so"):
        return "dda_card is not installed (halcompile --install linuxcnc/dda_card.c)"
    return None


LOCK = "/tmp/dda-card-linuxcnc.lock"


@contextlib.contextmanager
def one_linuxcnc():
    """LinuxCNC runs once per host (fixed lock file and shared memory): one test at a time."""
    with open(LOCK, "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        yield


def as_user(command, cwd, timeout):
    home = pwd.getpwnam(USER).pw_dir
    return subprocess.run(["runuser", "-u", USER, "--", "env", "-i", f"HOME={home}", "PATH=/usr/bin:/bin",
                           "LANG=C.UTF-8", *command], cwd=cwd, capture_output=True, text=True, timeout=timeout)


def run_folder():
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


MILL_RECORD_HAL = """loadrt sampler depth=16384 cfg=fffusub
addf sampler.0 servo-thread
net x-pos-cmd => sampler.0.pin.0
net y-pos-cmd => sampler.0.pin.1
net z-pos-cmd => sampler.0.pin.2
net card-clock dda-card.0.clock => sampler.0.pin.3
net fifo-level dda-card.0.fifo-level => sampler.0.pin.4
net underruns dda-card.0.underruns => sampler.0.pin.5
net drive-enable => sampler.0.pin.6
loadusr ./record.sh {samples}
"""
MILL_AXES = 3  # dda_xyz: X, Y, Z
ENCODER_RECORD_HAL = """loadrt sampler depth=16384 cfg=ffffffubbsbb
addf sampler.0 servo-thread
net x-pos-cmd => sampler.0.pin.0
net y-pos-cmd => sampler.0.pin.1
net x-pos-fb => sampler.0.pin.2
net y-pos-fb => sampler.0.pin.3
net x-f-error joint.0.f-error => sampler.0.pin.4
net y-f-error joint.1.f-error => sampler.0.pin.5
net card-clock dda-card.0.clock => sampler.0.pin.6
net card-fault => sampler.0.pin.7
net drive-enable => sampler.0.pin.8
net stop-reason dda-card.0.stop-reason => sampler.0.pin.9
net x-homed joint.0.homed => sampler.0.pin.10
net y-homed joint.1.homed => sampler.0.pin.11
loadusr ./record.sh {samples}
"""
# sample configuration: what the sampler records
CONFIGS = {"dda_xy": RECORD_HAL, "dda_xyz": MILL_RECORD_HAL, "dda_xy_encoders": ENCODER_RECORD_HAL}


def configure(run, config="dda_xy"):
    """The sample configuration ``config`` (linuxcnc/config/CONFIG.ini, .hal, .var) in ``run``,
    on the card server's socket, headless, with the sampler of ``CONFIGS``."""
    folder = ROOT / "linuxcnc" / "config"
    for suffix in (".ini", ".hal", ".var"):
        shutil.copy(folder / f"{config}{suffix}", run / f"{config}{suffix}")
    hal = (run / f"{config}.hal").read_text()
    assert "\nloadrt dda_card\n" in hal
    driver = f"\nloadrt dda_card sim={run}/card.sock keep_ahead={KEEP_AHEAD}\n"
    (run / f"{config}.hal").write_text(hal.replace("\nloadrt dda_card\n", driver))
    ini = (run / f"{config}.ini").read_text()
    # Everything LinuxCNC's user runs or reads is copied here: the checkout may sit in a folder
    # that user cannot enter (a 0700 temporary folder, a 0750 home folder).
    shutil.copy(ROOT / "linuxcnc" / "headless.py", run / "headless.py")
    ini = ini.replace("DISPLAY = axis", f"DISPLAY = {run}/headless.py")
    ini = ini.replace(f"HALFILE = {config}.hal", f"HALFILE = {config}.hal\nHALFILE = record.hal")
    (run / f"{config}.ini").write_text(ini)
    (run / "record.hal").write_text(CONFIGS[config].format(samples=run / "samples.txt"))
    (run / "record.sh").write_text('#!/bin/sh\nexec halsampler -t > "$1"\n')
    (run / "record.sh").chmod(0o755)
    for program in (Path(__file__).parent / "gcode").glob("lcnc_*.ngc"):
        shutil.copy(program, run / program.name)
    for path in run.iterdir():
        path.chmod(0o777 if path.suffix in (".sh", ".py") else 0o666)


def card_server(run, *options, name="card"):
    """A card server on run/NAME.sock, its record in run/NAME.json (one per simulated card)."""
    server = subprocess.Popen([sys.executable, "-m", "sim.card.card_server", "--socket", str(run / f"{name}.sock"),
                               "--log", str(run / f"{name}.json"), "--clock-hz", str(CLOCK_HZ), *options],
                              cwd=ROOT, stdout=subprocess.PIPE, stderr=open(run / f"{name}-server.err", "w"),
                              text=True)
    assert "listening" in server.stdout.readline()
    return server


def run_linuxcnc(run, jobs, *server_options, config="dda_xy"):
    """LinuxCNC (``config``, as ``configure`` left it) on the card server for ``jobs``
    (headless.py's arguments); (samples, pins, record)."""
    server = card_server(run, *server_options)
    try:
        lcnc = as_user(["linuxcnc", "-r", str(run / f"{config}.ini"), *jobs], run, 300)
        assert lcnc.returncode == 0, lcnc.stdout[-3000:] + lcnc.stderr[-3000:]
        server.wait(timeout=60)
    finally:
        server.kill()
    record = json.loads((run / "card.json").read_text())
    if config == "dda_xy":
        return read_samples(run / "samples.txt"), pin_positions(run / "card.json"), record
    return read_axis_samples(run / "samples.txt", MILL_AXES), axis_pin_positions(run / "card.json"), record


def run_and_kill(run, program, seconds, free_run):
    """LinuxCNC on ``program``, SIGKILLed (its whole process group: launcher, realtime,
    task, display) ``seconds`` after the program started; the card server runs the card
    on its own for FREE_RUN clocks once the driver's socket closes.  The card's record."""
    server = card_server(run, "--free-run", str(free_run))
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
        kill_linuxcnc(lcnc)
        lcnc.wait(timeout=30)
        assert server.wait(timeout=60) == 0, "the card server did not see the driver go"
    finally:
        server.kill()
        clean_up_after_kill(lcnc)
    return json.loads((run / "card.json").read_text())


def linuxcnc_processes():
    """{pid: name} of LinuxCNC's user and rtapi_app (setuid root, it runs as root): this
    test's LinuxCNC (the lock runs one LinuxCNC at a time)."""
    listing = subprocess.run(["ps", "-U", USER, "-C", "rtapi_app", "-o", "pid=,comm="],
                             capture_output=True, text=True).stdout
    return {int(pid): name for pid, name in (line.split(None, 1) for line in listing.splitlines())}


def kill_linuxcnc(lcnc):
    """SIGKILL the realtime process first (it runs the driver), then the launcher's process
    group and what left it (rtapi_app and the NML server start sessions of their own)."""
    realtime = [pid for pid, name in linuxcnc_processes().items() if name == "rtapi_app"]
    for pid in realtime:
        sigkill(os.kill, pid)
    sigkill(os.killpg, lcnc.pid)
    for pid in linuxcnc_processes():
        sigkill(os.kill, pid)


def sigkill(kill, pid):
    try:
        kill(pid, signal.SIGKILL)
    except ProcessLookupError:  # gone meanwhile
        pass


def clean_up_after_kill(lcnc):
    """What the killed LinuxCNC left: processes, the launcher's lock, shared memory
    (the realtime's by halrun -U, the NML segments of its user, unattached)."""
    if lcnc.poll() is None:
        kill_linuxcnc(lcnc)
    as_user(["halrun", "-U"], "/", 60)
    as_user(["sh", "-c", "ipcs -m | awk '$3 == \"%s\" && $6 == 0 {print $2}' | xargs -r -n1 ipcrm -m" % USER],
             "/", 60)
    Path("/tmp/linuxcnc.lock").unlink(missing_ok=True)
