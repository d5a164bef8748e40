"""SVG front end: element types, transforms, units, the y flip, and the curve
tolerance measured against ``svgelements``' own evaluation of each curve."""
import io
import math

import numpy
import pytest
import svgelements

from host.errors import ProgramError
from host.geometry import Arc, Line
from host.svg import parse

PX = 25.4 / 96  # mm


def drawing_of(body, width="100mm", height="100mm", view_box="0 0 100 100", tolerance=0.01):
    text = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
            f'viewBox="{view_box}">{body}</svg>')
    return parse(io.StringIO(text), tolerance=tolerance, feed=900.0, name="t.svg")


def fed(drawing):
    return [item for item in drawing if not item.rapid]


def close(a, b, tol=1e-9):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def test_line_in_mm_with_y_flipped_and_pen_up_before_it():
    drawing = drawing_of('<line id="l" x1="10" y1="20" x2="30" y2="20"/>')
    assert drawing == [Line((0.0, 0.0), (10.0, 80.0), None, "t.svg#l"),
                       Line((10.0, 80.0), (30.0, 80.0), 900.0, "t.svg#l")]


def test_pixels_are_96_per_inch_without_units():
    drawing = drawing_of('<line x1="0" y1="0" x2="96" y2="0"/>', width="96", height="96", view_box="0 0 96 96")
    assert close(fed(drawing)[0].end, (25.4, 25.4))


def test_inch_document_and_viewbox_scale():
    # 2 in wide, viewBox 200 units: one unit is 0.254 mm
    drawing = drawing_of('<line x1="0" y1="100" x2="100" y2="100"/>', width="2in", height="2in",
                         view_box="0 0 200 200")
    assert close(fed(drawing)[0].start, (0.0, 25.4), 1e-9) and close(fed(drawing)[0].end, (25.4, 25.4), 1e-9)


def test_polyline_polygon_and_rect_are_lines():
    drawing = drawing_of('<polyline points="0,0 10,0 10,10"/><polygon points="20,20 30,20 30,30"/>'
                         '<rect x="40" y="40" width="10" height="5"/>')
    lines = fed(drawing)
    assert all(isinstance(item, Line) for item in lines)
    assert len(lines) == 2 + 3 + 4


def test_circle_is_four_clockwise_arcs_about_its_centre():
    drawing = drawing_of('<circle id="c" cx="50" cy="30" r="10"/>')
    arcs = fed(drawing)
    assert len(arcs) == 4 and all(isinstance(a, Arc) for a in arcs)
    assert all(close(a.centre, (50.0, 70.0)) and a.start_radius == pytest.approx(10.0) for a in arcs)
    # on the page (y down) svgelements runs circles with a positive sweep; y up it is clockwise
    assert not any(a.ccw for a in arcs)
    assert sum(a.sweep for a in arcs) == pytest.approx(2 * math.pi)


def test_rounded_rect_has_quarter_arcs():
    arcs = [a for a in fed(drawing_of('<rect x="10" y="10" width="40" height="20" rx="5"/>')) if isinstance(a, Arc)]
    assert len(arcs) == 4 and all(a.sweep == pytest.approx(math.pi / 2) for a in arcs)


def test_transforms_are_applied():
    drawing = drawing_of('<g transform="translate(10 20)"><g transform="rotate(90)">'
                         '<line x1="0" y1="0" x2="10" y2="0"/></g></g>')
    line = fed(drawing)[0]
    # (10, 0) rotated by 90 degrees on the page is (0, 10), then moved by (10, 20): (10, 30)
    assert close(line.start, (10.0, 80.0)) and close(line.end, (10.0, 70.0))


def test_uniformly_scaled_arc_stays_an_arc_and_a_stretched_one_becomes_biarcs():
    circle = fed(drawing_of('<circle cx="50" cy="50" r="10" transform="scale(2)"/>'))
    assert all(isinstance(a, Arc) and a.start_radius == pytest.approx(20.0) for a in circle)
    stretched = fed(drawing_of('<circle cx="25" cy="50" r="10" transform="scale(2 1)"/>'))
    assert len(stretched) > 4


def svg_segments(body):
    """The curve segments as svgelements evaluates them, in page pixels."""
    text = f'<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">{body}</svg>'
    document = svgelements.SVG.parse(io.StringIO(text))
    scale = 100 / document.height  # mm per pixel: the page is 100 mm tall
    segments = []
    for element in document.elements():
        if isinstance(element, svgelements.Shape):
            segments += [s for s in svgelements.Path(element).segments()
                         if isinstance(s, (svgelements.CubicBezier, svgelements.QuadraticBezier, svgelements.Arc))]
    return segments, scale


def polyline_distances(points, vertices):
    """Distance of each of ``points`` to the polyline through ``vertices``."""
    a, b = vertices[:-1], vertices[1:]
    span = b - a
    length2 = numpy.maximum((span ** 2).sum(axis=1), 1e-300)
    offsets = points[:, None, :] - a[None, :, :]
    t = numpy.clip((offsets * span[None]).sum(axis=2) / length2[None], 0, 1)
    nearest = a[None] + t[..., None] * span[None]
    return numpy.sqrt(((points[:, None, :] - nearest) ** 2).sum(axis=2)).min(axis=1)


CURVES = {
    "cubic": '<path d="M 10 50 C 20 10 60 90 90 40"/>',
    "quadratic": '<path d="M 10 80 Q 50 0 90 80"/>',
    "smooth quadratic": '<path d="M 10 60 Q 25 30 40 60 T 70 60"/>',
    "cusp cubic": '<path d="M 10 10 C 90 90 10 90 90 10"/>',
    "ellipse": '<ellipse cx="50" cy="50" rx="40" ry="12" transform="rotate(30 50 50)"/>',
    "elliptical arc": '<path d="M 20 50 A 30 10 20 1 1 80 50"/>',
}


@pytest.mark.parametrize("tolerance", [0.1, 0.005])
@pytest.mark.parametrize("name", sorted(CURVES))
def test_curves_are_within_the_tolerance_both_ways(name, tolerance):
    drawing = fed(drawing_of(CURVES[name], tolerance=tolerance))
    segments, scale = svg_segments(CURVES[name])
    assert segments and drawing

    def machine(point):
        return point[0] * scale, 100 - point[1] * scale

    curve = [machine(s.point(i / 2000)) for s in segments for i in range(2001)]
    # every point of the curve is near the approximation ...
    worst = max(min(item.distance(p) for item in drawing) for p in curve[::4])
    assert worst <= tolerance
    # ... and every point of the approximation is near the curve (its dense polyline)
    samples = numpy.array([item.point(i / 20) for item in drawing for i in range(21)])
    assert polyline_distances(samples, numpy.array(curve)).max() <= tolerance
    # and the pieces join up
    assert all(close(a.end, b.start, 1e-9) for a, b in zip(drawing, drawing[1:]))


def test_a_tighter_tolerance_takes_more_pieces():
    counts = [len(fed(drawing_of(CURVES["cubic"], tolerance=t))) for t in (0.1, 0.01, 0.001)]
    assert counts[0] < counts[1] < counts[2]


def test_subpaths_start_with_a_rapid_move():
    drawing = drawing_of('<path d="M 10 10 L 20 10 M 30 10 L 40 10"/>')
    assert [item.rapid for item in drawing] == [True, False, True, False]


def test_text_is_refused_with_its_element():
    with pytest.raises(ProgramError, match=r"^t\.svg#words: text is not drawn"):
        drawing_of('<text id="words" x="10" y="10">hello</text>')


def test_unreadable_file_is_one_error():
    with pytest.raises(ProgramError, match="cannot read the SVG"):
        parse(io.StringIO("<svg"), name="t.svg")
