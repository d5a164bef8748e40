"""Figures of the whole card: ``python3 -m bench.card_figures [--no-synth] [--no-icarus]``.

Prints, at PCI's 33 MHz:
- the maximum step rate per axis (a long X line, then a diagonal, at one
  iteration every other clock, the most, and the shortest pulse timing);
- commands per second through the FIFO (MARK: the sequencer alone; LINE
  (1, 1): a move each);
- burst throughput into the FIFO over PCI (one memory-write burst, counted
  from FRAME# to the last data phase by the behavioural host);
- simulation speed of the end-to-end bench (host + target + card + monitor)
  on MyHDL, on the generated top in Icarus and on the generated card in
  Verilator, in clocks per second (``bench/sim_speed.py`` has more);
- with ``gen/top.v`` written: LCs, FFs, block RAMs and fmax of the whole top
  on iCE40 HX8K (``fpgaflow``).
"""
import argparse
import sys
import time
import warnings

from myhdl import ToVerilogWarning, now

from models import instructions as isa
from models import registers as regmap
from models.commands import command_words
from models.dda_model import LineCommand
from sim.card.card_bench import HALF_PERIOD, run_core
from sim.card.card_e2e import finish, program, run_card

PCI_HZ = 33e6
CLOCK_PERIOD = 30  # time units per PCI clock in the PCI bench


def _full_speed(driver):
    yield from driver.io_write(regmap.offset("FEED_RATE"), regmap.RATE_MAX)
    yield from driver.io_write(regmap.offset("CONTROL"), 1)


def _wait_idle(driver):
    while True:
        status = yield from driver.io_read(regmap.offset("STATUS"))
        if not regmap.field_value("STATUS", "BUSY", status):
            return


def step_rates(steps=400):
    """Steady-state STEP rises per second on X (straight) and on X+Y (diagonal)."""
    rates = {}
    for name, move in (("X alone", LineCommand(steps, 0)), ("X and Y together", LineCommand(steps, steps))):
        def scenario(driver, move=move):
            yield from _full_speed(driver)
            yield from driver.push_all(command_words(move))
            yield from _wait_idle(driver)

        log, _ = run_core(f"figures_rate_{len(rates)}", scenario, check_pins=False, fifo_depth=64)
        times = [r[0] for r in log.rises if r[1]]
        steady = times[len(times) // 4:]
        clocks_per_step = (steady[-1] - steady[0]) / (len(steady) - 1)
        rates[name] = (clocks_per_step, PCI_HZ / clocks_per_step)
    return rates


def command_rates(count=120):
    """Commands per second with the FIFO pre-filled, from the first to the last effect."""
    figures = {}
    for name, words in (("MARK", isa.encode("MARK", TAG=1)), ("LINE (1, 1)", command_words(LineCommand(1, 1)))):
        marks = []

        def scenario(driver, words=words):
            yield from driver.io_write(regmap.offset("FEED_RATE"), regmap.RATE_MAX)
            yield from driver.push_all(words * count)
            start = now()
            yield from driver.io_write(regmap.offset("CONTROL"), 1)
            yield from _wait_idle(driver)
            marks.append((now() - start) // (2 * HALF_PERIOD))

        run_core(f"figures_commands_{len(figures)}", scenario, check_pins=False, fifo_depth=512)
        clocks = marks[0] / count
        figures[name] = (clocks, PCI_HZ / clocks)
    return figures


def pci_burst(kind, words=192):
    """(MB/s, clocks, transactions) of one PCI memory-write burst into the FIFO."""
    result = {}

    def scenario(bench, target, out):
        yield from program(bench, target, control=0)
        result["burst"] = yield from bench.host.mem_write(target.mem, [0] * words)

    run_card(kind, scenario, f"figures_burst_{kind}", fifo_depth=512)
    transactions = result["burst"].transactions
    clocks = sum(t.end - t.start for t in transactions) / CLOCK_PERIOD
    return 4 * words * PCI_HZ / clocks / 1e6, clocks, len(transactions)


def e2e_speed(kind, steps=1500):
    """Simulated clocks per wall second of the end-to-end bench (host, bus model,
    monitor, card) during a long move: timed from inside the simulation, so
    elaboration and Verilog compilation are left out; card clocks, which on
    Verilator run ahead of the bench's time while it waits."""
    marks = []
    words = command_words(LineCommand(steps, steps // 3))

    def scenario(bench, target, out):
        yield from program(bench, target)
        marks.append((target.log.clock, time.perf_counter()))
        yield from bench.host.mem_write(target.mem, words)
        yield from finish(bench, target, out)
        marks.append((target.log.clock, time.perf_counter()))

    run_card(kind, scenario, f"figures_speed_{kind}")
    (start_clock, start_wall), (end_clock, end_wall) = marks
    return (end_clock - start_clock) / (end_wall - start_wall)


def synthesis():
    """The synthesis figures of the whole top, as ``python -m fpgaflow`` prints them."""
    from fpgaflow import SWEEP_SEEDS, format_figures, synthesize_closing
    from rtl.convert import GEN_DIR

    if not (GEN_DIR / "top.v").exists():
        return "gen/top.v missing: run python -m rtl.top --convert"
    figures = synthesize_closing("top", range(1, 1 + SWEEP_SEEDS))
    return "\n" + format_figures(figures) + f"\n   placement seed {figures['seed']}"


def main(argv=None):
    warnings.simplefilter("ignore", ToVerilogWarning)  # conversion notes, not figures
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-synth", action="store_true", help="skip the synthesis of the top")
    parser.add_argument("--no-icarus", action="store_true", help="skip the Icarus co-simulation figure")
    args = parser.parse_args(argv)
    for name, (clocks, rate) in step_rates().items():
        print(f"step rate, {name}: {clocks:.2f} clocks/step = {rate / 1e6:.2f} M steps/s per axis")
    for name, (clocks, rate) in command_rates().items():
        print(f"commands through the FIFO, {name}: {clocks:.2f} clocks each = {rate / 1e6:.2f} M commands/s")
    mbps, clocks, transactions = pci_burst("myhdl")
    print(f"PCI burst of 192 dwords into the FIFO: {clocks:.0f} clocks in {transactions} "
          f"transaction(s) = {mbps:.1f} MB/s")
    labels = {"myhdl": "MyHDL", "icarus": "Icarus co-simulation", "verilator": "Verilator"}
    for kind in labels:
        if kind == "icarus" and args.no_icarus:
            continue
        print(f"end-to-end bench speed ({labels[kind]}): {e2e_speed(kind):.0f} clocks/s")
    if not args.no_synth:
        print(f"whole top on iCE40 HX8K: {synthesis()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
