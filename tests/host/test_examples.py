"""The examples plan clean: every command accepted by the DDA model, the path
ends on the drawing's rounded end, within half a step of the drawing plus its
rounding (ideal geometry from ``host.geometry``, steps from ``models.dda_model``;
the three-axis ``mill.ngc`` on a three-axis card, ``models.dda_axes``)."""
import math

import pytest

from host import gcode, svg
from host.check import check
from host.geometry import Arc, Line
from host.machine import Machine
from host.planner import plan
from models.dda_axes import MoveIterator
from models.dda_model import ArcCommand, plan_arc
from rtl.convert import ROOT

ROUNDING = math.sqrt(2) / 2


def example(name):
    path = ROOT / "examples" / name
    if name.endswith(".svg"):
        return svg.parse(str(path), tolerance=0.01, name=name)
    return gcode.parse(path.read_text(), name)


@pytest.mark.parametrize("name", ["part.ngc", "drawing.svg"])
def test_example_plans_clean(name):
    drawing = example(name)
    machine = Machine()
    planned = plan(drawing, machine)
    for entry in planned.moves():
        if isinstance(entry.command, ArcCommand):
            plan_arc(entry.command, machine.coord_width)
    result = check(planned)
    last = drawing[-1].end
    assert result.end == (math.floor(last[0] * 200 + 0.5), math.floor(last[1] * 200 + 0.5))
    assert result.max_deviation_steps <= 0.5 + ROUNDING
    assert result.job_seconds == pytest.approx(result.ideal_seconds, rel=0.1)


def test_the_gcode_example_has_what_it_promises():
    drawing = example("part.ngc")
    arcs = [d for d in drawing if isinstance(d, Arc)]
    assert any(a.full_circle and a.ccw for a in arcs) and any(a.full_circle and not a.ccw for a in arcs)
    assert any(a.sweep > math.pi + 0.1 and a.ccw for a in arcs)
    assert any(a.sweep > math.pi + 0.1 and not a.ccw for a in arcs)
    assert any(abs(a.start_radius - a.end_radius) > 0.001 for a in arcs)


def test_the_mill_example_plans_clean_on_a_three_axis_card():
    drawing = gcode.parse((ROOT / "examples" / "mill.ngc").read_text(), "mill.ngc", axes=3)
    machine = Machine(steps_per_mm=(200.0,) * 3)
    planned = plan(drawing, machine)
    helical = []
    for entry in planned.moves():
        MoveIterator(entry.command, 3, machine.coord_width)  # the card's rules and the DDA's acceptance
        if isinstance(entry.command, ArcCommand) and entry.command.helix_axes:
            helical.append(entry.command)
    result = check(planned)
    assert result.end == tuple(math.floor(v * 200 + 0.5) for v in drawing[-1].end)
    # a 3-D line: half a step on each minor axis and the rounding of its ends; an arc: half a step
    # and the rounding radially, along the helix axis its bound (docs/axes.md) and the rounding
    # (the helix: docs/axes.md's 0.75 steps at the same angle, and half a step of rounding of its pieces' ends)
    bound = max(math.sqrt(2) / 2 + math.sqrt(3) / 2, math.hypot(0.5 + ROUNDING, 0.75 + 0.5))
    assert result.max_deviation_steps <= bound
    assert result.job_seconds == pytest.approx(result.ideal_seconds, rel=0.1)
    # what it promises: 3-D lines, a helical bore, arcs in G18 and G19
    planes = {item.plane for item in drawing if isinstance(item, Arc)}
    assert {(0, 1), (2, 0), (1, 2)} <= planes and len(helical) >= 3
    assert any(isinstance(i, Line) and i.start[2] != i.end[2] and i.start[:2] != i.end[:2] for i in drawing)
