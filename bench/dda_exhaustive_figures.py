"""Every legal move of the narrowest DDA build against the golden model:
``python -m bench.dda_exhaustive_figures [--kind arcs|improved|lines|refused ...] [--radius R]``.

Converts ``dda_arc`` at ``NARROW_WIDTH`` bits (coordinates -32..31) into
build/dda_narrow/, runs it on Verilator with ``advance`` always high and
compares every move with the model (``sim/card/dda_exhaustive.py``): every step
on its iteration's clock with its direction, the move over within 4 clocks
of its last iteration.  Kinds:

* ``arcs``: every legal arc in the precise mode (every start, every end the
  set-up accepts, both directions);
* ``improved``: the same arcs in the paper's improved variant with the
  normalised accumulator (ACC_BITS = 0) and lambda = 1 (LAMBDA = 0);
* ``lines``: every line (DX, DY) of the width;
* ``refused``: every arc the set-up refuses among the end points within two
  of the legal band, and the centre: ``error``, no step.

``--radius R`` keeps the arcs whose start lies within radius R (the whole
width takes about an hour of CPU for each arc kind: the model's iterations
in Python are most of it).  Prints, per kind, the moves, iterations, steps,
mismatches and seconds of wall time (the load average with them), and a
line every ``--every`` moves; exit status 1 on any mismatch.
"""
import argparse
import itertools
import os
import sys
import time

from models.dda_build import IMPROVED
from sim.card.dda_exhaustive import NARROW_WIDTH, Tally, every_arc, every_line, narrow_dda, run_all

KINDS = ("arcs", "improved", "lines", "refused")


def moves(kind, radius=None):
    if kind == "lines":
        return ((command, True) for command in every_line())
    starts = None
    if radius is not None:
        starts = {(x, y) for x in range(-radius, radius + 1) for y in range(-radius, radius + 1)
                  if x * x + y * y <= radius * radius}
    if kind == "refused":
        return ((command, False) for command, accepted in every_arc(starts=starts) if not accepted)
    fields = dict(variant=IMPROVED) if kind == "improved" else {}
    return ((command, True) for command, accepted in every_arc(starts=starts, **fields) if accepted)


def chunks(items, size):
    items = iter(items)
    while True:
        chunk = list(itertools.islice(items, size))
        if not chunk:
            return
        yield chunk


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.dda_exhaustive_figures", description=__doc__.split("\n\n")[0])
    parser.add_argument("--kind", action="append", choices=KINDS, help="kinds to run (default: all)")
    parser.add_argument("--radius", type=int, help="only arcs starting within this radius (default: all)")
    parser.add_argument("--every", type=int, default=100_000, help="a progress line every this many moves")
    args = parser.parse_args(argv)
    started = time.monotonic()
    dda = narrow_dda()
    print(f"dda_arc at {NARROW_WIDTH} bits, Verilator model built in {time.monotonic() - started:.0f} s")
    print(f"{'kind':9} {'moves':>9} {'iterations':>11} {'steps':>10} {'mismatches':>10} {'seconds':>8}")
    failed = False
    for kind in args.kind or KINDS:
        tally = Tally()
        for chunk in chunks(moves(kind, args.radius), args.every):
            run_all(dda, chunk, tally)
            # the arcs come in the order of their start's square: every start below this one is done
            last = chunk[-1][0]
            reached = f", starts up to x^2 + y^2 = {last.xs ** 2 + last.ys ** 2}" if kind != "lines" else ""
            print(f"    {kind}: {tally.moves + tally.refused:,} moves{reached}, {len(tally.mismatches)} mismatches, "
                  f"{tally.seconds:.0f} s", flush=True)
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
