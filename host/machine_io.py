"""The machine side of the card API (docs/machine.md): drive enable, feed
hold, input conditioning, the watchdog, the guard's state and homing.

``host.card.Card`` takes these methods from ``MachineIO``; they use the
card's ``read``, ``write``, ``field``, ``clocks``, ``check``, ``position``,
``identity`` and ``transport``.
"""
import math

from host import homing
from host.homing import ANY_AXIS_VERSION as INPUT_WORDS_VERSION   # 2.3: INPUT_ACTIVE, INPUT_RAW, AXIS_INDEX
from host.transports.base import POLL_SECONDS
from models import registers as regmap
from models.axes import AXIS_NAMES


class MachineStopped(RuntimeError):
    """The card's guard stopped the machine: ``reason`` (``ESTOP``,
    ``WATCHDOG`` or ``LIMIT``) and ``limits`` (the limits stepped towards)."""

    def __init__(self, reason, limits=()):
        which = f" ({', '.join(limits)})" if limits else ""
        super().__init__(f"the card stopped the machine: {reason}{which}")
        self.reason, self.limits = reason, tuple(limits)



class MachineIO:
    """Drive enable, feed hold, inputs, watchdog, stop state and homing of a ``Card``."""

    def drive(self, enable=True):
        """MACHINE_CONTROL.DRIVE_ENABLE: the DRIVE_ENABLE pin follows it while
        the card is not stopped.  A stop clears it and the card keeps no 1
        while stopped, so ``drive(True)`` on a stopped card raises
        ``MachineStopped`` with nothing written: ``clear_stop()`` first, then
        ``drive(True)`` re-energises the drives."""
        if enable and self.field("STATUS", "STOPPED"):
            raise MachineStopped(*self.stop_reason())
        self._machine_control(DRIVE_ENABLE=int(enable))

    def hold(self, timeout=1.0):
        """Feed hold (MACHINE_CONTROL.HOLD): the path ramps down to zero on
        RAMP_STEP and waits; the position once MACHINE_STATUS.HELD (its last
        step has left).  MachineStopped if the guard stops the card meanwhile."""
        self._machine_control(HOLD=1)
        deadline = self.transport.now() + timeout
        while not self.field("MACHINE_STATUS", "HELD"):
            self.check()
            if self.transport.now() >= deadline:
                raise TimeoutError(f"the feed did not hold within {timeout} s")
            self.transport.sleep(POLL_SECONDS)
        return self.position()

    def resume(self):
        """Release the feed hold: the path ramps up again from RAMP_START and goes on exactly."""
        self._machine_control(HOLD=0)

    def _machine_control(self, **fields):
        word = self.read("MACHINE_CONTROL") & ~regmap.field_of("MACHINE_CONTROL", **{f: -1 for f in fields})
        self.write("MACHINE_CONTROL", word | regmap.field_of("MACHINE_CONTROL", **fields))

    def inputs(self, active_low=(), filter_ns=100, sample_ns=None):
        """Input conditioning: ``active_low`` names the inputs wired active low
        (``ESTOP``, ``LIMIT_POS_X`` ..., as in INPUT_POLARITY); an input's new
        level counts once it held for ``filter_ns`` (INPUT_FILTER samples
        ``sample_ns`` apart, default: the shortest spacing that needs at most
        15); the filter time honoured, in ns."""
        polarity = regmap.field_of("INPUT_POLARITY", **{name: 1 for name in active_low})
        clocks = max(self.clocks(filter_ns), 1)
        tick = self.clocks(sample_ns) if sample_ns else math.ceil(clocks / 15)
        samples = min(max(math.ceil(clocks / max(tick, 1)), 1), 15)
        self.write("INPUT_POLARITY", polarity)
        self.write("INPUT_TICK", tick)
        self.write("INPUT_FILTER", samples)
        return samples * tick * 1e9 / self.identity.clock_hz

    def watchdog(self, seconds):
        """WATCHDOG: the card stops (reason WATCHDOG) unless this is called
        again within ``seconds``; 0 turns it off.  Returns the clocks written."""
        clocks = self.clocks(seconds * 1e9) if seconds else 0
        self.write("WATCHDOG", clocks)
        return clocks

    def _input_words(self):
        """(active, raw): every input of the card, bit n INPUT_NAMES[n] (INPUT_ACTIVE and INPUT_RAW; a
        card before register map 2.3 has X's and Y's only, in MACHINE_STATUS)."""
        if self.identity.version >= INPUT_WORDS_VERSION:
            return self.read("INPUT_ACTIVE"), self.read("INPUT_RAW")
        status = self.read("MACHINE_STATUS")
        return tuple(regmap.field_value("MACHINE_STATUS", name, status) for name in ("ACTIVE", "RAW"))

    def estop_state(self):
        """True while the (filtered) E-stop input is active."""
        return bool(self.field("MACHINE_STATUS", "ACTIVE") & 1 << regmap.INPUT_NAMES.index("ESTOP"))

    def limits(self):
        """The names of the limit inputs active now (filtered), of every axis, e.g. ``("LIMIT_POS_Z",)``."""
        active, _ = self._input_words()
        return tuple(name for bit, name in enumerate(regmap.INPUT_NAMES)
                     if name.startswith("LIMIT") and active >> bit & 1)

    def stop_reason(self):
        """(reason, which): STOP_REASON as names, ``("NONE", ())`` while not stopped; ``which``: the
        limits of a LIMIT stop, the axis of a FOLLOWING_ERROR stop (``("X",)``)."""
        word = self.read("STOP_REASON")
        reason = regmap.STOP_REASONS[regmap.field_value("STOP_REASON", "REASON", word)]
        if reason == "FOLLOWING_ERROR":
            return reason, (AXIS_NAMES[regmap.field_value("STOP_REASON", "AXIS", word)],)
        hit = regmap.field_value("STOP_REASON", "LIMITS", word)
        return reason, tuple(name for bit, name in enumerate(regmap.LIMIT_NAMES) if hit >> bit & 1)

    def clear_stop(self):
        """COMMAND.CLEAR_STOP; MachineStopped if the card stays stopped (the
        E-stop input still active: the refused CLEAR_STOP changed nothing, the
        FIFO kept its words).  A successful CLEAR_STOP empties the FIFO (the
        record of queued words starts afresh) and leaves the drives off:
        ``drive(True)`` enables them again."""
        self.transport.write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", CLEAR_STOP=1))
        if self.field("STATUS", "STOPPED"):
            raise MachineStopped(*self.stop_reason())
        self._forget()

    @property
    def machine(self):
        """The simulated machine on a simulated card's inputs (``press_estop``,
        ``release_estop``, ``state()``: docs/machine.md), None on a real card
        or a simulation without one."""
        return self.transport.machine

    def machine_side(self):
        """What the machine side shows now, by name: ``inputs`` (the filtered
        inputs active, after INPUT_POLARITY), ``raw`` (the pins as wired),
        ``stop`` (STOP_REASON as names, ``STOPPING`` or ``STOPPED`` too),
        ``drive_enable`` (the pin and MACHINE_CONTROL's request), ``hold``,
        ``watchdog`` (clocks left, 0: off) and ``homing`` (HOME_STATUS)."""
        status, control = self.read("MACHINE_STATUS"), self.read("MACHINE_CONTROL")
        active, raw = self._input_words()
        home = self.read("HOME_STATUS")
        homing = {name: regmap.field_value("HOME_STATUS", name, home) for name in ("BUSY", "DONE", "NOT_FOUND",
                                                                                  "REFUSED")}
        return dict(
            inputs=tuple(name for bit, name in enumerate(regmap.INPUT_NAMES) if active >> bit & 1),
            raw=tuple(name for bit, name in enumerate(regmap.INPUT_NAMES) if raw >> bit & 1),
            stop=self.stop_reason(), stopped=bool(regmap.field_value("MACHINE_STATUS", "STOPPED", status)),
            stopping=bool(regmap.field_value("MACHINE_STATUS", "STOPPING", status)),
            drive_enable=(bool(regmap.field_value("MACHINE_STATUS", "DRIVE_ENABLE", status)),
                          bool(regmap.field_value("MACHINE_CONTROL", "DRIVE_ENABLE", control))),
            hold=(bool(regmap.field_value("MACHINE_CONTROL", "HOLD", control)),
                  bool(regmap.field_value("MACHINE_STATUS", "HELD", status))),
            watchdog=self.read("WATCHDOG"),
            homing=dict(homing, PHASE=regmap.HOME_PHASES[regmap.field_value("HOME_STATUS", "PHASE", home)],
                        AXIS=self._homed_axis()))

    def _homed_axis(self):
        """The axis HOME asked last, by name (HOME.AXIS_INDEX; before register map 2.3 HOME.AXIS)."""
        if self.identity.version >= INPUT_WORDS_VERSION:
            index = self.field("HOME", "AXIS_INDEX")   # a refused HOME may have named 6 or 7
            return AXIS_NAMES[index] if index < len(AXIS_NAMES) else str(index)
        return AXIS_NAMES[self.field("HOME", "AXIS")]

    def home(self, axis, direction="negative", **settings):
        """HOME one axis; the position (``host.homing.home`` says how)."""
        return homing.home(self, axis, direction, **settings)
