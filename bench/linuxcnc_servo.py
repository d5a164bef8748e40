"""The dda_card driver's cost in the servo thread, on the simulated card:
``python3 -m bench.linuxcnc_servo [--periods N] [--strace]``.

Runs the installed component (``halcompile --install linuxcnc/dda_card.c``,
under /tmp/dda-card-component.lock) in a 1 ms ``servo-thread`` of halrun, as
LinuxCNC's ordinary user ``dda-cnc``, on the card server
(``sim.card.card_server``, lock-step, 1 MHz card), both axes moving
(``integ`` ramps into position-cmd).  Prints:

- the card server's requests per period (each a send and a receive on the
  socket: the simulation transport's system calls);
- with ``--strace``: every system call of rtapi_app's threads over the
  run, by name, per period (the servo thread's own sleep included);
- ``servo-thread.time`` over the run (``sampler``, every period): mean and
  max, and ``servo-thread.tmax``, and the driver's functions' own
  ``dda-card.0.read.time`` / ``write.time`` (write waits for the ADVANCE), in the TSC clocks LinuxCNC counts them
  in and in microseconds at the TSC's rate (/proc/cpuinfo's "cpu MHz" with
  constant_tsc).  The time includes the card server's simulation of each
  period (ADVANCE waits for it): an upper bound of the driver's own cost.
"""
import argparse
import collections
import json
import pwd
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
USER = "dda-cnc"
CLOCK_HZ = 1_000_000
VELOCITY = (2000.0, -1000.0)  # steps/s of X and Y (position-scale 1)

HAL = """loadrt threads name1=servo-thread period1=1000000
loadrt dda_card sim={socket}
loadrt integ count=2
loadrt sampler depth=4096 cfg=sss
addf dda-card.0.read servo-thread
addf integ.0 servo-thread
addf integ.1 servo-thread
addf dda-card.0.write servo-thread
addf sampler.0 servo-thread
setp integ.0.in {vx}
setp integ.1.in {vy}
net x-cmd integ.0.out => dda-card.0.stepgen.00.position-cmd
net y-cmd integ.1.out => dda-card.0.stepgen.01.position-cmd
net thread-time servo-thread.time => sampler.0.pin.0
net read-time dda-card.0.read.time => sampler.0.pin.1
net write-time dda-card.0.write.time => sampler.0.pin.2
setp dda-card.0.stepgen.00.enable 1
setp dda-card.0.stepgen.01.enable 1
start
loadusr -w ./sample.sh {periods} {samples}
getp servo-thread.tmax
getp dda-card.0.error
"""


def tsc_mhz():
    match = re.search(r"cpu MHz\s*:\s*([\d.]+)", Path("/proc/cpuinfo").read_text())
    return float(match.group(1)) if match else None


def as_user(command, cwd):
    home = pwd.getpwnam(USER).pw_dir
    return subprocess.Popen(["runuser", "-u", USER, "--", "env", "-i", f"HOME={home}", "PATH=/usr/bin:/bin",
                             "LANG=C.UTF-8", *command], cwd=cwd, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)


def strace_rtapi(out):
    """strace -c on every thread of rtapi_app, once it runs; the strace process or None."""
    for _ in range(200):
        found = subprocess.run(["pgrep", "-x", "rtapi_app"], capture_output=True, text=True).stdout.split()
        if found:
            tasks = [p.name for p in Path(f"/proc/{found[0]}/task").iterdir()]
            arguments = [a for task in tasks for a in ("-p", task)]
            return subprocess.Popen(["strace", "-c", "-o", str(out), *arguments],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(0.05)
    return None


def run(periods, trace):
    folder = Path(tempfile.mkdtemp(prefix="dda-servo-"))
    folder.chmod(0o777)
    socket, log, samples = folder / "card.sock", folder / "card.json", folder / "samples.txt"
    (folder / "servo.hal").write_text(HAL.format(socket=socket, vx=VELOCITY[0], vy=VELOCITY[1],
                                                 periods=periods, samples=samples))
    (folder / "sample.sh").write_text('#!/bin/sh\nexec halsampler -n "$1" > "$2"\n')
    (folder / "sample.sh").chmod(0o755)
    server = subprocess.Popen([sys.executable, "-m", "sim.card.card_server", "--socket", str(socket), "--log",
                               str(log), "--clock-hz", str(CLOCK_HZ)], cwd=ROOT, stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True)
    assert "listening" in server.stdout.readline()
    strace = None
    try:
        halrun = as_user(["halrun", "-f", str(folder / "servo.hal")], folder)
        if trace:
            strace = strace_rtapi(folder / "strace.txt")
        output, _ = halrun.communicate(timeout=600)
        server.wait(timeout=120)
    finally:
        server.kill()
        if strace is not None:
            strace.wait(timeout=60)
    values = [line for line in output.split() if line.lstrip("-").isdigit() or line in ("TRUE", "FALSE")]
    columns = list(zip(*(map(int, line.split()[-3:]) for line in samples.read_text().splitlines())))
    record = json.loads(log.read_text())
    calls = (folder / "strace.txt").read_text() if trace else None
    shutil.rmtree(folder, ignore_errors=True)
    return dict(tmax=int(values[-2]), error=values[-1], times=list(columns[0]), read=list(columns[1]),
                write=list(columns[2]), requests=record.get("requests"),
                advances=len(record["advances"]), strace=calls, output=output)


def print_strace(text, periods):
    print(f"system calls of rtapi_app's threads per period (strace -c, {periods} periods):")
    for line in text.splitlines():
        fields = line.split()
        if len(fields) >= 5 and fields[3].isdigit() and fields[-1] not in ("total", "syscall"):
            print(f"  {fields[-1]:<18} {int(fields[3]) / periods:8.2f}")


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.linuxcnc_servo", description=__doc__.splitlines()[0])
    parser.add_argument("--periods", type=int, default=2000, help="servo periods sampled (default 2000)")
    parser.add_argument("--strace", action="store_true", help="count rtapi_app's system calls (strace -c)")
    args = parser.parse_args(argv)
    if not shutil.which("halrun") or not Path("/usr/lib/linuxcnc/modules/dda_card.so").exists():
        parser.error("LinuxCNC and the installed dda_card component are needed (docs/linuxcnc.md)")
    result = run(args.periods, args.strace)
    times = result["times"][10:]  # the first periods: start-up (enable, the queue filled)
    mhz = tsc_mhz()
    requests = collections.Counter(result["requests"][10:] if result["requests"] else [])
    print(f"periods advanced: {result['advances']}, driver error at the end: {result['error']}")
    if requests:
        shares = ", ".join(f"{n} requests: {count}" for n, count in sorted(requests.items()))
        print(f"socket requests per period: {shares} (mean {statistics.mean(result['requests'][10:]):.2f})")
    scale = f" = {{:.1f}} us at {mhz:.0f} MHz" if mhz else ""
    mean, worst = statistics.mean(times), max(times)
    print(f"servo-thread.time: mean {mean:.0f} clocks" + (scale.format(mean / mhz)) +
          f", max {worst} clocks" + (scale.format(worst / mhz)) + f" ({len(times)} periods)")
    print(f"servo-thread.tmax: {result['tmax']} clocks" + (scale.format(result['tmax'] / mhz)))
    for name in ("read", "write"):
        own = result[name][10:]
        print(f"dda-card.0.{name}.time: mean {statistics.mean(own):.0f} clocks" + scale.format(statistics.mean(own) / mhz)
              + f", max {max(own)} clocks" + scale.format(max(own) / mhz))
    if result["strace"]:
        print_strace(result["strace"], result["advances"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
