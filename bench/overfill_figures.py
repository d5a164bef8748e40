"""Overfill figures of the card: ``python -m bench.overfill_figures [--kind verilog|myhdl] [--depth N]``.

Runs the overfill bench (``sim/card/card_overfill.py``) on the default build
(FIFO depth 512: ``gen/top.v`` in Icarus, or ``rtl.card`` in MyHDL, which
also records the FIFO's write port) and prints, for

* the queue disabled while the host writes twice the depth in linear bursts
  of 256 dwords (issue 10's bench), then enabled;
* a DWELL of 6,000 clocks at the head of the queue while the host writes
  four times the depth in bursts of 1..256 dwords, then the DWELL's end;

the dwords the bus completed while the queue was stopped and those the card
stored (STATUS.FIFO_LEVEL plus the instruction register's command), the
dwords completed and executed over the whole run (executed: the LINEs the
STEP/DIR pins give back, three words each), how the memory-write
transactions ended, and the register accesses: how many, and the most
clocks from the address phase to TRDY# while the FIFO was full and the
queue stopped, and over the run (a register access is never retried: the
bench fails on one).
"""
import argparse
import sys
import warnings

from myhdl import ToVerilogWarning

from sim.card.card_overfill import Overfill, run_overfill
from sim.card.fifo_scoreboard import DEFAULT_FIFO, LINE_WORDS

CASES = {
    "queue disabled, linear bursts of 256 dwords": dict(stop="disabled", resume="enable", factor=2,
                                                         max_burst=256, fixed_bursts=True, seed=10),
    "DWELL of 6,000 clocks at the head, bursts of 1..256": dict(stop="dwell", resume="dwell_end", factor=4,
                                                                dwell=6000, seed=11),
}


def report(title, case, run, kind):
    stretch = run.stretches[0]
    stored = stretch.level + case.held
    print(f"{title} (FIFO {case.fifo_depth}, {kind}):")
    print(f"  queue stopped: bus completed {stretch.taken} dwords, card stored {stored} "
          f"(FIFO_LEVEL {stretch.level} + {case.held} in the instruction register)")
    taken = "" if run.taken is None else f", FIFO took {len(run.taken)} (same words, same order: " \
                                          f"{run.taken == run.completed})"
    print(f"  whole run: bus completed {len(run.completed)} dwords{taken}; executed {run.executed} "
          f"({len(run.runs)} LINEs on the pins, as queued: {run.runs == run.commands})")
    endings = ", ".join(f"{count} {ending.value}" for ending, count in sorted(
        run.endings.items(), key=lambda item: item[0].value))
    print(f"  memory-write transactions: {endings}; {run.bursts} bursts, {run.offered} dwords offered")
    print(f"  register accesses: {len(run.accesses)}, none retried; clocks to TRDY#: at most "
          f"{run.worst_clocks(stopped=True, full=True)} with the FIFO full and the queue stopped, "
          f"{run.worst_clocks()} over the run ({run.clocks} clocks)")


def main(argv=None):
    warnings.simplefilter("ignore", ToVerilogWarning)  # conversion notes, not figures
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kind", choices=("verilog", "myhdl"), default="verilog",
                        help="generated top in Icarus (default) or the MyHDL card")
    parser.add_argument("--depth", type=int, default=DEFAULT_FIFO,
                        help=f"FIFO depth (default {DEFAULT_FIFO}: gen/; others are converted)")
    args = parser.parse_args(argv)
    if args.depth < 2 * LINE_WORDS:
        parser.error(f"--depth must be at least {2 * LINE_WORDS}")
    for title, settings in CASES.items():
        case = Overfill(fifo_depth=args.depth, **settings)
        report(title, case, run_overfill(args.kind, case), args.kind)
    return 0


if __name__ == "__main__":
    sys.exit(main())
