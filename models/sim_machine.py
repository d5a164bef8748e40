"""The simulated machine around the card: drives, switches and an E-stop (docs/machine.md, "Simulated machine").

What a user's test drives the simulated card's machine inputs with, and the
golden model the compiled Verilator harness (``sim/backends/verilator/harness.cpp``)
and the MyHDL process (``sim/card/sim_machine.py``) are judged against:

* ``Switch``: a switch on one axis at a step position, with hysteresis and
  seeded contact bounce.  ``switch_closed`` is its definition: where it reads
  closed, given whether it was closed before.
* ``MachineConfig``: which inputs have a switch, where the axes start, which
  DIR level moves an axis forward, how the E-stop is wired; JSON in and out
  (``python -m host run --machine FILE``, the card server's ``--machine``).
* ``SimMachine``: the machine clock by clock.  Each clock it takes the card's
  STEP, DIR and DRIVE_ENABLE pins as they are after a rising edge; a STEP rise
  moves its axis one step if DRIVE_ENABLE is high, else the drive loses it
  (``lost`` counts them); then every switch reads its axis's position, and
  ``pins`` is what the card's input pins show for the next rising edge.

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

INPUTS = regmap.input_names(2)      # the machine has X and Y: the two-axis card's inputs
SWITCH_INPUTS = INPUTS[1:]          # every input but the E-stop can have a switch
AXIS_OF = {name: AXIS_NAMES.index(name.rsplit("_", 1)[1]) for name in SWITCH_INPUTS}
MASK32 = 0xFFFFFFFF


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


@dataclass(frozen=True)
class MachineConfig:
    """``switches``: {input name (``SWITCH_INPUTS``): ``Switch``}; ``start``:
    the axes' positions at reset; ``dir_positive``: the DIR pin level that moves
    each axis forward; ``estop_active_low``: the E-stop pin is 0 while pressed."""
    switches: dict = field(default_factory=dict)
    start: tuple = (0, 0)
    dir_positive: tuple = (True, True)
    estop_active_low: bool = False

    def __post_init__(self):
        for name, switch in self.switches.items():
            if name not in SWITCH_INPUTS:
                raise ValueError(f"no switch input {name!r}: use one of {', '.join(SWITCH_INPUTS)}")
            if not isinstance(switch, Switch):
                raise ValueError(f"{name}: a Switch, not {switch!r}")
            switch.check(name)
        if len(self.start) != 2 or len(self.dir_positive) != 2:
            raise ValueError("start and dir_positive give both axes")

    def to_json(self):
        return json.dumps(dict(asdict(self), start=list(self.start), dir_positive=list(self.dir_positive)),
                          indent=1)

    @classmethod
    def from_json(cls, text):
        """A config from JSON (``to_json``'s form); ValueError naming what is wrong."""
        try:
            data = json.loads(text)
            switches = {name: Switch(**values) for name, values in data.pop("switches", {}).items()}
            return cls(switches=switches, start=tuple(data.pop("start", (0, 0))),
                       dir_positive=tuple(bool(v) for v in data.pop("dir_positive", (True, True))), **data)
        except (TypeError, json.JSONDecodeError) as error:
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
        x = self.state
        x ^= (x << 13) & MASK32
        x ^= x >> 17
        x ^= (x << 5) & MASK32
        self.state = x
        return 1 + x % self.switch.longest_run

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
    """The machine of ``config``, clock by clock (see the module's docstring)."""

    def __init__(self, config):
        self.config = config
        self.positions = list(config.start)
        self.lost = [0, 0]
        self.estop = False
        self._steps = [False, False]
        self._contacts = {name: _Contact(switch, self.positions[AXIS_OF[name]])
                          for name, switch in config.switches.items()}

    def press_estop(self, pressed=True):
        self.estop = bool(pressed)

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

    def clock(self, step_x, dir_x, step_y, dir_y, drive_enable):
        """One clock: the card's pins after a rising edge; returns ``pins``."""
        for axis, (step, direction) in enumerate(((step_x, dir_x), (step_y, dir_y))):
            rose = bool(step) and not self._steps[axis]
            self._steps[axis] = bool(step)
            if rose and drive_enable:
                self.positions[axis] += 1 if bool(direction) == self.config.dir_positive[axis] else -1
            elif rose:
                self.lost[axis] += 1
        for name, contact in self._contacts.items():
            contact.clock(self.positions[AXIS_OF[name]])
        return self.pins
