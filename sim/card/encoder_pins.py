"""The encoder pins of a simulated card built with encoders, driven on cue (the card server's
``--encoder-walk``, ``--encoder-pulses``, ``--encoder-glitch``, ``--index`` and ``--probe``): a walk of
an axis's A and B by a number of counts, one legal quadrature step every ``spacing`` clocks; a train of
step/dir pulses (B the direction, then A low and high ``spacing`` clocks each, once a pulse: what the
card counts in its step/dir mode, hostmot2's counter mode); a quadrature error (A and B change in the
same clock); index pulses and probe pulses, each at a card clock.  The LinuxCNC driver's tests read
them back as counts, latches, velocities and quadrature errors (docs/linuxcnc.md).

A cue is ``AXIS@CLOCK:VALUE``: AXIS 0 .. axes - 1 (X, Y, Z, ...), CLOCK the card clock since the
server opened the card, VALUE the counts of a walk or the pulses of a train (negative: backwards) or
an index pulse's width in clocks; a glitch cue is ``AXIS@CLOCK``, a probe cue ``CLOCK:WIDTH``.
``play`` clocks the golden encoder model (models/encoder_model.py) through the cues' pin changes.
"""
# (A, B) forwards, A leading B: each step along counts +1, each step back -1 (docs/encoders.md)
PHASES = ((0, 0), (1, 0), (1, 1), (0, 1))
AXIS_LETTERS = "xyzabc"
# clocks between a walk's edges: more than the 15 of the LinuxCNC driver's filter (hostmot2's), and
# no divisor of a 1 ms period at 1 MHz, so the counts of a period vary (33 or 34) while the edges do not
WALK_SPACING = 30


def parse_probe(text):
    """(clock, width) of ``CLOCK:WIDTH``; ValueError says what is wrong."""
    clock, _, width = text.partition(":")
    try:
        clock, width = int(clock), int(width)
    except ValueError:
        raise ValueError(f"{text!r} is not CLOCK:WIDTH (two integers)") from None
    if clock < 0:
        raise ValueError(f"{text!r}: the clock is a card clock since the server opened the card, not negative")
    return clock, width


def _axis_clock(text, where, axes, form):
    """(axis, clock) of ``where`` (``AXIS@CLOCK``), a part of cue ``text`` of the form ``form``."""
    axis, _, clock = where.partition("@")
    try:
        axis, clock = int(axis), int(clock)
    except ValueError:
        raise ValueError(f"{text!r} is not {form} (integers)") from None
    if not 0 <= axis < axes:
        raise ValueError(f"{text!r}: axis {axis} is not one of the card's 0..{axes - 1}")
    if clock < 0:
        raise ValueError(f"{text!r}: the clock is a card clock since the server opened the card, not negative")
    return axis, clock


def parse_cue(text, axes):
    """(axis, clock, value) of ``AXIS@CLOCK:VALUE``; ValueError says what is wrong."""
    where, _, value = text.partition(":")
    try:
        value = int(value)
    except ValueError:
        raise ValueError(f"{text!r} is not AXIS@CLOCK:VALUE (three integers)") from None
    return (*_axis_clock(text, where, axes, "AXIS@CLOCK:VALUE"), value)


def parse_glitch(text, axes):
    """(axis, clock) of ``AXIS@CLOCK``; ValueError says what is wrong."""
    return _axis_clock(text, text, axes, "AXIS@CLOCK")


class EncoderPins:
    """The pin changes of every cue given, in card clocks: ``due(deadline)`` hands out (and forgets)
    those at or before ``deadline`` in order, each (clock, pin name, level) with the card's pin names
    (``enc_a_x``, ``enc_index_y``, ...)."""

    def __init__(self, axes):
        self.axes = axes
        self.levels = [(0, 0)] * axes   # each axis's (A, B) after the cues given so far
        self.events = []

    def _set(self, axis, clock, a, b):
        """Axis ``axis``'s A and B to ``a`` and ``b`` at ``clock`` (only the pins that change)."""
        letter, (was_a, was_b) = AXIS_LETTERS[axis], self.levels[axis]
        self.events += [(clock, f"enc_{pin}_{letter}", level)
                        for pin, level, was in (("a", a, was_a), ("b", b, was_b)) if level != was]
        self.levels[axis] = (a, b)

    def cue(self, walks=(), pulses=(), glitches=()):
        """Walks and pulse trains ((axis, clock, counts) each) and glitches ((axis, clock)) of A and B,
        taken in the order of their clocks: each one starts from the levels the one before left."""
        cues = [(clock, self.walk, (axis, clock, counts)) for axis, clock, counts in walks]
        cues += [(clock, self.pulses, (axis, clock, counts)) for axis, clock, counts in pulses]
        cues += [(clock, self.glitch, (axis, clock)) for axis, clock in glitches]
        for _, act, arguments in sorted(cues, key=lambda cue: cue[0]):
            act(*arguments)

    def walk(self, axis, clock, counts, spacing=WALK_SPACING):
        """``counts`` legal steps of axis ``axis``'s A/B from ``clock`` on, one every ``spacing`` clocks
        (walks of one axis given in the order of their clocks, not overlapping)."""
        step = 1 if counts > 0 else -1
        for k in range(abs(counts)):
            phase = (PHASES.index(self.levels[axis]) + step) % len(PHASES)
            self._set(axis, clock + k * spacing, *PHASES[phase])

    def pulses(self, axis, clock, counts, spacing=WALK_SPACING):
        """``abs(counts)`` step/dir pulses of axis ``axis`` from ``clock`` on: B the direction at ``clock``
        (1 up, 0 down), then for each pulse A low ``spacing`` clocks, then high ``spacing`` clocks (a
        rising edge of A every 2 * ``spacing`` clocks, the first ``2 * spacing`` after ``clock``).  A is
        high after the train; a train that starts with A high lowers it ``spacing`` after ``clock``."""
        a = self.levels[axis][0]
        self._set(axis, clock, a, 1 if counts > 0 else 0)
        for k in range(abs(counts)):
            self._set(axis, clock + (2 * k + 1) * spacing, 0, self.levels[axis][1])
            self._set(axis, clock + (2 * k + 2) * spacing, 1, self.levels[axis][1])

    def glitch(self, axis, clock):
        """Axis ``axis``'s A and B both change at ``clock``: a quadrature error (two phases skipped)."""
        a, b = self.levels[axis]
        self._set(axis, clock, 1 - a, 1 - b)

    def pulse(self, axis, clock, width):
        """Axis ``axis``'s index high from ``clock`` for ``width`` clocks."""
        if width < 1:
            raise ValueError(f"an index pulse of {width} clocks: give 1 or more")
        name = f"enc_index_{AXIS_LETTERS[axis]}"
        self.events += [(clock, name, 1), (clock + width, name, 0)]

    def probe(self, clock, width):
        """The card's probe input high from ``clock`` for ``width`` clocks."""
        if width < 1:
            raise ValueError(f"a probe pulse of {width} clocks: give 1 or more")
        self.events += [(clock, "probe", 1), (clock + width, "probe", 0)]

    def due(self, deadline):
        self.events.sort(key=lambda event: event[0])
        count = next((k for k, event in enumerate(self.events) if event[0] > deadline), len(self.events))
        due, self.events = self.events[:count], self.events[count:]
        return due


def play(events, axis, clocks, model, arm_at=None):
    """Clock ``model`` (a models.encoder_model.EncoderModel: axis ``axis``'s encoder) through card clocks
    0 .. ``clocks`` of ``events`` (``EncoderPins.due``'s: (clock, pin name, level), in order), the index
    armed at clock ``arm_at``: what the card's encoder counts from those pins."""
    letter = AXIS_LETTERS[axis]
    level = {"a": 0, "b": 0, "index": 0}
    mine = [event for event in events if event[1].endswith(f"_{letter}")]
    for clock in range(clocks + 1):
        while mine and mine[0][0] == clock:
            _, name, value = mine.pop(0)
            level[name[len("enc_"):-2]] = value
        if clock == arm_at:
            model.arm_index()
        model.clock(level["a"], level["b"], level["index"])
