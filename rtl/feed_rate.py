"""Iteration clock enable of the interpolator with a linear rate ramp."""
from myhdl import Signal, always_seq, block, concat, intbv

from rtl.interfaces import card_reset
from rtl.registers import RATE_ONE

RATE_BITS = RATE_ONE.bit_length()
STEP_BITS = 16


@block
def feed_rate(clock, reset, run, hold, target, ramp_start, ramp_step, tick):
    """Phase accumulator giving ``tick`` on ``rate``/65536 of the clocks.

    Ports: ``run`` (a move is under way; low resets the accumulator and loads
    the starting rate), ``hold`` (freeze: the pulse outputs are full),
    ``target`` (rate to reach, 1..65536), ``ramp_start`` (rate a move starts
    with), ``ramp_step`` (rate change per tick towards ``target``; 0: the rate
    is ``target`` at once), ``tick`` (registered, one clock per iteration).
    Because the rate changes by a constant amount per iteration, the speed
    ramps linearly with the distance travelled; ``run`` stays high across
    chained segments so the ramp does not restart between them.

    rate 32768 (every other clock):
        clock  _/~\\_/~\\_/~\\_/~\\_/~\\_
        run    _/~~~~~~~~~~~~~~~~~~~
        tick   _______/~~~\\___/~~~\\_
    """
    rate = Signal(intbv(0, min=0, max=RATE_ONE + 1))
    phase = Signal(intbv(0)[RATE_BITS - 1:])

    @always_seq(clock.posedge, reset=reset)
    def accumulate():
        total = intbv(0)[RATE_BITS + 1:]
        raised = intbv(0)[RATE_BITS + 1:]
        lowered = intbv(0)[RATE_BITS + 1:]
        tick.next = 0
        if not run:
            phase.next = 0
            if ramp_step == 0:
                rate.next = target
            else:
                rate.next = ramp_start
        elif not hold:
            total[:] = concat(intbv(0)[2:], phase) + concat(False, rate)
            phase.next = total[RATE_BITS - 1:]
            raised[:] = concat(False, rate) + concat(intbv(0)[RATE_BITS + 1 - STEP_BITS:], ramp_step)
            lowered[:] = concat(False, target) + concat(intbv(0)[RATE_BITS + 1 - STEP_BITS:], ramp_step)
            if total >= RATE_ONE:
                tick.next = 1
                if ramp_step == 0:
                    rate.next = target
                elif raised <= concat(False, target):
                    rate.next = raised[RATE_BITS:]
                elif concat(False, rate) >= lowered:
                    rate.next = rate - ramp_step
                else:
                    rate.next = target

    return accumulate


def feed_rate_ports():
    """Fresh ports of ``feed_rate`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), run=Signal(bool(0)), hold=Signal(bool(0)),
                target=Signal(intbv(4096)[RATE_BITS:]), ramp_start=Signal(intbv(4096)[RATE_BITS:]),
                ramp_step=Signal(intbv(0)[STEP_BITS:]), tick=Signal(bool(0)))
