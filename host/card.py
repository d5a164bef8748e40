"""The card API: what host software does with the card, on any transport.

    card = Card(open_transport("verilator"))      # identify: ID, version, capabilities
    machine = card.configure(steps_per_mm=(200, 200), step_width_ns=2000)
    card.line(400, -120, blend=True)
    card.arc(centre=(0, 300), end=(300, 300), ccw=True)
    card.mark()
    card.wait_done()
    card.position()                                # (x, y) steps
    card.positions()                               # every axis's steps, at one instant
    card.direct(2, -400, period=100)               # direct pulses on Z (CONTROL.MODE = 1)

Every command is checked on the host before a word is queued (ValueError,
nothing sent): coordinates against the card's coordinate width, arcs against
the DDA's acceptance rule (``models.dda_model.plan_arc``), register values
against the register table.  What the card still refuses comes back as a
``CardError`` carrying the card's error name and the command that caused it:
the API keeps a record of the words queued since the last stop, and the
words the card has consumed (queued minus STATUS.FIFO_LEVEL) end inside the
command it refused (for DDA_REJECTED, the ARC among the last two: the
instruction register fetches the next command while the DDA checks an arc,
docs/instructions.md).  Times are converted with the card's CLOCK_HZ, sizes
come from FIFO_SIZE and BUILD: the host needs no knowledge of the build.

The registers by name come from ``host.card_registers`` (``read``, ``write``,
``field``, ``axis_read``, ``axis_write``), the identity from
``host.card_identity``, ``CardError`` and the record of queued commands from
``host.card_errors``.

The machine side (docs/machine.md) comes from ``host.machine_io``: ``drive``,
``hold``, ``resume``, ``inputs``, ``watchdog``, ``estop_state``, ``limits``,
``stop_reason``, ``clear_stop`` (the drives stay off after it: ``drive``
again), ``home``, ``machine_side``, ``machine`` (a simulated card's simulated
machine).  A card the guard has stopped raises ``MachineStopped`` from
``check`` and ``wait_done``.
"""
import math

from host.card_errors import ERROR_NAMES, CardError, CommandRecord, error_name
from host.card_identity import IdentityError, identify
from host.card_registers import CardRegisters
from host.machine import Machine
from host.machine_io import MachineIO, MachineStopped
from host.transports.base import POLL_SECONDS
from models.axes import names
from models import instructions as isa
from models import registers as regmap
from models.dda_model import ArcCommand, plan_arc

# the card API's names callers take from here (host.cli, the tests)
__all__ = ["Card", "CardError", "IdentityError", "MachineStopped"]


class Card(CardRegisters, MachineIO):
    """The card behind ``transport``, identified on construction."""

    def __init__(self, transport):
        self.transport = transport
        self.identity = self.identify()
        self.tag = 0
        self._forget()

    # ----- identity and set-up --------------------------------------------------
    def identify(self):
        """Read ID and the capability registers; IdentityError for another card or major version."""
        return identify(self)

    def clocks(self, nanoseconds):
        """Card clocks covering ``nanoseconds`` (rounded up)."""
        return math.ceil(nanoseconds * self.identity.clock_hz / 1e9 - 1e-9)

    def configure(self, steps_per_mm=(200.0, 200.0), step_width_ns=1000, dir_setup_ns=1000, dir_hold_ns=1000,
                  polarity=(0, 0), rapid=3000.0, acceleration=500.0, start_feed=60.0, mark_interval=256,
                  step_space_ns=None):
        """Pulse timing (ns, converted with CLOCK_HZ, each 1..255 clocks: STEP
        high, STEP low between steps (``step_space_ns``, default the high
        time), DIR set-up and hold) and DIR polarity into the card; the ``Machine`` the planner needs (feeds in
        mm/min, acceleration in mm/s^2).  Every value is checked before any is written."""
        timing = {}
        space_ns = step_width_ns if step_space_ns is None else step_space_ns
        for name, ns in (("STEP_WIDTH", step_width_ns), ("STEP_SPACE", space_ns), ("DIR_SETUP", dir_setup_ns),
                         ("DIR_HOLD", dir_hold_ns)):
            reg = regmap.register(name)
            clocks = max(reg.minimum, self.clocks(ns))
            if clocks > reg.maximum:
                limit = reg.maximum * 1e9 / self.identity.clock_hz
                raise ValueError(f"{name}: {ns} ns is {clocks} clocks at {self.identity.clock_hz} Hz; "
                                 f"the card allows {limit:.0f} ns at most")
            timing[name] = clocks
        if any(p not in (0, 1) for p in polarity) or len(polarity) != 2:
            raise ValueError(f"polarity is two values 0 or 1, not {polarity}")
        if len(steps_per_mm) > self.identity.axes:
            raise ValueError(f"steps per mm for {len(steps_per_mm)} axes: the card has {self.identity.axes} "
                             f"({names(range(self.identity.axes))})")
        machine = Machine(steps_per_mm=tuple(steps_per_mm), clock_hz=self.identity.clock_hz,
                          coord_width=self.identity.coord_width, rapid=rapid, acceleration=acceleration,
                          start_feed=start_feed, mark_interval=mark_interval)
        for name, clocks in timing.items():
            self.write(name, clocks)
        self.write("DIR_POLARITY", regmap.field_of("DIR_POLARITY", X=polarity[0], Y=polarity[1]))
        self.timing = timing
        return machine

    def start(self, interrupts=("ERROR",), low_water=0):
        """INT_ENABLE, LOW_WATER and CONTROL.ENABLE (DDA mode): the card executes what is queued."""
        self.write("LOW_WATER", low_water)
        self.write("INT_ENABLE", regmap.field_of("INT_ENABLE", **{name: 1 for name in interrupts}))
        self.write("CONTROL", regmap.field_of("CONTROL", ENABLE=1))

    # ----- commands -------------------------------------------------------------
    def _coordinates(self, what, *values):
        limit = (1 << (self.identity.coord_width - 1)) - 1
        for value in values:
            if not isinstance(value, int) or not -limit - 1 <= value <= limit:
                raise ValueError(f"{what}: {value} does not fit the card's {self.identity.coord_width}-bit "
                                 "coordinates")

    def line(self, dx, dy, blend=False):
        """Straight move by (dx, dy) steps."""
        self._coordinates("LINE", dx, dy)
        if (dx, dy) == (0, 0):
            raise ValueError("LINE (0, 0) moves nowhere")
        self.send(isa.encode("LINE", dx, dy, BLEND=int(blend)), f"LINE {dx} {dy}")

    def arc(self, centre, end, ccw=False, variant=3, blend=False):
        """Arc from here about ``centre`` to ``end``, both in steps from the arc's start."""
        cx, cy = centre
        xs, ys, xe, ye = -cx, -cy, end[0] - cx, end[1] - cy
        self._coordinates("ARC", xs, ys, xe, ye)
        if variant not in self.identity.variants:
            raise ValueError(f"ARC variant {variant} is not built into this card (built: {self.identity.variants})")
        try:
            plan_arc(ArcCommand(xs, ys, xe, ye, ccw=ccw, variant=variant), self.identity.coord_width)
        except ValueError as error:
            raise ValueError(f"ARC centre {centre} end {end}: {error}") from None
        self.send(isa.encode("ARC", xs, ys, xe, ye, CCW=int(ccw), VARIANT=variant, BLEND=int(blend)),
                  f"ARC centre {centre} end {end} {'ccw' if ccw else 'cw'}")

    def pulse(self, count_x, count_y):
        """Direct pulses on both axes at PULSE_PERIOD_X / _Y (signed 24-bit counts)."""
        for count in (count_x, count_y):
            if not -(1 << 23) <= count < 1 << 23:
                raise ValueError(f"PULSE: {count} does not fit 24 signed bits")
        self.send(isa.encode("PULSE", count_x, count_y), f"PULSE {count_x} {count_y}")

    def dwell(self, seconds):
        """Wait ``seconds`` (card clocks, at most 2^32 - 1 per DWELL) before the next command."""
        clocks = round(seconds * self.identity.clock_hz)
        if not 0 <= clocks < 1 << 32:
            raise ValueError(f"DWELL {seconds} s is {clocks} clocks: 0..{(1 << 32) - 1}")
        self.send(isa.encode("DWELL", clocks), f"DWELL {clocks}")

    def set(self, name, value):
        """Write register ``name`` at this point of the stream (SET)."""
        reg = regmap.register(name)
        if reg.set_index is None:
            raise ValueError(f"SET cannot write {name}: it has no SET index")
        low = reg.minimum if reg.minimum is not None else 0
        high = reg.maximum if reg.maximum is not None else (1 << reg.width) - 1
        if not low <= value <= high:
            raise ValueError(f"SET {name} = {value} is outside {low}..{high}")
        self.send(isa.encode("SET", value, INDEX=reg.set_index), f"SET {name} {value}")

    def mark(self, tag=None):
        """MARK ``tag`` (default: the next tag, counting from 0 modulo 65536); the tag."""
        tag = self.tag if tag is None else tag
        if not 0 <= tag < 1 << 16:
            raise ValueError(f"MARK tag {tag} is outside 0..65535")
        self.send(isa.encode("MARK", TAG=tag), f"MARK {tag}")
        self.tag = (tag + 1) & 0xFFFF
        return tag

    def send(self, words, what="", timeout=10.0):
        """Queue one command's ``words``, waiting up to ``timeout`` s of card
        time for room; ``what`` names it in a ``CardError``."""
        words = list(words)
        deadline = self.transport.now() + timeout
        while self.queue_space() < len(words):
            self.check()
            if self.transport.now() > deadline:
                raise TimeoutError(f"no room for {what or 'the command'} in {timeout} s: the card is not "
                                   "executing (CONTROL.ENABLE?)")
            self.transport.sleep(POLL_SECONDS)
        self.queue(words, [(len(words), what)])

    def queue(self, words, commands):
        """Write ``words`` into the FIFO now (the caller has made room);
        ``commands``: [(words, name)] in order, for error reports."""
        self._record.add(words, commands)
        self.transport.fifo_write(words)

    # ----- state ----------------------------------------------------------------
    def status(self):
        return self.read("STATUS")

    def queue_space(self):
        """Words the FIFO can take now."""
        return self.identity.fifo_words - self.field("STATUS", "FIFO_LEVEL")

    def consumed(self, status=None):
        """Words the card has taken from the FIFO since the last stop."""
        status = self.status() if status is None else status
        return self._record.written - regmap.field_value("STATUS", "FIFO_LEVEL", status)

    def last_mark(self):
        return self.field("MARK_TAG", "TAG")

    def position(self):
        """(x, y) steps that left the pins (POS_X snapshots POS_Y)."""
        x = self.field("POS_X", "STEPS")
        return x, self.field("POS_Y", "STEPS")

    def positions(self):
        """Every axis's steps that left the pins, X first, all of one clock
        (reading X's POS captures the others'; docs/registers.md)."""
        words = [self.axis_read("POS", axis) for axis in range(self.identity.axes)]
        return tuple(regmap.field_value("POS_X", "STEPS", word) for word in words)

    def direct(self, axis, count, period=None):
        """Direct pulses on ``axis`` (0 X): ``count`` signed pulses at ``period``
        clocks apart (PULSE_PERIOD; None: as it is).  Puts the card in direct
        mode (CONTROL.MODE = 1, which holds the command queue) if it is not;
        the pulses start at once, the axis's PULSE_COUNT reads what is left."""
        period_reg, count_reg = self._axis_register("PULSE_PERIOD", axis), self._axis_register("PULSE_COUNT", axis)
        if period is not None and not period_reg.minimum <= period <= period_reg.maximum:
            raise ValueError(f"{period_reg.name} = {period} is outside {period_reg.minimum}..{period_reg.maximum}")
        if not count_reg.minimum <= count <= count_reg.maximum:
            raise ValueError(f"{count_reg.name} = {count} is outside {count_reg.minimum}..{count_reg.maximum}")
        control = self.read("CONTROL")
        if not regmap.field_value("CONTROL", "MODE", control):
            self.write("CONTROL", control | regmap.field_of("CONTROL", MODE=1))
        if period is not None:
            self.axis_write("PULSE_PERIOD", axis, period)
        self.axis_write("PULSE_COUNT", axis, count)

    def pulses_left(self, axis):
        """Direct pulses still to go on ``axis``."""
        return regmap.field_value("PULSE_COUNT_X", "COUNT", self.axis_read("PULSE_COUNT", axis))

    def check(self, status=None):
        """MachineStopped if the guard has stopped the card, CardError if it stopped on an error."""
        status = self.status() if status is None else status
        if regmap.field_value("STATUS", "STOPPED", status):
            raise MachineStopped(*self.stop_reason())
        code = regmap.field_value("STATUS", "ERROR", status)
        if code:
            raise CardError(error_name(code), code, self.refused_command(code, self.consumed(status)))

    def refused_command(self, code, consumed):
        """The name of the command the card refused with ``code``, given the
        words it has consumed: the one they end in; for DDA_REJECTED the ARC
        among the last two consumed commands (the earlier if both are)."""
        return self._record.refused(code, consumed)

    def wait_done(self, timeout=60.0):
        """Wait until the queue has run empty after motion (STATUS.DONE, with
        BUSY low): on INTA# when DONE is enabled, else by polling; CardError
        on an error, TimeoutError after ``timeout`` s of card time."""
        deadline = self.transport.now() + timeout
        interrupts = self.read("INT_ENABLE")
        use_inta = regmap.field_value("INT_ENABLE", "DONE", interrupts)
        while True:
            status = self.status()
            self.check(status)
            if not regmap.field_value("STATUS", "BUSY", status) and regmap.field_value("STATUS", "FIFO_EMPTY",
                                                                                       status):
                return
            left = deadline - self.transport.now()
            if left <= 0:
                raise TimeoutError(f"the card is still busy after {timeout} s (STATUS {status:#010x})")
            if use_inta:
                if self.transport.wait_interrupt(left):
                    self.write("INT_STATUS", regmap.field_of("INT_STATUS", DONE=1))
            else:
                self.transport.sleep(min(left, POLL_SECONDS))

    def clear_error(self):
        """COMMAND.CLEAR_ERROR: execution resumes after the refused command;
        after BAD_OPCODE the card empties the FIFO (its words cannot be
        framed), and the record of queued words starts afresh."""
        code = self.field("STATUS", "ERROR")
        self.transport.write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", CLEAR_ERROR=1))
        if ERROR_NAMES.get(code) == "BAD_OPCODE":
            self._forget()

    def stop(self):
        """COMMAND.SOFT_RESET: motion stops at once, the FIFO is emptied, the error cleared; the position."""
        self.transport.write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", SOFT_RESET=1))
        self._forget()
        return self.position()

    def _forget(self):
        self._record = CommandRecord()

