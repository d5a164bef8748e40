"""DDA run stage: one iteration of the checked move per ``advance``, in two clocks."""
from myhdl import Signal, always_comb, always_seq, block, concat, intbv, modbv

from rtl.dda_build import IMPROVED, PRECISE, TRADITIONAL, WEIGHTED
from rtl.interfaces import TARGET_END, TARGET_RADIUS


@block
def dda_run(clock, reset, cmd, move, steps):
    """Run stage of the DDA: iterates the move it took from the check.

    Ports:
        clock, reset  clock and reset (``card_reset()``)
        cmd           ``DdaPort``: ``advance``, ``start`` and ``ready`` in (a taken
                      start clears ``error``); ``done``, ``error``, ``busy``,
                      ``quadrant``, ``stop_left`` out
        move          ``DdaMove`` in; ``move.take`` out (the run takes the move at this
                      edge: it is idle or applies its running move's last iteration)
        steps         ``AxisPulses`` out
    Parameters: none; widths and ``variants`` come from ``move``.

    An iteration takes the clock of its ``advance`` and the next one; an
    ``advance`` in that next clock is ignored::

        clock    _/~\\_/~\\_/~\\_/~\\_/~\\_
        advance  _/~~~\\___/~~~\\_______
        step_x   _____/~~~\\___/~~~\\___     step pulses and done leave with the decision
        applied  _________^_______^___     accumulators - T, |x|, the precise terms

    First clock (the decision, from registers): each accumulator plus its
    integrand (|y| for X, |x| for Y; a line's |dx|, |dy|) is kept and its
    sign is the overflow; the improved variant adds the integrand twice
    beside it (look-ahead); the precise mode's step is the one whose end
    point is nearest the circle: with E' = x**2 + y**2 - r**2 + 1 and the
    registers B_x = 2|y| - 4|x|, B_y = 4|y| - 2|x|, an inward step is taken
    when 2E' + B_out >= 0 and an outward one when 2E' + B_in < 0 (B_out and
    B_in by the quadrant, the inward one inverted with a carry); each axis
    stops at its piece's target (0, Rq or the end point: ``|x| - target`` is
    0, or +-1 one step before).  |y| steps here, E' takes X's part of the
    step.  Second clock: the accumulators that stepped lose T, |x| steps,
    E' takes Y's part (each part 2 min(|v|, |v'|) + 1, a magnitude the
    adder of |x| or |y| forms), the B terms their constants, the steps left
    (``stop_left``) count down, a new quadrant piece begins or the move ends.
    """
    width = move.coord_width
    acc_width = move.acc_width
    thr_width = move.threshold_width
    bias_width = move.bias_width
    left_width = move.left_width
    variants = move.variants
    has_traditional = TRADITIONAL in variants
    has_improved = IMPROVED in variants
    has_precise = PRECISE in variants
    saturates = bool(variants - {PRECISE})
    acc_max = (1 << (acc_width - 1)) - 1
    left_ones = (1 << left_width) - 1
    width_ones = (1 << width) - 1

    active, pending, first = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    line, ccw, blend = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    variant = Signal(intbv(PRECISE)[2:])
    right, up = Signal(bool(0)), Signal(bool(0))
    quadrant = Signal(modbv(0)[2:])
    x_inward = Signal(bool(0))
    crossings = Signal(intbv(0)[3:])
    target_x, target_y = Signal(intbv(0)[2:]), Signal(intbv(0)[2:])
    mag_x, mag_y = Signal(modbv(0)[width:]), Signal(modbv(0)[width:])
    end_x, end_y = Signal(intbv(0)[width:]), Signal(intbv(0)[width:])
    radius = Signal(intbv(0)[width:])
    threshold = Signal(intbv(0)[thr_width:])
    threshold_carry = Signal(bool(0))
    acc_x, acc_y = (Signal(intbv(0, min=-(1 << (acc_width - 1)), max=1 << (acc_width - 1))) for _ in range(2))
    error_term = Signal(modbv(0)[bias_width:])
    bias_x, bias_y = Signal(modbv(0)[bias_width:]), Signal(modbv(0)[bias_width:])
    most_left = Signal(modbv(left_ones)[left_width:])
    left_diff = Signal(modbv(0)[left_width:])

    # the second clock's registered decision
    dec_x, dec_y, dec_tail, dec_finished, dec_next_piece = (Signal(bool(0)) for _ in range(5))

    # first clock, combinational from registers
    sum_x, sum_y = Signal(modbv(0)[acc_width + 1:]), Signal(modbv(0)[acc_width + 1:])
    over_x, over_y = Signal(bool(0)), Signal(bool(0))
    stepped_x, stepped_y = Signal(modbv(0)[width:]), Signal(modbv(0)[width:])
    go_x, go_y, tail, finished, next_piece = (Signal(bool(0)) for _ in range(5))
    at_x, at_y, near_x, near_y = (Signal(bool(0)) for _ in range(4))
    inward_near, outward_near = Signal(bool(0)), Signal(bool(0))
    ahead_x, ahead_y = Signal(bool(0)), Signal(bool(0))
    trad_x, trad_over_x = Signal(modbv(0)[acc_width + 1:]), Signal(bool(0))
    error_step = Signal(modbv(0)[bias_width:])
    taking = Signal(bool(0))

    @always_comb
    def accumulate():
        # A - bias plus the integrand; the first clock keeps the sum, the second subtracts T
        # (T - 1 inverted, a line's T with a carry)
        operand_x = modbv(0)[acc_width + 1:]
        operand_y = modbv(0)[acc_width + 1:]
        carry = modbv(0)[acc_width + 1:]
        if pending:
            operand_x[:] = ~concat(intbv(0)[acc_width + 1 - thr_width:], threshold)
            operand_y[:] = operand_x
            carry[0] = threshold_carry
        else:
            operand_x[:] = concat(intbv(0)[acc_width + 1 - width:], mag_y)
            operand_y[:] = concat(intbv(0)[acc_width + 1 - width:], mag_x)
            carry[0] = first
        sum_x.next = concat(acc_x[acc_width - 1], acc_x) + operand_x + carry
        sum_y.next = concat(acc_y[acc_width - 1], acc_y) + operand_y + carry

    @always_comb
    def overflow():
        over_x.next = not sum_x[acc_width]
        over_y.next = not sum_y[acc_width]
        trad_over_x.next = not trad_x[acc_width]

    # the variants a build leaves out have no logic: their signals stay at 0
    variant_logic = []
    if has_traditional:
        @always_comb
        def traditional():
            # Y first: X integrates |y| after Y's step, which |y|'s adder forms
            trad_x.next = concat(acc_x[acc_width - 1], acc_x) + concat(intbv(0)[acc_width + 1 - width:], stepped_y)
        variant_logic.append(traditional)

    if has_improved:
        @always_comb
        def look_ahead():
            twice_x = modbv(0)[acc_width + 1:]
            twice_y = modbv(0)[acc_width + 1:]
            twice_x[:] = concat(acc_x[acc_width - 1], acc_x) + concat(intbv(0)[acc_width - width:], mag_y, False)
            twice_y[:] = concat(acc_y[acc_width - 1], acc_y) + concat(intbv(0)[acc_width - width:], mag_x, False)
            ahead_x.next = twice_x.signed() >= 0
            ahead_y.next = twice_y.signed() >= 0
        variant_logic.append(look_ahead)

    if has_precise:
        @always_comb
        def nearest():
            # signs of 2E' + B (x inward: B_x, B_y; y inward: ~B_y, ~B_x with a carry)
            first_bias = modbv(0)[bias_width + 1:]
            second_bias = modbv(0)[bias_width + 1:]
            close = modbv(0)[bias_width + 1:]
            far = modbv(0)[bias_width + 1:]
            if x_inward:
                first_bias[:] = concat(bias_x[bias_width - 1], bias_x)
                second_bias[:] = concat(bias_y[bias_width - 1], bias_y)
            else:
                first_bias[:] = ~concat(bias_y[bias_width - 1], bias_y)
                second_bias[:] = ~concat(bias_x[bias_width - 1], bias_x)
            close[:] = concat(error_term, False) + first_bias + concat(intbv(0)[bias_width:], not x_inward)
            far[:] = concat(error_term, False) + second_bias + concat(intbv(0)[bias_width:], not x_inward)
            inward_near.next = far.signed() >= 0
            outward_near.next = close.signed() < 0
        variant_logic.append(nearest)

    @always_comb
    def magnitude_adders():
        # |x| and |y| plus 0 or +-1: in the first clock |x| - (inward) for E' and |y| moved
        # a step towards its target; in the second |x| moved, |y| - (outward) for E'
        op_x = modbv(0)[width:]
        op_y = modbv(0)[width:]
        if pending:
            op_x[:] = 1
            if x_inward:
                op_x[:] = width_ones
            op_y[:] = 0
            if x_inward:
                op_y[:] = width_ones
        else:
            op_x[:] = 0
            if x_inward:
                op_x[:] = width_ones
            op_y[:] = width_ones
            if x_inward:
                op_y[:] = 1
        stepped_x.next = mag_x + op_x
        stepped_y.next = mag_y + op_y

    @always_comb
    def end_tests():
        # |v| - target: 0 at the target, +1 (inward) or -1 (outward) one step before it
        target = modbv(0)[width:]
        dx = modbv(0)[width:]
        dy = modbv(0)[width:]
        target[:] = 0
        if target_x == TARGET_RADIUS:
            target[:] = radius
        elif target_x == TARGET_END:
            target[:] = end_x
        dx[:] = mag_x - target
        target[:] = 0
        if target_y == TARGET_RADIUS:
            target[:] = radius
        elif target_y == TARGET_END:
            target[:] = end_y
        dy[:] = mag_y - target
        at_x.next = dx == 0
        at_y.next = dy == 0
        if x_inward:
            near_x.next = dx == 1
            near_y.next = dy == width_ones
        else:
            near_x.next = dx == width_ones
            near_y.next = dy == 1

    @always_comb
    def decide():
        step_x = over_x == 1
        step_y = over_y == 1
        if not line:
            if variant == TRADITIONAL:
                if over_y:
                    step_x = trad_over_x == 1
            elif variant == IMPROVED:
                if over_x and not over_y and ahead_y:
                    step_y = True
                elif over_y and not over_x and ahead_x:
                    step_x = True
            elif variant == PRECISE:
                step_x = False
                step_y = False
                if over_x or over_y:
                    step_x = inward_near == 1
                    step_y = outward_near == 1
                    if not x_inward:
                        step_x = outward_near == 1
                        step_y = inward_near == 1
            if at_x or at_y:
                step_x = not at_x
                step_y = not at_y
        go_x.next = step_x
        go_y.next = step_y
        tail.next = not line and (at_x or at_y)
        finished.next = False
        next_piece.next = False
        if line:
            finished.next = left_diff == 0
        elif (near_x and step_x or at_x) and (near_y and step_y or at_y):
            if crossings == 0:
                finished.next = True
            else:
                next_piece.next = True

    @always_comb
    def precise_step():
        # E' plus sigma (2 min(|v|, |v'|) + 1): sigma = -1 inward, as ~(2m) + ... with a carry
        magnitude = modbv(0)[width:]
        inward = False
        step_op = modbv(0)[bias_width:]
        magnitude[:] = stepped_x
        inward = x_inward == 1
        if pending:
            magnitude[:] = stepped_y
            inward = not x_inward
        step_op[:] = concat(intbv(0)[bias_width - width - 1:], magnitude, True)
        if inward:
            step_op[:] = ~concat(intbv(0)[bias_width - width - 1:], magnitude, True)
        error_step.next = error_term + step_op + concat(intbv(0)[bias_width - 1:], inward)

    @always_comb
    def handover():
        move.take.next = move.offer and (not active or (pending and dec_finished))
        taking.next = active and cmd.advance and not pending

    @always_seq(clock.posedge, reset=reset)
    def iterate():
        saturated = False
        steps.step_x.next = False
        steps.step_y.next = False
        cmd.done.next = False
        pending.next = False
        if taking:
            pending.next = True
            steps.step_x.next = go_x
            steps.step_y.next = go_y
            if line:
                steps.dir_x.next = right
                steps.dir_y.next = up
            else:
                steps.dir_x.next = (quadrant[0] == quadrant[1]) != x_inward
                steps.dir_y.next = (not quadrant[1]) == x_inward
            cmd.done.next = finished
            dec_x.next = go_x
            dec_y.next = go_y
            dec_tail.next = tail
            dec_finished.next = finished
            dec_next_piece.next = next_piece
            first.next = False
            if not tail:
                # a sum beyond the register saturates at its maximum (paper variants)
                saturated = saturates and not sum_x[acc_width] and sum_x[acc_width - 1]
                acc_x.next = sum_x[acc_width:].signed()
                if has_traditional and variant == TRADITIONAL and over_y and not line:
                    acc_x.next = trad_x[acc_width:].signed()
                    saturated = not trad_x[acc_width] and trad_x[acc_width - 1] == 1
                if saturated:
                    acc_x.next = acc_max
                acc_y.next = sum_y[acc_width:].signed()
                if saturates and not sum_y[acc_width] and sum_y[acc_width - 1]:
                    acc_y.next = acc_max
            if go_y and not line:
                mag_y.next = stepped_y
            if go_x and not line:
                error_term.next = error_step
        elif pending:
            if dec_x and not dec_tail:
                acc_x.next = sum_x[acc_width:].signed()
            if dec_y and not dec_tail:
                acc_y.next = sum_y[acc_width:].signed()
            if dec_x and not line:
                mag_x.next = stepped_x
            if dec_y and not line:
                error_term.next = error_step
            if dec_finished:
                active.next = False
            if dec_next_piece:
                x_inward.next = not x_inward
                crossings.next = crossings - 1
                if ccw:
                    quadrant.next = quadrant + 1
                else:
                    quadrant.next = quadrant - 1
                if crossings == 1:
                    target_x.next = TARGET_END
                    target_y.next = TARGET_END
                elif x_inward:
                    target_x.next = TARGET_RADIUS
                    target_y.next = 0
                else:
                    target_x.next = 0
                    target_y.next = TARGET_RADIUS
        if move.take and not move.error and not move.zero:
            active.next = True
            first.next = move.acc_carry
            line.next = move.line
            variant.next = move.variant
            ccw.next = move.ccw
            blend.next = move.blend
            right.next = move.right
            up.next = move.up
            quadrant.next = move.quadrant
            x_inward.next = move.x_inward
            crossings.next = move.crossings
            target_x.next = move.target_x
            target_y.next = move.target_y
            mag_x.next = move.mag_x
            mag_y.next = move.mag_y
            end_x.next = move.end_x
            end_y.next = move.end_y
            radius.next = move.radius
            threshold.next = move.threshold
            threshold_carry.next = move.line
            acc_x.next = move.acc_init
            acc_y.next = move.acc_init
            error_term.next = 1
        if move.take and move.zero:
            cmd.done.next = True
            quadrant.next = 0

    @always_seq(clock.posedge, reset=reset)
    def precise_bias():
        # B_x = 2|y| - 4|x| and B_y = 4|y| - 2|x| after the steps: x inward, |x| - 1 and
        # |y| + 1 add 4 dx + 2 dy and 2 dx + 4 dy; y inward, the same subtracted
        op_x = modbv(0)[bias_width:]
        op_y = modbv(0)[bias_width:]
        op_x[:] = concat(intbv(0)[bias_width - 3:], dec_x, dec_y, False)
        op_y[:] = concat(intbv(0)[bias_width - 3:], dec_y, dec_x, False)
        if not x_inward:
            op_x[:] = ~op_x
            op_y[:] = ~op_y
        if pending and not line:
            bias_x.next = bias_x + op_x + concat(intbv(0)[bias_width - 1:], not x_inward)
            bias_y.next = bias_y + op_y + concat(intbv(0)[bias_width - 1:], not x_inward)
        if move.take:
            bias_x.next = move.bias_x
            bias_y.next = move.bias_y

    @always_seq(clock.posedge, reset=reset)
    def steps_left():
        # each axis' steps over the rest of the move, as their difference and the larger one
        # minus one (stop_left); a line counts its iterations in the difference
        less = False
        change = modbv(0)[left_width:]
        if pending:
            # a line counts its iterations down; an arc adds -1 for an X step, +1 for a Y step
            if line or (dec_x and not dec_y):
                change[:] = left_ones
            elif dec_y and not dec_x:
                change[:] = 1
            left_diff.next = left_diff + change
            if line:
                less = True
            else:
                if left_diff == 0:
                    less = dec_x and dec_y
                elif left_diff[left_width - 1]:
                    less = dec_y == 1
                else:
                    less = dec_x == 1
            if less and not blend:
                most_left.next = most_left - 1
            if dec_finished:
                most_left.next = left_ones
        if move.take:
            left_diff.next = move.totals_diff
            if move.line:
                left_diff.next = move.totals_diff - 1
            most_left.next = left_ones
            if not move.blend and not move.error and not move.zero:
                most_left.next = move.totals_max - 1

    @always_seq(clock.posedge, reset=reset)
    def errors():
        if cmd.start and cmd.ready:
            cmd.error.next = False
        if move.take and move.error:
            cmd.error.next = True

    @always_comb
    def status():
        cmd.quadrant.next = quadrant
        cmd.stop_left.next = most_left
        cmd.busy.next = not cmd.ready or (active and not (pending and dec_finished))

    return (accumulate, overflow, variant_logic, magnitude_adders, end_tests, decide, precise_step, handover,
            iterate, precise_bias, steps_left, errors, status)
