"""Golden models of the machine side, in plain Python, clock by clock.

Written from the rules in the blocks' docstrings and ``docs/machine.md``
(clocks since an edge), like ``models/card_model.py``:

* ``InputFilterModel``: synchroniser, polarity and glitch filter (``rtl/machine/input_filter.py``).
* ``MachineGuardModel``: E-stop latch, watchdog, limits, drive enable (``rtl/machine/machine_guard.py``).
* ``paused_ticks``: the iterations of a long move on a feed hold (``FeedRateModel``).
* ``reaction_clocks``: the E-stop's reaction time, pin to DRIVE_ENABLE low (docs/machine.md).
"""
from models import registers as regmap
from models.card_model import FeedRateModel

REASON = {name: code for code, name in enumerate(regmap.STOP_REASONS)}
INPUT = {name: bit for bit, name in enumerate(regmap.INPUT_NAMES)}


class InputFilterModel:
    """Every input: two flip-flops, then ``samples`` samples in a row at the
    new level (samples ``tick`` clocks apart, the first in the first clock)."""

    def __init__(self, count=len(regmap.INPUT_NAMES)):
        self.count = count
        self.pipe = [0, 0]   # the synchroniser: pins seen one and two edges ago
        self.active = 0
        self.changed = False
        self.runs = [0] * count  # samples in a row at a level other than ``active``
        self.wait = 0  # clocks to the next sample; a sample sets it to the tick then in force, less one

    @property
    def raw(self):
        return self.pipe[1]

    def clock(self, pins, polarity, samples, tick):
        """One rising edge with these inputs (as they were in the clock before it)."""
        sample = self.wait == 0
        level = self.raw ^ polarity
        new_active = self.active
        for bit in range(self.count):
            if (level >> bit & 1) == (self.active >> bit & 1):
                self.runs[bit] = 0
            elif sample:
                self.runs[bit] += 1
                if self.runs[bit] >= max(samples, 1):
                    new_active ^= 1 << bit
                    self.runs[bit] = 0
        self.changed = new_active != self.active
        self.active = new_active
        self.wait = tick - 1 if sample else self.wait - 1
        self.pipe = [pins, self.pipe[0]]


class MachineGuardModel:
    """The guard's latch, watchdog and gates.

    A stop latches at the edge after its cause: the E-stop input active, the
    watchdog's count reaching 0, or a step request towards an active limit
    of any axis (that request itself is dropped, with every other axis's).  While stopped, or while the E-stop
    input is active, no step request passes (``halt``).  ``clear_stop``
    releases the latch unless the E-stop input is active.  DRIVE_ENABLE
    follows ``drive_request`` one clock late, low while stopped or E-stop,
    except that once high it stays high while ``pulsing`` (a STEP pulse
    starts at the coming edge or is high): the drive sees every step.

    With ``ramp`` (RAMP_STEP not 0) a watchdog or limit cause does not stop
    at once: ``stopping`` is set (the feed rate decelerates), every step
    request passes, and the stop latches at the edge after the feed rate
    reports ``held``; the E-stop latches at once still.
    """

    def __init__(self):
        self.stopped = False
        self.stopping = False
        self.stop_event = False
        self.reason = 0
        self.limits = 0
        self.drive_enable = False
        self.watchdog_left = 0

    def halt(self, active):
        return self.stopped or bool(active >> INPUT["ESTOP"] & 1)

    def limit_hits(self, active, steps, dirs):
        """STOP_REASON.LIMITS bits of the requests that step towards an active limit: ``steps`` and
        ``dirs`` (1: positive) one an axis, X first, as many as the card has."""
        hits = 0
        for axis, (step, positive) in enumerate(zip(steps, dirs)):
            if step and active >> regmap.limit_input(axis, positive) & 1:
                hits |= 1 << regmap.limit_bit(axis, positive)
        return hits

    def granted(self, active, steps, dirs, ramp=False):
        """The step requests that pass to the pulse outputs in this clock."""
        if self.halt(active) or (self.limit_hits(active, steps, dirs) and not ramp):
            return (False,) * len(steps)
        return tuple(steps)

    def clock(self, active=0, steps=(False, False), dirs=(False, False), drive_request=False,
              clear_stop=False, watchdog_load=False, watchdog_timeout=0, ramp=False, held=False, pulsing=False):
        estop = bool(active >> INPUT["ESTOP"] & 1)
        expired = self.watchdog_left == 1 and not watchdog_load
        hits = self.limit_hits(active, steps, dirs)
        was_stopped = self.stopped
        self.stop_event = False
        if not self.stopped:
            if estop:
                self.reason, self.limits = REASON["ESTOP"], 0
                self.stopped = True
            elif self.stopping:
                self.stopped = held
            elif expired or hits:
                self.reason = REASON["WATCHDOG" if expired else "LIMIT"]
                self.limits = 0 if expired else hits
                self.stopped, self.stopping = not ramp, ramp
            if self.stopped:
                self.stopping, self.stop_event = False, True
        elif clear_stop and not estop:
            self.stopped, self.reason, self.limits = False, 0, 0
        self.drive_enable = ((drive_request and not self.stopped and not was_stopped and not estop)
                             or (self.drive_enable and pulsing))
        if watchdog_load:
            self.watchdog_left = watchdog_timeout
        elif self.watchdog_left:
            self.watchdog_left -= 1


def paused_ticks(target, ramp_start, ramp_step, pause_at, limit=1 << 20):
    """Clocks of the iterations of a move far from its end (clock 0: the
    first with ``run``) whose feed holds from clock ``pause_at`` on, up to
    the rate's stop (``FeedRateModel``, the registers' rules)."""
    settings = dict(target=target, ramp_start=ramp_start, ramp_step=ramp_step)
    model, ticks = FeedRateModel(), []
    for _ in range(2):
        model.clock(run=False, hold=False, **settings)
    for clock in range(limit):
        model.clock(run=True, hold=False, pause=clock >= pause_at, **settings)
        if model.tick:
            ticks.append(clock)
        if model.held:
            return ticks
    raise AssertionError(f"the rate did not reach zero in {limit} clocks")


def reaction_clocks(samples, tick):
    """(fewest, most) clocks from the clock in which the E-stop pin changes to
    the one in which DRIVE_ENABLE reads low, no STEP pulse under way.

    The synchroniser takes the pin at the next edge and shows it one edge
    later (2); the first sample that sees it comes 0 .. tick - 1 clocks on
    (the shared prescaler's phase), ``samples`` - 1 more follow ``tick``
    clocks apart, ACTIVE changes at the edge after the last (1), the latch and
    DRIVE_ENABLE's flip-flop at the next (1): (samples - 1) x tick + 4 + wait.
    """
    first = (max(samples, 1) - 1) * tick + 4
    return first, first + tick - 1
