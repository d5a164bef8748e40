"""Figures of the machine side's rules (issue 28): ``python -m bench.machine_figures [--cosim]``.

Runs the card core (MyHDL, or its Verilog in Icarus with ``--cosim``) and prints:

1. homing: the clocks between consecutive STEP rises of the release and the
   back-off, the gap from the last release step to the first back-off step
   apart (HOME_RELEASE_PERIOD 800 and 5,000 with the filter at 3 samples,
   800 with a 100-clock filter: INPUT_FILTER 10 x INPUT_TICK 10);
2. WATCHDOG written 0x1000000 and 0x1001388: what it reads back 10 clocks
   later and INT_STATUS.CLAMPED;
3. the FIFO level after a CLEAR_STOP written with the E-stop input active
   (six words queued);
4. per stop cause, a line running (STEP_WIDTH 3, a step every 6 clocks),
   the cause at six phases: the clocks from the last STEP rise and from that
   STEP's fall to DRIVE_ENABLE low (the fewest), and the STEP pulses not
   inside DRIVE_ENABLE;
5. the E-stop's reaction, pin to DRIVE_ENABLE low, pressed at 16 phases, for
   INPUT_FILTER 3 and INPUT_TICK 1 and 8, beside the formula's range
   (``models.machine_model.reaction_clocks`` where the checkout has it).

Written against the benches' oldest helpers, so the same script measures an
older checkout (run from its folder) as well.
"""
import argparse

from models import registers as regmap
from models.commands import command_words
from models.dda_model import LineCommand
from models.homing_model import BouncingSwitch
from sim.card.machine_bench import drive_at, read, run_machine, set_input, wait_clocks, write

PULSE_WIDTH = 3


def _pulses(pin_log):
    pulses = []
    for bit in (1, 4):
        rose, before = None, 0
        for clock, state in pin_log.edges:
            if state & bit and not before & bit:
                rose = clock
            elif before & bit and not state & bit:
                pulses.append((rose, clock))
            before = state
    return sorted(pulses)


def homing_gaps(period, samples, tick, cosim):
    switch = BouncingSwitch(trip=12, hysteresis=1, chatter=10, longest_run=3, seed=4)

    def scenario(driver, pins, pin_log, machine_log):
        for name, value in (("STEP_WIDTH", 2), ("INPUT_FILTER", samples), ("INPUT_TICK", tick),
                            ("HOME_SEEK_PERIOD", 40), ("HOME_RELEASE_PERIOD", period), ("HOME_BACKOFF", 4),
                            ("HOME_SEARCH", 200), ("MACHINE_CONTROL", 1)):
            yield from write(driver, name, value)
        yield from write(driver, "HOME", 0)
        for _ in range(20000):
            status = yield from read(driver, "HOME_STATUS")
            if not regmap.field_value("HOME_STATUS", "BUSY", status):
                break
        yield from wait_clocks(driver, 50)

    pin_log, _ = run_machine(f"figures_home_{period}_{samples}_{tick}", scenario, cosim, switches=[("x", switch)])
    away = [rise[0] for rise in pin_log.rises if not rise[3]]   # the release and the back-off: DIR negative
    gaps = [b - a for a, b in zip(away, away[1:])]
    return gaps


def watchdog_writes(cosim):
    found = {}

    def scenario(driver, pins, pin_log, machine_log):
        for value in (0x1000000, 0x1001388):
            yield from write(driver, "WATCHDOG", value)
            yield from wait_clocks(driver, 10)
            left = yield from read(driver, "WATCHDOG")
            status = yield from read(driver, "INT_STATUS")
            yield from write(driver, "INT_STATUS", status)
            found[value] = (left, regmap.field_value("INT_STATUS", "CLAMPED", status))

    run_machine("figures_watchdog", scenario, cosim)
    return found


def refused_clear_stop(cosim):
    found = {}

    def scenario(driver, pins, pin_log, machine_log):
        yield from write(driver, "CONTROL", 1)
        yield from set_input(pins, pin_log, machine_log, "estop", 1)
        yield from wait_clocks(driver, 20)
        yield from driver.push_all(command_words(LineCommand(5, 3)) * 2)
        found["before"] = regmap.field_value("STATUS", "FIFO_LEVEL", (yield from read(driver, "STATUS")))
        yield from write(driver, "COMMAND", regmap.field_of("COMMAND", CLEAR_STOP=1))
        yield from wait_clocks(driver, 5)
        found["after"] = regmap.field_value("STATUS", "FIFO_LEVEL", (yield from read(driver, "STATUS")))

    run_machine("figures_clear_stop", scenario, cosim)
    return found


def drive_margins(cause, cosim):
    """(fewest clocks last STEP rise -> DRIVE_ENABLE low, fewest from its fall, pulses outside DRIVE_ENABLE)."""
    causes = []

    def scenario(driver, pins, pin_log, machine_log):
        for name, value in (("FEED_RATE", regmap.RATE_MAX // 2), ("RAMP_START", 1024),
                            ("STEP_WIDTH", PULSE_WIDTH), ("CONTROL", 1)):
            yield from write(driver, name, value)
        for phase in range(6):
            yield from write(driver, "RAMP_STEP", 512 if cause == "decelerated" else 0)
            yield from write(driver, "MACHINE_CONTROL", 1)
            yield from driver.push_all(command_words(LineCommand(150, 40)))
            yield from wait_clocks(driver, 60 + phase)
            causes.append(pin_log.clock)
            if cause in ("watchdog", "decelerated"):
                yield from write(driver, "WATCHDOG", 1)
            else:
                yield from set_input(pins, pin_log, machine_log, "estop" if cause == "estop" else "limit_pos_x", 1)
            yield from wait_clocks(driver, 400)
            if cause in ("estop", "limit"):
                yield from set_input(pins, pin_log, machine_log, "estop" if cause == "estop" else "limit_pos_x", 0)
                yield from wait_clocks(driver, 30)
            yield from write(driver, "COMMAND", regmap.field_of("COMMAND", CLEAR_STOP=1))
            yield from wait_clocks(driver, 5)

    pin_log, machine_log = run_machine(f"figures_drive_{cause}", scenario, cosim)
    pulses = _pulses(pin_log)
    outside = [(rise, fall) for rise, fall in pulses
               if not all(drive_at(machine_log, c) for c in range(rise, min(fall, len(machine_log.drive)) + 1))]
    from_rise, from_fall = [], []
    for at in causes:
        fell = next(c for c in range(at + 1, len(machine_log.drive)) if not drive_at(machine_log, c))
        before = [p for p in pulses if p[0] <= fell]
        if before:
            rise, fall = before[-1]
            from_rise.append(fell - rise)
            from_fall.append(fell - fall)
    return min(from_rise), min(from_fall), len(outside), len(pulses)


def estop_reactions(tick, cosim):
    presses = []

    def scenario(driver, pins, pin_log, machine_log):
        for name, value in (("INPUT_FILTER", 3), ("INPUT_TICK", tick), ("MACHINE_CONTROL", 1)):
            yield from write(driver, name, value)
        for wait in range(16):
            yield from wait_clocks(driver, 4 + wait)
            presses.append((yield from set_input(pins, pin_log, machine_log, "estop", 1)))
            yield from wait_clocks(driver, 6 * tick + 10)
            yield from set_input(pins, pin_log, machine_log, "estop", 0)
            yield from wait_clocks(driver, 6 * tick + 10)
            yield from write(driver, "COMMAND", regmap.field_of("COMMAND", CLEAR_STOP=1))
            yield from write(driver, "MACHINE_CONTROL", 1)
            yield from wait_clocks(driver, 3)

    _, machine_log = run_machine(f"figures_reaction_{tick}", scenario, cosim)
    return sorted({next(c for c in range(at, at + 200) if not drive_at(machine_log, c)) - at for at in presses})


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.machine_figures", description=__doc__.splitlines()[0])
    parser.add_argument("--cosim", action="store_true", help="the generated Verilog in Icarus (default: MyHDL)")
    cosim = parser.parse_args(argv).cosim
    print(f"card core on {'the generated Verilog (Icarus)' if cosim else 'MyHDL'}")
    print("1. homing: gaps between the release and back-off steps (clocks)")
    for period, samples, tick in ((800, 3, 1), (5000, 3, 1), (800, 10, 10)):
        gaps = homing_gaps(period, samples, tick, cosim)
        print(f"   period {period:5}, filter {samples} x {tick:2}: gaps {gaps}")
    print("2. WATCHDOG writes: read back 10 clocks later, CLAMPED")
    for value, (left, clamped) in watchdog_writes(cosim).items():
        print(f"   {value:#09x}: reads {left} (0x{left:06X}), CLAMPED {clamped}")
    found = refused_clear_stop(cosim)
    print(f"3. refused CLEAR_STOP (E-stop active): FIFO_LEVEL {found['before']} before, {found['after']} after")
    print("4. DRIVE_ENABLE low after the last STEP (fewest clocks over six phases), pulses outside DRIVE_ENABLE")
    for cause in ("estop", "limit", "watchdog", "decelerated"):
        rise, fall, outside, total = drive_margins(cause, cosim)
        print(f"   {cause:11}: {rise} clocks after its rise, {fall} after its fall; {outside} of {total} pulses outside")
    print("5. E-stop pin to DRIVE_ENABLE low, INPUT_FILTER 3, pressed at 16 phases")
    try:
        from models.machine_model import reaction_clocks
    except ImportError:   # an older checkout: no formula
        reaction_clocks = None
    for tick in (1, 8):
        seen = estop_reactions(tick, cosim)
        formula = f"; formula {reaction_clocks(3, tick)}" if reaction_clocks else ""
        print(f"   INPUT_TICK {tick}: {seen}{formula}")


if __name__ == "__main__":
    main()
