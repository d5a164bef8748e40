"""Command latch of the DDA's setup stage, and the geometry of the latched move."""
from myhdl import Signal, always, always_comb, block, concat, intbv, modbv


@block
def dda_latch(clock, reset, cmd, plan):
    """Latches a command into the plan and works out its quadrants and pieces.

    Ports:
        clock, reset  clock and reset (``card_reset()``)
        cmd           ``DdaPort``: command lines and ``start`` in, ``ready`` in
                      (driven by ``dda_setup``: a start is taken while it is high)
        plan          ``DdaPlan`` out: the command (``line``, ``variant``, ``ccw``,
                      ``blend``, magnitudes, the end's signs) and the geometry
                      (``quadrant``, ``crossings``, ``ahead``, ``x_inward``,
                      ``x_inward_end``, ``centre``); the compares' flags in
    Parameters: none; W is ``cmd.coord_width``.

    The magnitudes are formed as the command is taken (|v| is v - 1 inverted
    for a negative v: one adder with the sign as operand); the geometry is
    registered on every clock from the latched values, so it is ready a clock
    after the latch, and ``ahead`` once the compares have run::

        clock   _/~\\_/~\\_/~\\_
        start   _/~~~\\______
        mags    _____<  |v|  >
        geometry ________< q >

    A point on an axis belongs to the quadrant the motion enters: (R, 0) is
    in I counter-clockwise, in IV clockwise; the end's quadrant is the one
    it is reached from.  ``crossings`` is the difference of the two (4 for
    an end in the start's quadrant that is not ahead of it).

    Processes, by what they drive: ``magnitudes`` (|v| of the command
    lines), ``latch`` (the command's registers), ``zeros`` and ``quadrants``
    (of the latched values: the zero magnitudes, both quadrants and the
    turns between them), ``geometry`` (the geometry's registers).
    """
    width = cmd.coord_width
    width_ones = (1 << width) - 1
    neg_xs, neg_ys = Signal(bool(0)), Signal(bool(0))
    mag_xs, mag_ys, mag_xe, mag_ye = (Signal(intbv(0)[width:]) for _ in range(4))
    # of the latched move: which magnitudes are 0, its quadrants and the turns between them
    zero_xs, zero_ys, zero_xe, zero_ye = (Signal(bool(0)) for _ in range(4))
    start_quadrant = Signal(intbv(0)[2:])
    end_odd = Signal(bool(0))  # the end's quadrant is II or IV
    turn = Signal(modbv(0)[2:])

    @always_comb
    def magnitudes():
        # |v| is v - 1 inverted for a negative v, v itself otherwise: one adder whose
        # operand is the sign (all ones or zero), its sum inverted by the same sign
        sign_xs = modbv(0)[width:]
        sign_ys = modbv(0)[width:]
        sign_xe = modbv(0)[width:]
        sign_ye = modbv(0)[width:]
        less_xs = modbv(0)[width:]
        less_ys = modbv(0)[width:]
        less_xe = modbv(0)[width:]
        less_ye = modbv(0)[width:]
        if cmd.xs[width - 1]:
            sign_xs[:] = width_ones
        if cmd.ys[width - 1]:
            sign_ys[:] = width_ones
        if cmd.xe[width - 1]:
            sign_xe[:] = width_ones
        if cmd.ye[width - 1]:
            sign_ye[:] = width_ones
        less_xs[:] = cmd.xs[width:] + sign_xs
        less_ys[:] = cmd.ys[width:] + sign_ys
        less_xe[:] = cmd.xe[width:] + sign_xe
        less_ye[:] = cmd.ye[width:] + sign_ye
        mag_xs.next = less_xs ^ sign_xs
        mag_ys.next = less_ys ^ sign_ys
        mag_xe.next = less_xe ^ sign_xe
        mag_ye.next = less_ye ^ sign_ye

    @always(clock.posedge)
    def latch():
        if cmd.start and cmd.ready:
            plan.line.next = cmd.line
            plan.variant.next = cmd.variant
            plan.ccw.next = cmd.ccw
            plan.blend.next = cmd.blend
            neg_xs.next = cmd.xs < 0
            neg_ys.next = cmd.ys < 0
            plan.neg_xe.next = cmd.xe < 0
            plan.neg_ye.next = cmd.ye < 0
            plan.mag_xs.next = mag_xs
            plan.mag_ys.next = mag_ys
            plan.mag_xe.next = mag_xe
            plan.mag_ye.next = mag_ye

    @always_comb
    def zeros():
        zero_xs.next = plan.mag_xs == 0
        zero_ys.next = plan.mag_ys == 0
        zero_xe.next = plan.mag_xe == 0
        zero_ye.next = plan.mag_ye == 0

    @always_comb
    def quadrants():
        # departure quadrant of the start, arrival quadrant of the end, and the quarter
        # turns between them in the direction of motion
        q_s = intbv(0)[2:]
        q_e = intbv(0)[2:]
        if plan.ccw:
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
            turn.next = q_e - q_s
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
            turn.next = q_s - q_e
        start_quadrant.next = q_s
        end_odd.next = q_e[0]

    @always(clock.posedge)
    def geometry():
        # an end ahead in the start's quadrant is one piece: the inward magnitude does not
        # grow, the outward one does not shrink, and the end is not the start
        ahead = False
        if start_quadrant[0] != plan.ccw:
            ahead = not plan.start_below_x and (plan.start_below_y or plan.start_same_y)
        else:
            ahead = not plan.start_below_y and (plan.start_below_x or plan.start_same_x)
        ahead = ahead and not (plan.start_same_x and plan.start_same_y) and turn == 0
        plan.ahead.next = ahead
        plan.crossings.next = concat(False, turn)
        if turn == 0 and not ahead:
            plan.crossings.next = 4
        plan.quadrant.next = start_quadrant
        plan.x_inward.next = start_quadrant[0] != plan.ccw
        plan.x_inward_end.next = end_odd != plan.ccw
        if plan.line:
            plan.centre.next = zero_xe and zero_ye
        else:
            plan.centre.next = (zero_xs and zero_ys) or (zero_xe and zero_ye)

    return magnitudes, latch, zeros, quadrants, geometry
