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

    setting 1 (a pin change before edge e; a 1-clock glitch after it):
        edge     e     e+1   e+2   e+3   e+4   e+5   e+6
        pin    _/~~~~~~~~~~~~~~~~~~\\___/~~~~~~~~~~~~~
        synced _______/~~~~~~~~~~~~~~~~~~~\\___/~~~~~~~
        run       0     0     1     0     0     1     0
        level  _____________________/~~~~~~~~~~~~~~~~~
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
