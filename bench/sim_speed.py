"""Simulation speed of the whole card on its three back ends: ``python3 -m bench.sim_speed``.

Three jobs, each on MyHDL, Icarus (``top.v`` with its pads) and Verilator
(``card.v``), driven end to end by the behavioural PCI host with the
protocol monitor on every bus clock (``sim/card/card_e2e.py``):

* a long arc: one precise quarter arc, no bus traffic while it runs;
* a burst of 1,000 LINE commands: 3,000 words written back to back into
  the 512-word FIFO in bursts of up to 1,024 words (the 4 KiB window), which
  the host resumes after every retry and disconnect while the moves drain
  it;
* a random job of 10,000 segments (``sim/card/card_jobs.py``): LINE and ARC
  moves with SET, DWELL and MARK, streamed as host software does (burst
  what fits, sleep until LOW_WATER, read every MARK back).

Clocks/s counts the card's clocks from the first command word to the end of
the job over the wall time between the same two points (elaboration and
compilation left out); "per CPU s" over the CPU time of this process (for
Icarus that leaves its own process out), which the machine's other load
does not lower.  Then the Verilator goals: the bus-heavy jobs again
without the protocol monitor, a long arc at a slow feed (millions of
clocks), the bus path alone (one foreign call per clock, no host), and the
time to build the model.
"""
import argparse
import os
import resource
import sys
import tempfile
import time
import warnings
from pathlib import Path

from myhdl import ToVerilogWarning

from models import registers as regmap
from models.commands import command_words
from models.dda_model import ArcCommand, LineCommand
from rtl.convert import GEN_DIR
from sim.backends.verilator.build import _build, find_tool
from sim.backends.verilator.verilated_card import VerilatedCard
from sim.card.card_e2e import DEFAULT_FIFO, finish, program, run_card
from sim.card.card_jobs import LONGEST_WAIT, random_job, streaming_scenario

BACKENDS = ("myhdl", "icarus", "verilator")
LABELS = {"myhdl": "MyHDL", "icarus": "Icarus", "verilator": "Verilator"}


def timed(kind, job, monitor=True):
    """Run ``job(bench, target, out)`` after enumeration; (card clocks, wall
    seconds, CPU seconds of this process) of the job."""
    marks = []

    def scenario(bench, target, out):
        marks.append((target.log.clock, time.perf_counter(), time.process_time()))
        yield from job(bench, target, out)
        marks.append((target.log.clock, time.perf_counter(), time.process_time()))

    run_card(kind, scenario, f"speed_{kind}", DEFAULT_FIFO, trace=False,
             **({} if monitor else {"monitor": False}))
    (clock0, wall0, cpu0), (clock1, wall1, cpu1) = marks
    return clock1 - clock0, wall1 - wall0, cpu1 - cpu0


def arc_job(radius, feed):
    arc = ArcCommand(radius, 0, 0, radius, ccw=True)

    def job(bench, target, out):
        yield from program(bench, target, feed)
        yield from bench.host.mem_write(target.mem, command_words(arc))
        yield from finish(bench, target, out, limit=LONGEST_WAIT)

    return job


WINDOW_WORDS = 1024  # the memory BAR: 4 KiB


def line_burst_job(count):
    words = [w for i in range(count) for w in command_words(LineCommand(1 + i % 3, i % 2))]

    def job(bench, target, out):
        yield from program(bench, target)
        for start in range(0, len(words), WINDOW_WORDS):
            burst = yield from bench.host.mem_write(target.mem, words[start:start + WINDOW_WORDS])
            assert burst.complete, burst.termination
        yield from finish(bench, target, out, limit=LONGEST_WAIT)

    return job


def random_segments_job(segments):
    plan, results = random_job(1, segments), {}
    streamed = streaming_scenario(plan, DEFAULT_FIFO, results)

    def job(bench, target, out):
        yield from program(bench, target)
        yield from streamed(bench, target, out)
        assert results["position"] == plan.position

    return job


def bus_path_speed(clocks=200000):
    """Clocks/s of ``step_bus`` alone: a Python loop, one foreign call per clock, the host idle."""
    card = VerilatedCard()
    model = card.model
    bus = model.bus()
    model["reset"] = 1
    start, cpu = time.perf_counter(), time.process_time()
    for _ in range(clocks):
        model.step_bus(bus)
    seconds, cpu = time.perf_counter() - start, time.process_time() - cpu
    model.close()
    return clocks / seconds, clocks / cpu


def build_seconds():
    """(wall seconds, CPU seconds of the tools, tool) of a build of gen/card.v's
    model from nothing (outside the cache)."""
    tool = find_tool()
    with tempfile.TemporaryDirectory() as work:
        start, children = time.perf_counter(), resource.getrusage(resource.RUSAGE_CHILDREN)
        _build(Path(work), [GEN_DIR / "card.v"], "card", None, (), tool)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = after.ru_utime + after.ru_stime - children.ru_utime - children.ru_stime
        return time.perf_counter() - start, cpu, tool.version


def report(job, back_end, clocks, seconds, cpu):
    print(f"{job:<40} {back_end:<31} {clocks:>9} clocks {seconds:8.2f} s {clocks / seconds:>10,.0f} clocks/s "
          f"{clocks / max(cpu, 1e-6):>10,.0f} per CPU s", flush=True)


def main(argv=None):
    warnings.simplefilter("ignore", ToVerilogWarning)
    parser = argparse.ArgumentParser(prog="python3 -m bench.sim_speed", description=__doc__.splitlines()[0])
    parser.add_argument("--backends", default=",".join(BACKENDS),
                        help=f"comma-separated, of {', '.join(BACKENDS)} (default: all)")
    parser.add_argument("--radius", type=int, default=20000, help="radius of the long arc (default 20000)")
    parser.add_argument("--lines", type=int, default=1000, help="LINE commands in the burst (default 1000)")
    parser.add_argument("--segments", type=int, default=10000, help="segments of the random job (default 10000)")
    args = parser.parse_args(argv)
    backends = args.backends.split(",")
    unknown = set(backends) - set(BACKENDS)
    if unknown:
        parser.error(f"unknown back ends {sorted(unknown)}: use {', '.join(BACKENDS)}")
    if not 1 <= args.radius < 1 << 22 or args.lines < 1 or args.segments < 1:
        parser.error("radius must be 1 .. 2**22 - 1, lines and segments at least 1")
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    jobs = {f"long arc (R = {args.radius}, full speed)": arc_job(args.radius, regmap.RATE_MAX),
            f"burst of {args.lines} LINE commands": line_burst_job(args.lines),
            f"random job of {args.segments} segments": random_segments_job(args.segments)}
    for name, job in jobs.items():
        for kind in backends:
            report(name, LABELS[kind], *timed(kind, job))
    if "verilator" in backends:
        for name, job in list(jobs.items())[1:]:
            report(name, "Verilator, no protocol monitor", *timed("verilator", job, monitor=False))
        slow_arc = arc_job(100000, regmap.RATE_ONE // 16)
        clocks, seconds, cpu = timed("verilator", slow_arc)
        print(f"Verilator, long arc with no bus traffic (R = 100000, 16 clocks/iteration): {clocks} clocks in "
              f"{seconds:.2f} s = {clocks / seconds:,.0f} clocks/s, {clocks / cpu:,.0f} per CPU s (goal 1,000,000)")
        wall, cpu = bus_path_speed()
        print(f"Verilator, bus path alone (step_bus from a Python loop): {wall:,.0f} clocks/s, {cpu:,.0f} per CPU s")
        seconds, cpu, version = build_seconds()
        print(f"Verilator model build of gen/card.v: {seconds:.1f} s, {cpu:.1f} CPU s ({version}), "
              "then cached in build/vlt")
    return 0


if __name__ == "__main__":
    sys.exit(main())
