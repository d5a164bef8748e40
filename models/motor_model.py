"""A motor with an incremental encoder, for benches: STEP/DIR in, A/B/index out (docs/encoders.md).

``MotorModel`` takes the card's STEP, DIR and DRIVE_ENABLE pins as they are
after a rising edge, clock by clock, like ``models/sim_machine.SimMachine``:

* a STEP rise moves the motor one step (forward when DIR is ``dir_positive``)
  if DRIVE_ENABLE is high and the motor is not ``stalled``; otherwise the step
  is lost (``lost`` counts them);
* the shaft follows ``lag`` clocks later: its target in encoder counts is
  round(steps * ``counts_per_step`` / 2**16) as ``lag`` clocks before, the
  rounding of ``models.encoder_model.scaled_steps`` (so with no lag an encoder
  scaled by the same ratio reads no following error once the shaft is there);
* the encoder walks one count at a time towards the target, at most one
  count every ``spacing`` clocks (``spacing`` >= ENC_FILTER + 1 for the card to
  count them all), A and B the Gray code of ``models.encoder_model.GRAY``
  (A leads B forwards); ``index`` is high while the count is a multiple of
  ``index_period`` (0: no index).
"""
from collections import deque

from models.encoder_model import GRAY, SCALE_FRACTION_BITS, scaled_steps, signed32


class MotorModel:
    def __init__(self, counts_per_step=4 << SCALE_FRACTION_BITS, lag=0, spacing=4,
                 index_period=0, dir_positive=True):
        if lag < 0 or spacing < 1 or index_period < 0 or counts_per_step < 0:
            raise ValueError("lag and index_period must not be negative, spacing at least 1, "
                             "counts_per_step not negative")
        self.counts_per_step, self.spacing = counts_per_step, spacing
        self.index_period, self.dir_positive = index_period, dir_positive
        self.steps, self.lost, self.counts = 0, 0, 0
        self.stalled = False
        self._history = deque([0] * lag)   # the step position of the last ``lag`` clocks, oldest first
        self._step = False
        self._wait = 0

    def clock(self, step, direction, drive_enable=True):
        """One clock; returns the pins (A, B, index) for the next rising edge."""
        rose = bool(step) and not self._step
        self._step = bool(step)
        if rose and drive_enable and not self.stalled:
            self.steps += 1 if bool(direction) == self.dir_positive else -1
        elif rose:
            self.lost += 1
        self._history.append(self.steps)
        target = signed32(scaled_steps(self._history.popleft(), self.counts_per_step))
        if self._wait:
            self._wait -= 1
        elif target != self.counts:
            self.counts += 1 if target > self.counts else -1
            self._wait = self.spacing - 1
        return self.pins

    @property
    def pins(self):
        a, b = GRAY[self.counts % 4]
        index = bool(self.index_period) and self.counts % self.index_period == 0
        return a, b, int(index)
