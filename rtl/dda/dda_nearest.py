"""The precise mode's step choice: which of X, Y and the diagonal ends nearest the circle."""
from myhdl import Signal, always, always_comb, block, concat, intbv, modbv


@block
def dda_nearest(clock, step, move):
    """Radial error term and the two signs of the precise mode's choice.

    Ports:
        clock  clock (the registers are loaded with the move before they are read:
               no reset)
        step   ``DdaStep``: the run's registered decision and magnitudes in;
               ``inward_near``, ``outward_near`` out
        move   ``DdaMove``: ``take``, ``bias_in``, ``bias_out`` in
    Parameters: none; the widths come from ``step``.

    With a = the inward, b = the outward magnitude, E = x**2 + y**2 - r**2
    and the candidates E + d_in < E + d_in + d_out < E + d_out
    (d_in = 1 - 2a, d_out = 1 + 2b), the diagonal ends nearest when
    S1 = 2E + 2 d_in + d_out < 0 and S2 = 2E + d_in + 2 d_out > 0; the
    inward axis steps when S2 > 0, the outward one when S1 < 0.  With
    E' = E + 1, P = 2b - a and Q = b - 2a (registers): S2 > 0 is E' + P >= 0
    and S1 < 0 is E' + Q < 0, two adders on registers in the iteration's
    first clock.  In the second, E' takes the step (2b + 1 for an outward
    step, ~(2a) + 2 for an inward one: two adders, magnitudes before the
    step), P and Q theirs (an inward step adds 1 and 2, an outward one 2 and
    1); where a quadrant piece ends (a = 0, b = Rq: P = 2Rq, Q = Rq) the next
    one begins with a' = Rq, b' = 0: P' = -Q, Q' = -P, after the step::

        clock      _/~\\_/~\\_/~\\_
        advance    _/~~~\\_______
        pending    _____/~~~\\___
        signs      <  ok >-------     read in the first clock
        E', P, Q   ________^_____     updated at the end of the second
    """
    width = step.coord_width
    bias_width = step.bias_width
    ones = (1 << bias_width) - 1
    error_term = Signal(modbv(0)[bias_width:])
    bias_in, bias_out = Signal(modbv(0)[bias_width:]), Signal(modbv(0)[bias_width:])
    error_step = Signal(modbv(0)[bias_width:])

    @always_comb
    def signs():
        inward = modbv(0)[bias_width + 1:]
        outward = modbv(0)[bias_width + 1:]
        inward[:] = concat(error_term[bias_width - 1], error_term) + concat(bias_in[bias_width - 1], bias_in)
        outward[:] = concat(error_term[bias_width - 1], error_term) + concat(bias_out[bias_width - 1], bias_out)
        step.inward_near.next = inward.signed() >= 0
        step.outward_near.next = outward.signed() < 0

    @always_comb
    def error_change():
        # E' + (2b + 1) for an outward step, + ~(2a) + 2 for an inward one
        outward = modbv(0)[bias_width:]
        inward = modbv(0)[bias_width:]
        first_sum = modbv(0)[bias_width:]
        stepped_in = False
        if step.x_inward:
            stepped_in = step.step_x == 1
            if step.step_y:
                outward[:] = concat(intbv(0)[bias_width - width - 1:], step.mag_y, True)
            if step.step_x:
                inward[:] = ~concat(intbv(0)[bias_width - width - 1:], step.mag_x, False)
        else:
            stepped_in = step.step_y == 1
            if step.step_x:
                outward[:] = concat(intbv(0)[bias_width - width - 1:], step.mag_x, True)
            if step.step_y:
                inward[:] = ~concat(intbv(0)[bias_width - width - 1:], step.mag_y, False)
        first_sum[:] = error_term + outward + concat(intbv(0)[bias_width - 1:], stepped_in)
        error_step.next = first_sum + inward + concat(intbv(0)[bias_width - 1:], stepped_in)

    @always(clock.posedge)
    def update():
        # P and Q after the step (dP = in + 2 out, dQ = 2 in + out); a new quadrant piece:
        # -(Q + dQ) = ~Q + (-dQ) + 1 and -(P + dP) = ~P + (-dP) + 1
        base_in = modbv(0)[bias_width:]
        base_out = modbv(0)[bias_width:]
        op_in = modbv(0)[bias_width:]
        op_out = modbv(0)[bias_width:]
        stepped_in = step.step_y == 1
        stepped_out = step.step_x == 1
        if step.x_inward:
            stepped_in = step.step_x == 1
            stepped_out = step.step_y == 1
        base_in[:] = bias_in
        base_out[:] = bias_out
        op_in[:] = concat(intbv(0)[bias_width - 2:], stepped_out, stepped_in)
        op_out[:] = concat(intbv(0)[bias_width - 2:], stepped_in, stepped_out)
        turn = step.new_piece == 1
        if turn:
            base_in[:] = ~bias_out
            base_out[:] = ~bias_in
            if stepped_in and stepped_out:
                op_in[:] = intbv(ones - 2)[bias_width:]
                op_out[:] = intbv(ones - 2)[bias_width:]
            elif stepped_in:
                op_in[:] = intbv(ones - 1)[bias_width:]
                op_out[:] = intbv(ones)[bias_width:]
            elif stepped_out:
                op_in[:] = intbv(ones)[bias_width:]
                op_out[:] = intbv(ones - 1)[bias_width:]
            else:
                op_in[:] = 0
                op_out[:] = 0
        if step.pending and not step.line:
            bias_in.next = base_in + op_in + concat(intbv(0)[bias_width - 1:], turn)
            bias_out.next = base_out + op_out + concat(intbv(0)[bias_width - 1:], turn)
            error_term.next = error_step
        if move.take:
            bias_in.next = move.bias_in
            bias_out.next = move.bias_out
            error_term.next = 1

    return signs, error_change, update
