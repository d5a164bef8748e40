"""Step timing of the dda_card driver on the pins: ``python3 -m bench.linuxcnc_step_timing``.

The installed component (``halcompile --install linuxcnc/dda_card.c``, under
/tmp/dda-card-component.lock) in halrun as LinuxCNC's user ``dda-cnc``, on the
card server at the PCI clock (33.33 MHz, lock-step).  For each (steplen,
stepspace) pair the X axis makes a move at 20 steps a period; the table gives
the times in card clocks (each rounded up), the card's step cycle
(steplen + stepspace: STEP_WIDTH and STEP_SPACE, docs/linuxcnc.md), the
iteration period the driver planned (65536 / the FEED_RATE it SET), the
cycle of a card without STEP_SPACE (register map before 2.1: STEP low at
least STEP_WIDTH too, steplen + max(steplen, stepspace)), and the
rise-to-rise spacing measured on the STEP pin within a period's steps (the
most common, and the least).
"""
import collections
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from bench.linuxcnc_servo import ROOT, as_user
from models.commands import SetCommand, decode_words

CLOCK_HZ = 33_333_333
PAIRS = ((1000, 1000), (2000, 2000), (5000, 1000), (1000, 5000), (7650, 500), (300, 300))
STEPS_PER_PERIOD = 20
UNTIL = ('#!/bin/sh\nfor i in $(seq 6000); do v=$(halcmd getp "$1"); case "$2" in\n'
         '  not:*) [ "$v" != "${2#not:}" ] && exit 0;; *) [ "$v" = "$2" ] && exit 0;; esac; sleep 0.02\n'
         'done\necho "until: $1 is $(halcmd getp "$1"), not $2" >&2; exit 1\n')


def clocks(ns):
    return max(1, -(-ns * CLOCK_HZ // 1_000_000_000))


def script(socket):
    lines = ["loadrt threads name1=servo-thread period1=1000000", f"loadrt dda_card sim={socket}",
             "addf dda-card.0.read servo-thread", "addf dda-card.0.write servo-thread", "start",
             f"setp dda-card.0.stepgen.00.maxvel {STEPS_PER_PERIOD * 1000}"]
    for k, (steplen, stepspace) in enumerate(PAIRS):
        lines += ["setp dda-card.0.stepgen.00.enable 0", "loadusr -w ./until.sh dda-card.0.fifo-level 0",
                  f"setp dda-card.0.stepgen.00.steplen {steplen}", f"setp dda-card.0.stepgen.00.stepspace {stepspace}",
                  f"setp dda-card.0.stepgen.01.steplen {steplen}", f"setp dda-card.0.stepgen.01.stepspace {stepspace}",
                  "setp dda-card.0.stepgen.00.enable 1", "loadusr -w ./until.sh dda-card.0.fifo-level not:0",
                  f"setp dda-card.0.stepgen.00.position-cmd {(k + 1) * 200}",
                  f"loadusr -w ./until.sh dda-card.0.stepgen.00.counts {(k + 1) * 200}"]
    return "\n".join(lines) + "\n"


def starts(record):
    """[(clock of the start's burst, planned iteration clocks)] from the FEED_RATE SETs."""
    return [(clock, 65536 // command.value) for clock, words in record["fifo"] for command in decode_words(words)
            if isinstance(command, SetCommand) and command.register == "FEED_RATE"]


def main():
    folder = Path(tempfile.mkdtemp(prefix="dda-timing-"))
    folder.chmod(0o777)
    (folder / "until.sh").write_text(UNTIL)
    (folder / "until.sh").chmod(0o755)
    (folder / "timing.hal").write_text(script(folder / "card.sock"))
    server = subprocess.Popen([sys.executable, "-m", "sim.card.card_server", "--socket", str(folder / "card.sock"),
                               "--log", str(folder / "card.json"), "--clock-hz", str(CLOCK_HZ)], cwd=ROOT,
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    assert "listening" in server.stdout.readline()
    try:
        halrun = as_user(["halrun", "-f", str(folder / "timing.hal")], folder)
        output, _ = halrun.communicate(timeout=1800)
        server.wait(timeout=300)
    finally:
        server.kill()
    if halrun.returncode:
        sys.exit(output[-3000:])
    record = json.loads((folder / "card.json").read_text())
    shutil.rmtree(folder, ignore_errors=True)
    begun = starts(record) + [(float("inf"), None)]
    rises = [r[0] for r in record["rises"] if r[1]]
    print(f"card at {CLOCK_HZ} Hz, X moving {STEPS_PER_PERIOD} steps a period (clocks; one is 30 ns)")
    print("| steplen, stepspace (ns) | in clocks | card's step cycle | planned p | cycle without STEP_SPACE | "
          "measured rise to rise (most common, least) |")
    print("|---|---|---|---|---|---|")
    for (steplen, stepspace), (start, planned), (end, _) in zip(PAIRS, begun, begun[1:]):
        own = [r for r in rises if start <= r < end]
        gaps = collections.Counter(b - a for a, b in zip(own, own[1:]) if b - a < 2 * planned)
        cycle = clocks(steplen) + clocks(stepspace)
        before = clocks(steplen) + max(clocks(steplen), clocks(stepspace))
        print(f"| {steplen}, {stepspace} | {clocks(steplen)}, {clocks(stepspace)} | {cycle} | {planned} | {before} | "
              f"{gaps.most_common(1)[0][0]}, {min(gaps)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
