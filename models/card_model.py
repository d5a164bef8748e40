"""Golden models of the card's blocks around the DDA, in plain Python, clock by clock.

Each model has ``clock(**inputs)`` for one rising edge and exposes what the
RTL's outputs are after that edge.  They are written from the rules in the
documentation (timing stated as "clocks since an edge"), not from the RTL's
state machines, so a bench comparing the two checks the RTL against the spec.

* ``FifoModel``: the data FIFO (``rtl/regs/sync_fifo.py``).
* ``PulseOutModel``: STEP/DIR timing of both axes (``rtl/regs/pulse_out.py``).
* ``FeedRateModel``: the iteration enable with its ramp (``rtl/regs/feed_rate.py``).
* ``DirectPulseModel``: direct pulses of one axis (``rtl/regs/direct_pulse.py``).
* ``RegisterModel``: access semantics of the register table (``models/registers.py``).
"""
from collections import deque

from models import registers as regmap
from models.registers import STEP_MODES

DECEL_MARGIN = 2  # iterations: the registered comparison and a stop_left one iteration late

FAR_PAST = -(1 << 20)
TIMING_LIMIT = 255
QUADRATURE_AB = ((False, False), (True, False), (True, True), (False, True))   # (A, B) of counts 0..3


class FifoModel:
    """A bounded queue; ``dout`` is the word popped at the last edge."""

    def __init__(self, depth):
        self.depth = depth
        self.words = deque()
        self.dout = 0

    @property
    def level(self):
        return len(self.words)

    @property
    def full(self):
        return len(self.words) == self.depth

    def room(self, places):
        """At least ``places`` places are free."""
        return self.depth - self.level >= places

    def clock(self, push=False, din=0, pop=False, flush=False):
        can_push = push and not self.full
        can_pop = pop and self.words
        if can_pop:
            self.dout = self.words.popleft()
        if flush:
            self.words.clear()
        elif can_push:
            self.words.append(din)


class PulseOutModel:
    """Every axis (``axes``, 2 by default): rises, falls and DIR changes as the timing rules allow.

    Rules (clocks counted between the edges where the internal levels change;
    the pins follow one clock later): the steps of one iteration leave
    together; a step's pulse is high ``width`` clocks and low at least
    ``space`` clocks (STEP_SPACE; None: ``width``, the card before it)
    before the next; the direction changes only while the pulse is low, at
    least ``hold`` clocks after the last fall, and at least ``setup`` clocks
    before the next rise; ``position`` changes with the pulse's rise.

    ``mode`` (STEP_MODE, ``models.registers.STEP_MODES``) says what the pins
    carry; ``pin_dir`` is the direction after ``polarity`` (DIR_POLARITY):
    0 step/dir: STEP the pulse, DIR ``pin_dir``; 1 up/down: STEP the pulses
    of steps with ``pin_dir`` high, DIR those with it low; 2 quadrature:
    a 2-bit count per axis moves at each pulse's rise (up with ``pin_dir``
    high), and STEP, DIR show it as A, B (00, 10, 11, 01, up: A leads), so
    one pin changes per step, a step period after the last change.
    """

    def __init__(self, queue_depth=4, in_flight=2, axes=2):
        self.queue_depth, self.in_flight, self.axes = queue_depth, in_flight, axes
        self.queue = deque()
        self.edge = 0
        self.high = (False,) * axes
        self.direction = [True] * axes
        self.rise_edge = self.fall_edge = self.dir_edge = FAR_PAST
        self.in_setup = False
        self.pulses = (False,) * axes   # the step pulses as step/dir mode puts them on STEP
        self.quadrature = [0] * axes    # the quadrature counts, 0..3
        self.step_pins = (False,) * axes
        self.dir_pins = (False,) * axes
        self.positions = [0] * axes

    @property
    def ready(self):
        return len(self.queue) <= self.queue_depth - self.in_flight

    @property
    def active(self):
        return bool(self.queue) or self.in_setup or any(self.high) or any(self.pulses)

    def _needs_turn(self, entry):
        steps, dirs = entry
        return any(steps[a] and dirs[a] != self.direction[a] for a in range(self.axes))

    def clock(self, steps=None, dirs=None, clear=False, clear_position=False,
              width=1, setup=1, hold=1, polarity=None, space=None, mode=0):
        """One clock edge: ``steps``, ``dirs`` and ``polarity`` one an axis (None: all False)."""
        steps, dirs, polarity = ((False,) * self.axes if given is None else given
                                 for given in (steps, dirs, polarity))
        if mode not in range(len(STEP_MODES)):
            raise ValueError(f"step mode must be one of 0..{len(STEP_MODES) - 1}, not {mode}")
        space = width if space is None else space
        self.edge += 1
        n = self.edge
        level_before, dir_before = self.high, tuple(self.direction)
        low_time = min(n - self.fall_edge, TIMING_LIMIT)
        rise = False
        if any(self.high):
            if n - self.rise_edge >= width:
                self.high = (False,) * self.axes
                self.fall_edge = n
        elif self.in_setup:
            if clear:
                self.in_setup = False
            elif min(n - self.dir_edge, TIMING_LIMIT) >= setup and low_time >= space:
                rise = True
        elif self.queue and not clear:
            if not self._needs_turn(self.queue[0]):
                rise = low_time >= space
            elif low_time >= hold:
                head_steps, head_dirs = self.queue[0]
                for axis in range(self.axes):
                    if head_steps[axis]:
                        self.direction[axis] = head_dirs[axis]
                self.dir_edge = n
                self.in_setup = True
        if rise:
            head_steps, _ = self.queue.popleft()
            self.high, self.rise_edge, self.in_setup = tuple(head_steps), n, False
        if clear:
            self.queue.clear()
        elif any(steps):
            if len(self.queue) == self.queue_depth:
                raise AssertionError("step request into a full pulse queue")
            self.queue.append((tuple(map(bool, steps)), tuple(map(bool, dirs))))
        pin_dir = tuple(dir_before[a] != bool(polarity[a]) for a in range(self.axes))
        for axis in range(self.axes):
            rises = level_before[axis] and not self.pulses[axis]
            if clear_position:
                self.positions[axis] = 0
            elif rises:
                self.positions[axis] += 1 if dir_before[axis] else -1
            if rises:
                self.quadrature[axis] = (self.quadrature[axis] + (1 if pin_dir[axis] else -1)) % 4
        self.pulses = level_before
        if mode == 0:
            self.step_pins, self.dir_pins = level_before, pin_dir
        elif mode == 1:
            self.step_pins = tuple(level_before[a] and pin_dir[a] for a in range(self.axes))
            self.dir_pins = tuple(level_before[a] and not pin_dir[a] for a in range(self.axes))
        else:
            self.step_pins = tuple(QUADRATURE_AB[count][0] for count in self.quadrature)
            self.dir_pins = tuple(QUADRATURE_AB[count][1] for count in self.quadrature)


class FeedRateModel:
    """Phase accumulator: a tick whenever the phase passes 65536, with a
    trapezoidal ramp (``docs/registers.md``, RAMP_STEP).

    The ramp count is the number of ticks the rate needs to come back down to
    ``ramp_start``: up by one per increment (a clamped last one too), down by
    one per decrement.  Deceleration is due when ``stop_left`` is at most the
    count plus ``margin`` iterations.  Timing: the settings and ``stop_left``
    act one clock after they are presented (the unit registers them).

    Feed hold (``pause``): each tick decelerates as at the end of a path; the
    tick that finds the count at 0 leaves the rate at 0 (``held``), and no
    tick comes until ``pause`` falls: the rate is then ``ramp_start`` again
    (the target without a ramp).  Without a ramp the rate is 0 at once, the
    clock ``pause`` is presented bringing no tick.
    """

    def __init__(self, margin=DECEL_MARGIN):
        self.margin = margin
        self.rate = 0
        self.phase = 0
        self.count = 0
        self.tick = False
        self.held = False
        self.decelerate = False
        self.settings = (0, 0, 0)  # target, ramp_start, ramp_step, as after reset

    def clock(self, run, hold, target, ramp_start, ramp_step, stop_left=(1 << 27) - 1, pause=False):
        if not 1 <= target <= regmap.RATE_MAX or not 1 <= ramp_start <= regmap.RATE_MAX:
            raise ValueError(f"rates must be 1..{regmap.RATE_MAX}, got {target} and {ramp_start}")
        due, (goal, floor, step) = self.decelerate, self.settings
        self.decelerate = stop_left <= self.count + self.margin
        self.settings = (target, ramp_start, ramp_step)
        self.tick = False
        resume_rate = goal if step == 0 else floor
        if not run:
            self.phase, self.count, self.held = 0, 0, pause
            self.rate = 0 if pause else resume_rate
            return
        if self.held:
            if not pause:
                self.held, self.rate = False, resume_rate
            return
        if pause and step == 0:
            self.held, self.rate = True, 0
            return
        if hold:
            return
        total = self.phase + self.rate
        self.phase = total % regmap.RATE_ONE
        if total < regmap.RATE_ONE:
            return
        self.tick = True
        if step == 0:
            self.rate, self.count = goal, 0
        elif due or pause:
            if self.count:
                self.rate = floor if self.count == 1 else max(self.rate - step, floor)
                self.count -= 1
            elif pause:
                self.held, self.rate = True, 0
        elif self.rate < goal:
            self.rate = min(self.rate + step, goal)
            self.count += 1
        elif self.rate > goal:
            self.rate = max(self.rate - step, goal)
            self.count = max(self.count - 1, 0)


class DirectPulseModel:
    """A count of requests, one per ``period`` clocks while the output is ready."""

    def __init__(self):
        self.remaining = 0
        self.direction = False
        self.wait = 0
        self.request = False

    def busy(self, load):
        # the last request's own clock counts (the step is not yet in the outputs)
        return bool(load) or self.remaining != 0 or self.request

    def clock(self, load=False, count=0, period=1, ready=True, clear=False, retarget=False):
        """``retarget``: |``count``| pulses are left from now on, in the direction
        and at the period's count under way (a request now is the first of them)."""
        self.request = False
        if clear:
            self.remaining = 0
        elif load:
            self.remaining, self.direction, self.wait = abs(count), count >= 0, 0
        else:
            if retarget:
                self.remaining = abs(count)
            if self.wait:
                self.wait -= 1
            elif self.remaining and ready:
                self.request = True
                self.remaining -= 1
                self.wait = period - 1


class RegisterModel:
    """What a host reads back from the registers it can write (RW, W1C, W1S, WP)."""

    def __init__(self):
        self.values = {r.name: r.reset for r in regmap.REGISTERS}

    @staticmethod
    def byte_mask(be):
        return sum(0xFF << (8 * lane) for lane in range(4) if be >> lane & 1)

    @staticmethod
    def honour(reg, word):
        """(value kept, clamped?) for ``word`` written into ``reg``."""
        width = reg.width
        if reg.signed:
            word = word - (1 << 32) if word >> 31 else word
        low = reg.minimum if reg.minimum is not None else None
        high = reg.maximum if reg.maximum is not None else None
        if low is not None and word < low:
            return low & ((1 << width) - 1), True
        if high is not None and word > high:
            return high & ((1 << width) - 1), True
        return word & ((1 << width) - 1), False

    def write(self, name, data, be=0xF):
        """Apply a bus write; return True when the value was clamped."""
        reg = regmap.register(name)
        mask = self.byte_mask(be)
        if reg.access == "RW":
            merged = (self.values[name] & ~mask) | (data & mask)
        else:
            merged = data & mask
        kept, clamped = self.honour(reg, merged & 0xFFFFFFFF)
        if reg.access == "RW":
            self.values[name] = kept
        elif reg.access == "W1C":
            self.values[name] &= ~kept
        elif reg.access == "W1S":
            self.values[name] |= kept
        return clamped and reg.access in ("RW", "WP")

    def set_command(self, index, value):
        """The SET instruction: like a full-word write of the register with that index."""
        return self.write(regmap.SET_TARGETS[index].name, value)

    def read(self, name):
        return self.values[name]


class DdaContractModel:
    """The DDA as ``rtl.interfaces.DdaPort`` promises it to the card, clock by clock.

    Not a model of ``rtl/dda_arc.py``'s internals: a stand-in that keeps the
    contract with the fewest freedoms, to test the card's side against it.
    Two stages: setup (``setup_clocks(command)`` clocks from the ``start``
    edge, then the prepared move waits) and run (one iteration per
    ``advance``).  A prepared move enters the run at the edge of the running
    move's last iteration, so the next ``advance`` iterates it: no gap.
    ``ready``: the setup stage is free (it frees when its move enters the run
    or its error is raised).  A rejected move raises ``error`` once the run
    stage is empty.  ``done`` comes with each move's last step.
    ``stop_left``: the iterations left in the running move (exact, so a lower
    bound) unless it blends; all ones otherwise.  ``steps_of(command)``: the
    list of its iterations (``Step``; ValueError when rejected);
    ``blend_of(command)``: its BLEND bit.
    """

    def __init__(self, steps_of, blend_of, setup_clocks, left_width):
        self.steps_of, self.blend_of, self.setup_clocks = steps_of, blend_of, setup_clocks
        self.all_ones = (1 << left_width) - 1
        self.setup = None  # [clocks left, iterations or None (rejected), blend]
        self.run = None  # [iterations left (a deque), blend]
        self.ready, self.busy, self.done, self.error = True, False, False, False
        self.steps = (False, False, False, False)  # step_x, step_y, dir_x, dir_y
        self.stop_left = self.all_ones

    def clock(self, start=False, advance=False, command=None):
        self.done = False
        self.steps = (False, False) + self.steps[2:]
        if self.run and advance:
            step = self.run[0].popleft()
            self.steps = (step.step_x, step.step_y, step.dir_x, step.dir_y)
            if not self.run[0]:
                self.done, self.run = True, None
        if self.setup and self.setup[0]:
            self.setup[0] -= 1
        elif self.setup and self.run is None:
            _, iterations, blend = self.setup
            self.setup = None
            if iterations is None:
                self.error = True
            elif not iterations:
                self.done = True
            else:
                self.run = [iterations, blend]
        if start:
            if not self.ready:
                raise AssertionError("start while the DDA's setup stage is busy")
            try:
                iterations = deque(self.steps_of(command))
            except ValueError:
                iterations = None
            self.setup = [self.setup_clocks(command) - 1, iterations, self.blend_of(command)]
            self.error = False
        self.ready = self.setup is None
        self.busy = self.setup is not None or self.run is not None
        if self.run is None or self.run[1]:
            self.stop_left = self.all_ones
        else:
            self.stop_left = len(self.run[0])
