"""The index latch of one axis: armed by the host, latches the count at the next index rise, once."""
from myhdl import Signal, always_comb, always_seq, block


@block
def index_latch(clock, reset, index, port):
    """The filtered ``index`` (polarity applied) and ``port`` (``EncoderPort``).

    ``port.arm`` arms (at the edge that ends its clock, which is already
    armed for its own sample); at the first sample, armed, where ``index``
    rose since the sample before, ``latch`` takes ``count`` as it was before
    that edge, ``armed`` clears and ``fired`` is high for the clock after;
    with ``index_zero`` the same edge zeroes the count (``zeroing``, to the
    decoder and the following error).  Further rises do nothing until armed
    again.

    ENC_FILTER 0, count 5, A/B moving one phase up every other clock (the
    change before edge 2 counted at edge 5, in the sample the index fires):
        edge         1  2  3  4  5  6
        arm          1  0  0  0  0  0   (in the clock before the edge)
        pin index    0  1  1  1  1  1
        index level  0  0  0  1  1  1
        count        5  5  5  5  6  6
        armed        1  1  1  1  0  0
        latch        0  0  0  0  5  5   (the count before edge 5)
        fired        0  0  0  0  1  0
    """
    seen = Signal(bool(0))
    fire, armed_now = Signal(bool(0)), Signal(bool(0))

    @always_comb
    def arming():
        armed_now.next = port.armed or port.arm

    @always_comb
    def decide():
        fire.next = armed_now and index and not seen
        port.zeroing.next = armed_now and index and not seen and port.index_zero

    @always_seq(clock.posedge, reset=reset)
    def latch():
        seen.next = index
        port.fired.next = fire
        port.armed.next = armed_now and not fire
        if fire:
            port.latch.next = port.count

    return arming, decide, latch
