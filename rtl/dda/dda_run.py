"""DDA run stage: one iteration of the checked move per ``advance``, in two clocks."""
from myhdl import Signal, always, always_comb, always_seq, block, concat, intbv, modbv

from models.dda_build import IMPROVED, PRECISE, TRADITIONAL
from rtl.dda.dda_left import dda_left
from rtl.dda.dda_nearest import dda_nearest
from rtl.interfaces import TARGET_END, TARGET_RADIUS, DdaStep


@block
def dda_run(clock, reset, cmd, move, steps):
    """Run stage of the DDA: iterates the move it took from the check.

    Ports:
        clock, reset  clock and reset (``card_reset()``)
        cmd           ``DdaPort``: ``advance``, ``start`` and ``ready`` in (a taken
                      start clears ``error``); ``done``, ``error``, ``busy``,
                      ``quadrant``, ``stop_left``, ``iterate`` out, and
                      ``progress`` (the decision, with ``iterate``) if it has one
        move          ``DdaMove`` in; ``move.take`` out (the run takes the move at this
                      edge: it is idle or applies its running move's last iteration)
        steps         ``AxisPulses`` out
    Parameters: none; widths and ``variants`` come from ``move``.

    An iteration takes the clock of its ``advance`` and the next one; an
    ``advance`` in that next clock is ignored::

        clock    _/~\\_/~\\_/~\\_/~\\_/~\\_
        advance  _/~~~\\___/~~~\\_______
        step_x   _____/~~~\\___/~~~\\___     step pulses and done leave with the decision
        applied  _________^_______^___     the decision applied (second clock)

    First clock, the decision from registers: each accumulator plus its
    integrand (|y| for X, |x| for Y; a line's |dx|, |dy|) is registered and
    its sign is the overflow; the improved variant adds the integrand twice
    beside it (look-ahead); the precise mode's choice comes from
    ``dda_nearest``; each axis stops at its piece's target (0, Rq or the end
    point: ``|v| - target`` is 0, or +-1 one step before) and the other then
    steps alone.  Second clock, the registered decision applied: the
    accumulators that stepped lose T, |x| and |y| step, ``dda_nearest`` and
    ``dda_left`` (``stop_left``) follow, a new quadrant piece begins or the
    move ends and the run takes the next one.  Datapath registers, loaded
    with a move before they are read, have no reset.

    Processes, by what they drive: first clock, ``accumulate`` (the sums,
    and the second clock's differences), ``overflow``, ``traditional``,
    ``traditional_overflow``, ``look_ahead``, ``magnitudes`` (|x|, |y| a
    step on), ``goals`` and ``end_tests`` (the targets and the tests
    against them), ``decide`` (the decision), ``handover`` (``move.take``,
    ``taking``, ``cmd.iterate``), ``decision`` (the registered decision and the outputs);
    second clock, ``running_move`` (the move's registers and its piece) and
    ``datapath`` (accumulators, magnitudes, the move's values); ``errors``
    (``error``), ``status`` (``quadrant``, ``busy``).
    """
    width = move.coord_width
    acc_width = move.acc_width
    thr_width = move.threshold_width
    variants = move.variants
    has_traditional = TRADITIONAL in variants
    has_improved = IMPROVED in variants
    has_precise = PRECISE in variants
    saturates = bool(variants - {PRECISE})
    acc_max = (1 << (acc_width - 1)) - 1
    acc_ones = (1 << acc_width) - 1
    width_ones = (1 << width) - 1

    step = DdaStep(move)
    active, first = Signal(bool(0)), Signal(bool(0))
    ccw = Signal(bool(0))
    variant = Signal(intbv(PRECISE)[2:])
    right, up = Signal(bool(0)), Signal(bool(0))
    quadrant = Signal(modbv(0)[2:])
    crossings = Signal(intbv(0)[3:])
    target_x, target_y = Signal(intbv(0)[2:]), Signal(intbv(0)[2:])
    end_x, end_y = Signal(intbv(0)[width:]), Signal(intbv(0)[width:])
    radius = Signal(intbv(0)[width:])
    threshold = Signal(intbv(0)[thr_width:])
    threshold_carry = Signal(bool(0))
    acc_x, acc_y = (Signal(intbv(0, min=-(1 << (acc_width - 1)), max=1 << (acc_width - 1))) for _ in range(2))
    # the registered decision's own: the stopped-axis tail, a new piece, the sums to apply
    tail_taken = Signal(bool(0))
    kept_x, kept_y = (Signal(modbv(0)[acc_width:]) for _ in range(2))
    less_x, less_y = Signal(modbv(0)[acc_width:]), Signal(modbv(0)[acc_width:])
    # first clock, combinational from registers
    sum_x, sum_y = Signal(modbv(0)[acc_width + 1:]), Signal(modbv(0)[acc_width + 1:])
    over_x, over_y = Signal(bool(0)), Signal(bool(0))
    saturate_x, saturate_y = Signal(bool(0)), Signal(bool(0))
    stepped_x, stepped_y = Signal(modbv(0)[width:]), Signal(modbv(0)[width:])
    go_x, go_y, tail, finished, next_piece = (Signal(bool(0)) for _ in range(5))
    at_x, at_y, near_x, near_y = (Signal(bool(0)) for _ in range(4))
    goal_x, goal_y = Signal(modbv(0)[width:]), Signal(modbv(0)[width:])
    ahead_x, ahead_y = Signal(bool(0)), Signal(bool(0))
    # without the traditional variant its branches are never taken: its sum is the plain one
    trad_x = Signal(modbv(0)[acc_width + 1:]) if has_traditional else sum_x
    trad_over_x = Signal(bool(0)) if has_traditional else over_x
    taking = Signal(bool(0))

    left = dda_left(clock, reset, step, move, cmd)
    # the variants a build leaves out have no logic: their signals stay at 0
    variant_logic = [left]
    if has_precise:
        variant_logic.append(dda_nearest(clock, step, move))

    @always_comb
    def accumulate():
        # first clock: A - bias plus the integrand (a line's first sum takes the carry of its
        # initial load); second clock: the kept sum minus T for an axis that stepped (T - 1
        # inverted, a line's T inverted with a carry)
        minus_x = modbv(0)[acc_width:]
        minus_y = modbv(0)[acc_width:]
        sum_x.next = concat(acc_x[acc_width - 1], acc_x) + concat(intbv(0)[acc_width + 1 - width:], step.mag_y) + \
            concat(intbv(0)[acc_width:], first)
        sum_y.next = concat(acc_y[acc_width - 1], acc_y) + concat(intbv(0)[acc_width + 1 - width:], step.mag_x) + \
            concat(intbv(0)[acc_width:], first)
        if step.step_x:
            minus_x[:] = ~concat(intbv(0)[acc_width - thr_width:], threshold)
        if step.step_y:
            minus_y[:] = ~concat(intbv(0)[acc_width - thr_width:], threshold)
        less_x.next = kept_x + minus_x + concat(intbv(0)[acc_width - 1:], step.step_x and threshold_carry)
        less_y.next = kept_y + minus_y + concat(intbv(0)[acc_width - 1:], step.step_y and threshold_carry)

    @always_comb
    def overflow():
        over_x.next = not sum_x[acc_width]
        over_y.next = not sum_y[acc_width]
        saturate_x.next = not sum_x[acc_width] and sum_x[acc_width - 1]
        if has_traditional and variant == TRADITIONAL and over_y and not step.line:
            saturate_x.next = not trad_x[acc_width] and trad_x[acc_width - 1]
        saturate_y.next = not sum_y[acc_width] and sum_y[acc_width - 1]

    if has_traditional:
        @always_comb
        def traditional():
            # Y first: X integrates |y| after Y's step, which |y|'s adder forms
            trad_x.next = concat(acc_x[acc_width - 1], acc_x) + concat(intbv(0)[acc_width + 1 - width:], stepped_y)

        @always_comb
        def traditional_overflow():
            # X's overflow with the new |y| = |y| +- 1 from the sum S with the old |y| and an
            # equality beside its adder: S + 1 >= 0 is S >= 0 or S = -1 (acc = ~|y|), S - 1 >= 0
            # is S >= 0 and S != 0 (S = 0: every bit's a ^ b is the carry a | b of the one below)
            acc = modbv(0)[acc_width:]
            mag = modbv(0)[acc_width:]
            either = modbv(0)[acc_width - 1:]
            acc[:] = acc_x[acc_width:]
            mag[:] = concat(intbv(0)[acc_width - width:], step.mag_y)
            either[:] = acc[acc_width - 1:] | mag[acc_width - 1:]
            if step.x_inward:
                trad_over_x.next = over_x or (acc ^ mag) == intbv(acc_ones)[acc_width:]
            else:
                trad_over_x.next = over_x and (acc ^ mag) != concat(either, False)
        variant_logic.extend((traditional, traditional_overflow))

    if has_improved:
        @always_comb
        def look_ahead():
            # A + 2i straight from the registers (one adder each)
            twice_x = modbv(0)[acc_width + 1:]
            twice_y = modbv(0)[acc_width + 1:]
            twice_x[:] = concat(acc_x[acc_width - 1], acc_x) + concat(intbv(0)[acc_width - width:], step.mag_y, False)
            twice_y[:] = concat(acc_y[acc_width - 1], acc_y) + concat(intbv(0)[acc_width - width:], step.mag_x, False)
            ahead_x.next = twice_x.signed() >= 0
            ahead_y.next = twice_y.signed() >= 0
        variant_logic.append(look_ahead)

    @always_comb
    def magnitudes():
        # |x| and |y| moved a step towards their targets (also the traditional variant's new |y|)
        op_x = modbv(0)[width:]
        op_y = modbv(0)[width:]
        op_x[:] = 1
        op_y[:] = width_ones
        if step.x_inward:
            op_x[:] = width_ones
            op_y[:] = 1
        stepped_x.next = step.mag_x + op_x
        stepped_y.next = step.mag_y + op_y

    @always_comb
    def goals():
        goal_x.next = 0
        if target_x == TARGET_RADIUS:
            goal_x.next = radius
        elif target_x == TARGET_END:
            goal_x.next = end_x
        goal_y.next = 0
        if target_y == TARGET_RADIUS:
            goal_y.next = radius
        elif target_y == TARGET_END:
            goal_y.next = end_y

    @always_comb
    def end_tests():
        # |v| at its target, or one step before it (inward: target + 1 = |v|, outward:
        # |v| + 1 = target), without a carry chain: a + 1 = b when bit 0 differs and every
        # other bit differs exactly where the bit below carries (a and not b)
        diff_x = modbv(0)[width:]
        diff_y = modbv(0)[width:]
        up_x = modbv(0)[width - 1:]
        up_y = modbv(0)[width - 1:]
        down_x = modbv(0)[width - 1:]
        down_y = modbv(0)[width - 1:]
        diff_x[:] = step.mag_x ^ goal_x
        diff_y[:] = step.mag_y ^ goal_y
        up_x[:] = step.mag_x[width - 1:] & ~goal_x[width - 1:]
        up_y[:] = step.mag_y[width - 1:] & ~goal_y[width - 1:]
        down_x[:] = goal_x[width - 1:] & ~step.mag_x[width - 1:]
        down_y[:] = goal_y[width - 1:] & ~step.mag_y[width - 1:]
        at_x.next = diff_x == 0
        at_y.next = diff_y == 0
        if step.x_inward:
            near_x.next = diff_x == concat(down_x, True)
            near_y.next = diff_y == concat(up_y, True)
        else:
            near_x.next = diff_x == concat(up_x, True)
            near_y.next = diff_y == concat(down_y, True)

    @always_comb
    def decide():
        # the variant's steps (flat: few levels after the adders' signs); at a target an
        # axis stops and the other steps alone (tail); the move (or the piece) ends when both
        # axes are at their targets after this step: in a tail the stopped one is, so the
        # other needs to be at or one step before its target; otherwise both must be one
        # step before and the step a diagonal, which the precise signs decide last
        step_x = over_x == 1
        step_y = over_y == 1
        diagonal = over_x and over_y
        choose_x = False
        choose_y = False
        if has_precise:
            choose_x = step.outward_near == 1
            choose_y = step.inward_near == 1
            if step.x_inward:
                choose_x = step.inward_near == 1
                choose_y = step.outward_near == 1
        if has_traditional and variant == TRADITIONAL:
            step_x = (over_y and trad_over_x) or (not over_y and over_x)
            diagonal = over_y and trad_over_x
        elif has_improved and variant == IMPROVED:
            step_x = over_x or (over_y and ahead_x)
            step_y = over_y or (over_x and ahead_y)
            diagonal = (over_x or (over_y and ahead_x)) and (over_y or (over_x and ahead_y))
        elif has_precise and variant == PRECISE:
            step_x = (over_x or over_y) and choose_x
            step_y = (over_x or over_y) and choose_y
            diagonal = (over_x or over_y) and step.inward_near and step.outward_near
        if step.line:
            go_x.next = over_x
            go_y.next = over_y
        elif at_x or at_y:
            go_x.next = not at_x
            go_y.next = not at_y
        else:
            go_x.next = step_x
            go_y.next = step_y
        tail.next = not step.line and (at_x or at_y)
        tail_ends = not step.line and (at_x or at_y) and (at_x or near_x) and (at_y or near_y)
        both_near = not step.line and not at_x and not at_y and near_x and near_y
        last_piece = crossings == 0
        finished.next = (step.line and step.last) or (last_piece and (tail_ends or (both_near and diagonal)))
        next_piece.next = not last_piece and (tail_ends or (both_near and diagonal))

    if cmd.progress is not None:
        @always_comb
        def progress():
            # a helix follows the decision of the iteration taken (dda_helix)
            cmd.progress.step_u.next = go_x
            cmd.progress.step_v.next = go_y
            cmd.progress.u_inward.next = step.x_inward
        variant_logic.append(progress)

    @always_comb
    def handover():
        move.take.next = move.offer and (not active or (step.pending and step.finished))
        taking.next = active and cmd.advance and not step.pending
        cmd.iterate.next = active and cmd.advance and not step.pending

    @always_seq(clock.posedge, reset=reset)
    def decision():
        # first clock of an iteration: the decision and the outputs, registered (and the
        # done of a line of length 0, taken)
        steps.step_x.next = False
        steps.step_y.next = False
        cmd.done.next = False
        step.pending.next = False
        if taking:
            step.pending.next = True
            steps.step_x.next = go_x
            steps.step_y.next = go_y
            if step.line:
                steps.dir_x.next = right
                steps.dir_y.next = up
            else:
                steps.dir_x.next = (quadrant[0] == quadrant[1]) != step.x_inward
                steps.dir_y.next = (not quadrant[1]) == step.x_inward
            cmd.done.next = finished
            step.step_x.next = go_x
            step.step_y.next = go_y
            step.finished.next = finished
            tail_taken.next = tail
            step.new_piece.next = next_piece
        if move.take and move.zero:
            cmd.done.next = True

    @always_seq(clock.posedge, reset=reset)
    def running_move():
        # the running move: taken with its first piece, ended or on to its next piece when
        # its registered decision is applied (second clock)
        if taking:
            first.next = False
        elif step.pending:
            if step.finished:
                active.next = False
            if step.new_piece:
                step.x_inward.next = not step.x_inward
                crossings.next = crossings - 1
                if ccw:
                    quadrant.next = quadrant + 1
                else:
                    quadrant.next = quadrant - 1
                if crossings == 1:
                    target_x.next = TARGET_END
                    target_y.next = TARGET_END
                elif step.x_inward:
                    target_x.next = TARGET_RADIUS
                    target_y.next = 0
                else:
                    target_x.next = 0
                    target_y.next = TARGET_RADIUS
        if move.take and not move.error and not move.zero:
            active.next = True
            first.next = move.acc_carry
            step.line.next = move.line
            variant.next = move.variant
            ccw.next = move.ccw
            step.blend.next = move.blend
            right.next = move.right
            up.next = move.up
            quadrant.next = move.quadrant
            step.x_inward.next = move.x_inward
            crossings.next = move.crossings
            target_x.next = move.target_x
            target_y.next = move.target_y
            threshold_carry.next = move.line
        if move.take and move.zero:
            quadrant.next = 0

    @always(clock.posedge)
    def datapath():
        # registers loaded before they are read: no reset, so that a load of a constant
        # (the saturated sum) is a flip-flop's own synchronous set or reset
        if taking:
            kept_x.next = sum_x[acc_width:]
            if has_traditional and variant == TRADITIONAL and over_y and not step.line:
                kept_x.next = trad_x[acc_width:]
            kept_y.next = sum_y[acc_width:]
            # a sum beyond the register saturates at its maximum (paper variants)
            if saturates and saturate_x:
                kept_x.next = acc_max
            if saturates and saturate_y:
                kept_y.next = acc_max
        elif step.pending:
            if not tail_taken:
                acc_x.next = less_x.signed()
                acc_y.next = less_y.signed()
            if not step.line:
                if step.step_x:
                    step.mag_x.next = stepped_x
                if step.step_y:
                    step.mag_y.next = stepped_y
        if move.take:
            step.mag_x.next = move.mag_x
            step.mag_y.next = move.mag_y
            end_x.next = move.end_x
            end_y.next = move.end_y
            radius.next = move.radius
            threshold.next = move.threshold
            acc_x.next = move.acc_init
            acc_y.next = move.acc_init

    @always_seq(clock.posedge, reset=reset)
    def errors():
        if cmd.start and cmd.ready:
            cmd.error.next = False
        if move.take and move.error:
            cmd.error.next = True

    @always_comb
    def status():
        cmd.quadrant.next = quadrant
        cmd.busy.next = not cmd.ready or (active and not (step.pending and step.finished))

    return (variant_logic, accumulate, overflow, magnitudes, goals, end_tests, decide, handover, decision, running_move,
            datapath, errors, status)
