"""Simulation speed of the DDA interpolator: ``python -m bench.dda_speed [--radius R]``.

Runs one precise quarter arc (R, 0) -> (0, R) with ``advance`` always high
and prints clocks per second of wall time for

* the MyHDL block in MyHDL's simulator,
* ``gen/dda_arc.v`` in Icarus through MyHDL co-simulation,

each once with a bare driver (start, advance, wait for done) and once inside
the test bench that also runs the golden model and compares every clock.
Elaboration (and the Icarus compile) is not counted.  clocks/s is per second
of wall time, which the machine's other load lowers (the load average is
printed); the last column divides by the CPU time of the Python process
alone (for co-simulation that leaves out Icarus' own process).
"""
import argparse
import os
import sys
import time

from myhdl import StopSimulation, block, instance

from models.dda_model import ArcCommand
from rtl.convert import GEN_DIR
from rtl.dda_arc import dda_arc, dda_arc_ports
from sim.backends.clocking import clock_source
from sim.backends.icarus import cosimulate
from sim.card.dda_bench import Record, dda_bench


@block
def bare_driver(ports, command, counter, verilog):
    """Start ``command``, keep ``advance`` high, stop at ``done``; count clocks."""
    clock, reset, cmd = ports["clock"], ports["reset"], ports["cmd"]
    device = dda_arc(**ports) if verilog is None else cosimulate("dda_arc", ports, verilog)

    clock_driver = clock_source(clock, 2 * 5)

    @instance
    def stimulus():
        reset.next = reset.active
        yield clock.negedge
        reset.next = not reset.active
        cmd.xs.next, cmd.ys.next, cmd.xe.next, cmd.ye.next = (command.xs, command.ys,
                                                                command.xe, command.ye)
        cmd.start.next = True
        cmd.advance.next = True
        yield clock.negedge
        cmd.start.next = False
        while not cmd.done:
            yield clock.negedge
            counter.append(1)
        raise StopSimulation()

    return device, clock_driver, stimulus


def measure(command, verilog, checked):
    ports = dda_arc_ports()
    if checked:
        record = Record()
        bench = dda_bench(ports, [command], record, verilog=verilog, advance_rate=1.0, idle_gap=0)
    else:
        counter = []
        bench = bare_driver(ports, command, counter, verilog)
    started, cpu_started = time.perf_counter(), time.process_time()
    try:
        bench.run_sim(quiet=1)
    finally:
        if bench.sim is not None and not bench.sim._finished:
            bench.quit_sim()
    elapsed, cpu = time.perf_counter() - started, time.process_time() - cpu_started
    clocks = record.clocks if checked else len(counter)
    return clocks, elapsed, cpu


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.dda_speed", description=__doc__.split("\n")[0])
    parser.add_argument("--radius", type=int, default=2000, help="arc radius in steps (default 2000)")
    args = parser.parse_args(argv)
    if not 1 <= args.radius < 1 << 23:
        parser.error("radius must be 1 .. 2**23 - 1")
    command = ArcCommand(args.radius, 0, 0, args.radius)
    print(f"precise quarter arc, R = {args.radius}, advance always high; "
          f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    print(f"{'simulator':<34} {'clocks':>8} {'seconds':>8} {'clocks/s':>10} {'per Python CPU s':>17}")
    for label, verilog in (("MyHDL", None), ("Icarus co-simulation", [GEN_DIR / "dda_arc.v"])):
        for checked in (False, True):
            clocks, elapsed, cpu = measure(command, verilog, checked)
            name = f"{label}{' + model check' if checked else ''}"
            print(f"{name:<34} {clocks:>8} {elapsed:8.2f} {clocks / elapsed:10.0f} {clocks / cpu:17.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
