"""DDA arc and line interpolator: one iteration per clock in which ``advance`` is high.

The golden model is ``sim/dda_model.py``; its docstring and ``docs/dda.md``
give the algorithm.  The hardware has three parts:

* setup (arcs only): one adder-subtractor forms, by shift-add (one bit per
  clock, 4 * coord_width clocks), gap = xe**2 + ye**2 - xs**2 - ys**2 - 1,
  whose complement half-way is xs**2 + ys**2, the radicand; a restoring
  square root takes it (coord_width clocks) while the same adder checks the
  gap against the end-point limits, and one clock rounds the root to Rq
  (counting its bit length on the way);
* check (one clock): validation, quadrants, the axis-crossing count, the
  per-axis targets of the first quadrant piece, the accumulator threshold
  and initial load (bit inversions, no subtractor);
* run: accumulators, magnitudes and the radial error term, all updated by
  additions only, one iteration per enabled clock.  An axis stops in a
  piece when its magnitude reaches its target (0 inward, Rq outward, the end
  point in the last piece), so there are no step counters to precompute.
"""
from myhdl import Signal, always_comb, always_seq, block, concat, enum, intbv, modbv

from rtl.interfaces import AxisPulses, DdaPort, card_reset

TRADITIONAL, WEIGHTED, IMPROVED, PRECISE = range(4)
ACC_EXTRA_BITS = 8
ERROR_EXTRA_BITS = 6
MAX_THRESHOLD_EXTRA = 4


def _signed(width, value=0):
    return Signal(intbv(value, min=-(1 << (width - 1)), max=1 << (width - 1)))


def _unsigned(width, value=0):
    return Signal(intbv(value)[width:])


def _wrapping(width):
    """A signed register that wraps (two's complement) instead of overflowing."""
    return Signal(modbv(0, min=-(1 << (width - 1)), max=1 << (width - 1)))


@block
def dda_arc(clock, reset, cmd, steps, *, coord_width=24):
    """Two-axis DDA interpolator (arcs of the paper's section 4, and lines).

    Ports:
        clock, reset  clock and reset (``card_reset()``: async, active low)
        cmd           ``DdaPort``: command lines, ``start``, ``advance`` in;
                      ``busy``, ``done``, ``error``, ``quadrant`` out
        steps         ``AxisPulses``: ``step_x``/``step_y`` one clock per step,
                      ``dir_x``/``dir_y`` valid with them
    Parameters:
        coord_width   signed coordinate width (4..31); accumulators are
                      coord_width + 8 bits, the radial error term + 6

    Timing (an arc; a line has a single setup clock)::

        clock    _/~\\_/~\\_/~\\_ ... _/~\\_/~\\_/~\\_/~\\_/~\\_ ... _/~\\_/~\\_
        start    _/~~~\\______ ... ________________________________
        busy     _____/~~~~~~ ... ~~~~~~~~~~~~~~~~~~~~~~~ ... ~~~\\___
        advance  ____________ ... ______/~~~~~~~~~~~\\___ ... ~~~~~~~~
        step_x   ____________ ... __________/~~~\\___/~~~ ... ________
        done     ____________ ... ___________________________/~~~\\___
                      |<- 5*coord_width+2 ->|

    ``step_*`` follows the clock edge of the iteration that made the step;
    ``done`` comes with the last step.  ``error`` instead of the run when the
    check rejects the command.
    """
    if not 4 <= coord_width <= 31:
        raise ValueError(f"coord_width must be 4..31, not {coord_width}")
    width = coord_width
    acc_width = width + ACC_EXTRA_BITS
    err_width = width + ERROR_EXTRA_BITS
    thr_width = width + MAX_THRESHOLD_EXTRA + 1
    gap_width = 2 * width + 2
    acc_max = (1 << (acc_width - 1)) - 1
    fill_ones = (1 << (err_width - width - 2)) - 1
    minus_one = (1 << width) - 1  # -1 in width bits: one adder steps either way
    minus_one_wide = (1 << (width + 1)) - 1

    t_state = enum("S_IDLE", "S_MAC", "S_ROOT", "S_ROUND", "S_CHECK", "S_RUN")
    state = Signal(t_state.S_IDLE)

    # latched command
    is_line = Signal(bool(0))
    variant = _unsigned(2)
    lambda_shift = _unsigned(5)
    acc_bits = _unsigned(5)
    ccw = Signal(bool(0))
    xs, ys, xe, ye = (_signed(width) for _ in range(4))
    neg_xs, neg_ys = _signed(width + 1), _signed(width + 1)
    mag_xs, mag_ys, mag_xe, mag_ye = (_unsigned(width) for _ in range(4))
    cmd_mag_xs = _unsigned(width)

    # setup: one adder-subtractor forms gap = xe**2 + ye**2 - xs**2 - ys**2 - 1 (shift-add),
    # then checks it against the end-point limits; a restoring square root takes xs**2 + ys**2
    mac_op = Signal(modbv(0)[2:])
    mac_bit = Signal(intbv(0, min=0, max=width))
    multiplicand = Signal(modbv(0)[2 * width:])
    multiplier = _unsigned(width)
    gap = _wrapping(gap_width)
    gap_sum = _wrapping(gap_width)
    radicand = Signal(modbv(0)[2 * width:])
    remainder = _unsigned(width + 3)
    root = _unsigned(width)
    root_bit = Signal(intbv(0, min=0, max=width))
    root_trial_rem = _unsigned(width + 3)
    root_trial_diff = _unsigned(width + 3)
    root_trial_fits = Signal(bool(0))
    root_length = _unsigned(6)
    root_all_ones = Signal(bool(0))
    radius_q = _unsigned(width + 1)
    radius_length = _unsigned(6)
    end_reaches_low = Signal(bool(0))
    end_beyond_high = Signal(bool(0))

    # quadrants and pieces (registered, ahead of the check)
    geo_quadrant = _unsigned(2)
    geo_crossings = _unsigned(3)
    geo_ahead = Signal(bool(0))
    geo_end_inward = _unsigned(width)
    geo_centre = Signal(bool(0))

    # check results
    chk_error = Signal(bool(0))
    chk_threshold = _unsigned(thr_width)
    chk_acc_init = _signed(acc_width)
    chk_quadrant = _unsigned(2)
    chk_crossings = _unsigned(3)
    chk_target_x, chk_target_y = _unsigned(width), _unsigned(width)
    chk_mag_x, chk_mag_y = _unsigned(width), _unsigned(width)
    chk_radius = _unsigned(width)
    chk_neg_mag_x, chk_neg_mag_y = Signal(modbv(0)[width + 1:]), Signal(modbv(0)[width + 1:])

    # run state
    quadrant = Signal(modbv(0)[2:])
    x_inward = Signal(bool(0))  # quadrant[0] xor ccw, kept as a register: it selects early
    mag_x, mag_y = _unsigned(width), _unsigned(width)
    acc_x, acc_y = _signed(acc_width), _signed(acc_width)
    radial_error = _wrapping(err_width)
    # -|x|, -|y| (two's complement) beside the magnitudes, so that the change of x**2 on
    # the next step of x, 1 - 2|x| inward, 1 + 2|x| outward, needs no subtractor
    neg_mag_x, neg_mag_y = Signal(modbv(0)[width + 1:]), Signal(modbv(0)[width + 1:])
    # each axis stops in the current piece when its magnitude reaches its target:
    # 0 inward and Rq outward, |xe|, |ye| in the last piece; a line counts up to |dx|, |dy|
    target_x, target_y = _unsigned(width), _unsigned(width)
    crossings = _unsigned(3)
    threshold = _unsigned(thr_width)
    radius = _unsigned(width)

    # one iteration, combinational
    it_step_x, it_step_y = Signal(bool(0)), Signal(bool(0))
    it_dir_x, it_dir_y = Signal(bool(0)), Signal(bool(0))
    it_acc_x, it_acc_y = _signed(acc_width), _signed(acc_width)
    it_mag_x, it_mag_y = Signal(modbv(0)[width:]), Signal(modbv(0)[width:])
    it_neg_mag_x, it_neg_mag_y = Signal(modbv(0)[width + 1:]), Signal(modbv(0)[width + 1:])
    delta_x, delta_y = _wrapping(err_width), _wrapping(err_width)
    it_error = _wrapping(err_width)
    it_finished = Signal(bool(0))
    it_next_piece = Signal(bool(0))
    it_tail = Signal(bool(0))
    count_x, count_y = Signal(modbv(0)[width:]), Signal(modbv(0)[width:])
    at_x, at_y = Signal(bool(0)), Signal(bool(0))
    near_x, near_y = Signal(bool(0)), Signal(bool(0))
    # the magnitudes one step further (inward: -1, outward: +1), one adder each
    mag_x_step, mag_y_step = Signal(modbv(0)[width:]), Signal(modbv(0)[width:])
    neg_mag_x_step, neg_mag_y_step = Signal(modbv(0)[width + 1:]), Signal(modbv(0)[width + 1:])
    integrand_x, integrand_y = _unsigned(width), _unsigned(width)

    @always_comb
    def magnitudes():
        if cmd.xs < 0:
            cmd_mag_xs.next = -cmd.xs
        else:
            cmd_mag_xs.next = cmd.xs
        neg_xs.next = -concat(xs[width - 1], xs).signed()
        neg_ys.next = -concat(ys[width - 1], ys).signed()
        if xs < 0:
            mag_xs.next = neg_xs[width:]
        else:
            mag_xs.next = xs[width:]
        if ys < 0:
            mag_ys.next = neg_ys[width:]
        else:
            mag_ys.next = ys[width:]
        if xe < 0:
            mag_xe.next = -xe
        else:
            mag_xe.next = xe
        if ye < 0:
            mag_ye.next = -ye
        else:
            mag_ye.next = ye

    @always_comb
    def setup_adder():
        # gap - multiplicand while squaring xs, ys; gap + multiplicand while squaring xe, ye
        # and at the first limit; gap - multiplicand - 1 at the second (see control).  The
        # carry is the adder's carry input: one carry chain.
        subtract = bool(0)
        carry = bool(0)
        operand = modbv(0)[gap_width:]
        carry_in = intbv(0)[gap_width:]
        total = modbv(0)[gap_width:]
        if state == t_state.S_MAC:
            subtract = mac_op < 2
            carry = mac_op < 2
        else:
            subtract = root_bit == 2
        operand[:] = concat(intbv(0)[gap_width - 2 * width:], multiplicand)
        if subtract:
            operand[:] = ~operand
        carry_in[:] = concat(intbv(0)[gap_width - 1:], carry)
        total[:] = gap[gap_width:] + operand + carry_in
        gap_sum.next = total.signed()

    @always_comb
    def root_trial():
        # restoring square root, one bit per clock: one subtractor, its borrow is the compare
        trial_rem = intbv(0)[width + 3:]
        trial_diff = modbv(0)[width + 4:]
        trial_rem[:] = concat(remainder[width + 1:], radicand[2 * width:2 * width - 2])
        trial_diff[:] = concat(False, trial_rem) - concat(intbv(0)[2:], root, intbv(1)[2:])
        root_trial_rem.next = trial_rem
        root_trial_diff.next = trial_diff[width + 3:]
        root_trial_fits.next = not trial_diff[width + 3]

    @always_seq(clock.posedge, reset=reset)
    def geometry():
        # quadrants and pieces from the latched command alone, registered on every clock
        # (valid from the second setup clock on: ahead of the check, off its path)
        q_s = intbv(0)[2:]
        q_e = intbv(0)[2:]
        turns = intbv(0)[3:]
        turn = modbv(0)[2:]
        shrink_x = modbv(0)[width + 1:]
        shrink_y = modbv(0)[width + 1:]
        ahead = bool(0)

        # departure quadrant of the start, arrival quadrant of the end
        if ccw:
            if xs > 0 and ys >= 0:
                q_s[:] = 0
            elif xs <= 0 and ys > 0:
                q_s[:] = 1
            elif xs < 0 and ys <= 0:
                q_s[:] = 2
            else:
                q_s[:] = 3
            if xe >= 0 and ye > 0:
                q_e[:] = 0
            elif xe < 0 and ye >= 0:
                q_e[:] = 1
            elif xe <= 0 and ye < 0:
                q_e[:] = 2
            else:
                q_e[:] = 3
            turn[:] = q_e - q_s
        else:
            if xs >= 0 and ys > 0:
                q_s[:] = 0
            elif xs < 0 and ys >= 0:
                q_s[:] = 1
            elif xs <= 0 and ys < 0:
                q_s[:] = 2
            else:
                q_s[:] = 3
            if xe > 0 and ye >= 0:
                q_e[:] = 0
            elif xe <= 0 and ye > 0:
                q_e[:] = 1
            elif xe < 0 and ye <= 0:
                q_e[:] = 2
            else:
                q_e[:] = 3
            turn[:] = q_s - q_e

        turns[:] = concat(False, turn)

        # an end ahead in the start's quadrant is one piece: the inward magnitude does not
        # grow, the outward one does not shrink, and the end is not the start (x is inward
        # when quadrant[0] xor ccw; the differences' signs are the compares)
        shrink_x[:] = concat(False, mag_xs) - concat(False, mag_xe)
        shrink_y[:] = concat(False, mag_ys) - concat(False, mag_ye)
        if q_s[0] != ccw:
            ahead = not shrink_x[width] and (shrink_y[width] or shrink_y == 0)
        else:
            ahead = not shrink_y[width] and (shrink_x[width] or shrink_x == 0)
        geo_ahead.next = False
        if turns == 0 and ahead and not (shrink_x == 0 and shrink_y == 0):
            geo_ahead.next = True
        elif turns == 0:
            turns[:] = 4
        geo_quadrant.next = q_s
        geo_crossings.next = turns
        # otherwise the end must not lie beyond Rq on its inward axis (checked with Rq)
        if q_e[0] != ccw:
            geo_end_inward.next = mag_xe
        else:
            geo_end_inward.next = mag_ye
        geo_centre.next = (xs == 0 and ys == 0) or (xe == 0 and ye == 0)

    @always_comb
    def check_logic():
        rq = intbv(0)[width + 1:]
        exponent = modbv(0)[6:]
        thr = modbv(0)[thr_width:]
        thr_less = modbv(0)[thr_width:]
        one = intbv(1)[thr_width:]
        below = modbv(0)[acc_width:]
        half = modbv(0)[acc_width:]
        major = intbv(0)[width:]
        major_less = modbv(0)[width:]
        bad = False

        rq[:] = radius_q
        if geo_centre:
            bad = True
        if rq >= (1 << (width - 1)):
            bad = True
        if not end_reaches_low or end_beyond_high:
            bad = True

        # threshold of the paper's variants: 2**(n + k); n = acc_bits, or if that is 0
        # the bit length of Rq (left-shift normalisation); rejected when n + k > coord_width + 4
        if acc_bits != 0:
            exponent[:] = concat(False, acc_bits) + concat(False, lambda_shift)
        else:
            exponent[:] = radius_length + concat(False, lambda_shift)
        thr[:] = one << exponent
        thr_less[:] = thr - 1
        if variant != PRECISE and exponent > thr_width - 1:
            bad = True
        if variant == PRECISE:
            thr[:] = concat(intbv(0)[thr_width - width - 1:], rq) + 1
            thr_less[:] = concat(intbv(0)[thr_width - width - 1:], rq)
        # a line: T = max(|dx|, |dy|)
        if mag_xe > mag_ye:
            major[:] = mag_xe
        else:
            major[:] = mag_ye
        major_less[:] = major - 1
        if is_line:
            thr[:] = concat(intbv(0)[thr_width - width:], major)
            thr_less[:] = concat(intbv(0)[thr_width - width:], major_less)
        # the accumulators hold A - T (A - T - 1 for the strict compares), so the initial
        # load T // 2 is held as -ceil(T/2) = ~((T - 1) >> 1), zero as -T - 1 = ~T
        below[:] = concat(intbv(0)[acc_width - thr_width:], thr_less)
        half[:] = ~(below >> 1)
        if not is_line and (variant == WEIGHTED or variant == IMPROVED):
            half[:] = ~concat(intbv(0)[acc_width - thr_width:], thr)

        # an end ahead in the start's quadrant is one piece; otherwise the end must not lie
        # beyond Rq on its inward axis
        if is_line or geo_ahead:
            chk_target_x.next = mag_xe
            chk_target_y.next = mag_ye
        else:
            if concat(False, geo_end_inward) > rq:
                bad = True
            if geo_quadrant[0] != ccw:
                chk_target_x.next = 0
                chk_target_y.next = rq[width:]
            else:
                chk_target_x.next = rq[width:]
                chk_target_y.next = 0

        chk_error.next = bad
        chk_radius.next = rq[width:]
        # a line starts at magnitude 0 in quadrant 0 and counts its steps up to |dx|, |dy|
        chk_quadrant.next = geo_quadrant
        chk_crossings.next = geo_crossings
        chk_mag_x.next = mag_xs
        chk_mag_y.next = mag_ys
        if is_line or bad:
            chk_quadrant.next = 0
        if is_line:
            chk_crossings.next = 0
            chk_mag_x.next = 0
            chk_mag_y.next = 0
        chk_threshold.next = thr
        chk_acc_init.next = half.signed()
        # -|x| is x or -x
        if xs < 0:
            chk_neg_mag_x.next = concat(xs[width - 1], xs)
        else:
            chk_neg_mag_x.next = neg_xs
        if ys < 0:
            chk_neg_mag_y.next = concat(ys[width - 1], ys)
        else:
            chk_neg_mag_y.next = neg_ys

    @always_comb
    def piece_progress():
        # steps left in the current piece (the inward axis falls to its target); their zero
        # holds the accumulators, while the step choice uses the equality tests below
        if not is_line and x_inward:
            count_x.next = mag_x - target_x
            count_y.next = target_y - mag_y
        elif not is_line:
            count_x.next = target_x - mag_x
            count_y.next = mag_y - target_y
        else:
            count_x.next = target_x - mag_x
            count_y.next = target_y - mag_y
        # the magnitudes one step further, one adder each (-1 is the all-ones operand);
        # "at the target" and "one step before it" are then equality tests
        if not is_line and x_inward:
            mag_x_step.next = mag_x + minus_one
            neg_mag_x_step.next = neg_mag_x + 1
            mag_y_step.next = mag_y + 1
            neg_mag_y_step.next = neg_mag_y + minus_one_wide
        elif not is_line:
            mag_x_step.next = mag_x + 1
            neg_mag_x_step.next = neg_mag_x + minus_one_wide
            mag_y_step.next = mag_y + minus_one
            neg_mag_y_step.next = neg_mag_y + 1
        else:
            mag_x_step.next = mag_x + 1
            neg_mag_x_step.next = neg_mag_x + minus_one_wide
            mag_y_step.next = mag_y + 1
            neg_mag_y_step.next = neg_mag_y + minus_one_wide
        at_x.next = mag_x == target_x
        at_y.next = mag_y == target_y
        near_x.next = mag_x_step == target_x
        near_y.next = mag_y_step == target_y
        # change of x**2 (y**2) on the next step of x (y): 1 - 2|x| inward, 1 + 2|x| outward
        fill_x = intbv(0)[err_width - width - 2:]
        fill_y = intbv(0)[err_width - width - 2:]
        if neg_mag_x[width]:
            fill_x[:] = fill_ones
        if neg_mag_y[width]:
            fill_y[:] = fill_ones
        if x_inward:
            delta_x.next = concat(fill_x, neg_mag_x, True).signed()
            delta_y.next = concat(intbv(0)[err_width - width - 1:], mag_y, True).signed()
        else:
            delta_x.next = concat(intbv(0)[err_width - width - 1:], mag_x, True).signed()
            delta_y.next = concat(fill_y, neg_mag_y, True).signed()
        # a line's magnitudes count its steps; it integrates |dx|, |dy|
        if is_line:
            integrand_x.next = target_x
            integrand_y.next = target_y
        else:
            integrand_x.next = mag_y
            integrand_y.next = mag_x

    @always_comb
    def iteration_logic():
        x_right = bool(0)
        y_up = bool(0)
        to_mag = intbv(0)[acc_width + 1 - width:]
        sum_x = intbv(0, min=-(1 << acc_width), max=1 << acc_width)
        sum_x_step = intbv(0, min=-(1 << acc_width), max=1 << acc_width)
        sum_y = intbv(0, min=-(1 << acc_width), max=1 << acc_width)
        thr_low = intbv(0)[acc_width:]
        ahead_x = intbv(0, min=-(1 << acc_width), max=1 << acc_width)
        ahead_y = intbv(0, min=-(1 << acc_width), max=1 << acc_width)
        less_x = modbv(0)[acc_width:]
        less_y = modbv(0)[acc_width:]
        cand_d = modbv(0, min=-(1 << (err_width - 1)), max=1 << (err_width - 1))
        cand_x = modbv(0, min=-(1 << (err_width - 1)), max=1 << (err_width - 1))
        cand_y = modbv(0, min=-(1 << (err_width - 1)), max=1 << (err_width - 1))
        delta_xy = modbv(0, min=-(1 << (err_width - 1)), max=1 << (err_width - 1))
        half_xy = modbv(0, min=-(1 << err_width), max=1 << err_width)
        sum_le_0 = bool(0)
        sum_lt_0 = bool(0)
        d_le_x = bool(0)
        d_le_y = bool(0)
        x_le_y = bool(0)
        over_x = bool(0)
        over_x_step = bool(0)
        over_y = bool(0)
        go_x = bool(0)
        go_y = bool(0)

        x_right = quadrant[0] == quadrant[1]
        y_up = not quadrant[1]
        if is_line:
            it_dir_x.next = xe >= 0
            it_dir_y.next = ye >= 0
        else:
            it_dir_x.next = x_right != x_inward
            it_dir_y.next = y_up == x_inward

        # accumulators; the compares use the unsaturated sums (T is far below the
        # saturation value, so the result is the same) to keep the carry chains short
        to_mag[:] = 0
        thr_low[:] = concat(intbv(0)[acc_width - thr_width:], threshold)
        sum_y[:] = concat(acc_y[acc_width - 1], acc_y).signed() + concat(to_mag, integrand_y).signed()
        sum_x[:] = concat(acc_x[acc_width - 1], acc_x).signed() + concat(to_mag, integrand_x).signed()
        sum_x_step[:] = concat(acc_x[acc_width - 1], acc_x).signed() + concat(to_mag, mag_y_step).signed()
        # the registers hold A - bias: an overflow is a sum that is not negative
        over_x = not sum_x[acc_width]
        over_x_step = not sum_x_step[acc_width]
        over_y = not sum_y[acc_width]
        # traditional: Y first, X integrates the new |y| (sums and compares formed in parallel)
        if not is_line and variant == TRADITIONAL and over_y:
            sum_x[:] = sum_x_step
            over_x = over_x_step

        # precise: |a| <= |b| exactly when (a - b) and (a + b) differ in sign or one is 0
        # (all sums two adders deep: cand_x + cand_d = 2 cand_x + dy, and so on); the deltas
        # are odd, so dy, dx, 2 cand_x + dy and 2 cand_y + dx are never 0
        delta_xy[:] = delta_x + delta_y
        cand_x[:] = radial_error + delta_x
        cand_y[:] = radial_error + delta_y
        cand_d[:] = radial_error + delta_xy
        # X against Y: a - b = dx - dy, a + b = 2E + dx + dy = 2 (E + h + 1) with the odd
        # deltas' h = (dx >> 1) + (dy >> 1); a + b <= 0 is E + h < 0, a + b < 0 is E + h + 1 < 0
        # (signs only, no zero test on a sum)
        half_xy[:] = concat(delta_x[err_width - 1], delta_x[err_width - 1], delta_x[err_width:1]).signed() + \
            concat(delta_y[err_width - 1], delta_y[err_width - 1], delta_y[err_width:1]).signed()
        sum_le_0 = concat(radial_error[err_width - 1], radial_error).signed() + half_xy < 0
        sum_lt_0 = concat(radial_error[err_width - 1], radial_error).signed() + half_xy + 1 < 0
        d_le_x = (delta_y < 0) != (concat(cand_x[err_width:], False).signed() +
                                   concat(delta_y[err_width - 1], delta_y).signed() < 0)
        d_le_y = (delta_x < 0) != (concat(cand_y[err_width:], False).signed() +
                                   concat(delta_x[err_width - 1], delta_x).signed() < 0)
        x_le_y = delta_x == delta_y or (delta_x > delta_y and sum_le_0) or (delta_x < delta_y and not sum_lt_0)

        go_x = over_x
        go_y = over_y
        if is_line:
            go_x = over_x and not at_x
            go_y = over_y and not at_y
        elif variant == IMPROVED:
            # A + 2i straight from the registers (one adder)
            ahead_x[:] = concat(acc_x[acc_width - 1], acc_x).signed() + concat(to_mag[acc_width - width:], mag_y, False).signed()
            ahead_y[:] = concat(acc_y[acc_width - 1], acc_y).signed() + concat(to_mag[acc_width - width:], mag_x, False).signed()
            if over_x and not over_y and ahead_y >= 0:
                go_y = True
            elif over_y and not over_x and ahead_x >= 0:
                go_x = True
        elif variant == PRECISE:
            go_x = False
            go_y = False
            if over_x or over_y:
                if d_le_x and d_le_y:
                    go_x = True
                    go_y = True
                elif x_le_y:
                    go_x = True
                else:
                    go_y = True

        # an axis at its target stops; the other one steps alone, the accumulators hold
        it_tail.next = not is_line and (count_x == 0 or count_y == 0)
        if not is_line and (at_x or at_y):
            go_x = not at_x
            go_y = not at_y
        if not sum_x[acc_width] and sum_x[acc_width - 1]:
            sum_x[:] = acc_max
        if not sum_y[acc_width] and sum_y[acc_width - 1]:
            sum_y[:] = acc_max
        less_x[:] = sum_x[acc_width:]
        if go_x:
            less_x[:] = sum_x[acc_width:] - thr_low
        less_y[:] = sum_y[acc_width:]
        if go_y:
            less_y[:] = sum_y[acc_width:] - thr_low
        it_acc_x.next = less_x.signed()
        it_acc_y.next = less_y.signed()
        it_step_x.next = go_x
        it_step_y.next = go_y
        it_mag_x.next = mag_x
        it_mag_y.next = mag_y
        it_neg_mag_x.next = neg_mag_x
        it_neg_mag_y.next = neg_mag_y
        if go_x:
            it_mag_x.next = mag_x_step
            it_neg_mag_x.next = neg_mag_x_step
        if go_y:
            it_mag_y.next = mag_y_step
            it_neg_mag_y.next = neg_mag_y_step
        if go_x and go_y:
            it_error.next = cand_d
        elif go_x:
            it_error.next = cand_x
        elif go_y:
            it_error.next = cand_y
        else:
            it_error.next = radial_error

        it_finished.next = False
        it_next_piece.next = False
        if (near_x and go_x or at_x) and (near_y and go_y or at_y):
            if is_line or crossings == 0:
                it_finished.next = True
            else:
                it_next_piece.next = True

    @always_seq(clock.posedge, reset=reset)
    def control():
        steps.step_x.next = False
        steps.step_y.next = False
        cmd.done.next = False
        if state == t_state.S_IDLE:
            if cmd.start:
                cmd.busy.next = True
                cmd.error.next = False
                is_line.next = cmd.line
                variant.next = cmd.variant
                lambda_shift.next = cmd.lambda_shift
                acc_bits.next = cmd.acc_bits
                ccw.next = cmd.ccw
                xs.next = cmd.xs
                ys.next = cmd.ys
                xe.next = cmd.xe
                ye.next = cmd.ye
                gap.next = -1
                mac_op.next = 0
                mac_bit.next = 0
                multiplicand.next = concat(intbv(0)[width:], cmd_mag_xs)
                multiplier.next = cmd_mag_xs
                if cmd.line:
                    state.next = t_state.S_CHECK
                else:
                    state.next = t_state.S_MAC
        elif state == t_state.S_MAC:
            if multiplier[0]:
                gap.next = gap_sum
            if mac_op == 2 and mac_bit == 0:
                # gap = -1 - xs**2 - ys**2 now: its complement is the radicand
                radicand.next = ~gap[2 * width:]
            if mac_bit == width - 1:
                mac_bit.next = 0
                mac_op.next = mac_op + 1
                if mac_op == 0:
                    multiplicand.next = concat(intbv(0)[width:], mag_ys)
                    multiplier.next = mag_ys
                elif mac_op == 1:
                    multiplicand.next = concat(intbv(0)[width:], mag_xe)
                    multiplier.next = mag_xe
                elif mac_op == 2:
                    multiplicand.next = concat(intbv(0)[width:], mag_ye)
                    multiplier.next = mag_ye
                else:
                    # m = max(|xs|, |ys|) for the end-point limits
                    if mag_xs > mag_ys:
                        multiplicand.next = concat(intbv(0)[width:], mag_xs)
                    else:
                        multiplicand.next = concat(intbv(0)[width:], mag_ys)
                    remainder.next = 0
                    root.next = 0
                    root_bit.next = 0
                    root_length.next = 0
                    root_all_ones.next = True
                    state.next = t_state.S_ROOT
            else:
                mac_bit.next = mac_bit + 1
                multiplicand.next = multiplicand << 1
                multiplier.next = multiplier >> 1
        elif state == t_state.S_ROOT:
            if root_trial_fits:
                remainder.next = root_trial_diff
                root.next = concat(root[width - 1:], True)
            else:
                remainder.next = root_trial_rem
                root.next = concat(root[width - 1:], False)
                if root != 0:
                    root_all_ones.next = False
            if root != 0 or root_trial_fits:
                root_length.next = root_length + 1
            radicand.next = radicand << 2
            # end point within one step: -(2m - 1) <= re**2 - rs**2 <= 2m + 1 with
            # m = max(|xs|, |ys|) (|re - rs| <= 1 follows as m <= rs); the gap is
            # re**2 - rs**2 - 1: add 2m, test the sign, take 4m + 1, test the sign
            if root_bit == 0:
                multiplicand.next = multiplicand << 1
            elif root_bit == 1:
                gap.next = gap_sum
                multiplicand.next = multiplicand << 1
            elif root_bit == 2:
                end_reaches_low.next = not gap[gap_width - 1]
                gap.next = gap_sum
            elif root_bit == 3:
                end_beyond_high.next = not gap[gap_width - 1]
            if root_bit == width - 1:
                state.next = t_state.S_ROUND
            else:
                root_bit.next = root_bit + 1
        elif state == t_state.S_ROUND:
            # Rq: the integer whose square is nearest to xs**2 + ys**2
            # Rq = root + 1 when remainder > root: the next root bit (radicand bits 00 now)
            radius_q.next = concat(False, root) + concat(intbv(0)[width:], root_trial_fits)
            if root_trial_fits and root_all_ones:
                radius_length.next = root_length + 1
            else:
                radius_length.next = root_length
            state.next = t_state.S_CHECK
        elif state == t_state.S_CHECK:
            acc_x.next = chk_acc_init
            acc_y.next = chk_acc_init
            threshold.next = chk_threshold
            radial_error.next = 0
            quadrant.next = chk_quadrant
            x_inward.next = chk_quadrant[0] != ccw
            crossings.next = chk_crossings
            mag_x.next = chk_mag_x
            mag_y.next = chk_mag_y
            target_x.next = chk_target_x
            target_y.next = chk_target_y
            radius.next = chk_radius
            neg_mag_x.next = chk_neg_mag_x
            neg_mag_y.next = chk_neg_mag_y
            state.next = t_state.S_RUN
            if is_line and mag_xe == 0 and mag_ye == 0:
                cmd.busy.next = False
                cmd.done.next = True
                state.next = t_state.S_IDLE
            elif not is_line and chk_error:
                cmd.busy.next = False
                cmd.error.next = True
                state.next = t_state.S_IDLE
        elif cmd.advance:
            steps.step_x.next = it_step_x
            steps.step_y.next = it_step_y
            steps.dir_x.next = it_dir_x
            steps.dir_y.next = it_dir_y
            if not it_tail:
                acc_x.next = it_acc_x
                acc_y.next = it_acc_y
            mag_x.next = it_mag_x
            mag_y.next = it_mag_y
            neg_mag_x.next = it_neg_mag_x
            neg_mag_y.next = it_neg_mag_y
            radial_error.next = it_error
            if it_finished:
                cmd.busy.next = False
                cmd.done.next = True
                state.next = t_state.S_IDLE
            if it_next_piece:
                x_inward.next = not x_inward
                if x_inward:
                    target_x.next = radius
                    target_y.next = 0
                else:
                    target_x.next = 0
                    target_y.next = radius
                if crossings == 1:
                    target_x.next = mag_xe
                    target_y.next = mag_ye
                if ccw:
                    quadrant.next = quadrant + 1
                else:
                    quadrant.next = quadrant - 1
                crossings.next = crossings - 1

    @always_comb
    def status():
        cmd.quadrant.next = quadrant

    return magnitudes, setup_adder, root_trial, geometry, check_logic, piece_progress, iteration_logic, control, status


def dda_arc_ports(coord_width=24):
    """Fresh ports of ``dda_arc`` for conversion or a bench."""
    return dict(clock=Signal(bool(0)), reset=card_reset(),
                cmd=DdaPort(coord_width), steps=AxisPulses())
