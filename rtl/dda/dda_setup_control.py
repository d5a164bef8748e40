"""The micro-program of the DDA's setup stage: what its one adder does in each clock."""
from myhdl import Signal, always_comb, always_seq, block, intbv, modbv

from rtl.dda.dda_sequence import t_setup

# what the adder's accumulator does in a clock, and its operand register
G_HOLD, G_ADD, G_ZERO, G_ONES = range(4)
M_HOLD, M_SHIFT, M_LOAD = range(3)
# operand sources: the magnitudes and the root t
SRC_XS, SRC_YS, SRC_XE, SRC_YE, SRC_ROOT = range(5)


@block
def dda_setup_control(clock, reset, plan, sequence, root, control):
    """Tells the setup stage's adder (``rtl/dda/dda_setup.py``) what to do in
    each clock of each phase.

    Ports:
        clock, reset  clock and reset (``card_reset()``)
        plan          ``DdaPlan`` in: ``x_inward``, ``x_inward_end``, ``crossings``
        sequence      ``SetupSequence`` in: the phase and its next values
        root          ``DdaRoot`` in: ``root`` (t; its bit 0 is r)
        control       ``SetupControl``: ``multiplier``, ``m_is_y``, ``pick_x`` in;
                      ``gap_op``, ``operand_op``, ``source``, ``source_on``,
                      ``invert``, ``carry`` out
    Parameters: none; W is ``plan.coord_width``.

    Processes, by what they drive: ``operations`` (``gap_op``,
    ``operand_op``), ``operand_source`` (``source``, ``source_on``) and
    ``inversion`` (``invert``), from the phase's registers; ``carry_in``
    (``carry``, a register set from the phase's next values, so that it is
    there in the clock of its addition); ``rq_terms`` (how many Rq the
    larger total holds).  An operand is loaded in one clock and added in
    the next; a subtraction adds it inverted with a carry, e.g. |xs| - |ys|
    before the squares::

        clock       _/~\\_/~\\_/~\\_
        step        < 1  >< 2  >      (S_PRE)
        operand_op  <LOAD><LOAD>      loads ~|ys| (SRC_YS, invert) at the edge after step 1
        gap_op      <ADD ><ADD >      step 2 adds it: gap = |xs| + ~|ys| + 1
        carry       ______/~~~~\\      set at the edge before step 2 (next_step = 2)
    """
    width = plan.coord_width
    state, step, square = sequence.state, sequence.step, sequence.square
    next_state, next_step, next_square = sequence.next_state, sequence.next_step, sequence.next_square
    multiplier, m_is_y, pick_x = control.multiplier, control.m_is_y, control.pick_x
    twice = Signal(intbv(0)[2:])

    @always_comb
    def operations():
        # what the accumulator does (add the operand, hold, clear, all ones for the -1
        # before the squares) and whether the operand register loads, shifts or holds
        g_op = intbv(0)[2:]
        o_op = intbv(0)[2:]
        g_op[:] = G_HOLD
        o_op[:] = M_LOAD
        if state == t_setup.S_PRE:
            if step == 4:
                g_op[:] = G_ZERO
            elif step == 6:
                g_op[:] = G_ONES
            elif step != 0:
                g_op[:] = G_ADD
        elif state == t_setup.S_SQUARE:
            # shift-add: the operand shifts left, the multiplier's bit 0 says whether it adds
            o_op[:] = M_SHIFT
            if multiplier[0]:
                g_op[:] = G_ADD
            if step == width - 1:
                o_op[:] = M_LOAD
        elif state == t_setup.S_LIMIT:
            o_op[:] = M_SHIFT
            if step == 1:
                g_op[:] = G_ADD
                o_op[:] = M_LOAD
            elif step == 4:
                g_op[:] = G_ZERO
                o_op[:] = M_LOAD
        elif state == t_setup.S_POST:
            g_op[:] = G_ADD
            if step == 1:
                g_op[:] = G_HOLD
                o_op[:] = M_SHIFT
            elif step == 2:
                g_op[:] = G_ZERO
            elif step == 7:
                g_op[:] = G_ZERO
                o_op[:] = M_HOLD
            elif step == 8:
                g_op[:] = G_HOLD
        else:
            o_op[:] = M_HOLD
        control.gap_op.next = g_op
        control.operand_op.next = o_op

    @always_comb
    def operand_source():
        # what the operand register loads: xs, ys, ys, xe, ys, ye, xs before the squares (the
        # compares xs - ys, xs - xe, ys - ye), at the end of a square the next one's, then m
        src = intbv(0)[3:]
        on = True
        src[:] = SRC_XS
        if state == t_setup.S_PRE:
            if step == 1 or step == 2 or step == 4:
                src[:] = SRC_YS
            elif step == 3:
                src[:] = SRC_XE
            elif step != 0 and step != 6:
                src[:] = SRC_YE
        elif state == t_setup.S_SQUARE:
            if step == width - 1 and square != 3:
                src[:] = square + 1
            elif step == width - 1 and m_is_y:
                src[:] = SRC_YS
        elif state == t_setup.S_LIMIT:
            if step == 1 and m_is_y:
                src[:] = SRC_YS
            elif step == 4:
                src[:] = SRC_ROOT
        elif state == t_setup.S_POST:
            # |e| of the inward test; the totals' difference +-(|xs| + |ys|) +-(|xe| + |ye|)
            # +-2 Rq; the larger total: the axis the difference's sign picked, and its Rq
            if step == 0 or step == 5 or (step == 9 and not pick_x):
                src[:] = SRC_YE
            if (step == 0 and plan.x_inward_end) or step == 4 or (step == 9 and pick_x):
                src[:] = SRC_XE
            if step == 3 or (step == 8 and not pick_x):
                src[:] = SRC_YS
            if step == 6 or step >= 10:
                src[:] = SRC_ROOT
            if step == 6:
                on = plan.x_inward != plan.x_inward_end
            elif step >= 10:
                on = twice != 0
                if step == 11:
                    on = twice == 2
        else:
            src[:] = SRC_XS
        control.source.next = src
        control.source_on.next = on

    @always_comb
    def inversion():
        # an operand loaded inverted (a subtraction, with the carry's +1), and the bit a shift
        # brings in: ones while an inverted square or ~m shifts (-2 m - 1 in the limits)
        inv = False
        if state == t_setup.S_PRE:
            inv = step == 1 or step == 3 or step == 5 or step == 6
        elif state == t_setup.S_SQUARE:
            inv = square < 2
            if step == width - 1:
                inv = square == 0 or square == 3
        elif state == t_setup.S_LIMIT:
            inv = step == 0
        elif state == t_setup.S_POST:
            if step == 0 or step == 1:
                inv = True
            elif step == 2 or step == 3 or (step == 8 and pick_x):
                inv = not plan.x_inward
            elif step == 4 or step == 5 or (step == 9 and pick_x):
                inv = plan.x_inward_end == 1
            elif step == 6 or step == 8:
                inv = plan.x_inward == 1
            elif step == 9:
                inv = not plan.x_inward_end
        else:
            inv = False
        control.invert.next = inv

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
        control.carry.next = cin

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

    return operations, operand_source, inversion, carry_in, rq_terms
