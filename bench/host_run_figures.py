"""Figures of jobs run on the simulated card: ``python -m bench.host_run_figures``.

* the examples (``examples/part.ngc``, ``examples/drawing.svg``) through
  ``python -m host run --sim verilator`` at a feed override of 100,000 %
  and 40 steps/mm (so that a job is millions of clocks, not billions): what
  it prints (segments, words, steps on the pins, deviation, job time,
  simulated clocks, wall time);
* a short streamed job (``bench.host_jobs.streaming_job``, 40 segments) on
  MyHDL, Icarus and Verilator: clocks, wall time, pins against the model;
* the long streamed job (``--segments``, default 100,000) on Verilator:
  segments, words, bursts, interrupts, clocks, wall and CPU time, and the
  starvation measure on the pins (``host.pin_measure``): junctions measured, gaps.
"""
import argparse
import subprocess
import sys
import time

from bench.host_jobs import streaming_job
from host.card import Card
from host.check import check
from host.pin_measure import junction_gaps, period_violations, pin_moves
from host.planner import plan
from host.stream import stream
from host.transports.simulated import SimTransport
from rtl.convert import ROOT

FAST = ("--feed-override", "100000", "--steps-per-mm", "40", "--acceleration", "2000000", "--start-feed", "60000")
PULSES = dict(step_width_ns=30, dir_setup_ns=30, dir_hold_ns=30)


def examples():
    for name in ("part.ngc", "drawing.svg"):
        started = time.monotonic()
        result = subprocess.run([sys.executable, "-m", "host", "run", str(ROOT / "examples" / name), "--sim",
                                 "verilator", *FAST], cwd=ROOT, capture_output=True, text=True)
        print(f"== {name} on verilator ({time.monotonic() - started:.1f} s with the model load)")
        for line in (result.stdout + result.stderr).splitlines():
            print("  " + line)


def streamed(kind, segments, seed=1, monitor=True):
    wall, cpu = time.monotonic(), time.process_time()
    with SimTransport(kind, monitor=monitor) as transport:
        card = Card(transport)
        drawing, machine = streaming_job(segments, card.identity.clock_hz, card.identity.coord_width, seed=seed)
        card.configure(steps_per_mm=machine.steps_per_mm, **PULSES)
        planned = plan(drawing, machine)
        model = check(planned)
        first, clocks = len(transport.pins.rises), transport.clocks
        started, started_cpu = time.monotonic(), time.process_time()
        result = stream(card, planned)
        stream_wall, stream_cpu = time.monotonic() - started, time.process_time() - started_cpu
        rises = transport.pins.rises[first:]
        clocks = transport.clocks - clocks
    same = [p for _, pts in pin_moves(planned, model, rises) for p in pts[1:]] == \
        [p for _, pts in model.points for p in pts[1:]]
    measured, over = junction_gaps(planned, model, rises)
    late = period_violations(rises, planned.runs[0].feed_rate)
    print(f"== {segments} segments on {kind}{'' if monitor else ' (no protocol checker)'}: "
          f"{result.words} words in {result.bursts} bursts, {result.interrupts} interrupts; "
          f"FEED_RATE {planned.runs[0].feed_rate}, one run")
    print(f"  pins: {len(rises)} STEP rises, path {'identical to' if same else 'DIFFERENT from'} the model's; "
          f"end {result.position} (plan {planned.end})")
    print(f"  gaps seen: {len(over)} of {measured} junctions slower than the move before; "
          f"{len(late)} step intervals over one iteration + DIR set-up")
    print(f"  {clocks} clocks ({clocks / 33.333333e3:.3f} ms of card time at 33.3 MHz); streaming "
          f"{stream_wall:.1f} s wall, {stream_cpu:.1f} s CPU; all {time.monotonic() - wall:.1f} s wall, "
          f"{time.process_time() - cpu:.1f} s CPU")


def main(argv=None):
    options = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    options.add_argument("--segments", type=int, default=100_000, help="the long job (default 100000)")
    options.add_argument("--short", type=int, default=40, help="the short job on every back end (default 40)")
    args = options.parse_args(argv)
    examples()
    for kind in ("myhdl", "icarus", "verilator"):
        streamed(kind, args.short)
    streamed("verilator", args.segments, seed=7)


if __name__ == "__main__":
    main()
