"""DDA run stage: one iteration of the checked move per ``advance``, in two clocks."""
from myhdl import Signal, always, always_comb, always_seq, block, concat, intbv, modbv

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

    # the second clock's registered decision, and the sums it applies
    dec_x, dec_y, dec_tail, dec_finished, dec_next_piece = (Signal(bool(0)) for _ in range(5))
    dec_in, dec_out = Signal(bool(0)), Signal(bool(0))
    dec_sum_x, dec_sum_y = (Signal(modbv(0)[acc_width:]) for _ in range(2))
    less_x, less_y = Signal(modbv(0)[acc_width:]), Signal(modbv(0)[acc_width:])

    # first clock, combinational from registers
    sum_x, sum_y = Signal(modbv(0)[acc_width + 1:]), Signal(modbv(0)[acc_width + 1:])
    over_x, over_y = Signal(bool(0)), Signal(bool(0))
    saturate_x, saturate_y = Signal(bool(0)), Signal(bool(0))
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
        # first clock: A - bias plus the integrand (a line's first sum takes the carry of its
        # initial load); second clock: the kept sum minus T for an axis that stepped (T - 1
        # inverted, a line's T inverted with a carry)
        minus_x = modbv(0)[acc_width:]
        minus_y = modbv(0)[acc_width:]
        sum_x.next = concat(acc_x[acc_width - 1], acc_x) + concat(intbv(0)[acc_width + 1 - width:], mag_y) + \
            concat(intbv(0)[acc_width:], first)
        sum_y.next = concat(acc_y[acc_width - 1], acc_y) + concat(intbv(0)[acc_width + 1 - width:], mag_x) + \
            concat(intbv(0)[acc_width:], first)
        if dec_x:
            minus_x[:] = ~concat(intbv(0)[acc_width - thr_width:], threshold)
        if dec_y:
            minus_y[:] = ~concat(intbv(0)[acc_width - thr_width:], threshold)
        less_x.next = dec_sum_x + minus_x + concat(intbv(0)[acc_width - 1:], dec_x and threshold_carry)
        less_y.next = dec_sum_y + minus_y + concat(intbv(0)[acc_width - 1:], dec_y and threshold_carry)

    @always_comb
    def overflow():
        over_x.next = not sum_x[acc_width]
        over_y.next = not sum_y[acc_width]
        trad_over_x.next = not trad_x[acc_width]
        saturate_x.next = not sum_x[acc_width] and sum_x[acc_width - 1]
        if has_traditional and variant == TRADITIONAL and over_y and not line:
            saturate_x.next = not trad_x[acc_width] and trad_x[acc_width - 1]
        saturate_y.next = not sum_y[acc_width] and sum_y[acc_width - 1]

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
            # signs of 2E' + B_x, 2E' + B_y (x inward) and 2E' - B_y, 2E' - B_x (y inward):
            # four adders, the quadrant picks two signs after them
            twice_error = modbv(0)[bias_width + 1:]
            plus_x = modbv(0)[bias_width + 1:]
            plus_y = modbv(0)[bias_width + 1:]
            minus_x = modbv(0)[bias_width + 1:]
            minus_y = modbv(0)[bias_width + 1:]
            twice_error[:] = concat(error_term, False)
            plus_x[:] = twice_error + concat(bias_x[bias_width - 1], bias_x)
            plus_y[:] = twice_error + concat(bias_y[bias_width - 1], bias_y)
            minus_x[:] = twice_error - concat(bias_x[bias_width - 1], bias_x)
            minus_y[:] = twice_error - concat(bias_y[bias_width - 1], bias_y)
            if x_inward:
                inward_near.next = plus_y.signed() >= 0
                outward_near.next = plus_x.signed() < 0
            else:
                inward_near.next = minus_x.signed() >= 0
                outward_near.next = minus_y.signed() < 0
        variant_logic.append(nearest)

    @always_comb
    def magnitude_adders():
        # |x| and |y| moved a step towards their targets (also the traditional variant's new |y|)
        op_x = modbv(0)[width:]
        op_y = modbv(0)[width:]
        op_x[:] = 1
        op_y[:] = width_ones
        if x_inward:
            op_x[:] = width_ones
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
        # the variant's steps (flat, few levels after the adders' signs); at a target an axis
        # stops and the other steps alone (tail); the move (or the piece) ends when both
        # axes are at their targets after this step: in a tail the stopped one is, so the
        # other needs to be at or one step before its target; otherwise both must be one
        # step before and step
        step_x = over_x == 1
        step_y = over_y == 1
        choose_x = False
        choose_y = False
        ends = False
        if has_precise:
            choose_x = outward_near == 1
            choose_y = inward_near == 1
            if x_inward:
                choose_x = inward_near == 1
                choose_y = outward_near == 1
        if has_traditional and variant == TRADITIONAL:
            step_x = (over_y and trad_over_x) or (not over_y and over_x)
        elif has_improved and variant == IMPROVED:
            step_x = over_x or (over_y and ahead_x)
            step_y = over_y or (over_x and ahead_y)
        elif has_precise and variant == PRECISE:
            step_x = (over_x or over_y) and choose_x
            step_y = (over_x or over_y) and choose_y
        if line:
            go_x.next = over_x
            go_y.next = over_y
        elif at_x or at_y:
            go_x.next = not at_x
            go_y.next = not at_y
        else:
            go_x.next = step_x
            go_y.next = step_y
        tail.next = not line and (at_x or at_y)
        if at_x or at_y:
            ends = (at_x or near_x) and (at_y or near_y)
        else:
            ends = near_x and near_y and step_x and step_y
        finished.next = (line and left_diff == 0) or (not line and ends and crossings == 0)
        next_piece.next = not line and ends and crossings != 0

    @always_comb
    def precise_step():
        # E' plus the registered step, both magnitudes still those before it: an outward
        # step adds 2 m + 1, an inward one -(2 (m - 1) + 1) = ~(2 m) + 2 (two adders, each
        # with a carry of 1 for it)
        outward = modbv(0)[bias_width:]
        inward = modbv(0)[bias_width:]
        first_sum = modbv(0)[bias_width:]
        if dec_out:
            outward[:] = concat(intbv(0)[bias_width - width - 1:], mag_x, True)
            if x_inward:
                outward[:] = concat(intbv(0)[bias_width - width - 1:], mag_y, True)
        if dec_in:
            inward[:] = ~concat(intbv(0)[bias_width - width - 1:], mag_y, False)
            if x_inward:
                inward[:] = ~concat(intbv(0)[bias_width - width - 1:], mag_x, False)
        first_sum[:] = error_term + outward + concat(intbv(0)[bias_width - 1:], dec_in)
        error_step.next = first_sum + inward + concat(intbv(0)[bias_width - 1:], dec_in)

    @always_comb
    def handover():
        move.take.next = move.offer and (not active or (pending and dec_finished))
        taking.next = active and cmd.advance and not pending

    @always_seq(clock.posedge, reset=reset)
    def iterate():
        # the control state: the iteration's two clocks, the decision, the quadrant pieces
        steps.step_x.next = False
        steps.step_y.next = False
        cmd.done.next = False
        pending.next = False
        if taking:
            # first clock: the decision and the outputs, registered
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
            dec_in.next = (go_x and x_inward) or (go_y and not x_inward)
            dec_out.next = (go_x and not x_inward) or (go_y and x_inward)
            dec_tail.next = tail
            dec_finished.next = finished
            dec_next_piece.next = next_piece
            first.next = False
        elif pending:
            # second clock: the decision applied
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
            threshold_carry.next = move.line
        if move.take and move.zero:
            cmd.done.next = True
            quadrant.next = 0

    @always(clock.posedge)
    def datapath():
        # registers loaded before they are read: no reset, so that a load of a constant
        # (the saturated sum, E' = 1) is a flip-flop's own synchronous set or reset
        if taking:
            dec_sum_x.next = sum_x[acc_width:]
            if has_traditional and variant == TRADITIONAL and over_y and not line:
                dec_sum_x.next = trad_x[acc_width:]
            dec_sum_y.next = sum_y[acc_width:]
            # a sum beyond the register saturates at its maximum (paper variants)
            if saturates and saturate_x:
                dec_sum_x.next = acc_max
            if saturates and saturate_y:
                dec_sum_y.next = acc_max
        elif pending:
            if not dec_tail:
                acc_x.next = less_x.signed()
                acc_y.next = less_y.signed()
            if not line:
                if dec_x:
                    mag_x.next = stepped_x
                if dec_y:
                    mag_y.next = stepped_y
                error_term.next = error_step
        if move.take:
            mag_x.next = move.mag_x
            mag_y.next = move.mag_y
            end_x.next = move.end_x
            end_y.next = move.end_y
            radius.next = move.radius
            threshold.next = move.threshold
            acc_x.next = move.acc_init
            acc_y.next = move.acc_init
            error_term.next = 1

    @always(clock.posedge)
    def precise_bias():
        # B_x = 2|y| - 4|x| and B_y = 4|y| - 2|x| after the steps (dx, dy): X inward adds
        # 4 dx + 2 dy and 2 dx + 4 dy, Y inward subtracts them
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

    @always(clock.posedge)
    def steps_difference():
        # each axis' steps over the rest of the move: their difference (a line: its
        # iterations left, minus one), taken through the same adder
        base = modbv(0)[left_width:]
        change = modbv(0)[left_width:]
        base[:] = left_diff
        if move.take:
            base[:] = move.totals_diff
            if move.line:
                change[:] = left_ones
        elif pending:
            if line or (dec_x and not dec_y):
                change[:] = left_ones
            elif dec_y and not dec_x:
                change[:] = 1
        left_diff.next = base + change

    @always_seq(clock.posedge, reset=reset)
    def steps_left():
        # the larger axis' steps left, minus one (stop_left): it falls when the axis that has
        # more steps left steps (both, when they have as many); all ones while no move or a
        # blended one runs
        base = modbv(0)[left_width:]
        less = modbv(0)[left_width:]
        base[:] = most_left
        if move.take:
            base[:] = move.totals_max
            less[:] = left_ones
        elif pending and not blend:
            if line:
                less[:] = left_ones
            elif left_diff == 0:
                if dec_x and dec_y:
                    less[:] = left_ones
            elif left_diff[left_width - 1]:
                if dec_y:
                    less[:] = left_ones
            elif dec_x:
                less[:] = left_ones
        most_left.next = base + less
        if move.take:
            if move.blend or move.error or move.zero:
                most_left.next = left_ones
        elif pending and dec_finished:
            most_left.next = left_ones

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
            iterate, datapath, precise_bias, steps_difference, steps_left, errors, status)
