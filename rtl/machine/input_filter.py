"""The machine inputs' conditioning: synchroniser, polarity and glitch filter."""
from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, intbv

from models.parameters import AXES
from rtl.interfaces import InputConditioning, card_reset


@block
def input_filter(clock, reset, inputs):
    """Every machine input through two flip-flops, its polarity and a glitch filter.

    Ports (``rtl/interfaces/``): ``inputs`` (``InputConditioning``):
    ``pins`` in, asynchronous; ``raw`` the pins after the two-flip-flop
    synchroniser; ``active`` the filtered inputs, ``raw ^ polarity``, 1
    active; ``changed`` one clock after an ``active`` bit changed.

    The filter samples every ``tick`` clocks (one shared prescaler, its
    first sample in the first clock after reset).  An input whose level
    (``raw ^ polarity``) differs from its ``active`` bit counts the samples
    that see it so; at the ``samples``-th in a row ``active`` takes the new
    level; a sample that sees the old level again (a glitch, a bounce)
    restarts the count.  ``samples`` 1 (or 0): ``active`` follows at the
    first sample.  With ``tick`` 1, ``active`` changes at the edge
    ``samples`` + 1 clocks after the one that takes the pin's new level
    into the synchroniser.  Each input has only a count as wide as
    ``samples``.

    samples 2, tick 1:
        clock    _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        pin      ___/~~~~~~~~~~~~~~~~~~~~~~
        raw      _________/~~~~~~~~~~~~~~~~
        active   _________________/~~~~~~~~
        changed  _________________/~~~\\____
    """
    count = len(inputs.pins)
    sync = Signal(intbv(0)[count:])
    count_bits = len(inputs.samples)
    counts = [Signal(intbv(0)[count_bits:]) for _ in range(count)]
    # clocks to the next sample, 1 in its clock: reloaded with ``tick`` itself (>= 1), so no
    # second decrementer makes ``tick - 1``; 1 after reset, the first clock's sample
    prescale = Signal(intbv(1)[len(inputs.tick):])
    sample = Signal(bool(0))
    level = Signal(intbv(0)[count:])
    taken_bits = [Signal(bool(0)) for _ in range(count)]  # the new level counts with this sample
    taken = ConcatSignal(*reversed(taken_bits))

    @always_seq(clock.posedge, reset=reset)
    def synchronise():
        sync.next = inputs.pins
        inputs.raw.next = sync

    @always_comb
    def polarise():
        level.next = inputs.raw ^ inputs.polarity
        sample.next = prescale == 1

    @always_seq(clock.posedge, reset=reset)
    def prescaler():
        if sample:
            prescale.next = inputs.tick
        else:
            prescale.next = prescale - 1

    @always_seq(clock.posedge, reset=reset)
    def follow():
        inputs.active.next = inputs.active ^ taken
        inputs.changed.next = taken != 0

    units = [synchronise, polarise, prescaler, follow]
    for index in range(count):
        units.append(_input_count(clock, reset, level, inputs.active, sample, inputs.samples, counts[index],
                                  taken_bits[index], index=index))
    return units


@block
def _input_count(clock, reset, level, active, sample, samples, held, taken, *, index):
    """Input ``index``'s count of samples at a level other than ``active``;
    ``taken``: this sample completes ``samples`` of them."""

    @always_seq(clock.posedge, reset=reset)
    def count_samples():
        if level[index] == active[index]:
            held.next = 0
        elif sample:
            if taken:
                held.next = 0
            else:
                held.next = held + 1

    @always_comb
    def decide():
        taken.next = sample and level[index] != active[index] and held + 1 >= samples

    return count_samples, decide


def input_filter_ports(axes=AXES.default):
    """Fresh ports of ``input_filter`` for conversion and benches: the inputs of a card of ``axes`` axes."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), inputs=InputConditioning(axes))
