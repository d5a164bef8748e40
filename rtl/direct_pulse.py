"""Direct pulses of one axis: a host-given count at a host-given period."""
from myhdl import Signal, always_comb, always_seq, block, intbv

from rtl.interfaces import DirectPulseCommand, StepRequest, card_reset


@block
def direct_pulse(clock, reset, command, out):
    """Step requests for the pulses the host distributes itself (no interpolation).

    Ports (``rtl/interfaces.py``): ``command`` (``DirectPulseCommand``):
    ``load`` (one clock) takes ``count`` (signed: the sign is the
    direction); then one request (``out.step``, one clock, with ``out.dir``;
    ``out``: ``StepRequest``) is made every ``period`` clocks (>= 1) while
    ``out.ready``, the first one the clock after ``load``.  ``remaining``
    counts what is left, ``busy`` is high from ``load`` until the last
    request.  ``clear`` stops.

    count 2, period 3:
        clock     _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        load      _/~~~\\_____________________
        out.step  _____/~~~\\_______/~~~\\_____
        remaining ==0==X=2=X=1=========X=0====
    """
    gap = Signal(intbv(0)[len(command.period):])
    # remaining != 0 and gap != 0, each kept in a flip-flop next to its
    # counter: ``busy`` and the next decision then start from one register
    # instead of a 24-bit (16-bit) zero test.
    pending = Signal(bool(0))
    waiting = Signal(bool(0))

    @always_comb
    def activity():
        command.busy.next = command.load or pending

    @always_seq(clock.posedge, reset=reset)
    def emit():
        out.step.next = 0
        if command.clear:
            command.remaining.next = 0
            pending.next = 0
        elif command.load:
            if command.count < 0:
                command.remaining.next = -command.count
                out.dir.next = 0
            else:
                command.remaining.next = command.count
                out.dir.next = 1
            pending.next = command.count != 0
            gap.next = 0
            waiting.next = 0
        elif pending:
            if waiting:
                gap.next = gap - 1
                waiting.next = gap != 1
            elif out.ready:
                out.step.next = 1
                command.remaining.next = command.remaining - 1
                pending.next = command.remaining != 1
                gap.next = command.period - 1
                waiting.next = command.period != 1

    return activity, emit


def direct_pulse_ports():
    """Fresh ports of ``direct_pulse`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), command=DirectPulseCommand(), out=StepRequest())
