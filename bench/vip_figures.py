"""Verification IP figures: ``python -m bench.vip_figures [--core] [--delayed] [--xz] [--cocotb]``
(no option: all).

``--core``: the cost of one ``HostCore.step`` while bursts run, the host
engine alone: 256-dword memory reads and writes against lines that show a
target claiming at once and completing every data phase, so that every
edge does a data phase's work.

``--delayed``: the host against the delayed-transaction target model on the
pure-Python bus loop, protocol checker on: for each retry setting (retries
per delayed read) and prefetch off/on, bursts of 1, 16, 64 and 256 dwords
written and read back with random IRDY# waits: bursts moved, retries the
host saw, data errors, clocks, wall time.

``--xz``: clocks the X/Z detector watched and reported on the generated
Verilog in float mode: ``gen/pci_slave.v`` under 300 random transactions,
``gen/top.v`` enumerated, programmed and running an arc (the benches of
``sim/card/pci_slave_traffic.py`` and ``sim/card/card_e2e.py``), and the example
target of ``docs/verification.md``.

``--cocotb``: the cocotb test of ``gen/card.v`` (``sim/card/cocotb_card.py``):
its result and wall time.
"""
import argparse
import random
import sys
import time

from rtl.convert import ROOT
from sim.pci.delayed_target import DelayedTarget
from sim.pci.host_core import HostCore
from sim.pci.host_types import MEM_READ, MEM_WRITE, Request
from sim.pci.loop import PythonBus
from sim.pci.master import PciMaster, random_waits

BURST = 256
LENGTHS = (1, 16, 64, 256)
RETRY_SETTINGS = (0, 1, 2, 10, 100)
BASE = 0x80000000


def core_speed(bursts=400):
    """(edges, CPU seconds) of ``bursts`` alternating 256-dword writes and reads
    (CPU time: the figure should not depend on what else the machine runs)."""
    core = HostCore()
    drive = core.drive
    edges = 0
    start = time.process_time()
    for number in range(bursts):
        command = MEM_WRITE if number % 2 else MEM_READ
        request = core.submit(Request(command, 0x1000, [(0xF, number)] * BURST))
        while not request.done:
            edges += 1
            frame = drive.frame_out if drive.frame_oe else 1
            irdy = drive.irdy_out if drive.irdy_oe else 1
            core.step(30 * edges, 0x5A5A5A5A, 0, frame, irdy, 0, 0, 1)
    return edges, time.process_time() - start


def print_core():
    edges, seconds = core_speed()
    print(f"HostCore.step during {BURST}-dword bursts: {edges / seconds:,.0f} edges per CPU second, "
          f"{1e6 * seconds / edges:.2f} us per edge ({edges:,} edges)")


def delayed_run(retries, prefetch, seed=1):
    """Bursts moved, retries seen, data errors, clocks, wall and CPU seconds for one setting."""
    rng = random.Random(seed)
    target = DelayedTarget(base=BASE, size=0x1000, read_retries=retries, prefetch=prefetch,
                           latency=(0, 6), seed=seed)
    bus = PythonBus(PciMaster(irdy_waits=random_waits(seed, 3, 0.3), max_retries=1 << 30),
                    {"target": target})
    bus.reset()
    moved = seen = errors = 0
    start, cpu = time.perf_counter(), time.process_time()
    for length in LENGTHS:
        address = BASE + 4 * rng.randrange(1024 - length + 1)
        values = [rng.getrandbits(32) for _ in range(length)]
        write = bus.run(bus.host.mem_write(address, values))
        read = bus.run(bus.host.mem_read(address, length))
        moved += write.complete + read.complete
        seen += write.retries + read.retries
        errors += sum(a != b for a, b in zip(read.data, values)) + abs(len(read.data) - length)
    return moved, seen, errors, bus.edges, time.perf_counter() - start, time.process_time() - cpu


def print_delayed():
    print("Delayed-transaction target, pure-Python loop, checker on (bursts of "
          f"{', '.join(map(str, LENGTHS))} dwords, written and read back):")
    print(f"  {'retries/read':>12}{'prefetch':>9}{'bursts':>8}{'retries seen':>14}{'data errors':>13}"
          f"{'clocks':>10}{'wall s':>8}{'CPU s':>7}{'clocks/CPU s':>14}")
    for retries in RETRY_SETTINGS:
        for prefetch in (0, 8):
            moved, seen, errors, clocks, wall, cpu = delayed_run(retries, prefetch)
            print(f"  {retries:>12}{prefetch:>9}{moved:>8}{seen:>14,}{errors:>13}{clocks:>10,}"
                  f"{wall:>8.1f}{cpu:>7.2f}{clocks / cpu:>14,.0f}")


def print_xz():
    from models.dda_model import ArcCommand
    from sim.card.card_e2e import DEFAULT_FIFO, motion_scenario, run_card
    from sim.card.pci_slave_traffic import run_random
    from sim.pci.bench import PciBench
    from sim.pci.example_target import scenario, scratch_target

    quarter_arc = ArcCommand(40, 0, 0, 40, ccw=True)
    print("X/Z detector in float mode (clocks with a line X or Z while driven / clocks watched):")
    bench, _ = run_random("verilog", 300, seed=7)
    print(f"  gen/pci_slave.v, 300 random transactions: {bench.checker.unknown_clocks} / {bench.checker.edges:,}")
    _, _, _, bench = run_card("icarus", motion_scenario([quarter_arc]), "figures_xz_top", DEFAULT_FIFO)
    print(f"  gen/top.v, enumerate, program, arc:        {bench.checker.unknown_clocks} / {bench.checker.edges:,}")
    bench = PciBench(target=scratch_target())
    bench.run(scenario({}), "figures_xz_scratch", trace=False)
    print(f"  docs/example/scratch_target.v:             {bench.checker.unknown_clocks} / {bench.checker.edges:,}")


def print_cocotb():
    from cocotb_tools.runner import get_results, get_runner

    from rtl.convert import GEN_DIR, build_dir

    runner = get_runner("icarus")
    build = build_dir("cocotb", "figures")
    start = time.perf_counter()
    runner.build(sources=[GEN_DIR / "card.v"], hdl_toplevel="card", build_dir=build, timescale=("1ns", "1ps"),
                 always=True)
    built = time.perf_counter()
    results = runner.test(test_module="sim.card.cocotb_card", hdl_toplevel="card", build_dir=build,
                          test_dir=build, extra_env={"PYTHONPATH": str(ROOT)})
    tests, failures = get_results(results)
    done = time.perf_counter()
    print(f"cocotb test of gen/card.v: {tests - failures} of {tests} passed; build {built - start:.1f} s, "
          f"run {done - built:.1f} s")


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.vip_figures",
                                     description=__doc__.split("\n\n")[0])
    sections = {"core": print_core, "delayed": print_delayed, "xz": print_xz, "cocotb": print_cocotb}
    for name in sections:
        parser.add_argument(f"--{name}", action="store_true")
    args = parser.parse_args(argv)
    chosen = [name for name in sections if getattr(args, name)] or list(sections)
    for name in chosen:
        sections[name]()
    return 0


if __name__ == "__main__":
    sys.exit(main())
