"""Figures of HOME: ``python3 -m bench.homing_figures [--icarus]``.

Homes each axis in each direction on the card core (MyHDL, or its Verilog
in Icarus) with a bouncing switch (``models.homing_model.BouncingSwitch``) and
the settings of ``sim.card.homing_bench`` (seek every 9 clocks, release every
60, INPUT_FILTER 4, STEP_WIDTH 2, DIR_SETUP = DIR_HOLD = 1), and prints,
from the pins and the switch's pin:
- clocks from the switch's first contact, and from the edge at which the
  filtered input turns active, to the first STEP rise of the release;
- steps past the trip point (the seek's overrun) and release steps;
- clocks from the filtered release to the first back-off step, and the
  whole HOME in clocks.
"""
import argparse

from models.homing_model import BouncingSwitch, expected_homing
from sim.card.homing_bench import SAMPLES, homing_run


def measure(axis, negative, cosim, seed):
    switch = BouncingSwitch(trip=12 + seed, negative=negative, hysteresis=seed % 3, chatter=14, longest_run=3,
                            seed=seed)
    pin_log, words = homing_run(f"bench_home_{'xy'[axis]}{int(negative)}", cosim, axis, negative, switch)
    expect = expected_homing(pin_log.rises, axis, switch.levels, SAMPLES, negative)
    reversal = expect.release[0][0]
    contact = switch.changes[0][0]
    overrun = len(expect.seek) - switch.trip
    return dict(case=f"{'XY'[axis]}{'-' if negative else '+'}", contact=reversal - contact,
                filtered=reversal - expect.trip_edge, overrun=overrun, release=len(expect.release),
                backoff=expect.backoff[0][0] - expect.release_edge if expect.backoff else None,
                total=pin_log.rises[-1][0] - pin_log.rises[0][0], position=words["position"][axis])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--icarus", action="store_true", help="run the generated Verilog in Icarus")
    args = parser.parse_args(argv)
    print(f"HOME on the card core ({'Icarus' if args.icarus else 'MyHDL'}), clocks:")
    print("case  contact->reversal  filtered->reversal  overrun  release steps  release->back-off  "
          "first..last step  POS")
    for seed, (axis, negative) in enumerate(((0, False), (0, True), (1, False), (1, True)), start=1):
        row = measure(axis, negative, args.icarus, seed)
        print(f"{row['case']:<4}  {row['contact']:>17}  {row['filtered']:>18}  {row['overrun']:>7}  "
              f"{row['release']:>13}  {row['backoff']:>17}  {row['total']:>16}  {row['position']:>3}")


if __name__ == "__main__":
    main()
