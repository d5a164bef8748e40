"""The encoder pins of a simulated card built with encoders, driven on cue (the card server's
``--encoder-walk`` and ``--index``): a walk of an axis's A and B by a number of counts, one legal
quadrature step every ``spacing`` clocks, index pulses and probe pulses, each at a card clock.  The LinuxCNC
driver's tests read them back as counts, latches and velocities (docs/linuxcnc.md).

A cue is ``AXIS@CLOCK:VALUE``: AXIS 0 .. axes - 1 (X, Y, Z, ...), CLOCK the card clock since the
server opened the card, VALUE the counts of a walk (negative: backwards) or an index pulse's width
in clocks (a probe cue is ``CLOCK:WIDTH``).
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


def parse_cue(text, axes):
    """(axis, clock, value) of ``AXIS@CLOCK:VALUE``; ValueError says what is wrong."""
    where, _, value = text.partition(":")
    axis, _, clock = where.partition("@")
    try:
        axis, clock, value = int(axis), int(clock), int(value)
    except ValueError:
        raise ValueError(f"{text!r} is not AXIS@CLOCK:VALUE (three integers)") from None
    if not 0 <= axis < axes:
        raise ValueError(f"{text!r}: axis {axis} is not one of the card's 0..{axes - 1}")
    if clock < 0:
        raise ValueError(f"{text!r}: the clock is a card clock since the server opened the card, not negative")
    return axis, clock, value


class EncoderPins:
    """The pin changes of every cue given, in card clocks: ``due(deadline)`` hands out (and forgets)
    those at or before ``deadline`` in order, each (clock, pin name, level) with the card's pin names
    (``enc_a_x``, ``enc_index_y``, ...)."""

    def __init__(self, axes):
        self.axes = axes
        self.phase = [0] * axes
        self.events = []

    def walk(self, axis, clock, counts, spacing=WALK_SPACING):
        """``counts`` legal steps of axis ``axis``'s A/B from ``clock`` on, one every ``spacing`` clocks
        (walks of one axis given in the order of their clocks, not overlapping)."""
        letter, step = AXIS_LETTERS[axis], 1 if counts > 0 else -1
        for k in range(abs(counts)):
            self.phase[axis] = (self.phase[axis] + step) % len(PHASES)
            a, b = PHASES[self.phase[axis]]
            at = clock + k * spacing
            self.events += [(at, f"enc_a_{letter}", a), (at, f"enc_b_{letter}", b)]

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
