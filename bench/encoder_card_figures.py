"""Following-error reaction time of the whole card: ``python -m bench.encoder_card_figures``.

On a two-axis build with encoders (Verilator, ``sim/card/encoder_card_bench.py``): FERROR_LIMIT
``--limit``, ENC_SCALE 0, the drives enabled, legal quadrature edges ``--spacing`` clocks apart up
on one axis; prints the clocks from the pin change of the count that went beyond the limit to the
DRIVE_ENABLE pin low, per axis, and STOP_REASON (docs/encoders.md quotes the figure).
"""
import argparse

from models import registers as regmap
from models.encoder_model import FILTER_RESET
from sim.card.encoder_card_bench import following_error_trip


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.encoder_card_figures", description=__doc__.split("\n")[0])
    parser.add_argument("--limit", type=int, default=3, help="FERROR_LIMIT, counts (default: 3)")
    parser.add_argument("--spacing", type=int, default=6, help="clocks between encoder edges (default: 6)")
    args = parser.parse_args(argv)
    if args.limit < 1 or args.spacing < 1:
        parser.error("--limit and --spacing must be >= 1")
    print(f"ENC_FILTER {FILTER_RESET} (reset), FERROR_LIMIT {args.limit}, edges {args.spacing} clocks apart")
    for axis in range(2):
        clocks, reason, model_clocks = following_error_trip(axis, args.limit, args.spacing)
        print(f"axis {'XY'[axis]}: pin edge to DRIVE_ENABLE low {clocks} clocks "
              f"(to the model's stop flag {model_clocks}); STOP_REASON.REASON "
              f"{regmap.STOP_REASONS[regmap.field_value('STOP_REASON', 'REASON', reason)]}, "
              f"AXIS {regmap.field_value('STOP_REASON', 'AXIS', reason)}")


if __name__ == "__main__":
    main()
