#!/usr/bin/python3
"""Headless LinuxCNC front end for the driver's tests ([DISPLAY] DISPLAY = this file).

    linuxcnc -r INI PROGRAM[@SECONDS[:estop]] ...

Resets E-stop, turns the machine on, homes (the INI homes at once), then
runs each G-code PROGRAM to its end, or aborts it after SECONDS (a stop in
mid-program), or presses E-stop after SECONDS (``:estop``, the last job).  Between programs it
waits until motion has stopped.  Exit code 0 when everything ran.
"""
import sys
import time

import linuxcnc

TIMEOUT = 600.0


def wait_for(stat, condition, what, timeout=TIMEOUT):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        stat.poll()
        if condition(stat):
            return
        time.sleep(0.02)
    raise SystemExit(f"headless: timed out waiting for {what}")


def settle(stat):
    """Motion idle: nothing queued and no joint moving, for half a second in a row."""
    quiet_since = None
    while True:
        stat.poll()
        moving = stat.queue > 0 or any(abs(j["velocity"]) > 0 for j in stat.joint[:stat.joints]) or not stat.inpos
        if moving:
            quiet_since = None
        elif quiet_since is None:
            quiet_since = time.monotonic()
        elif time.monotonic() - quiet_since > 0.5:
            return
        time.sleep(0.02)


def main(argv):
    jobs = [a for a in argv[1:] if not a.startswith("-") and not a.endswith(".ini")]
    stat, command = linuxcnc.stat(), linuxcnc.command()
    wait_for(stat, lambda s: s.task_state != 0, "task")
    command.state(linuxcnc.STATE_ESTOP_RESET)
    command.state(linuxcnc.STATE_ON)
    wait_for(stat, lambda s: s.task_state == linuxcnc.STATE_ON, "machine on")
    command.mode(linuxcnc.MODE_MANUAL)
    command.teleop_enable(0)
    command.home(-1)
    wait_for(stat, lambda s: all(s.homed[:s.joints]), "homing")
    for job in jobs:
        program, _, seconds = job.partition("@")
        seconds, _, estop = seconds.partition(":")
        command.mode(linuxcnc.MODE_AUTO)
        wait_for(stat, lambda s: s.task_mode == linuxcnc.MODE_AUTO, "auto mode")
        command.program_open(program)
        command.auto(linuxcnc.AUTO_RUN, 0)
        wait_for(stat, lambda s: s.interp_state != linuxcnc.INTERP_IDLE, f"{program} to start")
        print(f"headless: {program} running", flush=True)
        if seconds:
            time.sleep(float(seconds))
            if estop:
                print(f"headless: E-stop in {program}", flush=True)
                command.state(linuxcnc.STATE_ESTOP)
                command.wait_complete(5)
                time.sleep(1.0)
                print(f"headless: {job} done", flush=True)
                return 0
            command.abort()
        wait_for(stat, lambda s: s.interp_state == linuxcnc.INTERP_IDLE, f"{program} to end")
        stat.poll()
        if stat.task_state != linuxcnc.STATE_ON:
            raise SystemExit(f"headless: the machine went off during {program}")
        settle(stat)
        print(f"headless: {job} done", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
