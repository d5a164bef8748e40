"""Steps per second per axis with every axis moving: ``python -m bench.axes_rate [--steps S] [--axes N ...]``.

On the card of N axes (``rtl/card_core.py`` built with ``--axes N``, on
MyHDL) at the fastest feed (FEED_RATE = RATE_MAX, no ramp: one iteration
every other clock) with the reset pulse timing (one-clock STEP pulses),
one N-axis LINE of S steps on every axis at once: the STEP rises of each axis
are counted over the card's clocks.  Printed per axis: its rises, the clocks
from its first rise to its last, and the rate at PCI's 33 MHz over the steady
part (the rises after the first quarter, as ``bench/card_figures.py`` counts
the two-axis rate), and over the whole move.  The rate the card is built for
is 16.5 M steps/s per axis (one step every other clock, docs/axes.md).
"""
import argparse
import warnings

from myhdl import ToVerilogWarning, block, instance

from models.axes import AXIS_NAMES
from models import registers as regmap
from models.commands import command_words
from models.dda_plan import AxesLineCommand
from models.parameters import AXES, Build
from rtl.card_core import card_core, card_core_ports
from sim.backends.clocking import clock_source
from sim.backends.waves import run_traced
from sim.card.card_bench import HALF_PERIOD, scenario_runner, wait_idle
from sim.card.local_bus_driver import LocalBusDriver

PCI_HZ = 33e6
DESIGN_RATE = PCI_HZ / 2   # one iteration every other clock, a step on every axis at each


@block
def _rise_clocks(clock, pins, axes, rises):
    """Append to ``rises[a]`` the clock count of every clock in which axis a's STEP rises."""

    @instance
    def watch():
        before, count = [False] * axes, 0
        while True:
            yield clock.negedge
            count += 1
            for axis in range(axes):
                level = bool(pins.step(axis))
                if level and not before[axis]:
                    rises[axis].append(count)
                before[axis] = level

    return watch


@block
def _bench(ports, build, scenario, rises):
    clock = ports["clock"]
    return (card_core(**ports, build=build), clock_source(clock, 2 * HALF_PERIOD),
            _rise_clocks(clock, ports["pins"], build.axes, rises),
            scenario_runner(clock, ports["reset"], LocalBusDriver(clock, ports["local"]), scenario))


def axis_rates(axes, steps):
    """Per axis: (rises, clocks from the first to the last rise, steady rate, whole-move rate) of an
    N-axis LINE of ``steps`` steps on every one of ``axes`` axes at the fastest feed."""
    build = Build(fifo_depth=16, axes=axes)
    ports = card_core_ports(axes)
    rises = [[] for _ in range(axes)]
    words = command_words(AxesLineCommand((steps,) * axes))

    def scenario(driver):
        yield from driver.io_write(regmap.offset("FEED_RATE"), regmap.RATE_MAX)
        yield from driver.io_write(regmap.offset("CONTROL"), 1)
        yield from driver.push_all(words)
        yield from wait_idle(driver)

    run_traced(_bench(ports, build, scenario, rises), f"axes_rate_{axes}", trace=False)
    figures = []
    for times in rises:
        if len(times) < 8:
            raise RuntimeError(f"an axis stepped {len(times)} times of {steps}")
        steady = times[len(times) // 4:]
        span = times[-1] - times[0]
        figures.append((len(times), span, PCI_HZ * (len(steady) - 1) / (steady[-1] - steady[0]),
                        PCI_HZ * (len(times) - 1) / span))
    return figures


def main(argv=None):
    warnings.simplefilter("ignore", ToVerilogWarning)
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=400, help="steps of the line on every axis (default: 400)")
    parser.add_argument("--axes", type=int, nargs="+", default=[2, 3, 4], help="card builds (default: 2 3 4)")
    args = parser.parse_args(argv)
    if args.steps < 8:
        parser.error("--steps must be 8 or more")
    for axes in args.axes:
        if not AXES.minimum <= axes <= AXES.maximum:
            parser.error(f"--axes {axes} is not {AXES.minimum}..{AXES.maximum}")
    print(f"N-axis LINE of {args.steps} steps on every axis, FEED_RATE {regmap.RATE_MAX} (fastest), "
          f"one-clock STEP pulses, at {PCI_HZ / 1e6:.0f} MHz; the card is built for "
          f"{DESIGN_RATE / 1e6:.1f} M steps/s per axis")
    for axes in args.axes:
        for axis, (count, span, steady, whole) in enumerate(axis_rates(axes, args.steps)):
            print(f"  {axes} axes, {AXIS_NAMES[axis]}: {count} rises over {span} clocks: "
                  f"{steady / 1e6:.2f} M steps/s steady, {whole / 1e6:.2f} M steps/s first to last rise")


if __name__ == "__main__":
    main()
