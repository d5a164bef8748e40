"""End to end on cards of three and four axes (``--axes N``): the behavioural
PCI host enumerates the card, bursts N-axis commands into the FIFO and waits
for INTA# (``sim/card/card_e2e.py``), on Verilator mostly; one short
scenario also on MyHDL and on the generated top level in Icarus.

Golden values: the STEP/DIR pins of every axis give the points of
``models.dda_axes.iterate_axes`` chained over the commands (3-D lines, arcs
in the ZX (G18) and YZ (G19) planes and others, helices in G17 rising on
Z and in G18 on Y); the short scenario's pin edges are identical, clock for
clock, on the three back ends.
"""
import pytest

from models import registers as regmap
from models.axes import PLANES
from models.dda_axes import with_area
from models.dda_plan import ArcCommand, AxesLineCommand
from sim.card.card_bench import axes_path
from sim.card.card_e2e import DEFAULT_FIFO, motion_scenario, run_card

G17, G18, G19 = PLANES[17], PLANES[18], PLANES[19]
RAMP = dict(feed=16384, ramp_start=2048, ramp_step=512)


def line(*deltas, blend=False):
    return AxesLineCommand(tuple(deltas), blend=blend)


def helix(*arc, **fields):
    """A helical arc with its AREA (the arc's W)."""
    return with_area(ArcCommand(*arc, **fields))


SHORT = [line(6, -4, 9, blend=True), helix(10, 0, 0, 10, plane=G18, helix=(0, 7, 0)), line(0, 3, -5),
         ArcCommand(0, 8, -8, 0, ccw=False, plane=G19, blend=True), helix(8, 0, 0, -8, ccw=False, helix=(0, 0, -6))]
MILL = [line(120, 0, -40, blend=True), ArcCommand(60, 0, 0, 60, plane=G18, blend=True), line(-30, 45, 25),
        ArcCommand(0, -50, 50, 0, ccw=False, plane=G19, blend=True), ArcCommand(40, 30, -30, 40, plane=G17),
        line(0, 0, 77), ArcCommand(25, 0, 25, 0, plane=(2, 1)), line(-3, -200, 1),
        helix(30, 0, 30, 0, plane=G17, helix=(0, 0, -60), blend=True), helix(0, 20, 20, 0, ccw=False, plane=G18,
                                                                           helix=(0, 25, 0))]
FOUR = [line(30, -20, 10, 55, blend=True), ArcCommand(40, 0, 0, 40, plane=(3, 2), blend=True),
        line(0, 0, 0, -90), ArcCommand(30, 40, -40, 30, ccw=False, plane=(1, 3)), line(5, 5, 5, 5)]


def _run(kind, commands, axes, name, **ramp):
    # the default FIFO: the three-axis Verilator model is the one the host's three-axis tests
    # build (tests/host/test_card_axes.py), not a build of its own
    out, log, _, _ = run_card(kind, motion_scenario(commands, **ramp), name, fifo_depth=DEFAULT_FIFO, axes=axes)
    assert regmap.field_value("STATUS", "ERROR", out["status"]) == 0
    assert regmap.field_value("INT_STATUS", "DONE", out["int_status"]) == 1
    return out, log


@pytest.mark.parametrize("axes, commands", [
    pytest.param(3, MILL, id="3-axis"),
    pytest.param(4, FOUR, id="4-axis", marks=pytest.mark.slow(reason="a second N-axis build: its Verilator model "
                                                                      "compiles for about 25 s"))])
def test_n_axis_card_steps_the_golden_paths_on_verilator(axes, commands):
    _, log = _run("verilator", commands, axes, f"e2e_axes_{axes}", **RAMP)
    assert log.axis_points(axes) == axes_path(commands, axes)


def test_three_axis_pins_identical_on_myhdl_icarus_and_verilator():
    logs = {kind: _run(kind, SHORT, 3, "e2e_axes_short")[1] for kind in ("myhdl", "icarus", "verilator")}
    assert logs["myhdl"].axis_points(3) == axes_path(SHORT, 3)
    assert logs["icarus"].edges == logs["myhdl"].edges
    assert logs["verilator"].edges == logs["myhdl"].edges
