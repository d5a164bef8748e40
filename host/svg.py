"""SVG front end (``svgelements``): a plotter drawing -> ``geometry`` primitives in mm.

* Every shape is drawn: path, line, polyline, polygon, rect (rounded corners
  too), circle, ellipse, with its transforms and the document's units and
  viewBox (``svgelements`` resolves them into pixels at 96 per inch; here
  1 px = 25.4 / 96 mm, or svgelements' own mm size for a document sized in
  mm or cm, so that its millimetres stay exact).
* Machine coordinates: y up, so ``y_machine = height - y_svg`` (the page's
  lower left corner is the origin).
* Straight segments are lines; circular arcs (equal radii after the
  transforms) are arcs; elliptical arcs and quadratic and cubic Beziers are
  biarcs within the tolerance (``host.curves``, error measured).
* Pen up / pen down: the move to the start of each subpath is a rapid move
  (pen up), everything drawn is a feed move (pen down); there is no pen
  command, the card drives X and Y only.
* Text and images are refused: convert them to paths first.
"""
import math

import svgelements as svg

from host.curves import approximate
from host.errors import ProgramError
from host.geometry import SAME_POINT, Arc, Line

MM_PER_PX = 25.4 / 96
# svgelements turns mm and cm into pixels with 0.0393701 in/mm (1/25.4 rounded, 5.4 ppm
# long); for a document sized in mm or cm this undoes that, so its millimetres stay exact
SVGELEMENTS_MM_PER_PX = 1 / (svg.DEFAULT_PPI * 0.0393701)
CIRCULAR = 1e-9  # relative radius difference below which an arc is circular


def parse(source, tolerance=0.01, feed=1200.0, name=None):
    """The primitives of the SVG file ``source`` (a path or file object).

    ``tolerance``: mm between a curve and its arcs; ``feed``: mm/min of the
    drawn (pen-down) moves.
    """
    name = name or str(source)
    if tolerance <= 0:
        raise ValueError("the tolerance must be positive")
    try:
        document = svg.SVG.parse(source)
    except Exception as error:  # svgelements raises whatever its XML parser raises
        raise ProgramError(name, f"cannot read the SVG: {error}") from None
    unit = str(document.values.get("width", "")).strip().lstrip("+-.0123456789eE")
    scale = SVGELEMENTS_MM_PER_PX if unit in ("mm", "cm") else MM_PER_PX
    reader = _Reader((document.height or 0) * scale, scale, tolerance, feed)
    for number, element in enumerate(document.elements()):
        where = f"{name}#{element.id}" if getattr(element, "id", None) else f"{name}: element {number}"
        if isinstance(element, (svg.Text, svg.Image)):
            raise ProgramError(where, f"{type(element).__name__.lower()} is not drawn: convert it to paths")
        if isinstance(element, svg.Shape):
            reader.shape(element, where)
    return reader.drawing


class _Reader:
    def __init__(self, height, scale, tolerance, feed):
        self.height, self.scale, self.tolerance, self.feed = height, scale, tolerance, feed
        self.position = (0.0, 0.0)
        self.drawing = []

    def machine(self, point):
        return point[0] * self.scale, self.height - point[1] * self.scale

    def shape(self, element, where):
        for segment in svg.Path(element).segments():
            if isinstance(segment, svg.Move):
                self.travel(self.machine(segment.end), where)
            elif isinstance(segment, (svg.Line, svg.Close)):
                self.line(segment, where)
            elif isinstance(segment, svg.Arc):
                self.arc(segment, where)
            elif isinstance(segment, (svg.QuadraticBezier, svg.CubicBezier)):
                self.curve(_bezier(segment, self.machine), where)

    def travel(self, point, where):
        if math.dist(point, self.position) > SAME_POINT:
            self.drawing.append(Line(self.position, point, None, where))
        self.position = point

    def draw(self, primitives):
        for item in primitives:
            self.drawing.append(item)
            self.position = item.end

    def line(self, segment, where):
        start, end = self.machine(segment.start), self.machine(segment.end)
        if math.dist(start, end) > SAME_POINT:
            self.draw([Line(self.position, end, self.feed, where)])

    def arc(self, segment, where):
        start, end = self.machine(segment.start), self.machine(segment.end)
        if abs(segment.rx - segment.ry) <= CIRCULAR * max(segment.rx, segment.ry):
            centre = self.machine(segment.center)
            # y flips, so the sense of rotation does too
            self.draw([Arc(self.position, end, centre, segment.sweep < 0, self.feed, where)])
            return
        start_t, sweep = segment.get_start_t(), segment.sweep
        rotation, rx, ry = segment.get_rotation(), segment.rx, segment.ry
        cos_r, sin_r = math.cos(rotation), math.sin(rotation)
        cx, cy = segment.center.x, segment.center.y

        def point(u):
            t = start_t + sweep * u
            x, y = rx * math.cos(t), ry * math.sin(t)
            return self.machine((cx + x * cos_r - y * sin_r, cy + x * sin_r + y * cos_r))

        def derivative(u):
            t = start_t + sweep * u
            x, y = -rx * math.sin(t) * sweep, ry * math.cos(t) * sweep
            return (x * cos_r - y * sin_r) * self.scale, -(x * sin_r + y * cos_r) * self.scale

        if math.dist(point(0), start) > 1e-6 or math.dist(point(1), end) > 1e-6:
            raise ProgramError(where, "elliptical arc does not meet its end points")
        self.curve((point, derivative), where)

    def curve(self, functions, where):
        point, derivative = functions
        pieces = approximate(point, derivative, self.tolerance, self.feed, where)
        self.draw(pieces)


def _bezier(segment, machine):
    """(point, derivative) of a quadratic or cubic Bezier in machine mm."""
    if isinstance(segment, svg.QuadraticBezier):
        controls = [segment.start, segment.control, segment.end]
    else:
        controls = [segment.start, segment.control1, segment.control2, segment.end]
    controls = [machine(p) for p in controls]
    degree = len(controls) - 1

    def point(u):
        return _de_casteljau(controls, u)

    def derivative(u):
        hodograph = [(degree * (b[0] - a[0]), degree * (b[1] - a[1])) for a, b in zip(controls, controls[1:])]
        return _de_casteljau(hodograph, u)

    return point, derivative


def _de_casteljau(points, u):
    while len(points) > 1:
        points = [(a[0] + (b[0] - a[0]) * u, a[1] + (b[1] - a[1]) * u) for a, b in zip(points, points[1:])]
    return points[0]
