"""One encoder input's conditioning: two-flip-flop synchroniser, polarity, filter."""
from myhdl import Signal, always_comb, always_seq, block, intbv


@block
def conditioner(clock, reset, pin, invert, setting, level):
    """``pin`` through two flip-flops, XORed with ``invert``, then the filter
    into ``level`` (``models.encoder_model.InputConditioner``).

    The filter keeps a run count of the clocks in a row the synchronised
    input (after polarity) has differed from ``level``: at an edge where it
    differs and the count has reached ``setting``, ``level`` takes it; one
    clock back at ``level`` restarts the count.  So a level is taken once
    seen ``setting`` + 1 clocks in a row and a glitch of w <= ``setting``
    clocks is rejected; every edge is delayed by 3 + ``setting`` edges.

    setting 1: the pin rises in the clock before edge 1, and a glitch of one
    clock low before edge 5 is removed (values after each edge; the pin's
    in the clock before it):
        edge    1  2  3  4  5  6  7  8
        pin     1  1  1  1  0  1  1  1
        sync    1  1  1  1  0  1  1  1
        synced  0  1  1  1  1  0  1  1
        run     0  0  1  0  0  0  1  0
        level   0  0  0  1  1  1  1  1
    """
    sync, synced, seen = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    run = Signal(intbv(0)[len(setting):])

    @always_comb
    def polarise():
        seen.next = synced ^ invert

    @always_seq(clock.posedge, reset=reset)
    def synchronise():
        sync.next = pin
        synced.next = sync

    @always_seq(clock.posedge, reset=reset)
    def filter_level():
        if seen == level:
            run.next = 0
        elif run >= setting:
            level.next = seen
            run.next = 0
        else:
            run.next = run + 1

    return polarise, synchronise, filter_level
