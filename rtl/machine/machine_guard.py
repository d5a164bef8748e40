"""The machine guard: E-stop latch, host watchdog, limit gates and drive enable."""
from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, intbv

from models import registers as regmap
from models.parameters import AXES
from rtl.interfaces import INPUT_ESTOP, AxisPulses, MachineGuard, axis_suffixes, card_reset, named

REASON_ESTOP, REASON_WATCHDOG, REASON_LIMIT, REASON_FOLLOWING_ERROR = (
    regmap.STOP_REASONS.index(name) for name in ("ESTOP", "WATCHDOG", "LIMIT", "FOLLOWING_ERROR"))


@block
def machine_guard(clock, reset, guard, request, granted, *, ferror_axes=0):
    """Stops the card, in hardware, when the machine or the host says so.

    Ports (``rtl/interfaces/``): ``guard`` (``MachineGuard``); ``request``
    (``AxisPulses``: the step requests of the DDA and the direct pulses);
    ``granted`` (``AxisPulses``: those that may go to the pulse outputs).
    Parameter: ``ferror_axes`` (the axes whose following error ``ferror``
    carries, a build with encoders; 0: none, the cause is not built).

    Causes, each latching ``stopped`` at the edge after it (first one wins,
    in this order; ``reason`` and ``limits`` say which):

    1. ESTOP: the filtered E-stop input is active.
    1a. FOLLOWING_ERROR: ``ferror`` is not 0 (bit i: axis i's following
       error is beyond its limit; ``axis`` says which, the lowest).  It
       latches at once, also during a decelerated stop: the motor no longer
       follows, a ramp would not slow it.
    2. WATCHDOG: ``watchdog_left`` reaches 0.  A ``watchdog_load`` sets it
       to ``watchdog_timeout`` (0: off); it counts down by one every clock.
    3. LIMIT: a step request of any axis towards its active limit
       (``limits``: which, bit 2 axis its positive end, 2 axis + 1 its
       negative: STOP_REASON.LIMITS).

    A WATCHDOG or LIMIT cause while ``ramp`` is high (RAMP_STEP not 0)
    starts a decelerated stop instead: ``stopping`` rises at the edge after
    it (``reason`` and ``limits`` with it), the feed rate ramps down on it,
    and ``stopped`` latches at the edge after ``held`` (the rate is zero
    and the last step has left the pins) is seen.  Until then every step request passes, those towards an
    active limit included, so the path slows down on itself; an E-stop
    still latches at once.

    ``halt`` (stopped, or the E-stop input active: a register's output,
    so at once) holds back every step request, of every axis; without a ramp a request
    towards an active limit is dropped too, whole, so the step that would
    hit the limit never reaches the pins, while requests away from it pass.
    ``clear_stop`` releases the latch (``reason`` and ``limits`` read 0
    again) unless the E-stop input is active.  ``drive_enable`` (the pin,
    from a flip-flop) is ``drive_request`` while not stopped (the card
    clears MACHINE_CONTROL.DRIVE_ENABLE at a stop, so it stays low after a
    ``clear_stop`` until the host writes it again), low from the edge the
    latch sets at (and while the E-stop input is active) unless ``pulsing``:
    a STEP pulse that starts or is high keeps it high, to the edge after
    that STEP has fallen on the pins, so a drive that obeys its enable at
    once sees every step the card counts.

    E-stop active (watchdog off):
        clock         _/~\\_/~\\_/~\\_/~\\_
        active[0]     _/~~~~~~~~~~~~~~~
        halt          _/~~~~~~~~~~~~~~~
        stopped       _____/~~~~~~~~~~~
        stop_event    _____/~~~\\_______
        drive_enable  ~~~~~\\___________

    A watchdog expiry (no ramp) with a pulse starting (STEP_WIDTH 2):
        clock         _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        expired       _/~~~\\_________________
        pulsing       _/~~~~~~~~~~~~~~~\\_____
        step (pin)    _________/~~~~~~~\\_____
        stopped       _____/~~~~~~~~~~~~~~~~~
        drive_enable  ~~~~~~~~~~~~~~~~~~~~~\\_

    Watchdog expiry with a ramp (``held`` after the feed rate's ramp):
        clock         _/~\\_/~\\_/~\\_ .. _/~\\_/~\\_/~\\_
        expired       _/~~~\\_______ .. _____________
        stopping      _____/~~~~~~~ .. ~~~~~~~\\_____
        held          _____________ .. _/~~~~~~~~~~~
        stopped       _____________ .. _______/~~~~~
        drive_enable  ~~~~~~~~~~~~~ .. ~~~~~~~\\_____
    """
    if not granted.axes == request.axes == guard.axes:
        raise ValueError(f"machine_guard: request has {request.axes} axes, granted {granted.axes}, "
                         f"guard {guard.axes}")
    if not 0 <= ferror_axes <= len(guard.ferror):
        raise ValueError(f"machine_guard: ferror_axes {ferror_axes} is not 0..{len(guard.ferror)}")
    estop, expired, passes = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    lagging, lagging_axis = Signal(bool(0)), Signal(intbv(0)[len(guard.axis):])
    hit_bits = [Signal(bool(0)) for _ in range(len(guard.limits))]   # STOP_REASON.LIMITS's order
    hits = ConcatSignal(*reversed(hit_bits))
    grants, checks = [], []
    for axis, suffix in enumerate(axis_suffixes(request.axes)):
        grants.append(named(f"grant_{suffix}", _grant(request.step(axis), request.dir(axis), passes,
                                                      granted.step(axis), granted.dir(axis))))
        ends = {positive: (guard.active(regmap.limit_input(axis, positive)), hit_bits[regmap.limit_bit(axis, positive)])
                for positive in (True, False)}
        checks.append(named(f"limit_{suffix}", _limit_hit(request.step(axis), request.dir(axis), *ends[True],
                                                          *ends[False])))

    @always_comb
    def causes():
        estop.next = guard.active[INPUT_ESTOP]
        expired.next = guard.watchdog_left == 1 and not guard.watchdog_load

    @always_comb
    def gate():
        guard.halt.next = guard.stopped or estop
        passes.next = not (guard.stopped or estop) and (hits == 0 or guard.ramp)

    @always_seq(clock.posedge, reset=reset)
    def latch():
        stopped = bool(guard.stopped)
        guard.stop_event.next = 0
        if not guard.stopped:
            if estop:
                stopped = True
                guard.stopping.next = 0
                guard.reason.next = REASON_ESTOP
                guard.limits.next = 0
            elif lagging:
                stopped = True
                guard.reason.next = REASON_FOLLOWING_ERROR
                guard.limits.next = 0
                guard.axis.next = lagging_axis
            elif guard.stopping:
                stopped = bool(guard.held)
            elif expired or hits != 0:
                stopped = not guard.ramp
                guard.stopping.next = guard.ramp
                guard.limits.next = 0
                if expired:
                    guard.reason.next = REASON_WATCHDOG
                else:
                    guard.reason.next = REASON_LIMIT
                    guard.limits.next = hits
            if stopped:
                guard.stopping.next = 0
                guard.stop_event.next = 1
        elif guard.clear_stop and not estop:
            stopped = False
            guard.reason.next = 0
            guard.limits.next = 0
            guard.axis.next = 0
        guard.stopped.next = stopped
        # a pulse that starts or is high keeps the drives enabled to its end (the pin falls a clock later);
        # the request counts from the clock after a release only (MACHINE_CONTROL.DRIVE_ENABLE is cleared
        # while stopped, so a CLEAR_STOP never re-energises by itself)
        guard.drive_enable.next = ((guard.drive_request != 0 and not stopped and not guard.stopped and not estop)
                                   or (guard.drive_enable and guard.pulsing))

    @always_seq(clock.posedge, reset=reset)
    def watchdog():
        if guard.watchdog_load:
            guard.watchdog_left.next = guard.watchdog_timeout
        elif guard.watchdog_left != 0:
            guard.watchdog_left.next = guard.watchdog_left - 1

    # the lowest axis of each combination of following-error flags (a table: a ROM once converted)
    lowest = tuple((flags & -flags).bit_length() - 1 if flags else 0 for flags in range(1 << ferror_axes))

    @always_comb
    def following():
        lagging.next = guard.ferror[ferror_axes:] != 0
        lagging_axis.next = lowest[int(guard.ferror[ferror_axes:])]

    return grants, checks, causes, gate, latch, watchdog, *([following] if ferror_axes else [])


@block
def _limit_hit(request_step, request_dir, at_pos, hit_pos, at_neg, hit_neg):
    """One axis's step request towards its limit: ``hit_pos`` a positive step while the positive
    end's limit input is active (``at_pos``), ``hit_neg`` a negative one at the negative end."""

    @always_comb
    def towards():
        hit_pos.next = request_step and request_dir and at_pos
        hit_neg.next = request_step and not request_dir and at_neg

    return towards


@block
def _grant(request_step, request_dir, passes, granted_step, granted_dir):
    """One axis's step request through the guard's gate: it ``passes`` or is held back."""

    @always_comb
    def pass_step():
        granted_step.next = request_step and passes
        granted_dir.next = request_dir

    return pass_step


def machine_guard_ports(axes=AXES.default):
    """Fresh ports of ``machine_guard`` for conversion and benches, of ``axes`` axes."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), guard=MachineGuard(axes), request=AxisPulses(axes),
                granted=AxisPulses(axes))
