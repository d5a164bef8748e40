"""The three-axis mill (linuxcnc/config/dda_xyz.ini) under LinuxCNC on the simulated 3-axis card.

The card server runs a card built with three axes (``--axes 3``); the driver serves
stepgen.00 .. 02 and sends each servo period's move as one LINE of X, Y and Z.  The
program (``gcode/lcnc_mill.ngc``) has 3-D lines, helical bores (G2 with Z, two
turns down; G3 with Z, one turn up) and arcs in the ZX (G18) and YZ (G19) planes:
LinuxCNC's trajectory planner turns them into joint positions, so every axis's pins
must follow the commanded joint positions as the X and Y pins do in test_linuxcnc.py:
within one step at every servo period (the queue's delay taken into account), no
underrun, exactly on the end point.  LinuxCNC runs a helix as joint moves through
the driver (a LINE of X, Y and Z each servo period): this exercises the driver's
path, not the card's HELIX command (``sim/card`` and ``tests/host`` run that).
"""
import pytest

from tests.linuxcnc.compare import axis_deviations
from tests.linuxcnc.session import (KEEP_AHEAD, MILL_AXES, PERIOD_CLOCKS, SCALE, configure, missing, run_folder,
                                    run_linuxcnc)

DELAY_PERIODS = KEEP_AHEAD - 1  # the period's command is done at the end of period k + keep_ahead - 1

pytestmark = [pytest.mark.linuxcnc, pytest.mark.xdist_group("linuxcnc"),
              pytest.mark.skipif(missing() is not None, reason=str(missing()))]


@pytest.mark.slow(reason="a Verilator build of the 3-axis card at 1 MHz and a 7-second program: about 100 s; "
                         "the two-axis LinuxCNC tests and the 3-axis card's benches run by default")
def test_mill_program_on_every_axis_from_the_pins(linuxcnc_alone):
    run = run_folder()
    configure(run, "dda_xyz")
    samples, pins, record = run_linuxcnc(run, [str(run / "lcnc_mill.ngc")], "--axes", str(MILL_AXES),
                                         config="dda_xyz")
    clocks, points = pins
    assert len(samples) > 1000 and len(clocks) > 1000
    moved = [max(abs(p[axis]) for p in points) for axis in range(MILL_AXES)]
    assert min(moved) >= 300, f"an axis hardly moved: {moved} steps at most"
    deviation = axis_deviations(samples, pins, SCALE, DELAY_PERIODS * PERIOD_CLOCKS)
    worst = [max(abs(d[axis]) for d in deviation) for axis in range(MILL_AXES)]
    print(f"\nmill: worst deviation X {worst[0]:.3f}, Y {worst[1]:.3f}, Z {worst[2]:.3f} steps; "
          f"{len(samples)} periods, {len(clocks)} step clocks, underruns {samples[-1][3]}")
    assert max(worst) <= 1.0, f"the pins left the commanded joint positions by {worst} steps"
    standstills = 0
    for k in range(1, len(samples) - DELAY_PERIODS - 1):
        if samples[k - 1][0] == samples[k][0] == samples[k + 1][0]:
            assert all(abs(d) <= 0.5 for d in deviation[k]), f"at rest at period {k} the pins are off by {deviation[k]}"
            standstills += 1
    assert standstills > 100
    assert samples[-1][3] == 0, "the FIFO ran dry"
    assert points[-1] == (0,) * MILL_AXES, f"the program ends at the origin; the pins at {points[-1]}"
    assert samples[-1][0] == (0.0,) * MILL_AXES
