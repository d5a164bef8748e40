"""Steps left of the running move: the lower bound ``stop_left`` and a line's last iteration."""
from myhdl import Signal, always, always_comb, always_seq, block, intbv, modbv


@block
def dda_left(clock, reset, step, move, cmd):
    """Each axis' steps over the rest of the move, as their difference and the larger one.

    Ports:
        clock, reset  clock and reset (``card_reset()``)
        step          ``DdaStep``: the run's registered decision in; ``last`` out
        move          ``DdaMove``: ``take`` and the totals in
        cmd           ``DdaPort``: ``stop_left`` out
    Parameters: none; the width comes from ``step``.

    An iteration steps each axis at most once, so the larger of the two
    axes' steps left is a lower bound of the iterations left.  The setup
    hands over their difference and the larger one; here the larger falls by
    one when the axis with more steps left steps (when both have as many,
    only a diagonal step lowers it) and the difference follows each step, in
    the iteration's second clock.  ``stop_left`` is the larger one minus one
    (the minus one covers the iteration under way), all ones while no move
    or a blended one runs.  A line counts its iterations in the difference:
    ``last`` when it is 0::

        clock      _/~\\_/~\\_/~\\_
        pending    _____/~~~\\___
        stop_left  ==<  n  ><n-1>
    """
    width = step.left_width
    ones = (1 << width) - 1
    difference = Signal(modbv(0)[width:])
    larger = Signal(modbv(ones)[width:])

    @always_comb
    def outputs():
        cmd.stop_left.next = larger
        step.last.next = difference == 0

    @always(clock.posedge)
    def follow():
        # the difference, and a taken move's value, through the same adder (a line's less one)
        base = modbv(0)[width:]
        change = modbv(0)[width:]
        base[:] = difference
        if move.take:
            base[:] = move.totals_diff
            if move.line:
                change[:] = intbv(ones)[width:]
        elif step.pending:
            if step.line or (step.step_x and not step.step_y):
                change[:] = intbv(ones)[width:]
            elif step.step_y and not step.step_x:
                change[:] = 1
        difference.next = base + change

    @always_seq(clock.posedge, reset=reset)
    def count_down():
        base = modbv(0)[width:]
        less = modbv(0)[width:]
        base[:] = larger
        if move.take:
            base[:] = move.totals_max
            less[:] = intbv(ones)[width:]
        elif step.pending and not step.blend:
            if step.line:
                less[:] = intbv(ones)[width:]
            elif difference == 0:
                if step.step_x and step.step_y:
                    less[:] = intbv(ones)[width:]
            elif difference[width - 1]:
                if step.step_y:
                    less[:] = intbv(ones)[width:]
            elif step.step_x:
                less[:] = intbv(ones)[width:]
        larger.next = base + less
        if move.take:
            if move.blend or move.error or move.zero:
                larger.next = intbv(ones)[width:]
        elif step.pending and step.finished:
            larger.next = intbv(ones)[width:]

    return outputs, follow, count_down
