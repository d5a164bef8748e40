"""Golden model of one axis's encoder input, clock by clock (docs/encoders.md).

Written from the rules in docs/encoders.md, for an RTL bench to compare
every clock (the card's RTL is not built yet):

* ``InputConditioner``: one input's two-flip-flop synchroniser, polarity and
  filter: a level is taken once the synchronised input has shown it
  ``filter`` + 1 clocks in a row (``filter`` 0 .. 15, a 4-bit run count).
* ``quadrature_delta``: the 4x decoder's rule for one sample of A and B.
* ``EncoderModel``: A, B and index conditioned, the decoder (quadrature or
  step/dir), the 32-bit count, the quadrature-error flag and counter, the
  time stamp of the last count edge, the index latch and the following
  error with its stop flag.
* ``ProbeModel``: the card's one probe input, latching every axis's count
  and step position at its edge.

Each ``clock`` is one rising edge: the pins as they were in the clock before
it, and the card's step position (POS) as it was then.  Every register's
next value comes from the registers' values before the edge, so the stages
are one clock apart: a pin that changes in the clock before edge e is in the
synchroniser's second flip-flop after e + 1, taken by the filter after
e + 2 + filter and counted at edge e + 3 + filter: at the (4 + filter)th
edge from the change (``pin_to_count``); it is in the following error one
edge later and in the stop flag two (``FERROR_CLOCKS``).
"""
COUNT_BITS = 32                 # ENC_COUNT, ENC_INDEX_LATCH, TIMESTAMP, ENC_TIME, ENC_FERROR: 32-bit words
MASK32 = (1 << COUNT_BITS) - 1
FILTER_BITS = 4                 # ENC_FILTER and the filter's run count
FILTER_MAX = (1 << FILTER_BITS) - 1
FILTER_RESET = 2
ERROR_COUNT_BITS = 8
ERROR_COUNT_MAX = (1 << ERROR_COUNT_BITS) - 1   # the quadrature-error counter saturates here
SCALE_BITS, SCALE_FRACTION_BITS = 32, 16        # ENC_SCALE: counts per step, unsigned 16.16
SCALE_MAX = (1 << SCALE_BITS) - 1
LIMIT_BITS = 32                 # FERROR_LIMIT, counts, unsigned (0: off)
MODE_QUADRATURE, MODE_STEP_DIR = 0, 1
POLARITY_A, POLARITY_B, POLARITY_INDEX = 1, 2, 4   # ENC_POLARITY's bits: 1 inverts that input
POLARITY_BITS = 3
GRAY = ((0, 0), (1, 0), (1, 1), (0, 1))            # (A, B) at phases 0..3; counting up goes 0, 1, 2, 3, 0
FERROR_CLOCKS = 2               # count to stop flag: the error's register, then the flag's


def pin_to_count(filter_setting):
    """Which rising edge after a pin's change (the first is 1) counts it."""
    return 4 + filter_setting


def signed32(value):
    """The 32-bit word ``value`` read as two's complement."""
    value &= MASK32
    return value - (1 << 32) if value >> 31 else value


def scaled_steps(steps, scale):
    """round(steps * scale / 2**16), half rounding up (towards +infinity):
    floor(steps * scale / 2**16 + 1/2), modulo 2**32."""
    return ((steps * scale + (1 << (SCALE_FRACTION_BITS - 1))) >> SCALE_FRACTION_BITS) & MASK32


def quadrature_delta(before, after):
    """The count's change for a sample of (A, B) ``after`` following ``before``:
    +1 one phase up the Gray code (A leads B), -1 one phase down, 0 no change;
    None when A and B both changed (an illegal transition, not counted)."""
    step = (GRAY.index(tuple(after)) - GRAY.index(tuple(before))) % 4
    return (0, 1, None, -1)[step]


class InputConditioner:
    """One input: two flip-flops (``pipe``), the polarity, then the filter.

    ``level`` is the filtered level; ``run`` counts the clocks in a row the
    synchronised input has differed from it.  At an edge where the input
    (after polarity) differs from ``level`` and ``run`` has reached the
    setting, ``level`` takes it and ``run`` returns to 0; one clock at
    ``level`` returns ``run`` to 0.  So a glitch of w clocks is rejected iff
    w <= setting, and a level that stays setting + 1 clocks is taken.
    """

    def __init__(self):
        self.pipe = [0, 0]
        self.level = 0
        self.run = 0

    def clock(self, pin, invert, setting):
        seen = self.pipe[1] ^ int(bool(invert))
        if seen == self.level:
            self.run = 0
        elif self.run >= setting:
            self.level, self.run = seen, 0
        else:
            self.run += 1
        self.pipe = [int(bool(pin)), self.pipe[0]]


class EncoderModel:
    """One axis's encoder input (module docstring; docs/encoders.md).

    Registers the host writes are attributes (``filter``, ``polarity``,
    ``mode``, ``index_zero``, ``limit``) or methods (``arm_index``,
    ``clear_quad_error``, ``set_scale``, ``align``, ``clear_stop``); a method
    call stands for a write at the edge before the next ``clock``.
    """

    def __init__(self):
        self.inputs = [InputConditioner() for _ in range(3)]   # A, B, index
        self.seen = (0, 0, 0)    # the filtered A, B, index as the decoder saw them a clock ago
        self.filter, self.polarity, self.mode = FILTER_RESET, 0, MODE_QUADRATURE
        self.index_zero, self.scale, self.limit = False, 0, 0
        self.count, self.direction = 0, 1
        self.quad_error, self.error_count = False, 0
        self.timestamp, self.time = 0, 0
        self.index_armed, self.index_latch, self.index_fired = False, 0, False
        self.count_origin, self.pos_origin = 0, 0
        self.ferror, self.stop = 0, False

    # host writes
    def arm_index(self):
        self.index_armed = True

    def clear_quad_error(self):
        """QUAD_ERROR is write-1-to-clear; the write clears the error counter too."""
        self.quad_error, self.error_count = False, 0

    def align(self, pos):
        """Re-align the following error: from here on the count and ``pos``
        (the step position now) are taken as agreeing, and the error reads 0."""
        self.count_origin, self.pos_origin = self.count, pos
        self.ferror = 0

    def set_scale(self, scale, pos):
        if not 0 <= scale <= SCALE_MAX:
            raise ValueError(f"ENC_SCALE {scale} outside 0 .. {SCALE_MAX}")
        self.scale = scale
        self.align(pos)

    def clear_stop(self):
        self.stop = False

    def error(self, pos):
        """The following error for the count now and step position ``pos``:
        (count - count_origin) - round((pos - pos_origin) * scale), signed 32 bits."""
        steps = signed32(pos - self.pos_origin)
        return signed32(self.count - self.count_origin - scaled_steps(steps, self.scale))

    def _decode(self, levels):
        """The count's change for this sample; None: an illegal transition."""
        if self.mode == MODE_STEP_DIR:
            rose = levels[0] and not self.seen[0]
            return (1 if levels[1] else -1) if rose else 0
        return quadrature_delta(self.seen[:2], levels[:2])

    def clock(self, a, b, index, pos=0):
        """One rising edge: the pins and the step position as they were in the clock before it."""
        if not 0 <= self.filter <= FILTER_MAX:
            raise ValueError(f"ENC_FILTER {self.filter} outside 0 .. {FILTER_MAX}")
        levels = tuple(conditioner.level for conditioner in self.inputs)
        delta = self._decode(levels)
        self.index_fired = self.index_armed and levels[2] and not self.seen[2]
        stop_now = self.limit and abs(self.ferror) > self.limit
        self.ferror = self.error(pos)
        self.stop = self.stop or bool(stop_now)
        self.timestamp = (self.timestamp + 1) & MASK32
        if delta is None:
            self.quad_error = True
            self.error_count = min(self.error_count + 1, ERROR_COUNT_MAX)
            delta = 0
        if self.index_fired:
            self.index_latch, self.index_armed = self.count, False
            if self.index_zero:
                self.count, self.count_origin, self.pos_origin = 0, 0, pos
        if delta:
            self.count = (self.count + delta) & MASK32
            self.direction = int(delta > 0)
            self.time = self.timestamp
        for conditioner, pin, bit in zip(self.inputs, (a, b, index), (POLARITY_A, POLARITY_B, POLARITY_INDEX)):
            conditioner.clock(pin, self.polarity & bit, self.filter)
        self.seen = levels

    @property
    def signed_count(self):
        return signed32(self.count)


class ProbeModel:
    """The card's probe input: conditioned as an encoder input (its own
    ``filter`` and ``invert``); armed by ``arm``, the first sample in which
    the filtered probe rises latches every axis's ENC_COUNT (as it was
    before that sample, as the index latch) into ``counts`` and the step
    positions into ``positions``, once, and disarms.  Call ``clock`` before
    the encoders' ``clock`` of the same edge."""

    def __init__(self):
        self.input = InputConditioner()
        self.seen = 0
        self.filter, self.invert = FILTER_RESET, False
        self.armed, self.fired = False, False
        self.counts, self.positions = (), ()

    def arm(self):
        self.armed = True

    def clock(self, pin, encoders, positions):
        """One rising edge: the pin and the axes' POS as they were in the clock before it."""
        level = self.input.level
        self.fired = bool(self.armed and level and not self.seen)
        if self.fired:
            self.counts = tuple(encoder.count for encoder in encoders)
            self.positions, self.armed = tuple(positions), False
        self.input.clock(pin, self.invert, self.filter)
        self.seen = level
