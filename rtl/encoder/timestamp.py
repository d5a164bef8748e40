"""The card's free-running time stamp (TIMESTAMP)."""
from myhdl import Signal, always_comb, always_seq, block

from rtl.interfaces import Timestamp, card_reset


@block
def timestamp(clock, reset, stamp):
    """``stamp.value`` counts clocks: 0 at reset, +1 at every edge, wrapping;
    ``stamp.coming`` is the value it takes at the coming edge (what an
    encoder stores as ENC_TIME when it counts at that edge).

        edge     r     1     2     3
        value  ==0==X==1==X==2==X==3==
        coming ==1==X==2==X==3==X==4==
    """

    @always_comb
    def ahead():
        stamp.coming.next = stamp.value + 1

    @always_seq(clock.posedge, reset=reset)
    def count():
        stamp.value.next = stamp.coming

    return ahead, count


def timestamp_ports():
    """Fresh ports of ``timestamp`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), stamp=Timestamp())
