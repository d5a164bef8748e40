"""The simulated machine around the card: drives, motors with encoders, switches and an E-stop
(docs/machine.md, "Simulated machine").

What a user's test drives the simulated card's machine inputs with, and the
golden model the compiled Verilator harness (``sim/backends/verilator/harness.cpp``)
and the MyHDL process (``sim/card/sim_machine.py``) are judged against:

* ``Switch``: a switch on one axis at a step position, with hysteresis and
  seeded contact bounce.  ``switch_closed`` is its definition: where it reads
  closed, given whether it was closed before.
* ``Motor``: a motor with an incremental encoder on one axis
  (``models/motor_model.MotorModel``): encoder counts per step (a whole number
  or a ratio), the lag from a step to the encoder's edges, the edges' least
  spacing (and a seeded jitter on it), an index every N counts, a stall from
  a given clock.
* ``MachineConfig``: which inputs have a switch, which axes a motor, where the
  axes start, which DIR level moves an axis forward, how the E-stop is wired;
  JSON in and out (``python -m host run --machine FILE``, the card server's
  ``--machine``).  It names axes of any build (X .. C); ``axes`` is the least
  build it needs.  On a card of more axes the axes it does not name have no
  switch and no motor, start at 0 and move forward with DIR high
  (``start`` and ``dir_positive`` may list fewer axes than the card has); a
  configuration naming an axis the card lacks is refused
  (``MachineConfig.check_axes``).
* ``SimMachine``: the machine of a card of ``axes`` axes, clock by clock.
  Each clock (``clocks`` counts them, 1 the first) it takes the card's STEP
  and DIR pins of every axis and DRIVE_ENABLE as they are after a rising
  edge; a STEP rise moves its axis one step if
  DRIVE_ENABLE is high and the axis's motor (if it has one) is not stalled,
  else the step is lost (``lost`` counts them); then each motor's encoder
  follows (``encoder_pins``), every switch reads its axis's position, and
  ``pins`` and ``encoder_pins`` are what the card's input pins show for the
  next rising edge.  A motor stalls from its ``stall_at`` clock on, or while
  ``stall(axis)`` asks it to.

Bounce: each change of a switch's contact makes its pin chatter for
``bounce`` clocks, in runs of 1 .. ``longest_run`` clocks at alternating
levels, the first run at the new level; the run lengths come from a 32-bit
xorshift generator (13, 17, 5) seeded with ``seed`` (0 is taken as 1):
``1 + next() % longest_run``.  Then the pin settles at the contact.
"""
import json
from dataclasses import asdict, dataclass, field

from models import registers as regmap
from models.axes import AXIS_NAMES
from models.encoder_model import FILTER_RESET
from models.motor_model import MASK32, MotorModel, xorshift32

INPUTS = regmap.INPUT_NAMES         # the largest build's inputs, bit n of the pins word: a card of N axes
                                    # has the first len(regmap.input_names(N)) of them
SWITCH_INPUTS = INPUTS[1:]          # every input but the E-stop can have a switch
AXIS_OF = {name: AXIS_NAMES.index(name.rsplit("_", 1)[1]) for name in SWITCH_INPUTS}
MOTOR_AXES = AXIS_NAMES             # every axis can have a motor
MIN_AXES = 2                        # the smallest build: X and Y
RATIO_MAX = 1 << 16     # a ratio's numerator and denominator
LAG_MAX = 1 << 20       # clocks of lag (the compiled harness keeps that many positions)
SPACING_MAX = 1 << 16   # clocks of spacing, and of jitter


@dataclass(frozen=True)
class Switch:
    """A switch on its input's axis: closed from ``position`` on towards the
    positive end (``positive``) or the negative end; once closed it opens again
    only ``hysteresis`` + 1 steps back; ``bounce`` clocks of chatter after each
    change; ``active_low``: wired normally closed (the pin is 0 while closed)."""
    position: int
    positive: bool = True
    hysteresis: int = 0
    bounce: int = 0
    longest_run: int = 2
    active_low: bool = False
    seed: int = 1

    def check(self, name):
        numbers = (self.position, self.hysteresis, self.bounce, self.longest_run, self.seed)
        if not all(isinstance(value, int) and not isinstance(value, bool) for value in numbers):
            raise ValueError(f"{name}: position, hysteresis, bounce, longest_run and seed are whole numbers")
        if self.hysteresis < 0 or self.bounce < 0 or self.longest_run < 1:
            raise ValueError(f"{name}: hysteresis and bounce must not be negative, longest_run at least 1")
        if not -(1 << 62) < self.position < 1 << 62 or not 0 <= self.seed <= MASK32:
            raise ValueError(f"{name}: position or seed out of range")


def switch_closed(switch, position, closed_before):
    """The golden definition: a switch reads closed at ``position`` when it is at
    least 0 steps into its side, or, if it was closed before, at least
    -``hysteresis`` steps (so a switch at p with hysteresis h on the positive
    side closes at p going up and opens at p - h - 1 going down)."""
    into = position - switch.position if switch.positive else switch.position - position
    return into >= (-switch.hysteresis if closed_before else 0)


def _whole(value):
    return isinstance(value, int) and not isinstance(value, bool)


@dataclass(frozen=True)
class Motor:
    """A motor with an encoder on its axis (``models/motor_model.MotorModel``):
    ``counts_per_step`` encoder counts per step, a whole number >= 1 or a ratio
    ``(numerator, denominator)`` (each 1 .. 2**16: (5, 2) is 2.5 counts a
    step, (1, 3) a count every third step); ``lag`` clocks from a step to its
    counts (0 .. 2**20); ``spacing``: at least this many clocks between two
    encoder edges (1 .. 2**16; the default, ENC_FILTER's reset + 1, is the
    closest the card counts at its reset filter), ``jitter``: 0 .. ``jitter``
    clocks more after each edge (0 .. 2**16), drawn from ``seed``;
    ``index_period``: the index is high while the count is a multiple of it
    (0: no index); ``stall_at``: the motor stalls from this clock of the
    machine on (1 is its first; None: only when asked, ``SimMachine.stall``)."""
    counts_per_step: object = 4
    lag: int = 0
    spacing: int = FILTER_RESET + 1
    jitter: int = 0
    seed: int = 1
    index_period: int = 0
    stall_at: object = None

    def __post_init__(self):
        if isinstance(self.counts_per_step, list):   # JSON's form of a ratio
            object.__setattr__(self, "counts_per_step", tuple(self.counts_per_step))

    @property
    def ratio(self):
        """(numerator, denominator) of ``counts_per_step``."""
        if _whole(self.counts_per_step):
            return self.counts_per_step, 1
        return tuple(self.counts_per_step)

    def check(self, name):
        ratio = self.counts_per_step
        if _whole(ratio):
            if not 1 <= ratio <= RATIO_MAX:
                raise ValueError(f"{name}: counts_per_step must be a whole number 1 .. {RATIO_MAX} or a ratio")
        elif (not isinstance(ratio, (tuple, list)) or len(ratio) != 2
              or not all(_whole(v) and 1 <= v <= RATIO_MAX for v in ratio)):
            raise ValueError(f"{name}: counts_per_step must be a whole number or a ratio [numerator, denominator], "
                             f"each 1 .. {RATIO_MAX}, not {ratio!r}")
        numbers = (self.lag, self.spacing, self.jitter, self.seed, self.index_period)
        if not all(_whole(value) for value in numbers) or not (self.stall_at is None or _whole(self.stall_at)):
            raise ValueError(f"{name}: lag, spacing, jitter, seed, index_period and stall_at are whole numbers")
        if not 0 <= self.lag <= LAG_MAX or not 1 <= self.spacing <= SPACING_MAX or not 0 <= self.jitter <= SPACING_MAX:
            raise ValueError(f"{name}: lag must be 0 .. {LAG_MAX}, spacing 1 .. {SPACING_MAX}, "
                             f"jitter 0 .. {SPACING_MAX} clocks")
        if not 0 <= self.index_period <= MASK32 >> 1 or not 0 <= self.seed <= MASK32:
            raise ValueError(f"{name}: index_period or seed out of range")
        if self.stall_at is not None and not 0 <= self.stall_at < 1 << 62:
            raise ValueError(f"{name}: stall_at must be a clock, 0 .. 2**62")

    def model(self, dir_positive):
        numerator, denominator = self.ratio
        return MotorModel(numerator, lag=self.lag, spacing=self.spacing, index_period=self.index_period,
                          dir_positive=dir_positive, denominator=denominator, jitter=self.jitter, seed=self.seed)


@dataclass(frozen=True)
class MachineConfig:
    """``switches``: {input name (``SWITCH_INPUTS``): ``Switch``}; ``start``:
    the axes' positions at reset; ``dir_positive``: the DIR pin level that moves
    each axis forward (both from X on, 2 .. 6 values; the axes after the last
    given start at 0 and move forward with DIR high); ``estop_active_low``: the
    E-stop pin is 0 while pressed; ``motors``: {axis name (``MOTOR_AXES``):
    ``Motor``}, on the encoder inputs of a card built with encoders."""
    switches: dict = field(default_factory=dict)
    start: tuple = (0, 0)
    dir_positive: tuple = (True, True)
    estop_active_low: bool = False
    motors: dict = field(default_factory=dict)

    def __post_init__(self):
        for name, switch in self.switches.items():
            if name not in SWITCH_INPUTS:
                raise ValueError(f"no switch input {name!r}: use one of {', '.join(SWITCH_INPUTS)}")
            if not isinstance(switch, Switch):
                raise ValueError(f"{name}: a Switch, not {switch!r}")
            switch.check(name)
        for name, motor in self.motors.items():
            if name not in MOTOR_AXES:
                raise ValueError(f"no motor axis {name!r}: use one of {', '.join(MOTOR_AXES)}")
            if not isinstance(motor, Motor):
                raise ValueError(f"{name}: a Motor, not {motor!r}")
            motor.check(f"motor {name}")
        for name in ("start", "dir_positive"):
            if not MIN_AXES <= len(getattr(self, name)) <= len(AXIS_NAMES):
                raise ValueError(f"{name} gives the axes from X on: {MIN_AXES} .. {len(AXIS_NAMES)} values, "
                                 f"not {len(getattr(self, name))}")
        if not all(_whole(value) for value in self.start):
            raise ValueError(f"start: whole numbers of steps, not {self.start!r}")

    def _needs(self):
        """[(axis index, what names it)] of everything in the configuration that belongs to an axis."""
        needs = [(AXIS_OF[name], name) for name in self.switches]
        needs += [(AXIS_NAMES.index(name), f"motor {name}") for name in self.motors]
        needs += [(len(self.start) - 1, f"start ({len(self.start)} axes)"),
                  (len(self.dir_positive) - 1, f"dir_positive ({len(self.dir_positive)} axes)")]
        return needs

    @property
    def axes(self):
        """The fewest axes a card must have for this machine (2 .. 6)."""
        return max(MIN_AXES, *(axis + 1 for axis, _ in self._needs()))

    def check_axes(self, axes):
        """ValueError naming what of the configuration belongs to an axis a card of ``axes`` axes lacks."""
        beyond = [what for axis, what in self._needs() if axis >= axes]
        if beyond:
            raise ValueError(f"the machine names axes the card lacks: {', '.join(beyond)}; the card has {axes} "
                             f"axes ({', '.join(AXIS_NAMES[:axes])}): build it with --axes {self.axes}")

    def start_of(self, axis):
        """Where ``axis`` starts (0 beyond ``start``)."""
        return self.start[axis] if axis < len(self.start) else 0

    def forward_level(self, axis):
        """The DIR level that moves ``axis`` forward (high beyond ``dir_positive``)."""
        return bool(self.dir_positive[axis]) if axis < len(self.dir_positive) else True

    def to_json(self):
        return json.dumps(dict(asdict(self), start=list(self.start), dir_positive=list(self.dir_positive)),
                          indent=1)

    @classmethod
    def from_json(cls, text):
        """A config from JSON (``to_json``'s form); ValueError naming what is wrong."""
        try:
            data = json.loads(text)
            switches = {name: Switch(**values) for name, values in data.pop("switches", {}).items()}
            motors = {name: Motor(**values) for name, values in data.pop("motors", {}).items()}
            return cls(switches=switches, motors=motors, start=tuple(data.pop("start", (0, 0))),
                       dir_positive=tuple(bool(v) for v in data.pop("dir_positive", (True, True))), **data)
        except (TypeError, AttributeError, json.JSONDecodeError) as error:
            raise ValueError(f"not a machine configuration: {error}") from None


class _Contact:
    """One switch's contact and pin, with its chatter."""

    def __init__(self, switch, position):
        self.switch = switch
        self.closed = switch_closed(switch, position, False)
        self.level = self.closed
        self.state = switch.seed or 1
        self.chatter_left = self.run_left = 0

    def _run(self):
        self.state = xorshift32(self.state)
        return 1 + self.state % self.switch.longest_run

    def clock(self, position):
        closed = switch_closed(self.switch, position, self.closed)
        if closed != self.closed:
            self.closed, self.chatter_left, self.run_left = closed, self.switch.bounce, 0
            self.level = not closed   # the first chatter run flips it to the new level
        if self.chatter_left:
            self.chatter_left -= 1
            if not self.run_left:
                self.level = not self.level
                self.run_left = self._run()
            self.run_left -= 1
        else:
            self.level = self.closed

    @property
    def pin(self):
        return self.level != self.switch.active_low


class SimMachine:
    """The machine of ``config`` on a card of ``axes`` axes (None: the fewest
    ``config`` needs), clock by clock (see the module's docstring)."""

    def __init__(self, config, axes=None):
        axes = config.axes if axes is None else axes
        if not MIN_AXES <= axes <= len(AXIS_NAMES):
            raise ValueError(f"axes {axes} is not {MIN_AXES}..{len(AXIS_NAMES)}")
        config.check_axes(axes)
        self.config, self.axes = config, axes
        self.inputs = regmap.input_names(axes)
        self.positions = [config.start_of(axis) for axis in range(axes)]
        self.lost = [0] * axes
        self.estop = False
        self.clocks = 0
        self._steps = [False] * axes
        self._stall = [False] * axes
        self._forward = [config.forward_level(axis) for axis in range(axes)]
        self.motors = [config.motors[name].model(self._forward[axis]) if name in config.motors else None
                       for axis, name in enumerate(MOTOR_AXES[:axes])]
        self._contacts = {name: _Contact(switch, self.positions[AXIS_OF[name]])
                          for name, switch in config.switches.items()}

    def press_estop(self, pressed=True):
        self.estop = bool(pressed)

    def stall(self, axis, stalled=True):
        """Stall (or free) the motor of ``axis`` (0: X) from the next clock on."""
        if not 0 <= axis < self.axes or self.motors[axis] is None:
            raise ValueError(f"axis {axis} has no motor")
        self._stall[axis] = bool(stalled)

    @property
    def encoder_pins(self):
        """The encoder pins as a word, bit 3n: axis n's A, 3n + 1: B, 3n + 2: index (0 without a motor)."""
        word = 0
        for axis, motor in enumerate(self.motors):
            if motor is not None:
                a, b, index = motor.pins
                word |= (a | b << 1 | index << 2) << 3 * axis
        return word

    def counts(self, axis):
        """The encoder count of ``axis``'s motor."""
        return self.motors[axis].counts

    @property
    def pins(self):
        """The input pins as a word, bit n: ``INPUTS[n]``."""
        word = int(self.estop != self.config.estop_active_low)
        for name, contact in self._contacts.items():
            word |= int(contact.pin) << INPUTS.index(name)
        return word

    def closed(self, name):
        """Whether the switch on input ``name`` is closed (its contact, without bounce)."""
        return self._contacts[name].closed

    def clock(self, *pins):
        """One clock: the card's pins after a rising edge, STEP and DIR of each
        axis from X on, then DRIVE_ENABLE (``clock(step_x, dir_x, step_y, dir_y,
        drive_enable)`` on two axes); returns ``pins``."""
        if len(pins) != 2 * self.axes + 1:
            raise ValueError(f"a clock of a {self.axes}-axis machine takes STEP and DIR of each axis and "
                             f"DRIVE_ENABLE: {2 * self.axes + 1} pins, not {len(pins)}")
        drive_enable = pins[-1]
        self.clocks += 1
        for axis in range(self.axes):
            self._clock_axis(axis, pins[2 * axis], pins[2 * axis + 1], drive_enable)
        for name, contact in self._contacts.items():
            contact.clock(self.positions[AXIS_OF[name]])
        return self.pins

    def _clock_axis(self, axis, step, direction, drive_enable):
        motor = self.motors[axis]
        if motor is not None:
            stall_at = self.config.motors[MOTOR_AXES[axis]].stall_at
            motor.stalled = self._stall[axis] or (stall_at is not None and self.clocks >= stall_at)
            steps, lost = motor.steps, motor.lost
            motor.clock(step, direction, drive_enable)
            self.positions[axis] += motor.steps - steps
            self.lost[axis] += motor.lost - lost
            return
        rose = bool(step) and not self._steps[axis]
        self._steps[axis] = bool(step)
        if rose and drive_enable:
            self.positions[axis] += 1 if bool(direction) == self._forward[axis] else -1
        elif rose:
            self.lost[axis] += 1
