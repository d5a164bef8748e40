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
        move   ``DdaMove``: ``take``, ``bias_x``, ``bias_y`` in
    Parameters: none; the widths come from ``step``.

    With a = the inward, b = the outward magnitude, E = x**2 + y**2 - r**2
    and the candidates E + d_in < E + d_in + d_out < E + d_out
    (d_in = 1 - 2a, d_out = 1 + 2b), the diagonal ends nearest when
    S1 = 2E + 2 d_in + d_out < 0 and S2 = 2E + d_in + 2 d_out > 0; the
    inward axis steps when S2 > 0, the outward one when S1 < 0.  In x, y with
    E' = E + 1, B_x = 2|y| - 4|x|, B_y = 4|y| - 2|x|: S1 < 0 is 2E' + B_x < 0
    (X inward) or 2E' - B_y < 0 (Y inward), S2 < 0 is 2E' + B_y < 0 or
    2E' - B_x < 0.  Four adders form the signs from registers in the
    iteration's first clock; in the second, E' takes the step (2b + 1 for an
    outward step, ~(2a) + 2 for an inward one: two adders, magnitudes before
    the step) and B_x, B_y their constants::

        clock      _/~\\_/~\\_/~\\_
        advance    _/~~~\\_______
        pending    _____/~~~\\___
        signs      <  ok >-------     read in the first clock
        E', B      ________^_____     updated at the end of the second
    """
    width = step.coord_width
    bias_width = step.bias_width
    error_term = Signal(modbv(0)[bias_width:])
    bias_x, bias_y = Signal(modbv(0)[bias_width:]), Signal(modbv(0)[bias_width:])
    error_step = Signal(modbv(0)[bias_width:])

    @always_comb
    def signs():
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
        if step.x_inward:
            step.inward_near.next = plus_y.signed() >= 0
            step.outward_near.next = plus_x.signed() < 0
        else:
            step.inward_near.next = minus_x.signed() >= 0
            step.outward_near.next = minus_y.signed() < 0

    @always_comb
    def error_change():
        # E' + (2b + 1) for an outward step, + ~(2a) + 2 for an inward one
        outward = modbv(0)[bias_width:]
        inward = modbv(0)[bias_width:]
        first_sum = modbv(0)[bias_width:]
        if step.step_out:
            outward[:] = concat(intbv(0)[bias_width - width - 1:], step.mag_x, True)
            if step.x_inward:
                outward[:] = concat(intbv(0)[bias_width - width - 1:], step.mag_y, True)
        if step.step_in:
            inward[:] = ~concat(intbv(0)[bias_width - width - 1:], step.mag_y, False)
            if step.x_inward:
                inward[:] = ~concat(intbv(0)[bias_width - width - 1:], step.mag_x, False)
        first_sum[:] = error_term + outward + concat(intbv(0)[bias_width - 1:], step.step_in)
        error_step.next = first_sum + inward + concat(intbv(0)[bias_width - 1:], step.step_in)

    @always(clock.posedge)
    def update():
        # B_x and B_y after the steps (dx, dy): X inward adds 4 dx + 2 dy and 2 dx + 4 dy,
        # Y inward subtracts them
        op_x = modbv(0)[bias_width:]
        op_y = modbv(0)[bias_width:]
        op_x[:] = concat(intbv(0)[bias_width - 3:], step.step_x, step.step_y, False)
        op_y[:] = concat(intbv(0)[bias_width - 3:], step.step_y, step.step_x, False)
        if not step.x_inward:
            op_x[:] = ~op_x
            op_y[:] = ~op_y
        if step.pending and not step.line:
            bias_x.next = bias_x + op_x + concat(intbv(0)[bias_width - 1:], not step.x_inward)
            bias_y.next = bias_y + op_y + concat(intbv(0)[bias_width - 1:], not step.x_inward)
            error_term.next = error_step
        if move.take:
            bias_x.next = move.bias_x
            bias_y.next = move.bias_y
            error_term.next = 1

    return signs, error_change, update
