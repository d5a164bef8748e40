"""Registered STEP/DIR outputs of both axes with pulse width and space, DIR set-up/hold, polarity
and the pins' mode (step/dir, up/down, quadrature)."""
from myhdl import Signal, always_comb, always_seq, block, concat, enum, intbv, modbv

from models import registers as regmap
from rtl.interfaces import AxisPulses, MotorPins, PulseControl, StepPositions, card_reset

ENTRY_BITS = 4  # step_x, step_y, dir_x, dir_y
MODE_UP_DOWN, MODE_QUADRATURE = (regmap.STEP_MODES.index(name) for name in ("UP_DOWN", "QUADRATURE"))
QUEUE_DEPTH, IN_FLIGHT = 4, 2


def _check_queue(queue_depth, in_flight):
    if in_flight < 1 or queue_depth < in_flight + 1 or queue_depth & (queue_depth - 1):
        raise ValueError(f"queue_depth {queue_depth} must be a power of two above in_flight {in_flight}")


@block
def pulse_out(clock, reset, request, control, pins, position, *, queue_depth=QUEUE_DEPTH, in_flight=IN_FLIGHT):
    """STEP and DIR pins of both axes, driven straight from flip-flops.

    Ports (``rtl/interfaces/``): ``request`` (``AxisPulses``: the steps
    of one iteration, a diagonal is both at once) goes into a small queue;
    ``control`` (``PulseControl``): ``ready`` is high while the queue has
    room for ``in_flight`` more (the steps already on their way from the
    interpolator when ``ready`` falls); ``active``: a step is queued or on
    the pins.  ``clear`` drops the queue (a pulse already high ends
    normally); ``clear_position`` zeroes the positions, ``zero`` one axis's
    (a step rising at that edge counts as its first).  Timing, shared by
    both axes so that a diagonal step leaves on both pins in the same clock:
    ``width``: a step's pulse high time in clocks (>= 1); ``space``: its
    minimum low time before the next (>= 1); ``setup``: clocks the direction
    is stable before a pulse's leading edge (>= 1); ``hold``: clocks it
    stays stable after the trailing edge (>= 1); ``polarity_*``: 1 inverts
    that axis's direction on the pins.  ``mode`` (``models.card_model.PulseOutModel``
    says it in full): 0 step/dir (STEP the pulse, DIR the direction); 1
    up/down (STEP the pulses going up, DIR those going down); 2 quadrature
    (STEP, DIR an A/B pair stepped once per pulse).  ``pins``: ``MotorPins``.
    ``position`` (``StepPositions``: ``x``, ``y``, signed) counts the steps
    at the edge where the pulse rises on the pins, so it tells what left them.

    step/dir mode, width 1, space 1, setup 1, hold 1; X steps +, then -:
        clock     _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        request   _/~~~\\___/~~~\\_____________
        step_x    _______/~~~\\___________/~~~\\_
        dir_x     ~~~~~~~~~~~~~~~~~~~\\_________
        position  ==0====X=1=============X=0==
    """
    _check_queue(queue_depth, in_flight)
    index_bits = queue_depth.bit_length() - 1
    phase_t = enum("P_IDLE", "P_SETUP", "P_HIGH")
    phase = Signal(phase_t.P_IDLE)
    queue = [Signal(intbv(0)[ENTRY_BITS:]) for _ in range(queue_depth)]
    count = Signal(intbv(0, min=0, max=queue_depth + 1))
    head = Signal(intbv(0)[ENTRY_BITS:])
    level_x, level_y = Signal(bool(0)), Signal(bool(0))
    pulse_x, pulse_y = Signal(bool(0)), Signal(bool(0))   # the pulses, as step/dir mode's STEP pins
    quad_x, quad_y = Signal(modbv(0)[2:]), Signal(modbv(0)[2:])   # quadrature counts (A = bit 0 ^ bit 1, B = bit 1)
    quad_next_x, quad_next_y = Signal(modbv(0)[2:]), Signal(modbv(0)[2:])
    up_x, up_y = Signal(bool(1)), Signal(bool(1))   # the direction on the pins (after polarity)
    dir_level_x, dir_level_y = Signal(bool(1)), Signal(bool(1))
    timing_bits = len(control.width)
    phase_clocks = Signal(intbv(0)[timing_bits:])
    low_clocks = Signal(intbv((1 << timing_bits) - 1)[timing_bits:])
    take, turn = Signal(bool(0)), Signal(bool(0))
    starts, high_ends = Signal(bool(0)), Signal(bool(0))
    phase_step, low_step = Signal(intbv(0)[timing_bits:]), Signal(intbv(0)[timing_bits:])  # 1, or 0 at the limit
    last_slot, free_slot = Signal(modbv(0)[index_bits:]), Signal(intbv(0)[index_bits:])
    # a step's count, +1 or -1, as wide as the counters
    delta_x, delta_y = (Signal(intbv(1, min=position.x.min, max=position.x.max)) for _ in range(2))
    limit = (1 << timing_bits) - 1

    @always_comb
    def room():
        control.ready.next = count <= queue_depth - in_flight
        control.active.next = count != 0 or phase != phase_t.P_IDLE or pulse_x or pulse_y
        control.pulsing.next = take or level_x or level_y or pulse_x or pulse_y

    @always_comb
    def peek():
        head.next = queue[0]

    @always_comb
    def decide():
        turn.next = count != 0 and ((head[0] and head[2] != dir_level_x) or (head[1] and head[3] != dir_level_y))
        take.next = False
        if phase != phase_t.P_HIGH and not control.clear and low_clocks >= control.space:
            if phase == phase_t.P_SETUP:
                take.next = phase_clocks >= control.setup
            elif count != 0:
                take.next = not ((head[0] and head[2] != dir_level_x) or (head[1] and head[3] != dir_level_y))

    @always_comb
    def restart():
        # a phase (STEP high, or DIR set-up) starts: its clock count restarts at 1
        starts.next = take or (phase == phase_t.P_IDLE and not control.clear and turn and low_clocks >= control.hold)
        high_ends.next = phase == phase_t.P_HIGH and phase_clocks >= control.width
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
                level_x.next = 0
                level_y.next = 0
                phase.next = phase_t.P_IDLE
        elif take:
            level_x.next = head[0]
            level_y.next = head[1]
            phase.next = phase_t.P_HIGH
        elif control.clear:
            phase.next = phase_t.P_IDLE
        elif phase == phase_t.P_IDLE and starts:
            if head[0]:
                dir_level_x.next = head[2]
            if head[1]:
                dir_level_y.next = head[3]
            phase.next = phase_t.P_SETUP

    @always_seq(clock.posedge, reset=reset)
    def fill():
        # The queue shifts when its head is taken; a new entry goes behind
        # the last one held after that shift: slot count - 1 or count.
        pushed = request.step_x or request.step_y
        entry = concat(request.dir_y, request.dir_x, request.step_y, request.step_x)
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

    @always_comb
    def step_sense():
        # one adder per counter, adding +1 or -1, instead of an incrementer and a decrementer
        delta_x.next = 1
        if not dir_level_x:
            delta_x.next = -1
        delta_y.next = 1
        if not dir_level_y:
            delta_y.next = -1

    @always_comb
    def pin_direction():
        # the pins' direction, and the quadrature counts after this edge:
        # one count up or down where a pulse rises
        up_x.next = dir_level_x ^ control.polarity_x
        up_y.next = dir_level_y ^ control.polarity_y
        quad_next_x.next = quad_x
        if level_x and not pulse_x:
            if dir_level_x ^ control.polarity_x:
                quad_next_x.next = quad_x + 1
            else:
                quad_next_x.next = quad_x - 1
        quad_next_y.next = quad_y
        if level_y and not pulse_y:
            if dir_level_y ^ control.polarity_y:
                quad_next_y.next = quad_y + 1
            else:
                quad_next_y.next = quad_y - 1

    @always_seq(clock.posedge, reset=reset)
    def drive_pins():
        pulse_x.next = level_x
        pulse_y.next = level_y
        quad_x.next = quad_next_x
        quad_y.next = quad_next_y
        if control.mode == MODE_UP_DOWN:
            pins.step_x.next = level_x and up_x
            pins.dir_x.next = level_x and not up_x
            pins.step_y.next = level_y and up_y
            pins.dir_y.next = level_y and not up_y
        elif control.mode == MODE_QUADRATURE:
            pins.step_x.next = quad_next_x[0] ^ quad_next_x[1]
            pins.dir_x.next = quad_next_x[1]
            pins.step_y.next = quad_next_y[0] ^ quad_next_y[1]
            pins.dir_y.next = quad_next_y[1]
        else:
            pins.step_x.next = level_x
            pins.dir_x.next = up_x
            pins.step_y.next = level_y
            pins.dir_y.next = up_y

    @always_seq(clock.posedge, reset=reset)
    def count_positions():
        if control.clear_position:
            position.x.next = 0
            position.y.next = 0
        else:
            # zero: the axis counts from 0, with the step that rises at this edge
            if control.zero[0]:
                position.x.next = 0
                if level_x and not pulse_x:
                    position.x.next = delta_x
            elif level_x and not pulse_x:
                position.x.next = position.x + delta_x
            if control.zero[1]:
                position.y.next = 0
                if level_y and not pulse_y:
                    position.y.next = delta_y
            elif level_y and not pulse_y:
                position.y.next = position.y + delta_y

    return (room, peek, decide, restart, count_clocks, step_phases, fill, slots, step_sense, pin_direction,
            drive_pins, count_positions)


def pulse_out_ports(queue_depth=QUEUE_DEPTH, in_flight=IN_FLIGHT):
    """Fresh ports of ``pulse_out`` for conversion and benches (the parameters
    are checked; they change no port)."""
    _check_queue(queue_depth, in_flight)
    return dict(clock=Signal(bool(0)), reset=card_reset(), request=AxisPulses(), control=PulseControl(),
                pins=MotorPins(), position=StepPositions())
