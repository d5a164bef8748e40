"""A motor with an incremental encoder: STEP/DIR in, A/B/index out (docs/encoders.md, docs/machine.md).

``MotorModel`` takes the card's STEP, DIR and DRIVE_ENABLE pins as they are
after a rising edge, clock by clock, like ``models/sim_machine.SimMachine``
(whose motors, ``Motor`` in its ``MachineConfig``, are these):

* a STEP rise moves the motor one step (forward when DIR is ``dir_positive``)
  if DRIVE_ENABLE is high and the motor is not ``stalled``; otherwise the step
  is lost (``lost`` counts them): a stalled motor stops turning, its encoder
  stops, the steps go on;
* the shaft follows ``lag`` clocks later: its target in encoder counts is
  round(steps * ``counts_per_step`` / ``denominator``) as ``lag`` clocks
  before, halves rounding up (towards +infinity), modulo 2**32 read as
  signed: with the default ``denominator`` 2**16, the rounding of
  ``models.encoder_model.scaled_steps``, so with no lag an encoder scaled by
  the same ENC_SCALE reads no following error once the shaft is there;
* the encoder walks one count at a time towards the target, at most one count
  every ``spacing`` clocks (``spacing`` >= ENC_FILTER + 1 for the card to
  count them all), plus, with ``jitter``, 0 .. ``jitter`` more clocks drawn
  after each count from a 32-bit xorshift generator (13, 17, 5) seeded with
  ``seed`` (0 is taken as 1): ``next() % (jitter + 1)``;
* A and B are the Gray code of ``models.encoder_model.GRAY`` at the count
  (A leads B forwards; count 0 is A = B = 0); ``index`` is high while the
  count is a multiple of ``index_period`` (0: no index).

Per clock, in this order: the step, the target from the history, the walk,
the pins for the next rising edge.
"""
from collections import deque

from models.encoder_model import GRAY, SCALE_FRACTION_BITS, signed32

MASK32 = 0xFFFFFFFF


def xorshift32(state):
    """The next state of the 32-bit xorshift generator (13, 17, 5) after ``state`` (not 0)."""
    state ^= (state << 13) & MASK32
    state ^= state >> 17
    return state ^ ((state << 5) & MASK32)


def round_ratio(steps, numerator, denominator):
    """round(steps * numerator / denominator), halves up: floor(x + 1/2)."""
    return (2 * steps * numerator + denominator) // (2 * denominator)


class MotorModel:
    def __init__(self, counts_per_step=4 << SCALE_FRACTION_BITS, lag=0, spacing=4,
                 index_period=0, dir_positive=True, *, denominator=1 << SCALE_FRACTION_BITS,
                 jitter=0, seed=1):
        if lag < 0 or spacing < 1 or index_period < 0 or counts_per_step < 0 or denominator < 1 or jitter < 0:
            raise ValueError("lag, index_period and jitter must not be negative, spacing and denominator at "
                             "least 1, counts_per_step not negative")
        self.counts_per_step, self.denominator = counts_per_step, denominator
        self.spacing, self.jitter = spacing, jitter
        self.index_period, self.dir_positive = index_period, dir_positive
        self.steps, self.lost, self.counts = 0, 0, 0
        self.stalled = False
        self._history = deque([0] * lag)   # the step position of the last ``lag`` clocks, oldest first
        self._step = False
        self._wait = 0
        self._state = (seed & MASK32) or 1

    def _draw(self):
        self._state = xorshift32(self._state)
        return self._state % (self.jitter + 1)

    def clock(self, step, direction, drive_enable=True):
        """One clock; returns the pins (A, B, index) for the next rising edge."""
        rose = bool(step) and not self._step
        self._step = bool(step)
        if rose and drive_enable and not self.stalled:
            self.steps += 1 if bool(direction) == self.dir_positive else -1
        elif rose:
            self.lost += 1
        self._history.append(self.steps)
        target = signed32(round_ratio(self._history.popleft(), self.counts_per_step, self.denominator))
        if self._wait:
            self._wait -= 1
        elif target != self.counts:
            self.counts += 1 if target > self.counts else -1
            self._wait = self.spacing - 1 + (self._draw() if self.jitter else 0)
        return self.pins

    @property
    def pins(self):
        a, b = GRAY[self.counts % 4]
        index = bool(self.index_period) and self.counts % self.index_period == 0
        return a, b, int(index)
