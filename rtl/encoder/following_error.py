"""One axis's following error: encoder count against the scaled step position, and its stop flag."""
from myhdl import Signal, always_comb, always_seq, block, intbv, modbv

from models.encoder_model import SCALE_FRACTION_BITS
from rtl.interfaces import FollowingErrorPort, card_reset

HALF = 1 << (SCALE_FRACTION_BITS - 1)   # kept added in: the integer bits are then rounded half up


@block
def following_error(clock, reset, check):
    """ENC_FERROR and the following-error stop, clock for clock
    ``models.encoder_model.EncoderModel``'s (docs/encoders.md).

    Ports: ``check`` (``FollowingErrorPort``).  With the count and step
    position at the last alignment (``origin``, and the position's origin
    folded into ``scaled``):

        error = (count - origin) - round((pos - pos_origin) * scale / 2**16)

    modulo 2**32, round half up.  No multiplier: ``scaled`` keeps
    (pos - pos_origin) * scale + 2**15 modulo 2**48, adding or taking
    ``scale`` as POS moves by one step (``pos_low``, its two low bits, tell
    which way: POS may change by at most one step a clock, and the model's
    product is the same while pos - pos_origin stays within a signed
    32-bit range), and its upper 32 bits are the rounded scaled steps.
    ``align`` and the index's ``zeroing`` re-align (the count's origin the
    count, or 0); ``align`` makes the error read 0 after its edge.
    ``stop`` sets at the edge after the one where ``error`` came to read
    |error| > ``limit`` (``limit`` 0: off), and stays until ``clear_stop``
    (a new cause in the same clock wins).

    limit 1, scale 1.0, pos 0; the encoder's count crosses to 2 at edge 1
    (``FERROR_CLOCKS`` = 2 edges from the count to the stop):
        edge    0  1  2  3
        count   1  2  2  2
        error   1  1  2  2
        stop    0  0  0  1
    """
    word = len(check.count)
    sum_bits = word + SCALE_FRACTION_BITS   # the scaled position: the count's integer bits, 16 fraction bits
    scaled, scaled_now = Signal(modbv(HALF)[sum_bits:]), Signal(modbv(0)[sum_bits:])
    # POS moves by at most one step a clock: its two low bits tell a step up (+1 mod 4) from one down (-1)
    last_pos, step = Signal(modbv(0)[len(check.pos_low):]), Signal(modbv(0)[len(check.pos_low):])
    rounded, moved_counts, origin, difference, folded = (Signal(modbv(0)[word:]) for _ in range(5))
    negative = Signal(bool(0))
    scale = Signal(intbv(0)[sum_bits:])
    beyond = Signal(bool(0))

    @always_comb
    def moved():
        step.next = check.pos_low - last_pos

    @always_comb
    def widen():
        scale.next = 0
        scale.next[len(check.scale):] = check.scale

    @always_comb
    def follow():
        if step == 1:
            scaled_now.next = scaled + scale
        elif step[1] and step[0]:   # -1 modulo 4
            scaled_now.next = scaled - scale
        else:
            scaled_now.next = scaled

    @always_comb
    def round_half_up():
        rounded.next = scaled_now[sum_bits:SCALE_FRACTION_BITS]
        moved_counts.next = check.count - origin

    @always_comb
    def compare():
        difference.next = moved_counts - rounded
        negative.next = check.error[word - 1]
        if check.error[word - 1]:
            folded.next = ~check.error   # |error| - 1
        else:
            folded.next = check.error

    @always_comb
    def judge():
        # |error| > limit: error > limit, or for a negative error ~error = |error| - 1 >= limit
        beyond.next = (check.limit != 0 and not check.align
                       and (folded > check.limit or (negative and folded == check.limit)))

    @always_seq(clock.posedge, reset=reset)
    def track():
        last_pos.next = check.pos_low
        if check.zeroing:
            origin.next = 0
            scaled.next = HALF
        elif check.align:
            origin.next = check.count
            scaled.next = HALF
        else:
            scaled.next = scaled_now
        if check.align:
            check.error.next = 0
        else:
            check.error.next = difference
        check.stop.next = beyond or (check.stop and not check.clear_stop)

    return moved, widen, follow, round_half_up, compare, judge, track


def following_error_ports():
    """Fresh ports of ``following_error`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), check=FollowingErrorPort())
