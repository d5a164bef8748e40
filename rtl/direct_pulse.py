"""Direct pulses of one axis: a host-given count at a host-given period."""
from myhdl import Signal, always_comb, always_seq, block, intbv

from rtl.interfaces import card_reset

COUNT_BITS = 24
PERIOD_BITS = 16


@block
def direct_pulse(clock, reset, load, count, period, ready, clear, request, request_dir, remaining, busy):
    """Step requests for the pulses the host distributes itself (no interpolation).

    Ports: ``load`` (one clock) takes ``count`` (signed: the sign is the
    direction); then one ``request`` (one clock, with ``request_dir``) is made
    every ``period`` clocks (>= 1) while the pulse output is ``ready``, the
    first one the clock after ``load``.  ``remaining`` counts what is left,
    ``busy`` is high from ``load`` until the last request.  ``clear`` stops.

    count 2, period 3:
        clock     _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        load      _/~~~\\_____________________
        request   _____/~~~\\_______/~~~\\_____
        remaining ==0==X=2=X=1=========X=0====
    """
    gap = Signal(intbv(0)[PERIOD_BITS:])
    # remaining != 0 and gap != 0, each kept in a flip-flop next to its
    # counter: ``busy`` and the next decision then start from one register
    # instead of a 24-bit (16-bit) zero test.
    pending = Signal(bool(0))
    waiting = Signal(bool(0))

    @always_comb
    def activity():
        busy.next = load or pending

    @always_seq(clock.posedge, reset=reset)
    def emit():
        request.next = 0
        if clear:
            remaining.next = 0
            pending.next = 0
        elif load:
            if count < 0:
                remaining.next = -count
                request_dir.next = 0
            else:
                remaining.next = count
                request_dir.next = 1
            pending.next = count != 0
            gap.next = 0
            waiting.next = 0
        elif pending:
            if waiting:
                gap.next = gap - 1
                waiting.next = gap != 1
            elif ready:
                request.next = 1
                remaining.next = remaining - 1
                pending.next = remaining != 1
                gap.next = period - 1
                waiting.next = period != 1

    return activity, emit


def direct_pulse_ports():
    """Fresh ports of ``direct_pulse`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), load=Signal(bool(0)),
                count=Signal(intbv(0, min=-(1 << (COUNT_BITS - 1)), max=1 << (COUNT_BITS - 1))),
                period=Signal(intbv(2)[PERIOD_BITS:]), ready=Signal(bool(1)), clear=Signal(bool(0)),
                request=Signal(bool(0)), request_dir=Signal(bool(0)),
                remaining=Signal(intbv(0)[COUNT_BITS:]), busy=Signal(bool(0)))
