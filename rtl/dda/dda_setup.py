"""DDA setup stage: a taken command worked out on one adder for its check."""
from myhdl import Signal, always, always_comb, always_seq, block, concat, intbv, modbv

from models.dda_build import PAPER_VARIANTS
from rtl.dda.dda_latch import dda_latch
from rtl.dda.dda_root import dda_root
from rtl.dda.dda_sequence import POST_STEPS, dda_sequence, t_setup
from rtl.dda.dda_setup_control import G_ADD, G_ONES, G_ZERO, M_LOAD, M_SHIFT, SRC_XE, SRC_XS, SRC_YE, SRC_YS, \
    dda_setup_control
from rtl.interfaces import DdaRoot, SetupControl, SetupSequence


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
    clock ahead.  The micro-program (``dda_setup_control``) says in each
    clock what the accumulator and the operand do, from which source, and
    the carry.  A line needs one clock after the latch (its threshold), an
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

    Sub-blocks: ``dda_latch`` (the command and its geometry),
    ``dda_sequence`` (the phase's next values), ``dda_setup_control``,
    ``dda_root``.  Processes, by what they drive: ``select_source`` (the
    source's value), ``adder`` (``total``; the root's radicand and load),
    ``datapath`` (``gap``, ``operand``, ``multiplier``), ``sequencer`` (the
    phase), ``line_major`` (a line's max(|dx|, |dy|)), ``threshold``
    (``plan.threshold``, ``plan.too_wide`` and their counters), ``captures``
    (what is read from the total: the compares, ``m_is_y``, ``pick_x``, the
    limits' signs, ``radius``, the totals), ``circle`` (``plan.off_circle``
    from the limits' signs), ``status`` (``ready``, ``plan.done``).
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
    # the micro-program's lines and the flags it reads (``rtl/dda/dda_setup_control.py``)
    control = SetupControl(width)
    gap_op, operand_op, source, source_on = control.gap_op, control.operand_op, control.source, control.source_on
    invert, carry, multiplier = control.invert, control.carry, control.multiplier
    m_is_y, pick_x = control.m_is_y, control.pick_x
    source_value = Signal(intbv(0)[width + 1:])

    root = DdaRoot(width)
    acc_bits = Signal(intbv(0)[5:])
    ones_left = Signal(intbv(0, min=0, max=64))
    grew = Signal(bool(0))
    major_width = max(thr_width, left_width)
    major = Signal(intbv(0)[major_width:])
    # the limits: gap - 2m - 1 < 0 (the sign at step 1) and gap + 2m >= 0 (at step 4): the end within one step
    within_outer, within_inner = Signal(bool(0)), Signal(bool(0))

    latch = dda_latch(clock, reset, cmd, plan)
    phase = dda_sequence(cmd, plan, sequence)
    square_root = dda_root(clock, reset, root)
    program = dda_setup_control(clock, reset, plan, sequence, root, control)

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
        # results read from the adder's total at the edge that forms them; |s| == |e| is the
        # low bits of gap + operand + 1 (the carry is set at steps 4 and 6) being zero, which is
        # gap ^ operand being all ones there: a test with no carry chain in front
        sign = total[gap_width - 1]
        same = (gap[width + 1:] ^ operand[width + 1:]) == (1 << (width + 1)) - 1
        if state == t_setup.S_PRE:
            if step == 2:
                m_is_y.next = sign
            elif step == 4:
                plan.start_below_x.next = sign
                plan.start_same_x.next = same
            elif step == 6:
                plan.start_below_y.next = sign
                plan.start_same_y.next = same
        elif state == t_setup.S_LIMIT:
            if step == 1:
                within_outer.next = sign
            elif step == 4:
                within_inner.next = not sign
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
    def circle():
        # from the limits' signs as taken, so that no decision follows the adder's carry (every arc
        # passes the limits before its plan is done; a line's plan ignores the flag)
        plan.off_circle.next = not (within_outer and within_inner)

    @always_comb
    def status():
        cmd.ready.next = state == t_setup.S_IDLE
        plan.done.next = state == t_setup.S_DONE

    return (latch, square_root, phase, program, select_source, adder, datapath, sequencer, line_major,
            threshold, captures, circle, status)
