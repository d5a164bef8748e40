"""DDA setup stage: a taken command worked out on one adder for its check."""
from myhdl import Signal, always, always_comb, always_seq, block, concat, intbv, modbv

from models.dda_build import PAPER_VARIANTS
from rtl.dda.dda_latch import dda_latch
from rtl.dda.dda_root import dda_root
from rtl.dda.dda_sequence import POST_STEPS, dda_sequence, t_setup
from rtl.interfaces import DdaRoot, SetupSequence

# what the adder's accumulator does in a clock, and its operand register
G_HOLD, G_ADD, G_ZERO, G_ONES = range(4)
M_HOLD, M_SHIFT, M_LOAD = range(3)
# operand sources: the magnitudes and the root t
SRC_XS, SRC_YS, SRC_XE, SRC_YE, SRC_ROOT = range(5)


@block
def dda_setup(clock, reset, cmd, plan):
    """Setup stage of the DDA: latch, compares, squares, root, limits, totals.

    Ports:
        clock, reset  clock and reset (``card_reset()``)
        cmd           ``DdaPort``: the command lines and ``start`` in, ``ready`` out
        plan          ``DdaPlan`` out (``plan.done`` while a finished plan waits);
                      ``plan.taken`` in
    Parameters: none; ``coord_width`` (W) and ``variants`` come from ``cmd``.

    One adder of 2W + 1 bits adds an operand register (loaded from the four
    magnitudes or the root, inverted for a subtraction, and shifting left) to
    its accumulator ``gap`` in every clock; its carry is a register, set a
    clock ahead.  A line needs one clock after the latch (its threshold), an
    arc 4W + 25::

        clock  _/~\\_/~\\_ ... _/~\\_ ... _/~\\_ ... _/~\\_ ... _/~\\_/~\\_
        start  _/~~~\\___ ... _____ ... _____ ... _____ ... __________
        ready  ~~~~~\\___ ... _____ ... _____ ... _____ ... ____/~~~~~  (taken)
                   |compares| squares | limits| totals |done
                   |   7    |   4W    |   5   |   13   |

    * compares: |xs| - |ys| (m = max(|xs|, |ys|)), |xs| - |xe|, |ys| - |ye|
      (is the end ahead in the start's quadrant);
    * squares: gap = -1 - xs**2 - ys**2 + xe**2 + ye**2 by shift-add, one
      multiplier bit a clock; half-way ~gap = xs**2 + ys**2 goes to the square
      root (``dda_root``), which runs beside the other two squares;
    * limits: gap - 2m - 1 < 0 and gap + 2m >= 0 (end within one step);
    * totals: Rq = (t + 1) >> 1, the end's inward magnitude against Rq
      (2 |e| <= t + r), and the two axes' steps over the whole move, their
      difference and the larger one, as signed sums of the magnitudes and
      2 Rq = t + r.

    The paper variants' threshold 2**(n + k) - 1 is shifted together in
    ``plan.threshold``, one bit a clock: n + k ones during the squares (n =
    acc_bits), or k ones and then one for each bit of the root (n = 0); a
    line's T = max(|dx|, |dy|) is loaded there.
    """
    width = cmd.coord_width
    gap_width = 2 * width + 1
    left_width = plan.left_width
    thr_width = plan.threshold_width
    paper = bool(cmd.variants & PAPER_VARIANTS)

    # the phase: state, step and square, and their next values (``rtl/dda/dda_sequence.py``)
    sequence = SetupSequence(t_setup.S_IDLE, max(width, POST_STEPS))
    state, step, square = sequence.state, sequence.step, sequence.square
    next_state, next_step, next_square = sequence.next_state, sequence.next_step, sequence.next_square

    gap = Signal(modbv(0)[gap_width:])
    operand = Signal(modbv(0)[gap_width:])
    total = Signal(modbv(0)[gap_width:])
    carry = Signal(bool(0))
    multiplier = Signal(intbv(0)[width:])
    gap_op = Signal(intbv(0)[2:])
    operand_op = Signal(intbv(0)[2:])
    source = Signal(intbv(0)[3:])
    source_on, invert = Signal(bool(0)), Signal(bool(0))
    source_value = Signal(intbv(0)[width + 1:])

    root = DdaRoot(width)
    m_is_y, pick_x = Signal(bool(0)), Signal(bool(0))
    twice = Signal(intbv(0)[2:])
    acc_bits = Signal(intbv(0)[5:])
    ones_left = Signal(intbv(0, min=0, max=64))
    grew = Signal(bool(0))
    major_width = max(thr_width, left_width)
    major = Signal(intbv(0)[major_width:])

    latch = dda_latch(clock, reset, cmd, plan)
    phase = dda_sequence(cmd, plan, sequence)
    square_root = dda_root(clock, reset, root)

    @always_comb
    def control():
        # this clock's micro-operation: what the accumulator does, what the operand loads
        # (source, inverted, or 0) or whether it shifts (``invert`` is the bit shifted in)
        g_op = intbv(0)[2:]
        o_op = intbv(0)[2:]
        src = intbv(0)[3:]
        on = True
        inv = False
        g_op[:] = G_HOLD
        o_op[:] = M_LOAD
        src[:] = SRC_XS
        if state == t_setup.S_PRE:
            # xs, -ys (m), +ys, -xe (xs vs xe), 0, ys, -ye (ys vs ye), then -1 for the squares
            if step == 1 or step == 3 or step == 5:
                inv = True
            if step == 0 or step == 6:
                src[:] = SRC_XS
                inv = step == 6
            elif step == 1 or step == 2 or step == 4:
                src[:] = SRC_YS
            elif step == 3:
                src[:] = SRC_XE
            else:
                src[:] = SRC_YE
            if step == 4:
                g_op[:] = G_ZERO
            elif step == 6:
                g_op[:] = G_ONES
            elif step != 0:
                g_op[:] = G_ADD
        elif state == t_setup.S_SQUARE:
            o_op[:] = M_SHIFT
            inv = square < 2
            if multiplier[0]:
                g_op[:] = G_ADD
            if step == width - 1:
                # the next square's magnitude, then ~m for the limits
                o_op[:] = M_LOAD
                inv = square == 0 or square == 3
                src[:] = square + 1
                if square == 3:
                    src[:] = SRC_XS
                    if m_is_y:
                        src[:] = SRC_YS
        elif state == t_setup.S_LIMIT:
            o_op[:] = M_SHIFT
            if step == 0:
                inv = True
            elif step == 1:
                g_op[:] = G_ADD
                o_op[:] = M_LOAD
                src[:] = SRC_XS
                if m_is_y:
                    src[:] = SRC_YS
            elif step == 4:
                g_op[:] = G_ZERO
                o_op[:] = M_LOAD
                src[:] = SRC_ROOT
        elif state == t_setup.S_POST:
            g_op[:] = G_ADD
            if step == 0:
                # t + 1 (Rq), then -2 |e| for the inward test
                src[:] = SRC_YE
                if plan.x_inward_end:
                    src[:] = SRC_XE
                inv = True
            elif step == 1:
                g_op[:] = G_HOLD
                o_op[:] = M_SHIFT
                inv = True
            elif step <= 5:
                # the difference of the totals: +-(|xs| + |ys|) +-(|xe| + |ye|) +-2 Rq
                inv = not plan.x_inward
                if step == 2:
                    g_op[:] = G_ZERO
                    src[:] = SRC_XS
                elif step == 3:
                    src[:] = SRC_YS
                else:
                    src[:] = SRC_XE
                    if step == 5:
                        src[:] = SRC_YE
                    inv = plan.x_inward_end == 1
            elif step == 6:
                src[:] = SRC_ROOT
                on = plan.x_inward != plan.x_inward_end
                inv = plan.x_inward == 1
            elif step == 7:
                g_op[:] = G_ZERO
                o_op[:] = M_HOLD
            elif step == 8:
                # the larger total: the axis the difference's sign picked
                g_op[:] = G_HOLD
                src[:] = SRC_YS
                inv = plan.x_inward == 1
                if pick_x:
                    src[:] = SRC_XS
                    inv = not plan.x_inward
            elif step == 9:
                src[:] = SRC_YE
                inv = not plan.x_inward_end
                if pick_x:
                    src[:] = SRC_XE
                    inv = plan.x_inward_end == 1
            else:
                src[:] = SRC_ROOT
                on = twice != 0
                if step == 11:
                    on = twice == 2
        else:
            o_op[:] = M_HOLD
        gap_op.next = g_op
        operand_op.next = o_op
        source.next = src
        source_on.next = on
        invert.next = inv

    @always_seq(clock.posedge, reset=reset)
    def carry_in():
        # the carry of the next clock's addition: +1 of a subtraction, r of 2 Rq = t + r
        # (-2 Rq = ~t + ~r), +1 of t + 1
        cin = False
        if next_state == t_setup.S_PRE:
            cin = next_step == 2 or next_step == 4 or next_step == 6
        elif next_state == t_setup.S_SQUARE:
            cin = next_square < 2
        elif next_state == t_setup.S_LIMIT:
            cin = next_step == 4
        elif next_state == t_setup.S_POST:
            if next_step == 0:
                cin = True
            elif next_step == 2:
                cin = root.root[0] == 1
            elif next_step == 3 or next_step == 4:
                cin = not plan.x_inward
            elif next_step == 5 or next_step == 6:
                cin = plan.x_inward_end == 1
            elif next_step == 7:
                cin = plan.x_inward != plan.x_inward_end and root.root[0] != plan.x_inward
            elif next_step == 9:
                cin = pick_x != plan.x_inward
            elif next_step == 10:
                cin = pick_x == plan.x_inward_end
            elif next_step == 11:
                cin = root.root[0] and twice != 0
            elif next_step == 12:
                cin = root.root[0] and twice == 2
        else:
            cin = False
        carry.next = cin

    @always_comb
    def rq_terms():
        # k / 2 of the larger axis' k Rq: k = (crossings - 1) + 1 if it starts outward (its
        # first piece ends at Rq) + 1 if it ends inward (its last piece starts at Rq)
        count = modbv(0)[3:]
        count[:] = plan.crossings - 1
        if plan.x_inward != pick_x:
            count[:] = count + 1
        if plan.x_inward_end == pick_x:
            count[:] = count + 1
        twice.next = count[3:1]
        if plan.crossings == 0:
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
            value[:] = root.root
        if not source_on:
            value[:] = 0
        source_value.next = value

    @always_comb
    def adder():
        total.next = gap + operand + concat(intbv(0)[gap_width - 1:], carry)
        root.radicand.next = ~gap[2 * width:]
        root.load.next = state == t_setup.S_SQUARE and square == 2 and step == 0

    @always(clock.posedge)
    def datapath():
        # registers loaded before they are read: no reset (a load of 0 or all ones is then a
        # flip-flop's own synchronous reset or set)
        loaded = modbv(0)[gap_width:]
        if gap_op == G_ADD:
            gap.next = total
        elif gap_op == G_ZERO:
            gap.next = 0
        elif gap_op == G_ONES:
            gap.next = (1 << gap_width) - 1
        if operand_op == M_SHIFT:
            operand.next = concat(operand[gap_width - 1:], invert)
        elif operand_op == M_LOAD:
            loaded[:] = concat(intbv(0)[gap_width - width - 1:], source_value)
            if invert and source_on:
                loaded[:] = ~loaded
            operand.next = loaded
        if state == t_setup.S_SQUARE and step != width - 1:
            multiplier.next = multiplier >> 1
        elif state == t_setup.S_PRE or state == t_setup.S_SQUARE:
            multiplier.next = source_value[width:]
        if state == t_setup.S_IDLE:
            gap.next = 0

    @always_seq(clock.posedge, reset=reset)
    def sequencer():
        state.next = next_state
        step.next = next_step
        square.next = next_square

    @always_comb
    def line_major():
        major.next = concat(intbv(0)[major_width - width:], plan.mag_ye)
        if plan.mag_xe >= plan.mag_ye:
            major.next = concat(intbv(0)[major_width - width:], plan.mag_xe)

    @always(clock.posedge)
    def threshold():
        # 2**(n + k) - 1, shifted together: n + k ones (or k) during the squares, then one
        # a clock as the root's length grows (n = 0); a line's T
        shift = False
        grew.next = root.grows
        if state == t_setup.S_IDLE and cmd.start:
            plan.threshold.next = 0
            plan.too_wide.next = False
            acc_bits.next = cmd.acc_bits
            if cmd.acc_bits != 0:
                ones_left.next = concat(False, cmd.acc_bits) + concat(False, cmd.lambda_shift)
            else:
                ones_left.next = concat(False, cmd.lambda_shift)
        elif state == t_setup.S_LINE:
            plan.threshold.next = major[thr_width:]
        elif paper:
            if state == t_setup.S_SQUARE and ones_left != 0:
                shift = True
                ones_left.next = ones_left - 1
            elif acc_bits == 0 and grew:
                shift = True
            if shift:
                plan.threshold.next = concat(plan.threshold[thr_width - 1:], True)
                if plan.threshold[thr_width - 1]:
                    plan.too_wide.next = True

    @always(clock.posedge)
    def captures():
        # results read from the adder's total at the edge that forms them
        sign = total[gap_width - 1]
        if state == t_setup.S_IDLE:
            plan.off_circle.next = False
        elif state == t_setup.S_PRE:
            if step == 2:
                m_is_y.next = sign
            elif step == 4:
                plan.start_below_x.next = sign
                plan.start_same_x.next = total[width + 1:] == 0
            elif step == 6:
                plan.start_below_y.next = sign
                plan.start_same_y.next = total[width + 1:] == 0
        elif state == t_setup.S_LIMIT:
            if (step == 1 and not sign) or (step == 4 and sign):
                plan.off_circle.next = True
        elif state == t_setup.S_POST:
            if step == 0:
                plan.radius.next = total[width + 2:1]
            elif step == 2:
                plan.beyond.next = sign
            elif step == 7:
                plan.totals_diff.next = total[left_width:].signed()
                pick_x.next = not total[left_width - 1]
            elif step == 12:
                plan.totals_max.next = total[left_width:]
        elif state == t_setup.S_LINE:
            plan.totals_diff.next = major[left_width:].signed()
            plan.totals_max.next = major[left_width:]
        else:
            m_is_y.next = m_is_y

    @always_comb
    def status():
        cmd.ready.next = state == t_setup.S_IDLE
        plan.done.next = state == t_setup.S_DONE

    return (latch, square_root, phase, control, carry_in, rq_terms, select_source, adder, datapath,
            sequencer, line_major, threshold, captures, status)
