"""What the planner needs to know about the machine and the card.

Lengths in millimetres, feeds in mm/min, acceleration in mm/s^2.  The card's
clock frequency and coordinate width are build parameters: the card API
reads them from the capability registers (``Card.configure`` returns the
``Machine``); ``python -m host plan`` takes them as options.

The machine's axes are the card's first ones, X, Y, Z, A, B, C in that order
(``models/axes.py``), one entry of ``steps_per_mm`` each: steps per mm of
a linear axis (X, Y, Z), steps per degree of a rotary one (A, B, C).
"""
import math
from dataclasses import dataclass

from models.axes import MAX_AXES, XY, names
from models.registers import RATE_MAX, RATE_ONE

DEFAULT_CLOCK_HZ = 33_000_000
DEFAULT_COORD_WIDTH = 24  # rtl.top's default


@dataclass(frozen=True)
class Machine:
    steps_per_mm: tuple = (200.0, 200.0)   # X, Y (, Z, A, B, C): per mm, per degree for A, B, C
    clock_hz: float = DEFAULT_CLOCK_HZ
    coord_width: int = DEFAULT_COORD_WIDTH
    rapid: float = 3000.0        # mm/min for G0 and pen-up moves
    acceleration: float = 500.0  # mm/s^2, at the top of each ramp
    start_feed: float = 60.0     # mm/min: the speed a move starts and stops with
    chord_tolerance: float = 0.002  # mm: arcs as chords when the axes' scales differ
    mark_interval: int = 256     # words between MARK tags (placed at stops)

    def __post_init__(self):
        checks = (
            (2 <= len(self.steps_per_mm) <= MAX_AXES, f"steps per mm are given for 2..{MAX_AXES} axes, "
             f"not {len(self.steps_per_mm)}"),
            (all(k > 0 for k in self.steps_per_mm), "steps per mm must be positive"),
            (self.clock_hz > 0, "the clock frequency must be positive"),
            (8 <= self.coord_width <= 32, "the coordinate width must be 8..32 bits"),
            (self.rapid > 0, "the rapid feed must be positive"),
            (self.acceleration > 0, "the acceleration must be positive"),
            (self.start_feed > 0, "the start feed must be positive"),
            (self.chord_tolerance > 0, "the chord tolerance must be positive"),
            (self.mark_interval > 0, "the MARK interval must be positive"),
        )
        for ok, message in checks:
            if not ok:
                raise ValueError(message)

    @property
    def axes(self):
        """The number of axes (X, Y, ... in order)."""
        return len(self.steps_per_mm)

    @property
    def axis_names(self):
        return names(range(self.axes))

    def square_plane(self, plane):
        """The plane's two axes have the same scale: circles in it stay circles in steps."""
        return self.steps_per_mm[plane[0]] == self.steps_per_mm[plane[1]]

    @property
    def square(self):
        """X and Y have the same scale."""
        return self.square_plane(XY)

    @property
    def coord_limit(self):
        """Largest coordinate magnitude a LINE or ARC operand may have."""
        return (1 << (self.coord_width - 1)) - 1

    def steps(self, point):
        """``point`` (mm) to the nearest step on each axis (halves round up)."""
        return tuple(math.floor(v * k + 0.5) for v, k in zip(point, self.steps_per_mm))

    def mm(self, point):
        """A step position in mm."""
        return tuple(v / k for v, k in zip(point, self.steps_per_mm))

    def rate_units(self, iterations_per_second):
        """FEED_RATE units (iterations per clock times 65536), unclamped, unrounded."""
        return iterations_per_second / self.clock_hz * RATE_ONE

    def rate_register(self, iterations_per_second):
        """The FEED_RATE / RAMP_START value nearest to ``iterations_per_second`` (1..RATE_MAX)."""
        return max(1, min(RATE_MAX, round(self.rate_units(iterations_per_second))))

    def iterations_per_second(self, rate):
        return rate * self.clock_hz / RATE_ONE

    def dwell_clocks(self, seconds):
        return round(seconds * self.clock_hz)
