"""DDA check: turns the setup stage's plan into the checked move the run takes."""
from myhdl import Signal, always_comb, block, concat, intbv, modbv

from models.dda_build import IMPROVED, PAPER_VARIANTS, PRECISE, WEIGHTED
from rtl.interfaces import TARGET_END, TARGET_RADIUS, TARGET_ZERO


@block
def dda_check(plan, move):
    """Validation and start values of a prepared move (no registers).

    Ports:
        plan   ``DdaPlan`` in (the setup stage's registers); ``plan.taken`` out
        move   ``DdaMove`` out: ``offer`` and the checked move; ``move.take`` in
    Parameters: none; the widths and ``variants`` come from ``plan``.

    The run loads the move at the edge where it takes it, so everything here
    is read from setup registers that hold still until then::

        clock      _/~\\_/~\\_/~\\_/~\\_
        plan.done  _____/~~~~~~~~~\\___
        move.take  _____________/~~~\\___   (the run is free)
        run loads  ________________^

    An arc is rejected when it starts or ends at the centre, its radius does
    not fit (Rq >= 2**(W - 1)), its end is not within one step of the start
    radius, lies beyond Rq on its inward axis (unless the end is ahead in the
    start's quadrant), the paper's n + k is too large, or its variant is not
    built.  Thresholds: a line's T = max(|dx|, |dy|), the precise mode's
    T = Rq + 1, the paper's T = 2**(n + k); the run gets T - 1 (T for a line),
    and the accumulators A - T: -ceil(T / 2) when half loaded (a line's odd
    half in ``acc_carry``), -T - 1 (zero load, strict compare).
    """
    width = plan.coord_width
    acc_width = move.acc_width
    thr_width = move.threshold_width
    bias_width = move.bias_width
    built = tuple(int(code in plan.variants) for code in range(4))
    paper = bool(plan.variants & PAPER_VARIANTS)
    variant_built = Signal(bool(0))

    @always_comb
    def lookup_variant():
        variant_built.next = built[plan.variant]

    @always_comb
    def handshake():
        move.offer.next = plan.done
        plan.taken.next = move.take

    @always_comb
    def validate():
        bad = plan.centre or plan.off_circle or plan.radius[width + 1:width - 1] != 0
        if not plan.ahead and plan.beyond:
            bad = True
        if plan.variant != PRECISE and plan.too_wide:
            bad = True
        if not variant_built:
            bad = True
        move.error.next = bad and not plan.line
        move.zero.next = plan.line and plan.centre

    @always_comb
    def geometry():
        move.line.next = plan.line
        move.variant.next = plan.variant
        move.ccw.next = plan.ccw
        move.blend.next = plan.blend
        move.right.next = not plan.neg_xe
        move.up.next = not plan.neg_ye
        move.x_inward.next = plan.x_inward
        move.quadrant.next = plan.quadrant
        move.crossings.next = plan.crossings
        if plan.line:
            move.quadrant.next = 0
            move.crossings.next = 0
        # the first piece ends on the axis (inward) and at Rq (outward), or at the end
        # point when the end is ahead in the start's quadrant
        if plan.crossings == 0:
            move.target_x.next = TARGET_END
            move.target_y.next = TARGET_END
        elif plan.x_inward:
            move.target_x.next = TARGET_ZERO
            move.target_y.next = TARGET_RADIUS
        else:
            move.target_x.next = TARGET_RADIUS
            move.target_y.next = TARGET_ZERO

    @always_comb
    def magnitudes():
        # a line's integrands are |dx| for X's accumulator, |dy| for Y's: the run's |y|, |x|
        move.mag_x.next = plan.mag_xs
        move.mag_y.next = plan.mag_ys
        if plan.line:
            move.mag_x.next = plan.mag_ye
            move.mag_y.next = plan.mag_xe
        move.end_x.next = plan.mag_xe
        move.end_y.next = plan.mag_ye
        move.radius.next = plan.radius[width:]
        move.totals_diff.next = plan.totals_diff
        move.totals_max.next = plan.totals_max

    @always_comb
    def thresholds():
        less = intbv(0)[thr_width:]
        below = modbv(0)[acc_width:]
        ones = intbv(0)[thr_width + 1:]
        less[:] = plan.threshold
        if not plan.line and (not paper or plan.variant == PRECISE):
            less[:] = 0
            less[width:] = plan.radius[width:]
        move.threshold.next = less
        # A - T of the first iteration, as a bit inversion: -ceil(T/2) = ~((T - 1) >> 1)
        # (a line holds T itself: its carry adds the 1 for an even T), -T - 1 = ~T
        below[:] = ~concat(intbv(0)[acc_width - thr_width + 1:], less[thr_width:1])
        if paper and not plan.line and (plan.variant == WEIGHTED or plan.variant == IMPROVED):
            # T = (T - 1) + 1 = 2**e: the bit above the ones
            ones[:] = concat(less, True) & ~concat(False, less)
            below[:] = ~concat(intbv(0)[acc_width - thr_width - 1:], ones)
        move.acc_init.next = below.signed()
        move.acc_carry.next = plan.line and not less[0]

    @always_comb
    def precise_terms():
        # P = 2b - a and Q = b - 2a at the start point (a inward, b outward)
        inward = modbv(0)[bias_width:]
        outward = modbv(0)[bias_width:]
        bias_in = modbv(0)[bias_width:]
        bias_out = modbv(0)[bias_width:]
        inward[:] = concat(intbv(0)[bias_width - width:], plan.mag_ys)
        outward[:] = concat(intbv(0)[bias_width - width:], plan.mag_xs)
        if plan.x_inward:
            inward[:] = concat(intbv(0)[bias_width - width:], plan.mag_xs)
            outward[:] = concat(intbv(0)[bias_width - width:], plan.mag_ys)
        bias_in[:] = concat(outward[bias_width - 1:], False) - inward
        bias_out[:] = outward - concat(inward[bias_width - 1:], False)
        move.bias_in.next = bias_in.signed()
        move.bias_out.next = bias_out.signed()

    processes = [lookup_variant, handshake, validate, geometry, magnitudes, thresholds]
    if PRECISE in plan.variants:
        # P and Q: only the precise mode reads them
        processes.append(precise_terms)
    return processes
