"""Stall to stop on the card with encoders and simulated motors: ``python -m bench.motor_figures``.

On the two-axis Verilator build with encoders (``bench/motor_runs.py``): a motor on X of
``--counts-per-step`` counts a step, ENC_SCALE the same, FERROR_LIMIT ``--limit``; a line of X steps at
each FEED_RATE of ``--feed-rates``, the motor stalled after ``--stall-after`` steps.  Prints per feed
rate the clocks between two steps, the clocks from the stall (the first clock the motor did not
turn) to the DRIVE_ENABLE pin low, and their parts: the steps lost until the error passed the limit,
the clocks from the STEP rise that took it there to the golden model's stop flag and to DRIVE_ENABLE
low; and STOP_REASON.  Then the largest following error a following move showed (read over PCI, and
the golden model's over every clock).  docs/encoders.md quotes the figures.
"""
import argparse

from models.sim_machine import MachineConfig, Motor
from bench.motor_runs import motor_run, stop_reason


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.motor_figures", description=__doc__.split("\n")[0])
    parser.add_argument("--counts-per-step", type=int, default=4, help="encoder counts a step (default: 4)")
    parser.add_argument("--limit", type=int, default=8, help="FERROR_LIMIT, counts (default: 8)")
    parser.add_argument("--feed-rates", default="250,500,1000", help="FEED_RATE values (default: 250,500,1000)")
    parser.add_argument("--stall-after", type=int, default=60, help="steps before the stall (default: 60)")
    parser.add_argument("--lag", type=int, default=40, help="the following move's motor lag, clocks (default: 40)")
    args = parser.parse_args(argv)
    try:
        rates = [int(value) for value in args.feed_rates.split(",")]
    except ValueError:
        parser.error(f"--feed-rates: whole numbers separated by commas, not {args.feed_rates!r}")
    if args.limit < 1 or args.stall_after < 1 or not 1 <= args.counts_per_step <= 1 << 16 or args.lag < 0 \
            or any(rate < 1 for rate in rates):
        parser.error("--limit, --stall-after, --feed-rates and --counts-per-step must be >= 1, --lag >= 0")
    motor = Motor(counts_per_step=args.counts_per_step, spacing=3)
    print(f"X motor: {args.counts_per_step} counts a step, edges >= 3 clocks apart; FERROR_LIMIT {args.limit}; "
          f"stalled after {args.stall_after} steps")
    for rate in rates:
        run = motor_run(MachineConfig(motors={"X": motor}), [(4 * args.stall_after + 400, 0)], args.limit,
                        feed_rate=rate, stall_after=args.stall_after)
        after = [clock for clock in run.x_rises if clock >= run.stall_at]
        crossing = after[run.machine.lost[0] - 1]
        period = after[1] - after[0]
        print(f"FEED_RATE {rate}: a step every {period} clocks; stall to DRIVE_ENABLE low {run.stall_to_stop} "
              f"clocks ({run.machine.lost[0]} steps lost; the last STEP rise to the model's flag "
              f"{run.model_stop_at - crossing}, to DRIVE_ENABLE low {run.drive_low_at - crossing}, "
              f"STEP_WIDTH {run.step_width}); STOP_REASON {'/'.join(map(str, stop_reason(run.stop_reason)))}")
    config = MachineConfig(motors={"X": Motor(counts_per_step=args.counts_per_step, lag=args.lag, spacing=3)})
    for rate in rates:
        run = motor_run(config, [(400, 0)], 1 << 20, feed_rate=rate, read_every=500)
        read = max(abs(value) for value in run.ferror_reads[0])
        print(f"following at FEED_RATE {rate}, lag {args.lag} clocks: largest |ENC_FERROR| read {read}, "
              f"golden model's over every clock {run.model_worst[0]} counts; ENC_COUNT {run.counts[0]} "
              f"for {run.positions[0]} steps")


if __name__ == "__main__":
    main()
