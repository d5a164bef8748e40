"""The encoder inputs of a card built with encoders (BUILD.ENCODERS; docs/encoders.md): each axis's
count, latches and following error, and a velocity from ENC_TIME.

Velocity (hostmot2's time-stamp idea): between two reads, the counts that came over the clocks
between the last count edges (ENC_TIME of each read) give counts per clock without the one-count
quantisation of a fixed read interval; when no count came since the last read, the motor is at most
one count in (TIMESTAMP - ENC_TIME) clocks away from still, so the speed is the smaller of the last
one and that bound (it falls towards 0 while the motor stands).
"""
from dataclasses import dataclass

from models import registers as regmap

MASK32 = (1 << 32) - 1


def _signed(word):
    return word - (1 << 32) if word >> 31 else word


def _field(name, field_name, word):
    item = regmap.axis_spec(name).field(field_name)
    return (word >> item.lsb) & ((1 << item.width) - 1)


@dataclass(frozen=True)
class EncoderReading:
    """One axis's encoder registers read at once: ``count`` (signed), ``time`` (ENC_TIME),
    ``stamp`` (TIMESTAMP read after it), ``index_latch``, ``index_armed``, ``quad_error``,
    ``error_count``, ``ferror`` (ENC_FERROR, signed counts), ``probe_count``, ``probe_position``."""
    count: int
    time: int
    stamp: int
    index_latch: int
    index_armed: bool
    quad_error: bool
    error_count: int
    ferror: int
    probe_count: int
    probe_position: int


def _need(card):
    if not card.identity.encoders:
        raise ValueError("the card was built without encoders (BUILD.ENCODERS is 0)")


def read_encoder(card, axis):
    """Axis ``axis``'s ``EncoderReading``."""
    _need(card)
    count, time = card.axis_read("ENC_COUNT", axis), card.axis_read("ENC_TIME", axis)
    stamp = card.read("TIMESTAMP")
    status, control = card.axis_read("ENC_STATUS", axis), card.axis_read("ENC_CONTROL", axis)
    return EncoderReading(_signed(count), time, stamp, _signed(card.axis_read("ENC_INDEX_LATCH", axis)),
                          bool(_field("ENC_CONTROL", "INDEX_ARM", control)),
                          bool(_field("ENC_STATUS", "QUAD_ERROR", status)), _field("ENC_STATUS", "ERROR_COUNT", status),
                          _signed(card.axis_read("ENC_FERROR", axis)), _signed(card.axis_read("PROBE_ENC", axis)),
                          _signed(card.axis_read("PROBE_POS", axis)))


def velocity(before, after, clock_hz, last=0.0):
    """Counts per second between two ``EncoderReading``s of one axis (module docstring); ``last``:
    the velocity this gave for the reads before."""
    counts = _signed((after.count - before.count) & MASK32)
    if counts:
        clocks = (after.time - before.time) & MASK32
        return counts * clock_hz / max(clocks, 1)
    bound = clock_hz / max((after.stamp - after.time) & MASK32, 1)
    return max(-bound, min(bound, last))


def set_following_error(card, axis, counts_per_step, limit):
    """ENC_SCALE (counts per step, rounded to 1/65536; the write re-aligns the error) and FERROR_LIMIT
    (counts, 0 off) of axis ``axis``."""
    _need(card)
    scale = round(counts_per_step * 65536)
    card.axis_write("ENC_SCALE", axis, scale)
    card.axis_write("FERROR_LIMIT", axis, limit)


def arm_index(card, axis, zero=False):
    """Arm axis ``axis``'s index latch (with ``zero``: the index edge zeroes ENC_COUNT), keeping
    ENC_CONTROL's other fields."""
    _need(card)
    spec = regmap.axis_spec("ENC_CONTROL")
    control = card.axis_read("ENC_CONTROL", axis) & ~spec.field("INDEX_ZERO").mask
    control |= spec.field("INDEX_ARM").mask | (spec.field("INDEX_ZERO").mask if zero else 0)
    card.axis_write("ENC_CONTROL", axis, control)
