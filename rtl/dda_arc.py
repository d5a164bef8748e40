"""DDA arc and line interpolator: one iteration per ``advance`` pulse, in two clocks.

The golden model is ``sim/dda_model.py``; its docstring and ``docs/dda.md``
give the algorithm.  Two stages work in parallel: the setup stage (setup and
check below) prepares the next move while the run stage iterates the current
one, and hands it over in the clock after the running move's last iteration.
The hardware has three parts:

* setup (arcs only): one adder-subtractor forms, by shift-add (one bit per
  clock, 4 * coord_width clocks), gap = xe**2 + ye**2 - xs**2 - ys**2 - 1,
  whose complement half-way is xs**2 + ys**2, the radicand; a restoring
  square root takes it (coord_width clocks) while the same adder checks the
  gap against the end-point limits, and one clock rounds the root to Rq
  (counting its bit length on the way);
* check (one clock, registered): validation, quadrants, the axis-crossing
  count, the per-axis targets of the first quadrant piece, the accumulator
  threshold and initial load, each axis' steps over the whole move (for
  ``stop_left``); the checked move then waits for the run stage;
* run: an iteration takes two clocks.  In the clock of ``advance`` every
  decision is formed from registers alone (overflows, the precise mode's
  step choice, the end tests) and registered with the sums it needs; in the
  next clock the registered decision is applied (accumulators minus T,
  magnitudes, the radial error term, the piece change or the handover) and
  the values the next decision needs are stepped beside the magnitudes, so
  that each clock has about one adder between registers.  An axis stops in
  a piece when its magnitude reaches its target (0 inward, Rq outward, the
  end point in the last piece); a line counts its steps left instead.
  Beside them, each axis' steps left over the whole move count down;
  ``stop_left`` comes from the larger one (an iteration steps each axis at
  most once).
"""
from myhdl import Signal, always_comb, always_seq, block, concat, enum, intbv, modbv

from rtl.interfaces import AxisPulses, DdaPort, card_reset
from rtl.parameters import COORD_WIDTH

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
def dda_arc(clock, reset, cmd, steps):
    """Two-axis DDA interpolator (arcs of the paper's section 4, and lines).

    Ports:
        clock, reset  clock and reset (``card_reset()``: async, active low)
        cmd           ``DdaPort``: command lines, ``start``, ``blend``, ``advance``
                      in; ``ready``, ``busy``, ``done``, ``error``, ``quadrant``,
                      ``stop_left`` out; its ``coord_width`` is the signed
                      coordinate width; accumulators are coord_width + 8
                      bits, the radial error term + 6
        steps         ``AxisPulses``: ``step_x``/``step_y`` one clock per step,
                      ``dir_x``/``dir_y`` valid with them

    Timing (an arc; a line has two setup clocks)::

        clock    _/~\\_/~\\_/~\\_ ... _/~\\_/~\\_/~\\_/~\\_/~\\_ ... _/~\\_/~\\_
        start    _/~~~\\______ ... ________________________________
        ready    ~~~~~\\______ ... _____/~~~~~~~~~~~~~~~~~ ... ~~~~~~~~
        busy     _____/~~~~~~ ... ~~~~~~~~~~~~~~~~~~~~~~~ ... ~~~\\___
        advance  ____________ ... ______/~~~\\___/~~~\\___ ... ~~~~~~~~
        step_x   ____________ ... __________/~~~\\___/~~~ ... ________
        done     ____________ ... ___________________________/~~~\\___
                      |<- 5*coord_width+3 ->|

    An iteration takes the clock of its ``advance`` and the next one: an
    ``advance`` in the clock after a taken one is ignored (the card sends at
    most one every other clock).  ``step_*`` follows the clock edge of the
    iteration that made the step; ``done`` comes with the last step.  A
    ``start`` taken while a move runs (``ready`` high) is set up meanwhile;
    the run takes it in the clock after its last iteration, so the next
    ``advance`` iterates the new move::

        advance  _/~\\_/~\\_/~\\_/~\\_      every other clock
        step_x   _____/~\\_/~\\_/~\\_/~\\_  last of move n, then move n + 1
        done     _____/~\\________

    ``error`` (a rejected move) and the ``done`` of a line of length 0 come
    once no move runs.  ``quadrant`` changes in the clock after the
    iteration.  ``stop_left`` is registered from the steps left as the
    second clock of the iterations leaves them, minus one: with its own
    register one iteration behind the ``advance`` pulses at the fastest rate,
    it still never exceeds the iterations left.
    """
    width = cmd.coord_width
    acc_width = width + ACC_EXTRA_BITS
    err_width = width + ERROR_EXTRA_BITS
    thr_width = width + MAX_THRESHOLD_EXTRA + 1
    gap_width = 2 * width + 2
    gap_split = width + 1
    acc_max = (1 << (acc_width - 1)) - 1
    left_width = cmd.left_width
    tot_width = left_width + 1
    left_all_ones = (1 << left_width) - 1
    width_ones = (1 << width) - 1

    t_state = enum("S_IDLE", "S_MAC", "S_ROOT", "S_ROUND", "S_CHECK", "S_WAIT")
    state = Signal(t_state.S_IDLE)

    # latched command (with the magnitudes of its coordinates)
    is_line = Signal(bool(0))
    variant = _unsigned(2)
    lambda_shift = _unsigned(5)
    acc_bits = _unsigned(5)
    ccw = Signal(bool(0))
    blend = Signal(bool(0))
    # the coordinates as sign and magnitude (a zero magnitude is the zero test)
    neg_xs, neg_ys, neg_xe, neg_ye = (Signal(bool(0)) for _ in range(4))
    mag_xs, mag_ys, mag_xe, mag_ye = (_unsigned(width) for _ in range(4))
    cmd_mag_xs, cmd_mag_ys, cmd_mag_xe, cmd_mag_ye = (_unsigned(width) for _ in range(4))

    # setup: one adder-subtractor forms gap = xe**2 + ye**2 - xs**2 - ys**2 - 1 (shift-add),
    # then checks it against the end-point limits; a restoring square root takes xs**2 + ys**2
    mac_op = Signal(modbv(0)[2:])
    mac_bit = Signal(intbv(0, min=0, max=width))
    multiplicand = Signal(modbv(0)[2 * width:])
    multiplier = _unsigned(width)
    # the gap in two halves with the carry between them registered (two short carry chains):
    # its value is (gap_high + gap_carry) * 2**gap_split + gap_low
    gap_low, gap_sum_low = Signal(modbv(0)[gap_split:]), Signal(modbv(0)[gap_split:])
    gap_high, gap_sum_high = Signal(modbv(0)[gap_width - gap_split:]), Signal(modbv(0)[gap_width - gap_split:])
    gap_carry, gap_sum_carry = Signal(bool(0)), Signal(bool(0))
    gap_top = Signal(modbv(0)[gap_width - gap_split:])
    radicand = Signal(modbv(0)[2 * width:])
    remainder = _unsigned(width + 3)
    root = _unsigned(width)
    root_up = _unsigned(width + 1)   # root + 1, kept beside root: no adder after the last trial
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
    geo_x_in_start, geo_x_in_end = Signal(bool(0)), Signal(bool(0))

    # each axis' steps over the whole arc, s1 |start| + s2 |end| + k Rq (k = 0, 2 or 4 per
    # axis, from the quadrants): the signed magnitudes during the squares, k Rq with the check
    tot_x, tot_y = _wrapping(tot_width), _wrapping(tot_width)
    tot_sum_x, tot_sum_y = _wrapping(tot_width), _wrapping(tot_width)
    tot_k2_x, tot_k2_y = Signal(bool(0)), Signal(bool(0))
    tot_k4_x, tot_k4_y = Signal(bool(0)), Signal(bool(0))

    # the check (combinational) and its registered results
    check_error, check_zero = Signal(bool(0)), Signal(bool(0))
    check_threshold = _unsigned(thr_width)
    check_acc_init = _signed(acc_width)
    check_quadrant = _unsigned(2)
    check_crossings = _unsigned(3)
    check_target_x, check_target_y = _unsigned(width), _unsigned(width)
    check_left_x, check_left_y = _wrapping(left_width), _wrapping(left_width)
    check_neg_in = _wrapping(err_width - 1)
    chk_error, chk_zero = Signal(bool(0)), Signal(bool(0))
    chk_threshold = _unsigned(thr_width)
    chk_acc_init = _signed(acc_width)
    chk_quadrant = _unsigned(2)
    chk_crossings = _unsigned(3)
    chk_target_x, chk_target_y = _unsigned(width), _unsigned(width)
    chk_left_x, chk_left_y = _wrapping(left_width), _wrapping(left_width)
    chk_neg_in = _wrapping(err_width - 1)
    # what the first iteration needs beside the magnitudes, from the registered check
    first_integrand_x, first_integrand_y = _unsigned(width), _unsigned(width)
    first_stepped_x, first_stepped_y = Signal(modbv(0)[width:]), Signal(modbv(0)[width:])
    first_out = _unsigned(width)
    first_half = _wrapping(err_width + 1)
    first_q_in, first_q_out = _wrapping(err_width + 2), _wrapping(err_width + 2)

    # handover from the setup stage to the run stage
    hand_load, hand_end = Signal(bool(0)), Signal(bool(0))

    # run state, with its own copy of the command
    run_active = Signal(bool(0))
    run_line, run_ccw, run_blend = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    run_variant = _unsigned(2)
    run_end_x, run_end_y = _unsigned(width), _unsigned(width)
    run_right, run_up = Signal(bool(0)), Signal(bool(0))
    quadrant = Signal(modbv(0)[2:])
    x_inward = Signal(bool(0))  # quadrant[0] xor ccw, kept as a register: it selects early
    acc_x, acc_y = _signed(acc_width), _signed(acc_width)
    radial_error = _wrapping(err_width)
    # what each accumulator adds: |y| for X and |x| for Y on an arc (|dx|, |dy| on a line),
    # and the same after the other axis' next step (|y| - 1 inward, |y| + 1 outward)
    integrand_x, integrand_y = Signal(modbv(0)[width:]), Signal(modbv(0)[width:])
    stepped_x, stepped_y = Signal(modbv(0)[width:]), Signal(modbv(0)[width:])
    # each axis stops in the current piece when its magnitude reaches its target:
    # 0 inward and Rq outward, |xe|, |ye| in the last piece
    target_x, target_y = _unsigned(width), _unsigned(width)
    crossings = _unsigned(3)
    threshold = _unsigned(thr_width)
    radius = _unsigned(width)
    # steps left per axis over the rest of the move, minus one (a line ends on them)
    left_x, left_y = _wrapping(left_width), _wrapping(left_width)
    # the precise mode's terms, by inward magnitude a and outward magnitude b: -a, b,
    # h = b - a, q_in = 2 d_in + d_out = 3 + 2b - 4a, q_out = 2 d_out + d_in = 3 + 4b - 2a
    # (d_in = 1 - 2a, d_out = 1 + 2b: the change of E on an inward, outward step)
    neg_in = _wrapping(err_width - 1)
    pos_out = Signal(modbv(0)[width:])
    half_sum = _wrapping(err_width + 1)
    q_in, q_out = _wrapping(err_width + 2), _wrapping(err_width + 2)

    # second clock of an iteration: the registered decision of the first
    pending = Signal(bool(0))
    dec_step_x, dec_step_y = Signal(bool(0)), Signal(bool(0))
    dec_tail = Signal(bool(0))
    dec_finished, dec_next_piece = Signal(bool(0)), Signal(bool(0))
    dec_in, dec_out = Signal(bool(0)), Signal(bool(0))
    dec_sum_x, dec_sum_y = _signed(acc_width), _signed(acc_width)

    # first clock of an iteration, combinational from registers
    it_step_x, it_step_y = Signal(bool(0)), Signal(bool(0))
    it_dir_x, it_dir_y = Signal(bool(0)), Signal(bool(0))
    it_sum_x, it_sum_y = _signed(acc_width), _signed(acc_width)
    it_finished = Signal(bool(0))
    it_next_piece = Signal(bool(0))
    it_tail = Signal(bool(0))
    at_x, at_y = Signal(bool(0)), Signal(bool(0))
    near_x, near_y = Signal(bool(0)), Signal(bool(0))

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
        cmd_mag_xs.next = less_xs ^ sign_xs
        cmd_mag_ys.next = less_ys ^ sign_ys
        cmd_mag_xe.next = less_xe ^ sign_xe
        cmd_mag_ye.next = less_ye ^ sign_ye

    @always_comb
    def setup_adder():
        # gap - multiplicand while squaring xs, ys; gap + multiplicand while squaring xe, ye
        # and at the first limit; gap - multiplicand - 1 at the second (see control).  The
        # carry is the adder's carry input.  The high half adds the low half's carry of the
        # clock before (gap_top: with no operand, the resolved high half).
        subtract = bool(0)
        carry = bool(0)
        operand = modbv(0)[gap_width:]
        total_low = modbv(0)[gap_split + 1:]
        total_high = modbv(0)[gap_width - gap_split:]
        if state == t_state.S_MAC:
            subtract = mac_op < 2
            carry = mac_op < 2
        else:
            subtract = root_bit == 2
        operand[:] = concat(intbv(0)[gap_width - 2 * width:], multiplicand)
        if subtract:
            operand[:] = ~operand
        total_low[:] = concat(False, gap_low) + concat(False, operand[gap_split:]) + \
            concat(intbv(0)[gap_split:], carry)
        total_high[:] = gap_high + operand[gap_width:gap_split] + \
            concat(intbv(0)[gap_width - gap_split - 1:], gap_carry)
        gap_sum_low.next = total_low[gap_split:]
        gap_sum_carry.next = total_low[gap_split]
        gap_sum_high.next = total_high
        gap_top.next = gap_high + concat(intbv(0)[gap_width - gap_split - 1:], gap_carry)

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
        zero_xs = bool(0)
        zero_ys = bool(0)
        zero_xe = bool(0)
        zero_ye = bool(0)

        zero_xs = mag_xs == 0
        zero_ys = mag_ys == 0
        zero_xe = mag_xe == 0
        zero_ye = mag_ye == 0
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
            if not neg_xe and not neg_ye and not zero_ye:
                q_e[:] = 0
            elif neg_xe and not neg_ye:
                q_e[:] = 1
            elif (neg_xe or zero_xe) and neg_ye:
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
            if not neg_xe and not zero_xe and not neg_ye:
                q_e[:] = 0
            elif (neg_xe or zero_xe) and not neg_ye and not zero_ye:
                q_e[:] = 1
            elif neg_xe and (neg_ye or zero_ye):
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
        geo_centre.next = (zero_xs and zero_ys) or (zero_xe and zero_ye)
        geo_x_in_start.next = q_s[0] != ccw
        geo_x_in_end.next = q_e[0] != ccw

    @always_comb
    def totals_k():
        # first piece (|xs| inward, Rq - |xs| outward) + (crossings - 1) Rq + last piece
        # (Rq - |xe| inward, |xe| outward): k = crossings - 1 + (x outward at the start)
        # + (x inward at the end), for y with the axes swapped; 0 within one quadrant
        out_in = not geo_x_in_start and geo_x_in_end
        in_out = geo_x_in_start and not geo_x_in_end
        tot_k4_x.next = geo_crossings == 4 or (geo_crossings == 3 and out_in)
        tot_k4_y.next = geo_crossings == 4 or (geo_crossings == 3 and in_out)
        tot_k2_x.next = geo_crossings == 2 or (geo_crossings == 1 and out_in) or (geo_crossings == 3 and in_out)
        tot_k2_y.next = geo_crossings == 2 or (geo_crossings == 1 and in_out) or (geo_crossings == 3 and out_in)

    @always_comb
    def totals_adder():
        # s1 is + for the inward axis at the start, s2 - for the inward axis at the end
        operand_x = modbv(0)[tot_width:]
        operand_y = modbv(0)[tot_width:]
        invert_x = bool(0)
        invert_y = bool(0)
        carry_x = bool(0)
        carry_y = bool(0)
        total_x = modbv(0)[tot_width:]
        total_y = modbv(0)[tot_width:]
        if state == t_state.S_MAC and mac_op == 0 and mac_bit == 1:
            operand_x[:] = concat(intbv(0)[tot_width - width:], mag_xs)
            operand_y[:] = concat(intbv(0)[tot_width - width:], mag_ys)
            invert_x = not geo_x_in_start
            invert_y = geo_x_in_start == 1
        elif state == t_state.S_MAC and mac_op == 0 and mac_bit == 2:
            operand_x[:] = concat(intbv(0)[tot_width - width:], mag_xe)
            operand_y[:] = concat(intbv(0)[tot_width - width:], mag_ye)
            invert_x = geo_x_in_end == 1
            invert_y = not geo_x_in_end
        if invert_x:
            operand_x[:] = ~operand_x
            carry_x = True
        if invert_y:
            operand_y[:] = ~operand_y
            carry_y = True
        total_x[:] = tot_x[tot_width:] + operand_x + concat(intbv(0)[tot_width - 1:], carry_x)
        total_y[:] = tot_y[tot_width:] + operand_y + concat(intbv(0)[tot_width - 1:], carry_y)
        tot_sum_x.next = total_x.signed()
        tot_sum_y.next = total_y.signed()

    @always_comb
    def totals_check():
        # the last term: k Rq for an arc, |dx|, |dy| for a line
        operand_x = modbv(0)[left_width:]
        operand_y = modbv(0)[left_width:]
        total_x = modbv(0)[left_width:]
        total_y = modbv(0)[left_width:]
        if is_line:
            operand_x[:] = concat(intbv(0)[left_width - width:], mag_xe)
            operand_y[:] = concat(intbv(0)[left_width - width:], mag_ye)
        else:
            if tot_k2_x:
                operand_x[:] = concat(intbv(0)[left_width - width - 2:], radius_q, False)
            elif tot_k4_x:
                operand_x[:] = concat(radius_q, intbv(0)[2:])
            if tot_k2_y:
                operand_y[:] = concat(intbv(0)[left_width - width - 2:], radius_q, False)
            elif tot_k4_y:
                operand_y[:] = concat(radius_q, intbv(0)[2:])
        total_x[:] = tot_x[left_width:] + operand_x
        total_y[:] = tot_y[left_width:] + operand_y
        check_left_x.next = total_x[left_width:].signed()
        check_left_y.next = total_y[left_width:].signed()
    @always_comb
    def check_logic():
        rq = intbv(0)[width + 1:]
        exponent = modbv(0)[6:]
        thr = modbv(0)[thr_width:]
        thr_less = modbv(0)[thr_width:]
        mask = modbv(0)[thr_width:]
        below = modbv(0)[acc_width:]
        half = modbv(0)[acc_width:]
        major = intbv(0)[width:]
        major_less = modbv(0)[width:]
        inward = intbv(0)[width:]
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
        # 2**e - 1 is the e low bits set (one shifter, no subtractor); 2**e is its
        # lowest clear bit (0 when e is beyond the width, as the shift would give)
        mask[:] = (1 << thr_width) - 1
        mask[:] = mask << exponent
        thr_less[:] = ~mask
        thr[:] = concat(thr_less[thr_width - 1:], True) & mask
        if variant != PRECISE and exponent > thr_width - 1:
            bad = True
        if variant == PRECISE:
            thr[:] = concat(intbv(0)[thr_width - width - 1:], rq) + 1
            thr_less[:] = concat(intbv(0)[thr_width - width - 1:], rq)
        # a line: T = max(|dx|, |dy|)
        # (both decrements formed beside the compare)
        if mag_xe > mag_ye:
            major[:] = mag_xe
            major_less[:] = mag_xe + width_ones
        else:
            major[:] = mag_ye
            major_less[:] = mag_ye + width_ones
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
        # beyond Rq on its inward axis (a line's targets are unused: it counts its steps left)
        if is_line or geo_ahead:
            check_target_x.next = mag_xe
            check_target_y.next = mag_ye
        else:
            if concat(False, geo_end_inward) > rq:
                bad = True
            if geo_quadrant[0] != ccw:
                check_target_x.next = 0
                check_target_y.next = rq[width:]
            else:
                check_target_x.next = rq[width:]
                check_target_y.next = 0

        check_error.next = bad and not is_line
        check_zero.next = is_line and mag_xe == 0 and mag_ye == 0
        # a line starts in quadrant 0
        check_quadrant.next = geo_quadrant
        check_crossings.next = geo_crossings
        if is_line:
            check_quadrant.next = 0
            check_crossings.next = 0
        check_threshold.next = thr
        check_acc_init.next = half.signed()
        # -|inward start coordinate|
        inward[:] = mag_ys
        if geo_x_in_start:
            inward[:] = mag_xs
        check_neg_in.next = -concat(intbv(0)[err_width - 1 - width:], inward).signed()
    @always_comb
    def first_iteration():
        # the run's stepped values for the first iteration, from registers (the checked
        # move waits at least one clock): integrands, magnitudes one step further and the
        # precise mode's terms (b the outward magnitude at the start, -a from the check)
        fill = intbv(0)[2:]
        half = modbv(0)[err_width + 1:]
        twice_in = modbv(0)[err_width + 2:]
        twice_out = modbv(0)[err_width + 2:]
        out = intbv(0)[width:]
        first_integrand_x.next = mag_ys
        first_integrand_y.next = mag_xs
        if is_line:
            first_integrand_x.next = mag_xe
            first_integrand_y.next = mag_ye
        # +1 or -1 as the operand of one adder per axis (constant bits, no select)
        step_in = modbv(1)[width:]
        step_out = modbv(1)[width:]
        if geo_x_in_start:
            step_out[:] = width_ones
            out[:] = mag_ys
        else:
            step_in[:] = width_ones
            out[:] = mag_xs
        first_stepped_x.next = mag_ys + step_in
        first_stepped_y.next = mag_xs + step_out
        first_out.next = out
        if chk_neg_in[err_width - 2]:
            fill[:] = 3
        half[:] = concat(intbv(0)[err_width + 1 - width:], out) + concat(fill, chk_neg_in[err_width - 1:])
        twice_in[:] = concat(fill[0], chk_neg_in[err_width - 1:], intbv(3)[2:]) + concat(intbv(0)[err_width + 1 - width:], out, False)
        twice_out[:] = concat(intbv(0)[err_width - width:], out, intbv(3)[2:]) + concat(fill, chk_neg_in[err_width - 1:], False)
        first_half.next = half.signed()
        first_q_in.next = twice_in.signed()
        first_q_out.next = twice_out.signed()

    @always_comb
    def end_tests():
        # an arc's axis is at its target, or one step before it; a line's steps left
        # (minus one) are -1 or 0
        if run_line:
            at_x.next = left_x[left_width:] == intbv(left_all_ones)[left_width:]
            at_y.next = left_y[left_width:] == intbv(left_all_ones)[left_width:]
            near_x.next = left_x == 0
            near_y.next = left_y == 0
        else:
            at_x.next = integrand_y == target_x
            at_y.next = integrand_x == target_y
            near_x.next = stepped_y == target_x
            near_y.next = stepped_x == target_y

    @always_comb
    def iteration_logic():
        # the first clock of an iteration: every sum is one adder on registers
        x_right = bool(0)
        y_up = bool(0)
        sum_x = intbv(0, min=-(1 << acc_width), max=1 << acc_width)
        sum_x_step = intbv(0, min=-(1 << acc_width), max=1 << acc_width)
        sum_y = intbv(0, min=-(1 << acc_width), max=1 << acc_width)
        ahead_x = intbv(0, min=-(1 << acc_width), max=1 << acc_width)
        ahead_y = intbv(0, min=-(1 << acc_width), max=1 << acc_width)
        twice_in = intbv(0, min=-(1 << (err_width + 1)), max=1 << (err_width + 1))
        twice_out = intbv(0, min=-(1 << (err_width + 1)), max=1 << (err_width + 1))
        error_half = modbv(0)[err_width + 1:]
        d_le_in = bool(0)
        d_le_out = bool(0)
        x_le_y = bool(0)
        over_x = bool(0)
        over_x_step = bool(0)
        over_y = bool(0)
        go_x = bool(0)
        go_y = bool(0)

        x_right = quadrant[0] == quadrant[1]
        y_up = not quadrant[1]
        if run_line:
            it_dir_x.next = run_right
            it_dir_y.next = run_up
        else:
            it_dir_x.next = x_right != x_inward
            it_dir_y.next = y_up == x_inward

        # accumulators; the compares use the unsaturated sums (T is far below the
        # saturation value, so the result is the same)
        sum_y[:] = concat(acc_y[acc_width - 1], acc_y).signed() + \
            concat(intbv(0)[acc_width + 1 - width:], integrand_y).signed()
        sum_x[:] = concat(acc_x[acc_width - 1], acc_x).signed() + \
            concat(intbv(0)[acc_width + 1 - width:], integrand_x).signed()
        sum_x_step[:] = concat(acc_x[acc_width - 1], acc_x).signed() + \
            concat(intbv(0)[acc_width + 1 - width:], stepped_x).signed()
        # the registers hold A - bias: an overflow is a sum that is not negative
        over_x = not sum_x[acc_width]
        over_x_step = not sum_x_step[acc_width]
        over_y = not sum_y[acc_width]
        # traditional: Y first, X integrates the new |y| (sums and compares formed in parallel)
        if not run_line and run_variant == TRADITIONAL and over_y:
            sum_x[:] = sum_x_step
            over_x = over_x_step

        # precise: |u| <= |v| exactly when (u - v) and (u + v) differ in sign or one is 0.
        # Diagonal against inward only: u - v = d_out > 0, u + v = 2E + q_in (odd);
        # against outward only: u - v = d_in (< 0 unless a = 0), u + v = 2E + q_out (odd);
        # inward against outward: u - v = -2 (a + b), u + v = 2 (E + h + 1), so inward is
        # closer or as close when E + h + 1 >= 0, outward when E + h + 1 <= 0, i.e. E + h < 0
        twice_in[:] = concat(radial_error[err_width - 1], radial_error, False).signed() + q_in
        twice_out[:] = concat(radial_error[err_width - 1], radial_error, False).signed() + q_out
        # E + h + 1 >= 0 (x inward) and E + h < 0 (x outward) by one adder, the carry
        # input being x_inward
        error_half[:] = concat(radial_error[err_width - 1], radial_error) + half_sum[err_width + 1:] + \
            concat(intbv(0)[err_width:], x_inward)
        d_le_in = twice_in < 0
        d_le_out = (neg_in < 0) != (twice_out < 0)
        x_le_y = (error_half.signed() < 0) != x_inward

        go_x = over_x
        go_y = over_y
        if run_line:
            go_x = over_x and not at_x
            go_y = over_y and not at_y
        elif run_variant == IMPROVED:
            # A + 2i straight from the registers (one adder)
            ahead_x[:] = concat(acc_x[acc_width - 1], acc_x).signed() + \
                concat(intbv(0)[acc_width - width:], integrand_x, False).signed()
            ahead_y[:] = concat(acc_y[acc_width - 1], acc_y).signed() + \
                concat(intbv(0)[acc_width - width:], integrand_y, False).signed()
            if over_x and not over_y and ahead_y >= 0:
                go_y = True
            elif over_y and not over_x and ahead_x >= 0:
                go_x = True
        elif run_variant == PRECISE:
            go_x = False
            go_y = False
            if over_x or over_y:
                if d_le_in and d_le_out:
                    go_x = True
                    go_y = True
                elif x_le_y:
                    go_x = True
                else:
                    go_y = True

        # an axis at its target stops; the other one steps alone, the accumulators hold
        it_tail.next = not run_line and (at_x or at_y)
        if not run_line and (at_x or at_y):
            go_x = not at_x
            go_y = not at_y
        if not sum_x[acc_width] and sum_x[acc_width - 1]:
            sum_x[:] = intbv(acc_max)[acc_width + 1:]
        if not sum_y[acc_width] and sum_y[acc_width - 1]:
            sum_y[:] = intbv(acc_max)[acc_width + 1:]
        it_sum_x.next = sum_x[acc_width:].signed()
        it_sum_y.next = sum_y[acc_width:].signed()
        it_step_x.next = go_x
        it_step_y.next = go_y

        it_finished.next = False
        it_next_piece.next = False
        if (near_x and go_x or at_x) and (near_y and go_y or at_y):
            if run_line or crossings == 0:
                it_finished.next = True
            else:
                it_next_piece.next = True

    @always_comb
    def handover_logic():
        # the run takes a checked move when it is idle or in the second clock of its last
        # iteration; a rejected move and a line of length 0 end only once no move runs
        free = not run_active or (pending and dec_finished)
        hand_load.next = False
        hand_end.next = False
        if state == t_state.S_WAIT:
            if chk_zero or chk_error:
                hand_end.next = free
            else:
                hand_load.next = free

    @always_seq(clock.posedge, reset=reset)
    def setup_control():
        if state == t_state.S_IDLE:
            if cmd.start:
                cmd.error.next = False
                is_line.next = cmd.line
                variant.next = cmd.variant
                lambda_shift.next = cmd.lambda_shift
                acc_bits.next = cmd.acc_bits
                ccw.next = cmd.ccw
                blend.next = cmd.blend
                # the totals start at -1: the run counts steps left - 1 (see left_output)
                tot_x.next = -1
                tot_y.next = -1
                neg_xs.next = cmd.xs < 0
                neg_ys.next = cmd.ys < 0
                neg_xe.next = cmd.xe < 0
                neg_ye.next = cmd.ye < 0
                mag_xs.next = cmd_mag_xs
                mag_ys.next = cmd_mag_ys
                mag_xe.next = cmd_mag_xe
                mag_ye.next = cmd_mag_ye
                gap_low.next = (1 << gap_split) - 1
                gap_high.next = (1 << (gap_width - gap_split)) - 1
                gap_carry.next = False
                mac_op.next = 0
                mac_bit.next = 0
                multiplicand.next = concat(intbv(0)[width:], cmd_mag_xs)
                multiplier.next = cmd_mag_xs
                if cmd.line:
                    state.next = t_state.S_CHECK
                else:
                    state.next = t_state.S_MAC
        elif state == t_state.S_MAC:
            tot_x.next = tot_sum_x
            tot_y.next = tot_sum_y
            gap_high.next = gap_top
            gap_carry.next = False
            if multiplier[0]:
                gap_low.next = gap_sum_low
                gap_high.next = gap_sum_high
                gap_carry.next = gap_sum_carry
            if mac_op == 2 and mac_bit == 0:
                # gap = -1 - xs**2 - ys**2 now: its complement is the radicand
                radicand.next = ~concat(gap_top[2 * width - gap_split:], gap_low)
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
                    root_up.next = 1
                    root_bit.next = 0
                    root_length.next = 0
                    root_all_ones.next = True
                    state.next = t_state.S_ROOT
            else:
                mac_bit.next = mac_bit + 1
                multiplicand.next = multiplicand << 1
                multiplier.next = multiplier >> 1
        elif state == t_state.S_ROOT:
            # root + 1 doubles with a 1 bit and is 2 root + 1 after a 0 bit
            if root_trial_fits:
                remainder.next = root_trial_diff
                root.next = concat(root[width - 1:], True)
                root_up.next = concat(root_up[width:], False)
            else:
                remainder.next = root_trial_rem
                root.next = concat(root[width - 1:], False)
                root_up.next = concat(False, root[width - 1:], True)
                if root != 0:
                    root_all_ones.next = False
            if root != 0 or root_trial_fits:
                root_length.next = root_length + 1
            radicand.next = radicand << 2
            # end point within one step: -(2m - 1) <= re**2 - rs**2 <= 2m + 1 with
            # m = max(|xs|, |ys|) (|re - rs| <= 1 follows as m <= rs); the gap is
            # re**2 - rs**2 - 1: add 2m, test the sign, take 4m + 1, test the sign
            gap_high.next = gap_top
            gap_carry.next = False
            if root_bit == 0:
                multiplicand.next = multiplicand << 1
            elif root_bit == 1:
                gap_low.next = gap_sum_low
                gap_high.next = gap_sum_high
                gap_carry.next = gap_sum_carry
                multiplicand.next = multiplicand << 1
            elif root_bit == 2:
                end_reaches_low.next = not gap_top[gap_width - gap_split - 1]
                gap_low.next = gap_sum_low
                gap_high.next = gap_sum_high
                gap_carry.next = gap_sum_carry
            elif root_bit == 3:
                end_beyond_high.next = not gap_top[gap_width - gap_split - 1]
            if root_bit == width - 1:
                state.next = t_state.S_ROUND
            else:
                root_bit.next = root_bit + 1
        elif state == t_state.S_ROUND:
            # Rq: the integer whose square is nearest to xs**2 + ys**2
            # Rq = root + 1 when remainder > root: the next root bit (radicand bits 00 now)
            if root_trial_fits:
                radius_q.next = root_up
            else:
                radius_q.next = concat(False, root)
            if root_trial_fits and root_all_ones:
                radius_length.next = root_length + 1
            else:
                radius_length.next = root_length
            state.next = t_state.S_CHECK
        elif state == t_state.S_CHECK:
            # the check's results are registered: the handover depends on registers only
            chk_error.next = check_error
            chk_zero.next = check_zero
            chk_threshold.next = check_threshold
            chk_acc_init.next = check_acc_init
            chk_quadrant.next = check_quadrant
            chk_crossings.next = check_crossings
            chk_target_x.next = check_target_x
            chk_target_y.next = check_target_y
            chk_left_x.next = check_left_x
            chk_left_y.next = check_left_y
            chk_neg_in.next = check_neg_in
            state.next = t_state.S_WAIT
        else:
            # S_WAIT: the checked move waits for the run stage
            if hand_load or hand_end:
                state.next = t_state.S_IDLE
            if hand_end and not chk_zero:
                cmd.error.next = True
    @always_seq(clock.posedge, reset=reset)
    def run_control():
        step_op_x = modbv(0)[width:]
        step_op_y = modbv(0)[width:]
        base_x = modbv(0)[width:]
        base_y = modbv(0)[width:]
        base_op_x = modbv(0)[width:]
        base_op_y = modbv(0)[width:]
        less_x = modbv(0)[acc_width:]
        less_y = modbv(0)[acc_width:]
        inverse = modbv(0)[err_width + 1:]
        neg_base = modbv(0)[err_width - 1:]
        half_base = modbv(0)[err_width + 1:]
        q_in_base = modbv(0)[err_width + 2:]
        q_out_base = modbv(0)[err_width + 2:]
        in_out = intbv(0)[2:]
        q_in_op = intbv(0)[3:]
        q_out_op = intbv(0)[3:]
        error_op = modbv(0)[err_width:]
        error_sum = modbv(0)[err_width:]

        steps.step_x.next = False
        steps.step_y.next = False
        cmd.done.next = False
        # the decision of this clock, kept for the next one (used there only after an advance)
        pending.next = False
        dec_step_x.next = it_step_x
        dec_step_y.next = it_step_y
        dec_tail.next = it_tail
        dec_finished.next = it_finished
        dec_next_piece.next = it_next_piece
        dec_in.next = (it_step_x and x_inward or it_step_y and not x_inward) and not run_line
        dec_out.next = (it_step_x and not x_inward or it_step_y and x_inward) and not run_line
        dec_sum_x.next = it_sum_x
        dec_sum_y.next = it_sum_y

        if run_active and cmd.advance and not pending:
            # first clock of an iteration: the outputs go with the decision
            pending.next = True
            steps.step_x.next = it_step_x
            steps.step_y.next = it_step_y
            steps.dir_x.next = it_dir_x
            steps.dir_y.next = it_dir_y
            cmd.done.next = it_finished
        elif pending:
            # second clock: apply the registered decision
            if not dec_tail:
                less_x[:] = dec_sum_x[acc_width:]
                if dec_step_x:
                    less_x[:] = dec_sum_x[acc_width:] - concat(intbv(0)[acc_width - thr_width:], threshold)
                less_y[:] = dec_sum_y[acc_width:]
                if dec_step_y:
                    less_y[:] = dec_sum_y[acc_width:] - concat(intbv(0)[acc_width - thr_width:], threshold)
                acc_x.next = less_x.signed()
                acc_y.next = less_y.signed()
            # E plus its change by the registered step: d_in = 1 - 2a, d_out = 1 + 2b or
            # both, 2 + 2h (one adder behind a select of registers, still unchanged here)
            error_op[:] = concat(intbv(0)[err_width - width - 1:], pos_out, True)
            if dec_in and dec_out:
                error_op[:] = concat(half_sum[err_width - 1:], True)
            elif dec_in:
                error_op[:] = concat(neg_in[err_width - 1:], True)
            error_sum[:] = radial_error[err_width:] + error_op + \
                concat(intbv(0)[err_width - 1:], dec_in and dec_out)
            if dec_in or dec_out:
                radial_error.next = error_sum.signed()
            left_x.next = left_x - concat(intbv(0)[left_width - 1:], dec_step_x).signed()
            left_y.next = left_y - concat(intbv(0)[left_width - 1:], dec_step_y).signed()
            # |x| (Y's integrand) and |y| (X's) step by +-1; on a piece change their stepped
            # copies restart from Rq - 1 (the axis turns inward at Rq) or 1 (outward at 0)
            # (the step's axis and sense decoded here, off the first clock's path: x_inward
            # and run_line hold through the iteration)
            if dec_step_x and not run_line:
                step_op_y[:] = 1
                if x_inward:
                    step_op_y[:] = width_ones
            if dec_step_y and not run_line:
                step_op_x[:] = width_ones
                if x_inward:
                    step_op_x[:] = 1
            integrand_y.next = integrand_y + step_op_y
            integrand_x.next = integrand_x + step_op_x
            base_y[:] = stepped_y
            base_op_y[:] = step_op_y
            base_x[:] = stepped_x
            base_op_x[:] = step_op_x
            if dec_next_piece:
                base_op_y[:] = 1
                base_y[:] = 0
                base_op_x[:] = 1
                base_x[:] = 0
                if x_inward:
                    base_op_x[:] = width_ones
                    base_x[:] = radius
                else:
                    base_op_y[:] = width_ones
                    base_y[:] = radius
            stepped_y.next = base_y + base_op_y
            stepped_x.next = base_x + base_op_x
            # the precise terms: a falls by an inward step, b grows by an outward one; a new
            # piece starts at a = Rq, b = 0 (-Rq = ~Rq + 1, 3 - 4Rq = {~Rq, 11} + 4, ...)
            in_out[:] = concat(dec_in, dec_out)
            neg_base[:] = neg_in
            half_base[:] = half_sum
            q_in_base[:] = q_in
            q_out_base[:] = q_out
            q_in_op[:] = concat(dec_in, dec_out, False)
            q_out_op[:] = concat(dec_out, dec_in, False)
            pos_out.next = pos_out + concat(intbv(0)[width - 1:], dec_out)
            if dec_next_piece:
                inverse[:] = ~concat(intbv(0)[err_width + 1 - width:], radius)
                neg_base[:] = inverse[err_width - 1:]
                half_base[:] = inverse[err_width + 1:]
                q_in_base[:] = concat(inverse[err_width:], intbv(3)[2:])
                q_out_base[:] = concat(inverse[err_width + 1:], True)
                in_out[:] = 1
                q_in_op[:] = 4
                q_out_op[:] = 4
                pos_out.next = 0
            neg_base[:] = neg_base + concat(intbv(0)[err_width - 2:], dec_in or dec_next_piece)
            half_base[:] = half_base + concat(intbv(0)[err_width:], in_out[1]) + concat(intbv(0)[err_width:], in_out[0])
            q_in_base[:] = q_in_base + concat(intbv(0)[err_width - 1:], q_in_op)
            q_out_base[:] = q_out_base + concat(intbv(0)[err_width - 1:], q_out_op)
            neg_in.next = neg_base.signed()
            half_sum.next = half_base.signed()
            q_in.next = q_in_base.signed()
            q_out.next = q_out_base.signed()
            if dec_finished:
                run_active.next = False
            if dec_next_piece:
                x_inward.next = not x_inward
                if x_inward:
                    target_x.next = radius
                    target_y.next = 0
                else:
                    target_x.next = 0
                    target_y.next = radius
                if crossings == 1:
                    target_x.next = run_end_x
                    target_y.next = run_end_y
                if run_ccw:
                    quadrant.next = quadrant + 1
                else:
                    quadrant.next = quadrant - 1
                crossings.next = crossings - 1
        if hand_end and chk_zero:
            cmd.done.next = True
            quadrant.next = 0
        if hand_load:
            # the run's own copy of what the setup stage overwrites with the next move
            run_active.next = True
            run_line.next = is_line
            run_variant.next = variant
            run_ccw.next = ccw
            run_blend.next = blend
            run_end_x.next = mag_xe
            run_end_y.next = mag_ye
            run_right.next = not neg_xe
            run_up.next = not neg_ye
            acc_x.next = chk_acc_init
            acc_y.next = chk_acc_init
            threshold.next = chk_threshold
            radial_error.next = 0
            quadrant.next = chk_quadrant
            x_inward.next = chk_quadrant[0] != ccw
            crossings.next = chk_crossings
            target_x.next = chk_target_x
            target_y.next = chk_target_y
            radius.next = radius_q[width:]
            left_x.next = chk_left_x
            left_y.next = chk_left_y
            integrand_x.next = first_integrand_x
            integrand_y.next = first_integrand_y
            stepped_x.next = first_stepped_x
            stepped_y.next = first_stepped_y
            neg_in.next = chk_neg_in
            pos_out.next = first_out
            half_sum.next = first_half
            q_in.next = first_q_in
            q_out.next = first_q_out

    @always_seq(clock.posedge, reset=reset)
    def left_output():
        # a lower bound of the iterations left: the larger count of steps left (minus one)
        # as the second clock of the iterations leaves it; the register lags the counts by
        # a clock, so at the next advance one more iteration may have been taken (the
        # minus one covers it)
        larger = intbv(0, min=-(1 << (left_width - 1)), max=1 << (left_width - 1))
        if left_x >= left_y:
            larger[:] = left_x
        else:
            larger[:] = left_y
        if run_active and not run_blend:
            if larger < 0:
                cmd.stop_left.next = 0
            else:
                cmd.stop_left.next = larger[left_width:]
        else:
            cmd.stop_left.next = intbv(left_all_ones)[left_width:]

    @always_comb
    def status():
        cmd.quadrant.next = quadrant
        cmd.ready.next = state == t_state.S_IDLE
        cmd.busy.next = state != t_state.S_IDLE or (run_active and not (pending and dec_finished))

    return (magnitudes, setup_adder, root_trial, geometry, totals_k, totals_adder, totals_check,
            check_logic, first_iteration, end_tests, iteration_logic, handover_logic, setup_control,
            run_control, left_output, status)


def dda_arc_ports(coord_width=COORD_WIDTH.default):
    """Fresh ports of ``dda_arc`` for conversion or a bench."""
    return dict(clock=Signal(bool(0)), reset=card_reset(),
                cmd=DdaPort(coord_width), steps=AxisPulses())
