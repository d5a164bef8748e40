"""DDA setup stage: latches a command and works out what its check needs, on one adder.

See ``dda_setup``'s docstring; ``docs/dda.md`` has the sequence with its clock counts.
"""
from myhdl import Signal, always_comb, always_seq, block, concat, enum, intbv, modbv

from rtl.dda_build import PAPER_VARIANTS

# what the adder's accumulator does in a clock, and the operand register
G_HOLD, G_ADD, G_ZERO, G_ONES = range(4)
M_HOLD, M_SHIFT, M_FLIP, M_LOAD = range(4)
# operand sources
SRC_XS, SRC_YS, SRC_XE, SRC_YE, SRC_ROOT = range(5)
PRE_STEPS, LIMIT_STEPS, POST_STEPS = 7, 3, 12


@block
def dda_setup(clock, reset, cmd, plan):
    """Setup stage of the DDA: latch, magnitude compares, squares, root, limits, totals.

    Ports:
        clock, reset  clock and reset (``card_reset()``)
        cmd           ``DdaPort``: the command lines and ``start`` in, ``ready`` out
                      (the stage is free); ``error``, ``done`` and the rest are the run's
        plan          ``DdaPlan`` out: the latched command and what was worked out;
                      ``plan.done`` while a finished plan waits, ``plan.taken`` in
    Parameters: none; ``coord_width`` (W) and ``variants`` come from ``cmd``.

    One adder of 2W + 1 bits (``gap``) adds a shifting operand register
    (``operand``, loaded from the four magnitudes or the root) in every
    clock: a line needs one clock after the latch, an arc 4W + 22::

        clock   _/~\\_/~\\_ ... _/~\\_ ... _/~\\_ ... _/~\\_ ... _/~\\_/~\\_
        start   _/~~~\\___ ... _____ ... _____ ... _____ ... __________
        ready   ~~~~~\\___ ... _____ ... _____ ... _____ ... ____/~~~~~  (taken)
                    |compares| squares | limits| totals |done
                    |   7    |   4W    |   3   |   12   |

    * compares: |xs| - |ys| (which is m = max(|xs|, |ys|)), |xs| - |xe|,
      |ys| - |ye| (whether the end lies ahead in the start's quadrant);
    * squares: gap = -1 - xs**2 - ys**2 + xe**2 + ye**2 by shift-add, the
      multiplier bits from ``multiplier``; half-way ~gap = xs**2 + ys**2 goes to
      the radicand and a restoring square root (its own subtractor) takes
      W + 1 clocks beside the other two squares: t = 2 root + r, r the rounding;
    * limits: gap + 2m >= 0 and gap - 2m - 1 < 0 (the end within one step);
    * totals: Rq = (t + 1) >> 1, the end's inward magnitude against Rq, and
      each axis' steps over the whole move (difference, larger) as signed sums
      of the magnitudes and 2 Rq = t + r.

    The paper variants' threshold 2**(n + k) - 1 is shifted together one bit
    a clock in ``plan.threshold`` (n = acc_bits, or the root's bit length as it
    appears), a line's T = max(|dx|, |dy|) is loaded there.
    """
    width = cmd.coord_width
    gap_width = 2 * width + 1
    left_width = plan.left_width
    thr_width = plan.threshold_width
    width_ones = (1 << width) - 1
    paper = bool(cmd.variants & PAPER_VARIANTS)

    t_state = enum("S_IDLE", "S_LINE", "S_PRE", "S_SQUARE", "S_LIMIT", "S_POST", "S_DONE")
    state = Signal(t_state.S_IDLE)
    step = Signal(intbv(0, min=0, max=max(width, POST_STEPS)))
    square = Signal(modbv(0)[2:])

    acc_bits = Signal(intbv(0)[5:])
    neg_xs, neg_ys = Signal(bool(0)), Signal(bool(0))
    cmd_mag_xs, cmd_mag_ys, cmd_mag_xe, cmd_mag_ye = (Signal(intbv(0)[width:]) for _ in range(4))

    # the adder: gap + operand (+ carry), the operand shifting left one bit a clock
    gap = Signal(modbv(0)[gap_width:])
    operand = Signal(modbv(0)[gap_width:])
    total = Signal(modbv(0)[gap_width:])
    multiplier = Signal(intbv(0)[width:])
    gap_op = Signal(intbv(0)[2:])
    operand_op = Signal(intbv(0)[2:])
    source = Signal(intbv(0)[3:])
    source_on, invert, carry = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    source_value = Signal(intbv(0)[width + 1:])

    # square root of xs**2 + ys**2, one bit a clock, and the rounding bit after it
    radicand = Signal(modbv(0)[2 * width:])
    remainder = Signal(intbv(0)[width + 2:])
    root = Signal(intbv(0)[width + 1:])
    root_steps = Signal(intbv(0, min=0, max=width + 2))
    root_started, root_all_ones = Signal(bool(0)), Signal(bool(0))
    trial_fits = Signal(bool(0))
    trial_keep = Signal(intbv(0)[width + 2:])

    # what the compares found, and the geometry of the latched command
    m_is_y = Signal(bool(0))
    shrink_x_neg, shrink_x_zero, shrink_y_neg, shrink_y_zero = (Signal(bool(0)) for _ in range(4))
    x_inward_end = Signal(bool(0))
    pick_x = Signal(bool(0))
    twice = Signal(intbv(0)[2:])
    ones_left = Signal(intbv(0, min=0, max=64))
    major_width = max(thr_width, left_width)
    major = Signal(intbv(0)[major_width:])

    @always_comb
    def magnitudes():
        # |v| is v - 1 inverted for a negative v, v itself otherwise: one adder whose
        # operand is the sign (all ones or zero), its sum inverted by the same sign
        sign_xs = modbv(0)[width:]
        sign_ys = modbv(0)[width:]
        sign_xe = modbv(0)[width:]
        sign_ye = modbv(0)[width:]
        if cmd.xs[width - 1]:
            sign_xs[:] = width_ones
        if cmd.ys[width - 1]:
            sign_ys[:] = width_ones
        if cmd.xe[width - 1]:
            sign_xe[:] = width_ones
        if cmd.ye[width - 1]:
            sign_ye[:] = width_ones
        less_xs = modbv(0)[width:]
        less_ys = modbv(0)[width:]
        less_xe = modbv(0)[width:]
        less_ye = modbv(0)[width:]
        less_xs[:] = cmd.xs[width:] + sign_xs
        less_ys[:] = cmd.ys[width:] + sign_ys
        less_xe[:] = cmd.xe[width:] + sign_xe
        less_ye[:] = cmd.ye[width:] + sign_ye
        cmd_mag_xs.next = less_xs ^ sign_xs
        cmd_mag_ys.next = less_ys ^ sign_ys
        cmd_mag_xe.next = less_xe ^ sign_xe
        cmd_mag_ye.next = less_ye ^ sign_ye

    @always_comb
    def control():
        # the micro-operation of this clock (see the docstring's sequence): what the adder's
        # accumulator does and what the operand register loads (source, inverted) for the next
        g_op = intbv(0)[2:]
        o_op = intbv(0)[2:]
        src = intbv(0)[3:]
        on = True
        inv = False
        g_op[:] = G_HOLD
        o_op[:] = M_HOLD
        src[:] = SRC_XS
        if state == t_state.S_PRE:
            o_op[:] = M_LOAD
            if step == 0:
                src[:] = SRC_XS
            elif step == 1:
                g_op[:] = G_ADD
                src[:] = SRC_YS
                inv = True
            elif step == 2:
                g_op[:] = G_ADD
                src[:] = SRC_YS
            elif step == 3:
                g_op[:] = G_ADD
                src[:] = SRC_XE
                inv = True
            elif step == 4:
                g_op[:] = G_ZERO
                src[:] = SRC_YS
            elif step == 5:
                g_op[:] = G_ADD
                src[:] = SRC_YE
                inv = True
            else:
                g_op[:] = G_ONES
                src[:] = SRC_XS
                inv = True
        elif state == t_state.S_SQUARE:
            o_op[:] = M_SHIFT
            inv = square < 2
            if multiplier[0]:
                g_op[:] = G_ADD
            if step == width - 1:
                o_op[:] = M_LOAD
                if square == 0:
                    src[:] = SRC_YS
                    inv = True
                elif square == 1:
                    src[:] = SRC_XE
                    inv = False
                elif square == 2:
                    src[:] = SRC_YE
                    inv = False
                else:
                    # m for the limits
                    inv = False
                    src[:] = SRC_XS
                    if m_is_y:
                        src[:] = SRC_YS
        elif state == t_state.S_LIMIT:
            if step == 0:
                o_op[:] = M_SHIFT
            elif step == 1:
                g_op[:] = G_ADD
                o_op[:] = M_FLIP
            else:
                g_op[:] = G_ZERO
                o_op[:] = M_LOAD
                src[:] = SRC_ROOT
        elif state == t_state.S_POST:
            g_op[:] = G_ADD
            o_op[:] = M_LOAD
            if step == 0:
                # t + 1, then the end's inward magnitude, doubled and negated
                src[:] = SRC_YE
                if x_inward_end:
                    src[:] = SRC_XE
                inv = True
            elif step == 1:
                g_op[:] = G_HOLD
                o_op[:] = M_SHIFT
                inv = True
            elif step == 2:
                # the inward test; then the difference of the totals, term by term
                g_op[:] = G_ZERO
                src[:] = SRC_XS
                inv = not plan.x_inward
            elif step == 3:
                src[:] = SRC_YS
                inv = not plan.x_inward
            elif step == 4:
                src[:] = SRC_XE
                inv = x_inward_end == 1
            elif step == 5:
                src[:] = SRC_YE
                inv = x_inward_end == 1
            elif step == 6:
                src[:] = SRC_ROOT
                on = plan.x_inward != x_inward_end
                inv = plan.x_inward == 1
            elif step == 7:
                # the larger total: its start term first (the sign of the difference just
                # formed picks the axis)
                g_op[:] = G_ZERO
                src[:] = SRC_YS
                inv = plan.x_inward == 1
                if not total[left_width - 1]:
                    src[:] = SRC_XS
                    inv = not plan.x_inward
            elif step == 8:
                src[:] = SRC_YE
                inv = not x_inward_end
                if pick_x:
                    src[:] = SRC_XE
                    inv = x_inward_end == 1
            elif step == 9:
                # k Rq, k = 0, 2 or 4: up to two terms 2 Rq = t + r
                src[:] = SRC_ROOT
                on = twice != 0
            elif step == 10:
                src[:] = SRC_ROOT
                on = twice == 2
            else:
                o_op[:] = M_HOLD
        else:
            g_op[:] = G_HOLD
        gap_op.next = g_op
        operand_op.next = o_op
        source.next = src
        source_on.next = on
        invert.next = inv

    @always_comb
    def carry_in():
        # the adder's carry: the +1 of a subtraction (the operand was loaded inverted), and
        # 2 Rq = t + r (r = t's low bit; -2 Rq = ~t + ~r)
        cin = False
        if state == t_state.S_PRE:
            cin = step == 2 or step == 4 or step == 6
        elif state == t_state.S_SQUARE:
            cin = square < 2
        elif state == t_state.S_POST:
            if step == 0:
                cin = True
            elif step == 2:
                cin = root[0] == 1
            elif step == 3 or step == 4:
                cin = not plan.x_inward
            elif step == 5 or step == 6:
                cin = x_inward_end == 1
            elif step == 7:
                cin = plan.x_inward != x_inward_end and root[0] != plan.x_inward
            elif step == 8:
                cin = pick_x != plan.x_inward
            elif step == 9:
                cin = pick_x == x_inward_end
            elif step == 10:
                cin = root[0] and twice != 0
            elif step == 11:
                cin = root[0] and twice == 2
        else:
            cin = False
        carry.next = cin

    @always_comb
    def rq_terms():
        # k / 2 for the larger axis: k = (crossings - 1) + 1 if it starts outward (its first
        # piece ends at Rq) + 1 if it ends inward (its last piece starts at Rq); 0 for one piece
        starts_inward = plan.x_inward == pick_x
        ends_inward = x_inward_end == pick_x
        count = modbv(0)[3:]
        count[:] = plan.crossings - 1
        if not starts_inward:
            count[:] = count + 1
        if ends_inward:
            count[:] = count + 1
        twice.next = count[3:1]
        if plan.ahead or plan.crossings == 0:
            twice.next = 0

    @always_comb
    def select_source():
        value = intbv(0)[width + 1:]
        if source == SRC_XS:
            value[:] = concat(False, plan.mag_xs)
        elif source == SRC_YS:
            value[:] = concat(False, plan.mag_ys)
        elif source == SRC_XE:
            value[:] = concat(False, plan.mag_xe)
        elif source == SRC_YE:
            value[:] = concat(False, plan.mag_ye)
        else:
            value[:] = root
        if not source_on:
            value[:] = 0
        source_value.next = value

    @always_comb
    def adder():
        total.next = gap + operand + concat(intbv(0)[gap_width - 1:], carry)

    @always_seq(clock.posedge, reset=reset)
    def datapath():
        loaded = modbv(0)[gap_width:]
        if gap_op == G_ADD:
            gap.next = total
        elif gap_op == G_ZERO:
            gap.next = 0
        elif gap_op == G_ONES:
            gap.next = (1 << gap_width) - 1
        if operand_op == M_SHIFT:
            operand.next = concat(operand[gap_width - 1:], invert)
        elif operand_op == M_FLIP:
            operand.next = ~concat(operand[gap_width - 1:], False)
        elif operand_op == M_LOAD:
            loaded[:] = concat(intbv(0)[gap_width - width - 1:], source_value)
            if invert and source_on:
                loaded[:] = ~loaded
            operand.next = loaded
        if state == t_state.S_SQUARE:
            multiplier.next = multiplier >> 1
            if step == width - 1:
                multiplier.next = source_value[width:]
        elif state == t_state.S_PRE and step == 6:
            multiplier.next = source_value[width:]
        if state == t_state.S_IDLE and cmd.start:
            gap.next = 0

    @always_comb
    def root_trial():
        # restoring square root: {remainder, next two radicand bits} - {root, 01}
        # (the new remainder, when the trial fits, is below 2 root: the difference of the low
        # W + 2 bits is the whole difference, and the two top bits of the trial only say "fits")
        trial = intbv(0)[width + 4:]
        difference = modbv(0)[width + 3:]
        trial[:] = concat(remainder, radicand[2 * width:2 * width - 2])
        difference[:] = concat(False, trial[width + 2:]) - concat(False, root[width:], intbv(1)[2:])
        trial_fits.next = trial[width + 4:width + 2] != 0 or not difference[width + 2]
        trial_keep.next = trial[width + 2:]
        if trial[width + 4:width + 2] != 0 or not difference[width + 2]:
            trial_keep.next = difference[width + 2:]

    @always_seq(clock.posedge, reset=reset)
    def square_root():
        if state == t_state.S_SQUARE and square == 1 and step == width - 1:
            # -1 - xs**2 - ys**2 goes into gap at this edge: its complement is the radicand
            if multiplier[0]:
                radicand.next = ~total[2 * width:]
            else:
                radicand.next = ~gap[2 * width:]
            remainder.next = 0
            root.next = 0
            root_steps.next = width + 1
            root_started.next = False
            root_all_ones.next = True
        elif root_steps != 0:
            remainder.next = trial_keep
            root.next = concat(root[width:], trial_fits)
            radicand.next = radicand << 2
            root_steps.next = root_steps - 1
            if root_steps != 1:
                if trial_fits:
                    root_started.next = True
                elif root_started:
                    root_all_ones.next = False

    @always_comb
    def line_major():
        major.next = concat(intbv(0)[major_width - width:], plan.mag_ye)
        if plan.mag_xe >= plan.mag_ye:
            major.next = concat(intbv(0)[major_width - width:], plan.mag_xe)

    @always_seq(clock.posedge, reset=reset)
    def threshold():
        # the paper's 2**(n + k) - 1, one bit a clock: n + k ones, or k ones and then one
        # for each bit of the root from its first 1 on (and one more when the rounding
        # carries into a new bit)
        shift = False
        if state == t_state.S_IDLE and cmd.start:
            plan.threshold.next = 0
            plan.too_wide.next = False
            if cmd.acc_bits != 0:
                ones_left.next = concat(False, cmd.acc_bits) + concat(False, cmd.lambda_shift)
            else:
                ones_left.next = concat(False, cmd.lambda_shift)
        elif state == t_state.S_LINE:
            plan.threshold.next = major[thr_width:]
        elif paper:
            if state == t_state.S_SQUARE and ones_left != 0:
                shift = True
                ones_left.next = ones_left - 1
            elif root_steps > 1 and acc_bits == 0 and (root_started or trial_fits):
                shift = True
            elif root_steps == 1 and acc_bits == 0 and trial_fits and root_all_ones and root_started:
                shift = True
            if shift:
                plan.threshold.next = concat(plan.threshold[thr_width - 1:], True)
                if plan.threshold[thr_width - 1]:
                    plan.too_wide.next = True

    @always_seq(clock.posedge, reset=reset)
    def captures():
        # results read from the adder's total at the edge that forms them
        if state == t_state.S_IDLE:
            plan.off_circle.next = False
        elif state == t_state.S_PRE:
            if step == 2:
                m_is_y.next = total[gap_width - 1]
            elif step == 4:
                shrink_x_neg.next = total[gap_width - 1]
                shrink_x_zero.next = total[width + 1:] == 0
            elif step == 6:
                shrink_y_neg.next = total[gap_width - 1]
                shrink_y_zero.next = total[width + 1:] == 0
        elif state == t_state.S_LIMIT:
            if step == 1:
                plan.off_circle.next = total[gap_width - 1]
            elif step == 2 and not total[gap_width - 1]:
                plan.off_circle.next = True
        elif state == t_state.S_POST:
            if step == 0:
                plan.radius.next = total[width + 2:1]
            elif step == 2:
                plan.beyond.next = total[gap_width - 1]
            elif step == 7:
                plan.totals_diff.next = total[left_width:].signed()
                pick_x.next = not total[left_width - 1]
            elif step == 11:
                plan.totals_max.next = total[left_width:]
        elif state == t_state.S_LINE:
            plan.totals_diff.next = major[left_width:].signed()
            plan.totals_max.next = major[left_width:]
        else:
            m_is_y.next = m_is_y

    @always_seq(clock.posedge, reset=reset)
    def sequence():
        if state == t_state.S_IDLE:
            if cmd.start:
                plan.line.next = cmd.line
                plan.variant.next = cmd.variant
                plan.ccw.next = cmd.ccw
                plan.blend.next = cmd.blend
                acc_bits.next = cmd.acc_bits
                neg_xs.next = cmd.xs < 0
                neg_ys.next = cmd.ys < 0
                plan.neg_xe.next = cmd.xe < 0
                plan.neg_ye.next = cmd.ye < 0
                plan.mag_xs.next = cmd_mag_xs
                plan.mag_ys.next = cmd_mag_ys
                plan.mag_xe.next = cmd_mag_xe
                plan.mag_ye.next = cmd_mag_ye
                step.next = 0
                square.next = 0
                if cmd.line:
                    state.next = t_state.S_LINE
                else:
                    state.next = t_state.S_PRE
        elif state == t_state.S_LINE:
            state.next = t_state.S_DONE
        elif state == t_state.S_PRE:
            if step == PRE_STEPS - 1:
                step.next = 0
                state.next = t_state.S_SQUARE
            else:
                step.next = step + 1
        elif state == t_state.S_SQUARE:
            if step == width - 1:
                step.next = 0
                square.next = square + 1
                if square == 3:
                    state.next = t_state.S_LIMIT
            else:
                step.next = step + 1
        elif state == t_state.S_LIMIT:
            if step == LIMIT_STEPS - 1:
                step.next = 0
                state.next = t_state.S_POST
            else:
                step.next = step + 1
        elif state == t_state.S_POST:
            if step == POST_STEPS - 1:
                step.next = 0
                state.next = t_state.S_DONE
            else:
                step.next = step + 1
        elif plan.taken:
            state.next = t_state.S_IDLE

    @always_seq(clock.posedge, reset=reset)
    def geometry():
        # quadrants and pieces from the latched command, registered on every clock
        q_s = intbv(0)[2:]
        q_e = intbv(0)[2:]
        turn = modbv(0)[2:]
        ahead = False
        zero_xs = plan.mag_xs == 0
        zero_ys = plan.mag_ys == 0
        zero_xe = plan.mag_xe == 0
        zero_ye = plan.mag_ye == 0
        ccw = plan.ccw
        # departure quadrant of the start, arrival quadrant of the end
        if ccw:
            if not neg_xs and not zero_xs and not neg_ys:
                q_s[:] = 0
            elif (neg_xs or zero_xs) and not neg_ys and not zero_ys:
                q_s[:] = 1
            elif neg_xs and (neg_ys or zero_ys):
                q_s[:] = 2
            else:
                q_s[:] = 3
            if not plan.neg_xe and not plan.neg_ye and not zero_ye:
                q_e[:] = 0
            elif plan.neg_xe and not plan.neg_ye:
                q_e[:] = 1
            elif (plan.neg_xe or zero_xe) and plan.neg_ye:
                q_e[:] = 2
            else:
                q_e[:] = 3
            turn[:] = q_e - q_s
        else:
            if not neg_xs and not neg_ys and not zero_ys:
                q_s[:] = 0
            elif neg_xs and not neg_ys:
                q_s[:] = 1
            elif (neg_xs or zero_xs) and neg_ys:
                q_s[:] = 2
            else:
                q_s[:] = 3
            if not plan.neg_xe and not zero_xe and not plan.neg_ye:
                q_e[:] = 0
            elif (plan.neg_xe or zero_xe) and not plan.neg_ye and not zero_ye:
                q_e[:] = 1
            elif plan.neg_xe and (plan.neg_ye or zero_ye):
                q_e[:] = 2
            else:
                q_e[:] = 3
            turn[:] = q_s - q_e
        # an end ahead in the start's quadrant is one piece: the inward magnitude does not
        # grow, the outward one does not shrink, and the end is not the start
        if q_s[0] != ccw:
            ahead = not shrink_x_neg and (shrink_y_neg or shrink_y_zero)
        else:
            ahead = not shrink_y_neg and (shrink_x_neg or shrink_x_zero)
        plan.ahead.next = turn == 0 and ahead and not (shrink_x_zero and shrink_y_zero)
        plan.crossings.next = concat(False, turn)
        if turn == 0 and not (ahead and not (shrink_x_zero and shrink_y_zero)):
            plan.crossings.next = 4
        plan.quadrant.next = q_s
        plan.x_inward.next = q_s[0] != ccw
        x_inward_end.next = q_e[0] != ccw
        if plan.line:
            plan.centre.next = zero_xe and zero_ye
        else:
            plan.centre.next = (zero_xs and zero_ys) or (zero_xe and zero_ye)

    @always_comb
    def status():
        cmd.ready.next = state == t_state.S_IDLE
        plan.done.next = state == t_state.S_DONE

    return (magnitudes, control, carry_in, rq_terms, select_source, adder, datapath, root_trial, square_root, line_major,
            threshold, captures, sequence, geometry, status)

