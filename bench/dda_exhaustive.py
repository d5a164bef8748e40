"""Every legal move of the narrowest DDA build against the golden model:
``python -m bench.dda_exhaustive [--kind arcs|improved|lines|refused ...]``.

Converts ``dda_arc`` at ``NARROW_WIDTH`` bits (coordinates -32..31) into
build/dda_narrow/, runs it on Verilator with ``advance`` always high and
compares every move with the model (``sim/dda_exhaustive.py``): every step
on its iteration's clock with its direction, the move over within 4 clocks
of its last iteration.  Kinds:

* ``arcs``: every legal arc in the precise mode (every start, every end the
  set-up accepts, both directions);
* ``improved``: the same arcs in the paper's improved variant with the
  normalised accumulator (ACC_BITS = 0) and lambda = 1 (LAMBDA = 0);
* ``lines``: every line (DX, DY) of the width;
* ``refused``: every arc the set-up refuses among the end points within two
  of the legal band, and the centre: ``error``, no step.

Prints, per kind, the moves, iterations, steps, mismatches and seconds of
wall time (the load average with them); exit status 1 on any mismatch.
"""
import argparse
import os
import sys
import time

from rtl.dda_build import IMPROVED
from sim.dda_exhaustive import NARROW_WIDTH, Tally, every_arc, every_line, narrow_dda, run_all

KINDS = ("arcs", "improved", "lines", "refused")


def moves(kind):
    if kind == "lines":
        return ((command, True) for command in every_line())
    if kind == "refused":
        return ((command, False) for command, accepted in every_arc() if not accepted)
    fields = dict(variant=IMPROVED) if kind == "improved" else {}
    return ((command, True) for command, accepted in every_arc(**fields) if accepted)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.dda_exhaustive", description=__doc__.split("\n\n")[0])
    parser.add_argument("--kind", action="append", choices=KINDS, help="kinds to run (default: all)")
    args = parser.parse_args(argv)
    started = time.monotonic()
    dda = narrow_dda()
    print(f"dda_arc at {NARROW_WIDTH} bits, Verilator model built in {time.monotonic() - started:.0f} s")
    print(f"{'kind':9} {'moves':>9} {'iterations':>11} {'steps':>10} {'mismatches':>10} {'seconds':>8}")
    failed = False
    for kind in args.kind or KINDS:
        tally = run_all(dda, moves(kind), Tally())
        count = tally.refused if kind == "refused" else tally.moves
        print(f"{kind:9} {count:9,} {tally.iterations:11,} {tally.steps:10,} {len(tally.mismatches):10,} "
              f"{tally.seconds:8.0f}", flush=True)
        for line in tally.mismatches[:5]:
            print(f"    {line}")
        failed |= bool(tally.mismatches)
    print(f"offsets from start to iteration 0: {tally.offsets}; load average {os.getloadavg()[0]:.1f}")
    dda.close()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
