"""The 4x quadrature / step-dir decoder and the count of one axis."""
from myhdl import Signal, always_comb, always_seq, block, modbv

from models.encoder_model import ERROR_COUNT_MAX


@block
def decoder(clock, reset, a, b, port):
    """The filtered ``a`` and ``b`` into ``port.count`` (``EncoderPort``),
    exactly ``models.encoder_model.EncoderModel``'s decoder.

    Each clock compares (``a``, ``b``) with the sample before it.  Mode 0
    (quadrature, 4x): one input changed counts +1 when the phase moved
    forwards (00 -> 10 -> 11 -> 01 -> 00, A leads B), -1 backwards; both
    changed is an illegal transition: not counted, ``quad_error`` set
    (sticky) and ``error_count`` + 1 (saturating).  Mode 1 (step/dir): a
    rise of ``a`` counts +1 when ``b`` is 1, -1 when 0.  A count sets
    ``direction`` and stores ``port.coming`` (the time stamp of this edge) in
    ``time``.  ``port.zeroing`` (the index latch's) zeroes the count at the
    edge, a count in the same sample counting from 0.  ``clear_error``
    clears flag and counter; an error in the same sample sets them again.

    ENC_FILTER 0, TIMESTAMP 100 + n at edge n: A rises, B rises, then both
    fall in one clock (values after each edge; the pins' in the clock
    before it; the filtered levels 2 edges after the pins):
        edge        1    2    3    4    5    6    7    8
        pin A       1    1    1    1    0    0    0    0
        pin B       0    0    1    1    0    0    0    0
        a (level)   0    0    1    1    1    1    0    0
        b (level)   0    0    0    0    1    1    0    0
        count       0    0    0    1    1    2    2    2
        time        0    0    0  104  104  106  106  106
        quad_error  0    0    0    0    0    0    0    1
    """
    seen_a, seen_b = Signal(bool(0)), Signal(bool(0))
    changed_a, changed_b = Signal(bool(0)), Signal(bool(0))
    up, down, illegal = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    base = Signal(modbv(0)[len(port.count):])   # the count this sample counts from: 0 when the index zeroes it

    @always_comb
    def changes():
        changed_a.next = a != seen_a
        changed_b.next = b != seen_b

    @always_comb
    def decode():
        if port.mode:
            up.next = a and not seen_a and b
            down.next = a and not seen_a and not b
            illegal.next = False
        else:
            # one input changed: forwards when A's change left A != B, or B's left A == B
            up.next = (changed_a and not changed_b and a != b) or (changed_b and not changed_a and a == b)
            down.next = (changed_a and not changed_b and a == b) or (changed_b and not changed_a and a != b)
            illegal.next = changed_a and changed_b

    @always_comb
    def start():
        if port.zeroing:
            base.next = 0
        else:
            base.next = port.count

    @always_seq(clock.posedge, reset=reset)
    def count():
        seen_a.next = a
        seen_b.next = b
        if up:
            port.count.next = base + 1
            port.direction.next = True
            port.time.next = port.coming
        elif down:
            port.count.next = base - 1
            port.direction.next = False
            port.time.next = port.coming
        elif port.zeroing:
            port.count.next = 0

    @always_seq(clock.posedge, reset=reset)
    def errors():
        port.quad_error.next = illegal or (port.quad_error and not port.clear_error)
        if port.clear_error:
            port.error_count.next = 1 if illegal else 0
        elif illegal and port.error_count != ERROR_COUNT_MAX:
            port.error_count.next = port.error_count + 1

    return changes, decode, start, count, errors
