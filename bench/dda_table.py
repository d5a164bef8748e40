"""Accuracy table of the DDA interpolator: ``python -m bench.dda_table``.

Quarter arc (R, 0) -> (0, R), counter-clockwise, step 1, from the golden
model (``models/dda_model.py``; the RTL equals it clock for clock):

* the paper's configuration of each variant (figures 6, 7, 10) beside the
  paper's V_arc; for weighted and improved also the same settings with the
  hardware's end rule (per-axis step counters);
* the paper's three variants at the same R = 100 with the hardware's own
  settings (normalised accumulators), and the default precise mode at
  R = 100, 1,000, 10,000, 100,000.

Columns: V_arc (eq. 12), maximum and RMS radial error (steps), sawteeth,
diagonal steps, iterations (``advance`` pulses) and clocks from ``start`` to
``done`` at the fastest feed rate (an iteration every other clock), including
the setup.
"""
import sys

from models.dda_model import (IMPROVED, PAPER_V_ARC, PRECISE, TRADITIONAL, VARIANT_NAMES, WEIGHTED, ArcCommand, iterate,
                              metrics, paper_configuration, setup_clocks)

RADII = (100, 1000, 10000, 100000)
HEADER = (f"{'configuration':<44} {'R':>7} {'V_arc':>8} {'paper':>8} {'max err':>8} "
          f"{'rms err':>8} {'saw':>6} {'diag':>7} {'iter':>8} {'clocks':>8}")


def row(label, command, options=None, paper=None):
    path = iterate(command, **(options or {}))
    result = metrics(path)
    radius = command.xs
    paper_text = f"{paper:8.4f}" if paper is not None else f"{'':>8}"
    clocks = setup_clocks(24, line=False) + 2 * result.iterations
    return (f"{label:<44} {radius:>7} {result.v_arc:8.4f} {paper_text} "
            f"{result.max_radial_error:8.3f} {result.rms_radial_error:8.3f} {result.sawteeth:>6} "
            f"{result.diagonal_steps:>7} {result.iterations:>8} {clocks:>8}")


def paper_rows():
    lines = []
    for variant in (TRADITIONAL, WEIGHTED, IMPROVED):
        command, options = paper_configuration(variant)
        settings = f"n={command.acc_bits}, k={command.lambda_shift}"
        label = f"paper {VARIANT_NAMES[variant]} ({settings}{', reach' if options else ''})"
        lines.append(row(label, command, options, PAPER_V_ARC[variant]))
        if options:
            lines.append(row("  same, hardware end (counters)", command))
    return lines


def hardware_rows():
    lines = []
    for variant, shift in ((TRADITIONAL, 0), (WEIGHTED, 3), (IMPROVED, 3)):
        command = ArcCommand(100, 0, 0, 100, variant=variant, lambda_shift=shift)
        lines.append(row(f"{VARIANT_NAMES[variant]} (normalised n, k={shift})", command))
    for radius in RADII:
        lines.append(row("precise (default)", ArcCommand(radius, 0, 0, radius, variant=PRECISE)))
    return lines


def main():
    print(HEADER)
    print("-" * len(HEADER))
    for line in paper_rows() + hardware_rows():
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
