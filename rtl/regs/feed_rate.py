"""Iteration clock enable of the interpolator: a trapezoidal rate ramp."""
from myhdl import Signal, always_comb, always_seq, block, concat, intbv, modbv

from models.card_model import DECEL_MARGIN
from models.parameters import COORD_WIDTH
from models.registers import RATE_MAX, RATE_ONE
from rtl.interfaces import FeedPort, RampSettings, card_reset

RATE_BITS = RATE_MAX.bit_length()  # 16: the rate is at most one iteration every other clock
PHASE_BITS = RATE_ONE.bit_length() - 1
COUNT_BITS = 16  # ramp ticks: at most one per unit of rate


@block
def feed_rate(clock, reset, settings, feed):
    """Phase accumulator giving ``tick`` on ``rate``/65536 of the clocks, with
    a linear ramp up to ``target`` and down again before the path stops.

    Ports (``rtl/interfaces/``): ``settings`` (``RampSettings``:
    ``target``, the rate to reach, 1..32768; ``ramp_start``, the rate a move
    starts and stops with, 1..32768; ``ramp_step``, the rate change per
    tick, 0: the rate is ``target`` at once); ``feed`` (``FeedPort``:
    ``run``, a move is under way, low resets the accumulator and the ramp
    count and loads the starting rate; ``hold``, freeze: the pulse outputs
    are full; ``stop_left``, the DDA's lower bound of the iterations before
    the path stops; ``tick``, registered, one clock per iteration, never two
    clocks in a row).

    Rules, applied at every tick to the rate of the next iteration:

    1. ``ramp_step`` = 0: the rate becomes ``target``; the ramp count is 0.
    2. deceleration (``stop_left`` <= ramp count + DECEL_MARGIN, compared one
       clock earlier): with a ramp count of 1, or when one more step would go
       below ``ramp_start``, the rate becomes ``ramp_start``; otherwise it
       drops by ``ramp_step``; the count goes down by one.  With a count of 0
       the rate stays.
    3. rate below ``target``: up by ``ramp_step``, at most to ``target``;
       the count goes up by one (a clamped last increment counts as one).
    4. rate above ``target``: down by ``ramp_step``, at least to ``target``;
       the count goes down by one (not below 0).

    Feed hold (``pause``): while it is high every tick decelerates as in
    rule 2, and the tick that finds the count at 0 sets the rate to 0
    (``held``): the path waits where it is, the phase kept.  With
    ``ramp_step`` = 0 the rate is 0 in the clock after ``pause`` rises,
    without a tick in that clock.  A held rate comes back, in the clock after
    ``pause`` falls, at ``ramp_start`` (``target`` with ``ramp_step`` = 0)
    and ramps up again from a count of 0.  ``pause`` while ``run`` is low
    loads 0, so a move that starts on hold waits.

    The count is the number of ticks the rate needs to come back down to
    ``ramp_start``; deceleration begins when the iterations left are no more
    than that (plus the margin), so a path ends at ``ramp_start``: the speed
    ramps up and down linearly with the distance travelled.  ``run`` stays
    high across chained segments, so the ramp does not restart between them.

    Every decision uses registers only: ``target``, ``ramp_start`` and
    ``ramp_step`` are taken one clock late, and the limits of rules 2-4 are
    compared on the candidates themselves (``rate`` +- ``ramp_step`` against
    ``target`` or ``ramp_start``), so no sum of the settings is kept in
    flip-flops.  A settings change reaches the ramp one clock later.

    Processes, by what they drive: ``register_settings`` (the settings),
    ``end_ahead`` (``decelerate``), ``candidates``, ``limits``,
    ``count_direction`` and ``count_steps`` (the next rates, counts and
    their conditions), ``gate``
    (``advancing``), ``accumulate`` (the phase, ``tick``), ``ramp_count``
    (the ramp count), ``ramp_rate`` (the rate, ``held``).

    rate 32768 (every other clock):
        clock  _/~\\_/~\\_/~\\_/~\\_/~\\_
        run    _/~~~~~~~~~~~~~~~~~~~
        tick   _______/~~~\\___/~~~\\_

    feed hold, ramp_step = 0:
        clock  _/~\\_/~\\_/~\\_/~\\_/~\\_
        pause  _/~~~~~~~~~~~\\_______
        held   _____/~~~~~~~~~~~\\___
        rate   =X===X=0=========X===
    """
    step_bits = len(settings.ramp_step)
    rate = Signal(intbv(0, min=0, max=RATE_MAX + 1))
    phase = Signal(intbv(0)[PHASE_BITS:])
    total = Signal(intbv(0)[PHASE_BITS + 1:])
    count = Signal(intbv(DECEL_MARGIN, min=0, max=1 << COUNT_BITS))  # ramp ticks + DECEL_MARGIN
    # the count one up (rule 3) or one down (rules 2 and 4), from one adder
    count_addend, count_moved = Signal(modbv(0)[COUNT_BITS:]), Signal(modbv(0)[COUNT_BITS:])
    count_empty, count_last = Signal(bool(1)), Signal(bool(0))
    decelerate = Signal(bool(0))
    advancing = Signal(bool(0))  # the phase moves on in this clock: running, not held, outputs not full
    # settings and their sums, registered
    target_s, start_s = (Signal(intbv(0, min=0, max=RATE_MAX + 1)) for _ in range(2))
    step_s = Signal(intbv(0)[step_bits:])
    step_zero = Signal(bool(1))
    # candidates, from the registers, in full (rate + step, rate - step) for the limits' compares;
    # their low bits (``raised``, ``lowered``) are taken only when in range
    raised_full = Signal(intbv(0)[max(RATE_BITS, step_bits) + 1:])
    lowered_full = Signal(intbv(0, min=-(1 << step_bits), max=RATE_MAX + 1))
    raised, lowered = Signal(modbv(0)[RATE_BITS:]), Signal(modbv(0)[RATE_BITS:])
    can_raise, can_lower, above_floor, below, above = (Signal(bool(0)) for _ in range(5))
    left_pad = len(feed.stop_left) - COUNT_BITS
    if left_pad < 1:
        raise ValueError(f"stop_left must be wider than {COUNT_BITS} bits")

    @always_seq(clock.posedge, reset=reset)
    def register_settings():
        target_s.next = settings.target
        start_s.next = settings.ramp_start
        step_s.next = settings.ramp_step
        step_zero.next = settings.ramp_step == 0

    @always_seq(clock.posedge, reset=reset)
    def end_ahead():
        decelerate.next = feed.stop_left <= concat(intbv(0)[left_pad:], count)

    @always_comb
    def candidates():
        total.next = concat(False, phase) + concat(False, rate)
        raised_full.next = rate + step_s
        lowered_full.next = concat(False, rate).signed() - concat(False, step_s).signed()
        below.next = rate < target_s
        above.next = rate > target_s
        count_empty.next = count == DECEL_MARGIN
        count_last.next = count == DECEL_MARGIN + 1

    @always_comb
    def limits():
        # rate + step <= target; rate - step >= target; rate - step >= ramp_start
        raised.next = raised_full[RATE_BITS:]
        lowered.next = lowered_full[RATE_BITS:]
        can_raise.next = raised_full <= concat(False, target_s)
        can_lower.next = lowered_full >= concat(False, target_s).signed()
        above_floor.next = lowered_full >= concat(False, start_s).signed()

    @always_comb
    def count_direction():
        # up only where rule 3 raises the rate; where the count goes down, ramp_count keeps a count of 0
        count_addend.next = (1 << COUNT_BITS) - 1
        if below and not (decelerate or feed.pause):
            count_addend.next = 1

    @always_comb
    def count_steps():
        count_moved.next = count + count_addend

    @always_comb
    def gate():
        advancing.next = feed.run and not feed.held and not (step_zero and feed.pause) and not feed.hold

    @always_seq(clock.posedge, reset=reset)
    def accumulate():
        # the phase: rate/65536 of an iteration a clock, its carry the tick
        feed.tick.next = 0
        if not feed.run:
            phase.next = 0
        elif advancing:
            phase.next = total[PHASE_BITS:]
            if total[PHASE_BITS]:
                feed.tick.next = 1

    @always_seq(clock.posedge, reset=reset)
    def ramp_count():
        # the ticks the rate needs to come back down to ramp_start (+ DECEL_MARGIN)
        if not feed.run:
            count.next = DECEL_MARGIN
        elif advancing and total[PHASE_BITS]:
            if step_zero:
                count.next = DECEL_MARGIN
            elif decelerate or feed.pause:
                if not count_empty:
                    count.next = count_moved
            elif below:
                count.next = count_moved
            elif above and not count_empty:
                count.next = count_moved

    @always_seq(clock.posedge, reset=reset)
    def ramp_rate():
        # the rate of the next iteration (rules 1-4 at a tick), and the feed hold
        if not feed.run:
            feed.held.next = feed.pause
            if feed.pause:
                rate.next = 0
            elif step_zero:
                rate.next = target_s
            else:
                rate.next = start_s
        elif feed.held:
            if not feed.pause:
                feed.held.next = 0
                if step_zero:
                    rate.next = target_s
                else:
                    rate.next = start_s
        elif step_zero and feed.pause:
            rate.next = 0
            feed.held.next = 1
        elif not feed.hold and total[PHASE_BITS]:
            if step_zero:
                rate.next = target_s
            elif decelerate or feed.pause:
                if not count_empty:
                    if count_last or not above_floor:
                        rate.next = start_s
                    else:
                        rate.next = lowered
                elif feed.pause:
                    rate.next = 0
                    feed.held.next = 1
            elif below:
                if can_raise:
                    rate.next = raised
                else:
                    rate.next = target_s
            elif above:
                if can_lower:
                    rate.next = lowered
                else:
                    rate.next = target_s

    return register_settings, end_ahead, candidates, limits, count_direction, count_steps, gate, accumulate, ramp_count, ramp_rate


def feed_rate_ports(coord_width=COORD_WIDTH.default):
    """Fresh ports of ``feed_rate`` for conversion and benches: ``feed.stop_left``
    as the ``DdaPort`` of ``coord_width`` carries it."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), settings=RampSettings(), feed=FeedPort(coord_width))
