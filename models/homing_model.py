"""Golden model of homing: a bouncing home switch, and what HOME must make of it.

Written from docs/machine.md ("Homing"), not from ``rtl/machine/homing.py``:

* ``BouncingSwitch``: one axis's home switch, driven clock by clock by the
  axis position rebuilt from the STEP/DIR pins.  It trips where the
  position reaches ``trip`` (counted towards the switch) and releases,
  with ``hysteresis``, where it falls below ``trip - hysteresis``; each
  change chatters for ``chatter`` clocks (seeded runs of 1..``longest_run``
  clocks at alternating levels) before it settles.
* ``filtered_changes``: the edges at which the card's input filter
  (``models.machine_model.InputFilterModel``) changes the switch's ACTIVE bit,
  from the pin levels the switch drove.
* ``expected_homing``: from those, what the card must show: where the
  position is zeroed, what POS reads, the seek and release steps and their
  spacing.
"""
import random
from dataclasses import dataclass

from models.machine_model import InputFilterModel


class BouncingSwitch:
    """A home switch on the positive (``negative`` False) or negative end of an axis."""

    def __init__(self, trip, negative=False, hysteresis=2, chatter=12, longest_run=2, seed=1):
        if trip < 1 or hysteresis < 0 or chatter < 0 or longest_run < 1:
            raise ValueError("trip >= 1, hysteresis >= 0, chatter >= 0, longest_run >= 1")
        self.trip, self.sense, self.hysteresis = trip, -1 if negative else 1, hysteresis
        self.chatter, self.longest_run = chatter, longest_run
        self.rng = random.Random(seed)
        self.position = 0
        self.closed = False      # the contact, without its bounce
        self.level = False       # the pin
        self.chatter_left = self.run_left = 0
        self.levels = [False]    # the pin in clock n (``PinLog`` numbering: after rising edge n)
        self.changes = []        # (clock, position, closed) where the contact changed

    @property
    def release_point(self):
        """The position, in steps, where the released switch is first open."""
        return self.sense * (self.trip - self.hysteresis - 1)

    @property
    def trip_point(self):
        return self.sense * self.trip

    def clock(self, step, positive):
        """Clock n: a STEP rose at edge n (``step``, in direction ``positive``);
        the pin level for this clock."""
        if step:
            self.position += 1 if positive else -1
        towards = self.sense * self.position
        closed = towards >= self.trip if not self.closed else towards >= self.trip - self.hysteresis
        if closed != self.closed:
            self.closed = closed
            self.changes.append((len(self.levels), self.position, closed))
            self.chatter_left, self.run_left = self.chatter, 0
        if self.chatter_left:
            self.chatter_left -= 1
            if not self.run_left:
                self.level = not self.level
                self.run_left = self.rng.randint(1, self.longest_run)
            self.run_left -= 1
        else:
            self.level = self.closed
        self.levels.append(self.level)
        return self.level


def filtered_changes(levels, samples, tick=1):
    """[(edge, active)]: the rising edges (``PinLog`` numbering) after which the
    filtered input changes, for pin ``levels`` per clock."""
    model = InputFilterModel(count=1)
    changes = []
    for clock, level in enumerate(levels):
        model.clock(int(level), 0, samples, tick)   # rising edge clock + 1 takes this clock's level
        if model.changed:
            changes.append((clock + 1, bool(model.active)))
    return changes


@dataclass
class HomingExpectation:
    trip_edge: int           # the filtered input active after this edge
    release_edge: int        # ... inactive again after this one
    zero_point: int          # the pins' position (steps from the start) that HOME zeroes
    position: int            # what POS reads at rest: steps counted from the zero point
    seek: list               # STEP rises (PinLog tuples) towards the switch
    release: list            # rises away from it up to the zero point
    backoff: list            # rises after it


def expected_homing(rises, axis, levels, samples, negative, tick=1):
    """What HOME on ``axis`` (0 X, 1 Y) must do, given the pins' ``rises``
    (``PinLog.rises``) and the switch's pin ``levels``: the position counts
    from 0 the steps whose STEP rises after the edge at which the filtered
    switch input goes inactive (the sequencer sees it in the clock after
    that edge and zeroes at the next, with a step rising there)."""
    changes = filtered_changes(levels, samples, tick)
    trip_edge = next(edge for edge, active in changes if active)
    release_edge = next(edge for edge, active in changes if not active and edge > trip_edge)
    towards = not negative
    seek, release, backoff, position, zero_point = [], [], [], 0, None
    for rise in rises:
        clock, stepped, positive = rise[0], rise[1 + axis], rise[3 + axis]
        if not stepped:
            continue
        if clock > release_edge:
            if zero_point is None:
                zero_point = position
            backoff.append(rise)
        elif positive == towards:
            seek.append(rise)
        else:
            release.append(rise)
        position += 1 if positive else -1
    if zero_point is None:
        zero_point = position
    return HomingExpectation(trip_edge, release_edge, zero_point, position - zero_point, seek, release, backoff)
