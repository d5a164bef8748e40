"""The examples plan clean: every command accepted by the DDA model, the path
ends on the drawing's rounded end, within half a step of the drawing plus its
rounding (ideal geometry from ``host.geometry``, steps from ``models.dda_model``)."""
import math

import pytest

from host import gcode, svg
from host.check import check
from host.geometry import Arc
from host.machine import Machine
from host.planner import plan
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
