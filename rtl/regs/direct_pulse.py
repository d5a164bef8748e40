"""Direct pulses of one axis: a host-given count at a host-given period."""
from myhdl import Signal, always_comb, always_seq, block, intbv, modbv

from rtl.interfaces import DirectPulseCommand, StepRequest, card_reset


@block
def direct_pulse(clock, reset, command, out):
    """Step requests for the pulses the host distributes itself (no interpolation).

    Ports (``rtl/interfaces/``): ``command`` (``DirectPulseCommand``):
    ``load`` (one clock) takes ``count`` (signed: the sign is the
    direction); then one request (``out.step``, one clock, with ``out.dir``;
    ``out``: ``StepRequest``) is made every ``period`` clocks (>= 1) while
    ``out.ready``, the first one the clock after ``load``.  ``remaining``
    counts what is left, ``busy`` is high from ``load`` until the last
    request, that request's clock included; ``running`` the same but for
    the clock of ``load``.  ``clear`` stops.  ``retarget``
    makes |``count``| what is left from this clock on (a request in this
    clock is the first of them; 0 stops), without touching the direction or
    the period's count: the next request comes when it would have come.

    count 2, period 3:
        clock     _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        load      _/~~~\\_____________________
        out.step  _____/~~~\\_______/~~~\\_____
        remaining ==0==X=2=X=1=========X=0====
    """
    count_bits, period_bits = len(command.remaining), len(command.period)
    gap = Signal(intbv(0)[period_bits:])
    # remaining != 0 and gap != 0, each kept in a flip-flop next to its
    # counter: ``busy`` and the next decision then start from one register
    # instead of a 24-bit (16-bit) zero test.
    pending = Signal(bool(0))
    waiting = Signal(bool(0))
    stepping = Signal(bool(0))   # a request at the coming edge
    # ``stepping`` but for a retarget of 0: the adder's operands take it, so
    # that the 24-bit zero test of ``count`` (behind the source's selection)
    # is not in series with the carry chain; a retarget of 0 then writes 0.
    may_step = Signal(bool(0))
    # a request could go at the coming edge (no clear, the period's wait over,
    # the outputs ready): with a retarget and no load that is may_step, so the
    # adder's operands take it without may_step's retarget and pending terms
    can_step = Signal(bool(0))
    # One adder per counter: remaining takes |count| (count ^ sign + sign) on
    # a load and remaining - 1 on a request; gap takes period - 1 on a
    # request and gap - 1 while waiting.
    count_operand, count_addend = Signal(intbv(0)[count_bits:]), Signal(intbv(0)[count_bits:])
    counted = Signal(modbv(0)[count_bits:])
    gap_operand = Signal(intbv(0)[period_bits:])
    gap_less = Signal(modbv(0)[period_bits:])
    all_ones = (1 << count_bits) - 1

    @always_comb
    def activity():
        # the clock of the last request too: that step is not yet in the pulse
        # outputs, so the card is not idle (a HOME then is refused)
        command.busy.next = command.load or pending or out.step
        command.running.next = pending or out.step

    @always_comb
    def decide():
        can_step.next = not command.clear and not waiting and out.ready
        may_step.next = can_step and not command.load and (command.retarget or pending)
        # a retarget of 0 stops at once, a request in its clock included
        stepping.next = may_step and not (command.retarget and command.count == 0)

    @always_comb
    def count_operands():
        # |count| on a load or a retarget (less one with a request in the retarget's clock,
        # or one that may come: see can_step), remaining - 1 otherwise
        if not command.load and not command.retarget:
            count_operand.next = command.remaining
            count_addend.next = all_ones
        elif command.count < 0:
            count_operand.next = ~command.count[count_bits:]
            count_addend.next = 1
            if can_step and not command.load:
                count_addend.next = 0
        else:
            count_operand.next = command.count[count_bits:]
            count_addend.next = 0
            if can_step and not command.load:
                count_addend.next = all_ones

    @always_comb
    def gap_operands():
        if waiting:
            gap_operand.next = gap
        else:
            gap_operand.next = command.period

    @always_comb
    def sums():
        counted.next = count_operand + count_addend
        gap_less.next = gap_operand - 1

    @always_seq(clock.posedge, reset=reset)
    def emit():
        out.step.next = 0
        if command.clear:
            command.remaining.next = 0
            pending.next = 0
        elif command.load:
            command.remaining.next = counted
            out.dir.next = command.count >= 0
            pending.next = command.count != 0
            gap.next = 0
            waiting.next = 0
        elif stepping:
            out.step.next = 1
            command.remaining.next = counted
            if command.retarget:
                # counted != 0 (|count| less this request) from count itself, so
                # that no zero test waits for the adder's carry chain
                pending.next = not (command.count == 1 or command.count == -1)
            else:
                pending.next = command.remaining != 1
            gap.next = gap_less
            waiting.next = command.period != 1
        else:
            if command.retarget:
                pending.next = command.count != 0
                if command.count != 0:
                    command.remaining.next = counted
                else:   # the adder may have taken a request off 0
                    command.remaining.next = 0
            if waiting:   # the period's count runs on after the last request too (a retarget may follow)
                gap.next = gap_less
                waiting.next = gap != 1

    return activity, decide, count_operands, gap_operands, sums, emit


def direct_pulse_ports():
    """Fresh ports of ``direct_pulse`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), command=DirectPulseCommand(), out=StepRequest())
