"""The machine side: input conditioning, E-stop, limits, watchdog, drive enable."""
from myhdl import Signal, intbv

from models import registers as regmap
from models.axes import AXIS_NAMES
from models.parameters import AXES
from rtl.interfaces.bundle import adopt
from rtl.interfaces.card import machine_inputs


class InputConditioning:
    """The machine inputs' conditioning (``rtl/machine/input_filter.py``) of a card of ``axes`` axes.

    The card drives ``pins`` (the input pins as one vector, bit n the input
    n of ``MACHINE_INPUTS``, as many as ``machine_inputs(axes)``), ``polarity`` (INPUT_POLARITY: 1 inverts that
    input, for switches active low), ``samples`` (INPUT_FILTER) and
    ``tick`` (INPUT_TICK, clocks per sample, >= 1); the filter drives
    ``raw`` (the pins after the two-flip-flop synchroniser, as wired),
    ``active`` (filtered, polarity applied: 1 active) and ``changed`` (one
    clock after an ``active`` bit changed)."""

    def __init__(self, axes=AXES.default, **given):
        self.axes = axes
        count = len(machine_inputs(axes))
        samples, tick = regmap.register("INPUT_FILTER"), regmap.register("INPUT_TICK")
        adopt(self, given, pins=Signal(intbv(0)[count:]), polarity=Signal(intbv(0)[count:]),
               samples=Signal(intbv(samples.reset)[samples.width:]), tick=Signal(intbv(tick.reset)[tick.width:]),
               raw=Signal(intbv(0)[count:]), active=Signal(intbv(0)[count:]), changed=Signal(bool(0)))


class MachineGuard:
    """The machine guard's seam with the registers (``rtl/machine/machine_guard.py``) of a card of
    ``axes`` axes.

    The card drives ``active`` (the filtered inputs, ``InputConditioning``),
    ``drive_request`` (MACHINE_CONTROL.DRIVE_ENABLE), ``clear_stop``
    (COMMAND.CLEAR_STOP, one clock), ``watchdog_load`` (one clock per
    WATCHDOG write) with ``watchdog_timeout`` (its value, clocks; 0: off),
    ``ramp`` (RAMP_STEP is not 0: a watchdog or limit stop decelerates),
    ``held`` (``FeedPort.held``, and no step on its way to the pins) and
    ``pulsing`` (``PulseControl.pulsing``: a STEP pulse starts, or is high)
    and ``ferror`` (bit i: axis i's following error is beyond its limit,
    ``EncoderRegisters.ferror``; a build with encoders).
    The guard drives ``halt`` (no new STEP edge, no command, no direct
    pulse: stopped, or the E-stop input active), ``stopping`` (a
    decelerated stop is under way: the feed rate pauses), ``stopped`` (the
    latch), ``stop_event`` (one clock, as the latch sets), ``reason``,
    ``limits`` and ``axis`` (STOP_REASON; ``limits`` has the card's axes' bits, two an axis),
    ``drive_enable`` (the pin, from a flip-flop)
    and ``watchdog_left`` (clocks before the watchdog expires)."""

    def __init__(self, axes=AXES.default, **given):
        self.axes = axes
        reason, watchdog = regmap.register("STOP_REASON"), regmap.register("WATCHDOG")
        adopt(self, given, active=Signal(intbv(0)[len(machine_inputs(axes)):]), drive_request=Signal(bool(0)),
               clear_stop=Signal(bool(0)), watchdog_load=Signal(bool(0)),
               watchdog_timeout=Signal(intbv(0)[watchdog.width:]), ramp=Signal(bool(0)), held=Signal(bool(0)),
               pulsing=Signal(bool(0)),
               halt=Signal(bool(0)), stopping=Signal(bool(0)),
               stopped=Signal(bool(0)), stop_event=Signal(bool(0)),
               reason=Signal(intbv(0)[reason.field("REASON").width:]),
               limits=Signal(intbv(0)[2 * axes:]), drive_enable=Signal(bool(0)),
               ferror=Signal(intbv(0)[len(AXIS_NAMES):]), axis=Signal(intbv(0)[reason.field("AXIS").width:]),
               watchdog_left=Signal(intbv(0)[watchdog.width:]))


class Homing:
    """The homing sequencer's seam with the card (``rtl/machine/homing.py``) of a card of ``axes`` axes.

    The card drives ``start`` (one clock per HOME write) with ``request``
    (HOME's AXIS, NEGATIVE and AXIS_INDEX as written), ``seek_period``,
    ``release_period``, ``backoff`` and ``search`` (HOME_SEEK_PERIOD,
    HOME_RELEASE_PERIOD, HOME_BACKOFF, HOME_SEARCH), ``home`` (the filtered
    home inputs, bit i axis i's: HOME_X, HOME_Y, HOME_Z, ...), ``idle`` (nothing queued, moving or
    stopped: a HOME may start), ``clear`` (a stop or SOFT_RESET),
    ``pulse_busy`` (a direct-pulse generator is busy) and ``outputs_active``
    (a step is queued in the pulse outputs or on the pins).  The sequencer
    drives ``busy``, the homed axis's direct-pulse command (``load`` one
    clock with ``count``, signed, at ``period``; ``cut`` clears it;
    ``retarget`` makes |``count``| its steps still to go, timing kept),
    ``zero`` (one clock: zero the homed axis's position; bit i axis i),
    ``ended`` (one clock as a HOME ends: done, not found or refused),
    ``taken`` (what HOME reads: AXIS, NEGATIVE and AXIS_INDEX of the last HOME) and
    ``state`` (what HOME_STATUS reads)."""

    def __init__(self, axes=AXES.default, **given):
        self.axes = axes
        home, status, seek, backoff, search = (regmap.register(name) for name in (
            "HOME", "HOME_STATUS", "HOME_SEEK_PERIOD", "HOME_BACKOFF", "HOME_SEARCH"))
        count = search.width + 1
        adopt(self, given, start=Signal(bool(0)), request=Signal(intbv(0)[home.width:]),
               seek_period=Signal(intbv(1)[seek.width:]), release_period=Signal(intbv(1)[seek.width:]),
               backoff=Signal(intbv(0)[backoff.width:]), search=Signal(intbv(1)[search.width:]),
               home=Signal(intbv(0)[axes:]), idle=Signal(bool(0)), clear=Signal(bool(0)),
               pulse_busy=Signal(bool(0)), outputs_active=Signal(bool(0)), busy=Signal(bool(0)),
               load=Signal(bool(0)), count=Signal(intbv(0, min=-(1 << (count - 1)), max=1 << (count - 1))),
               period=Signal(intbv(1)[seek.width:]), cut=Signal(bool(0)), retarget=Signal(bool(0)),
               zero=Signal(intbv(0)[axes:]), ended=Signal(bool(0)), taken=Signal(intbv(0)[home.width:]),
               state=Signal(intbv(0)[status.width:]))
