"""Seeded random encoder waveforms for the encoder units' benches, one ``Sample`` a clock.

``encoder_waves(rng, clocks)``: quadrature walks with reversals at every
spacing the filter passes (down to ENC_FILTER + 1 clocks), glitches of
1 .. ENC_FILTER clocks inside the holds (which the filter must remove),
illegal samples (A and B together), pure noise, step/dir stretches, index
pulses, and the host's writes (filter, polarity, mode, INDEX_ZERO,
INDEX_ARM, QUAD_ERROR's clear); ``Walk`` is the waveform's state.
``sim/card/encoder_bench.py`` drives the units with them.
"""
from dataclasses import dataclass, field

from models.encoder_model import FILTER_MAX, GRAY, MODE_QUADRATURE, MODE_STEP_DIR

FILTERS = (0, 0, 1, 2, 3, 7, FILTER_MAX)   # the smallest filter most often: the closest spacing


@dataclass
class Sample:
    """One clock of stimulus: the pins and the host's writes in it (``settings``:
    register values from this clock on; ``strobes``: names of one-clock writes)."""
    a: int
    b: int
    index: int
    settings: dict = field(default_factory=dict)
    strobes: tuple = ()


class Walk:
    """The waveform's state: the encoder's phase, the walk's position (legal
    edges only) and the settings in force."""

    def __init__(self, rng):
        self.rng = rng
        self.phase, self.position, self.index = 0, 0, 0
        self.a, self.b = 0, 0
        self.filter, self.mode, self.legal_only = 2, MODE_QUADRATURE, True
        self.pending = {}

    def sample(self, a=None, b=None):
        """The next clock: the pins (A, B as given, else as they are), the index
        toggling now and then, the strobes at random, the settings pending."""
        if a is not None:
            self.a, self.b = a, b
        if self.rng.random() < 0.01:
            self.index ^= 1
        chosen = []
        if self.rng.random() < 0.01:
            chosen.append("arm")
        if self.rng.random() < 0.005:
            chosen.append("clear_error")
        settings, self.pending = self.pending, {}
        return Sample(self.a, self.b, self.index, settings, tuple(chosen))

    def hold(self, clocks, glitch=True):
        """Hold the pins ``clocks`` clocks; with room, a glitch the filter removes in the middle."""
        width = self.rng.randint(1, self.filter) if self.filter else 0
        if glitch and width and clocks >= 2 * (self.filter + 1) + width and self.rng.random() < 0.5:
            before = self.filter + 1
            for _ in range(before):
                yield self.sample()
            pin = self.rng.choice("ab")
            steady = (self.a, self.b)
            for _ in range(width):
                yield self.sample(self.a ^ (pin == "a"), self.b ^ (pin == "b"))
                self.a, self.b = steady
            for _ in range(clocks - before - width):
                yield self.sample()
            return
        for _ in range(clocks):
            yield self.sample()


def _spacing(walk):
    """Clocks between edges: the closest the filter passes, often."""
    closest = walk.filter + 1
    return closest if walk.rng.random() < 0.5 else closest + walk.rng.randrange(1, 3 * closest + 4)


def _quadrature(walk, edges):
    for _ in range(edges):
        move = walk.rng.choice((1, 1, -1))
        walk.phase, walk.position = (walk.phase + move) % 4, walk.position + move
        walk.a, walk.b = GRAY[walk.phase]
        yield from walk.hold(_spacing(walk))


def _illegal(walk, count):
    walk.legal_only = False
    for _ in range(count):
        walk.phase = (walk.phase + 2) % 4
        walk.a, walk.b = GRAY[walk.phase]
        yield from walk.hold(_spacing(walk), glitch=False)


def _noise(walk, clocks):
    walk.legal_only = False
    for _ in range(clocks):
        yield walk.sample(walk.rng.randrange(2), walk.rng.randrange(2))
    walk.phase = GRAY.index((walk.a, walk.b))


def _step_dir(walk, pulses):
    walk.legal_only = False
    for _ in range(pulses):
        direction = walk.b if walk.rng.random() < 0.7 else 1 - walk.b
        walk.a, walk.b = 0, direction
        yield from walk.hold(_spacing(walk))
        walk.a = 1
        yield from walk.hold(_spacing(walk))
    walk.phase = GRAY.index((walk.a, walk.b))


def encoder_waves(rng, clocks, kinds=("walk", "walk", "walk", "illegal", "noise", "step_dir"), host=True):
    """About ``clocks`` Samples of a random encoder waveform (module
    docstring), in segments of the ``kinds`` named, each with its
    ``Walk``; ``Walk.legal_only`` stays True while only legal quadrature
    walks were made.  Without ``host`` the polarity stays 0 and INDEX_ZERO
    off (the count then is the walk's position)."""
    walk = Walk(rng)
    made = 0
    while made < clocks:
        kind = rng.choice(kinds)
        # the last edge through the filter first: an edge in flight while the
        # setting changes may be taken out of order with the next (docs/encoders.md)
        for sample in walk.hold(walk.filter + 4, glitch=False):
            made += 1
            yield sample, walk
        walk.filter = rng.choice(FILTERS)
        mode = MODE_STEP_DIR if kind == "step_dir" else MODE_QUADRATURE
        walk.pending = dict(filter=walk.filter, mode=mode, index_zero=host and rng.random() < 0.3)
        if host and rng.random() < 0.1:
            walk.pending["polarity"] = rng.randrange(8)
            walk.legal_only = False
        if mode != walk.mode:
            walk.legal_only = False
            walk.mode = mode
        segment = {"walk": lambda: _quadrature(walk, rng.randrange(5, 40)),
                   "illegal": lambda: _illegal(walk, rng.randrange(1, 4)),
                   "noise": lambda: _noise(walk, rng.randrange(5, 30)),
                   "step_dir": lambda: _step_dir(walk, rng.randrange(3, 12))}[kind]()
        for sample in segment:
            made += 1
            yield sample, walk
    # the pipeline emptied: the last edge counted
    for _ in range(FILTER_MAX + 6):
        yield walk.sample(), walk
