"""Registered STEP/DIR outputs of every axis with pulse width and space, DIR set-up/hold, polarity
and the pins' mode (step/dir, up/down, quadrature)."""
from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, concat, enum, intbv, modbv

from models import registers as regmap
from models.parameters import AXES
from rtl.interfaces import AxisPulses, MotorPins, PulseControl, StepPositions, axis_suffixes, card_reset, named

MODE_UP_DOWN, MODE_QUADRATURE = (regmap.STEP_MODES.index(name) for name in ("UP_DOWN", "QUADRATURE"))
QUEUE_DEPTH, IN_FLIGHT = 4, 2


def _check_queue(queue_depth, in_flight):
    if in_flight < 1 or queue_depth < in_flight + 1 or queue_depth & (queue_depth - 1):
        raise ValueError(f"queue_depth {queue_depth} must be a power of two above in_flight {in_flight}")


@block
def pulse_out(clock, reset, request, control, pins, position, *, queue_depth=QUEUE_DEPTH, in_flight=IN_FLIGHT):
    """STEP and DIR pins of every axis, driven straight from flip-flops.

    Ports (``rtl/interfaces/``), all of the same number of axes N:
    ``request`` (``AxisPulses``: the steps of one iteration, several axes at
    once for a diagonal) goes into a small queue, an entry of 2N bits (bit i
    axis i's step, bit N + i its direction);
    ``control`` (``PulseControl``): ``ready`` is high while the queue has
    room for ``in_flight`` more (the steps already on their way from the
    interpolator when ``ready`` falls); ``active``: a step is queued or on
    the pins.  ``clear`` drops the queue (a pulse already high ends
    normally); ``clear_position`` zeroes the positions, ``zero`` one axis's
    (a step rising at that edge counts as its first).  Timing, shared by
    every axis so that a diagonal step leaves on all its pins in the same clock:
    ``width``: a step's pulse high time in clocks (>= 1); ``space``: its
    minimum low time before the next (>= 1); ``setup``: clocks the direction
    is stable before a pulse's leading edge (>= 1); ``hold``: clocks it
    stays stable after the trailing edge (>= 1); ``polarity_*``: 1 inverts
    that axis's direction on the pins.  ``mode`` (``models.card_model.PulseOutModel``
    says it in full): 0 step/dir (STEP the pulse, DIR the direction); 1
    up/down (STEP the pulses going up, DIR those going down); 2 quadrature
    (STEP, DIR an A/B pair stepped once per pulse).  ``pins``: ``MotorPins``.
    ``position`` (``StepPositions``: ``x``, ``y``, ..., signed) counts the steps
    at the edge where the pulse rises on the pins, so it tells what left them.
    Each axis's pins, direction and position are an ``_axis_pins``,
    instance ``axis_x``, ``axis_y``, ...; the queue and the timing are shared.

    step/dir mode, width 1, space 1, setup 1, hold 1; X steps +, then -:
        clock     _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        request   _/~~~\\___/~~~\\_____________
        step_x    _______/~~~\\___________/~~~\\_
        dir_x     ~~~~~~~~~~~~~~~~~~~\\_________
        position  ==0====X=1=============X=0==
    """
    _check_queue(queue_depth, in_flight)
    axes = request.axes
    if (control.axes, pins.axes, position.axes) != (axes, axes, axes):
        raise ValueError(f"pulse_out: request has {axes} axes, control {control.axes}, pins {pins.axes}, "
                         f"position {position.axes}")
    entry_bits = 2 * axes   # an entry: the steps (bit i: axis i), then their directions
    index_bits = queue_depth.bit_length() - 1
    phase_t = enum("P_IDLE", "P_SETUP", "P_HIGH")
    phase = Signal(phase_t.P_IDLE)
    queue = [Signal(intbv(0)[entry_bits:]) for _ in range(queue_depth)]
    count = Signal(intbv(0, min=0, max=queue_depth + 1))
    head = Signal(intbv(0)[entry_bits:])
    timing_bits = len(control.width)
    phase_clocks = Signal(intbv(0)[timing_bits:])
    low_clocks = Signal(intbv((1 << timing_bits) - 1)[timing_bits:])
    take, turn, set_dir = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    starts, high_ends = Signal(bool(0)), Signal(bool(0))
    phase_step, low_step = Signal(intbv(0)[timing_bits:]), Signal(intbv(0)[timing_bits:])  # 1, or 0 at the limit
    last_slot, free_slot = Signal(modbv(0)[index_bits:]), Signal(intbv(0)[index_bits:])
    # per axis: the head steps it in a new direction; the pulse is high inside; it is on the pins
    axis_turns, axis_levels, axis_pulses = ([Signal(bool(0)) for _ in range(axes)] for _ in range(3))
    turns, levels, pulses = (ConcatSignal(*reversed(bits)) for bits in (axis_turns, axis_levels, axis_pulses))
    request_steps = ConcatSignal(*reversed([request.step(axis) for axis in range(axes)]))
    request_dirs = ConcatSignal(*reversed([request.dir(axis) for axis in range(axes)]))
    units = [named(f"axis_{suffix}", _axis_pins(
        clock, reset, head(axis), head(axes + axis), take, high_ends, set_dir, control, control.polarity(axis),
        axis_turns[axis], axis_levels[axis], axis_pulses[axis], pins.step(axis), pins.dir(axis), position.of(axis),
        axis=axis)) for axis, suffix in enumerate(axis_suffixes(axes))]
    limit = (1 << timing_bits) - 1

    @always_comb
    def room():
        control.ready.next = count <= queue_depth - in_flight
        control.active.next = count != 0 or phase != phase_t.P_IDLE or pulses != 0
        control.pulsing.next = take or levels != 0 or pulses != 0

    @always_comb
    def peek():
        head.next = queue[0]

    @always_comb
    def decide():
        turn.next = count != 0 and turns != 0
        take.next = False
        if phase != phase_t.P_HIGH and not control.clear and low_clocks >= control.space:
            if phase == phase_t.P_SETUP:
                take.next = phase_clocks >= control.setup
            elif count != 0:
                take.next = turns == 0

    @always_comb
    def restart():
        # a phase (STEP high, or DIR set-up) starts: its clock count restarts at 1
        starts.next = take or (phase == phase_t.P_IDLE and not control.clear and turn and low_clocks >= control.hold)
        high_ends.next = phase == phase_t.P_HIGH and phase_clocks >= control.width
        # the DIR set-up starts: the axes the head steps take its directions
        set_dir.next = (phase == phase_t.P_IDLE and not control.clear and turn and low_clocks >= control.hold
                        and not take)
        phase_step.next = 0
        if phase_clocks != limit:
            phase_step.next = 1
        low_step.next = 0
        if low_clocks != limit:
            low_step.next = 1

    @always_seq(clock.posedge, reset=reset)
    def count_clocks():
        # Both counters run in every phase (saturating: the increment is 0 at
        # the limit) and restart at 1, so that the comparisons only choose a
        # value at the end and never gate a clock enable.  phase_clocks is
        # only read in P_SETUP and P_HIGH, which both start at 1; low_clocks
        # is not read in P_HIGH and restarts when it ends.
        if starts:
            phase_clocks.next = 1
        else:
            phase_clocks.next = phase_clocks + phase_step
        if high_ends:
            low_clocks.next = 1
        else:
            low_clocks.next = low_clocks + low_step

    @always_seq(clock.posedge, reset=reset)
    def step_phases():
        if phase == phase_t.P_HIGH:
            if high_ends:
                phase.next = phase_t.P_IDLE
        elif take:
            phase.next = phase_t.P_HIGH
        elif control.clear:
            phase.next = phase_t.P_IDLE
        elif phase == phase_t.P_IDLE and starts:
            phase.next = phase_t.P_SETUP

    @always_seq(clock.posedge, reset=reset)
    def fill():
        # The queue shifts when its head is taken; a new entry goes behind
        # the last one held after that shift: slot count - 1 or count.
        pushed = request_steps != 0
        entry = concat(request_dirs, request_steps)
        if control.clear:
            count.next = 0
        elif take:
            for i in range(queue_depth - 1):
                queue[i].next = queue[i + 1]
            if pushed:
                queue[last_slot].next = entry
            else:
                count.next = count - 1
        elif pushed:
            queue[free_slot].next = entry
            count.next = count + 1

    @always_comb
    def slots():
        last_slot.next = count[index_bits:] - 1   # wraps: only used with count >= 1
        free_slot.next = count[index_bits:]

    return units, room, peek, decide, restart, count_clocks, step_phases, fill, slots


@block
def _axis_pins(clock, reset, step, direction, take, high_ends, set_dir, control, polarity, turns, level, pulse,
               pin_step, pin_dir, position, *, axis):
    """Axis ``axis`` of ``pulse_out``: ``step`` and ``direction`` are its bits of
    the queue's head; ``take`` (the head's pulses start), ``high_ends`` (they
    end) and ``set_dir`` (the DIR set-up starts) are the shared timing's.
    Drives ``turns`` (the head steps this axis in a new direction), ``level``
    (its pulse is high inside), ``pulse`` (it is on the pins a clock later),
    its pins in ``control.mode`` and ``polarity`` and its ``position``
    (``control.clear_position`` zeroes it, bit ``axis`` of ``control.zero``
    too, counting a step rising at that edge)."""
    quad, quad_next = Signal(modbv(0)[2:]), Signal(modbv(0)[2:])   # quadrature count (A = bit 0 ^ bit 1, B = bit 1)
    up, dir_level = Signal(bool(1)), Signal(bool(1))   # the direction on the pins (after polarity), and before
    delta = Signal(intbv(1, min=position.min, max=position.max))   # a step's count, +1 or -1

    @always_comb
    def turning():
        turns.next = step and direction != dir_level

    @always_seq(clock.posedge, reset=reset)
    def step_level():
        if high_ends:
            level.next = 0
        elif take:
            level.next = step
        if set_dir and step:
            dir_level.next = direction

    @always_comb
    def step_sense():
        # one adder per counter, adding +1 or -1, instead of an incrementer and a decrementer
        delta.next = 1
        if not dir_level:
            delta.next = -1

    @always_comb
    def pin_direction():
        # the pins' direction, and the quadrature count after this edge:
        # one count up or down where a pulse rises
        up.next = dir_level ^ polarity
        quad_next.next = quad
        if level and not pulse:
            if dir_level ^ polarity:
                quad_next.next = quad + 1
            else:
                quad_next.next = quad - 1

    @always_seq(clock.posedge, reset=reset)
    def drive_pins():
        pulse.next = level
        quad.next = quad_next
        if control.mode == MODE_UP_DOWN:
            pin_step.next = level and up
            pin_dir.next = level and not up
        elif control.mode == MODE_QUADRATURE:
            pin_step.next = quad_next[0] ^ quad_next[1]
            pin_dir.next = quad_next[1]
        else:
            pin_step.next = level
            pin_dir.next = up

    @always_seq(clock.posedge, reset=reset)
    def count_position():
        if control.clear_position:
            position.next = 0
        elif control.zero[axis]:
            # the axis counts from 0, with the step that rises at this edge
            position.next = 0
            if level and not pulse:
                position.next = delta
        elif level and not pulse:
            position.next = position + delta

    return turning, step_level, step_sense, pin_direction, drive_pins, count_position


def pulse_out_ports(queue_depth=QUEUE_DEPTH, in_flight=IN_FLIGHT, axes=AXES.default):
    """Fresh ports of ``pulse_out`` for conversion and benches, of ``axes`` axes
    (the queue's parameters are checked; they change no port)."""
    _check_queue(queue_depth, in_flight)
    return dict(clock=Signal(bool(0)), reset=card_reset(), request=AxisPulses(axes), control=PulseControl(axes),
                pins=MotorPins(axes), position=StepPositions(axes))
