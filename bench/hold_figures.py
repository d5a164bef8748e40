"""Feed hold and stop reaction figures: ``python -m bench.hold_figures [--cosim]``.

Runs the card core (``rtl.card_core`` in MyHDL, or its Verilog in Icarus)
on a line of 1,500 x 400 steps at FEED_RATE 8192 (an iteration every 8
clocks) and, once it runs at speed, sets MACHINE_CONTROL.HOLD, lets the
watchdog expire, or trips the X+ limit; for each ramp (RAMP_START,
RAMP_STEP; RAMP_STEP 0: no ramp) it prints the steps that left the pins
after the cause and the clocks from the cause to the last STEP rise and,
for the stops, to DRIVE_ENABLE low.  The cause's clock: the bus write's
last clock (HOLD, WATCHDOG + its timeout), the clock the filtered limit
input is active (its pin's change + INPUT_FILTER + 2).  Beside them, the
feed rate model's (``models.machine_model.paused_ticks``) iterations and
clocks from a pause to the rate's stop, at that rate.
"""
import argparse

from models import registers as regmap
from models.commands import command_words
from models.dda_model import LineCommand
from models.machine_model import paused_ticks
from sim.card.machine_bench import REACTION, WIDTH, drive_at, run_machine, set_input, wait_clocks, write

TARGET = 8192
RAMPS = ((1024, 512), (1024, 2048), (1024, 0))
AT_SPEED = 1500   # clocks after the queue is written
TIMEOUT = 2000    # the watchdog's, in clocks


def measure(cause_name, ramp_start, ramp_step, cosim):
    """(steps after the cause, clocks to the last rise, clocks to DRIVE_ENABLE low or None)."""
    found = {}

    def scenario(driver, pins, pin_log, machine_log):
        for name, value in (("FEED_RATE", TARGET), ("RAMP_START", ramp_start), ("RAMP_STEP", ramp_step),
                            ("STEP_WIDTH", WIDTH), ("CONTROL", 1), ("MACHINE_CONTROL", 1)):
            yield from write(driver, name, value)
        if cause_name == "watchdog":
            yield from write(driver, "WATCHDOG", TIMEOUT)
            found["at"] = pin_log.clock + TIMEOUT
        yield from driver.push_all(command_words(LineCommand(1500, 400)))
        if cause_name != "watchdog":
            yield from wait_clocks(driver, AT_SPEED)
        if cause_name == "hold":
            yield from write(driver, "MACHINE_CONTROL", regmap.field_of("MACHINE_CONTROL", DRIVE_ENABLE=1, HOLD=1))
            found["at"] = pin_log.clock
        elif cause_name == "limit":
            found["at"] = (yield from set_input(pins, pin_log, machine_log, "limit_pos_x", 1)) + REACTION - 1
        yield from wait_clocks(driver, TIMEOUT + 1500)

    pin_log, machine_log = run_machine(f"figures_{cause_name}_{ramp_step}", scenario, cosim)
    at = found["at"]
    after = [rise[0] for rise in pin_log.rises if rise[0] > at]
    last = (after or [at])[-1] - at
    drop = next((c for c in range(at, len(machine_log.drive) + 1) if not drive_at(machine_log, c)), None)
    return len(after), last, None if drop is None else drop - at


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cosim", action="store_true", help="the generated Verilog in Icarus, not MyHDL")
    args = parser.parse_args(argv)
    print(f"line 1500 x 400 at FEED_RATE {TARGET} (8 clocks an iteration), STEP_WIDTH {WIDTH}, "
          f"{'Icarus' if args.cosim else 'MyHDL'}")
    print(f"{'cause':10} {'RAMP_START':>10} {'RAMP_STEP':>9} {'steps after':>11} {'last rise':>9} "
          f"{'DRIVE_ENABLE low':>16} {'model: steps':>12} {'clocks':>6}")
    for cause_name in ("hold", "watchdog", "limit"):
        for ramp_start, ramp_step in RAMPS:
            steps, last, drop = measure(cause_name, ramp_start, ramp_step, args.cosim)
            model = paused_ticks(TARGET, ramp_start, ramp_step, pause_at=AT_SPEED) if ramp_step else []
            since = [t - AT_SPEED for t in model if t >= AT_SPEED]
            print(f"{cause_name:10} {ramp_start:>10} {ramp_step:>9} {steps:>11} {last:>9} "
                  f"{'-' if drop is None else drop:>16} {len(since):>12} {since[-1] if since else 0:>6}")


if __name__ == "__main__":
    main()
