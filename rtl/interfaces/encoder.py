"""The encoder inputs (docs/encoders.md): pins, the per-axis unit's controls
and outputs, the card's time stamp, the following error and the probe.

Every width and reset value comes from ``models/encoder_model.py``.
"""
from myhdl import Signal, intbv, modbv

from models.encoder_model import (COUNT_BITS, ERROR_COUNT_BITS, FILTER_BITS, FILTER_RESET, LIMIT_BITS,
                                  POLARITY_BITS, SCALE_BITS)
from models.parameters import AXES
from rtl.interfaces.bundle import adopt, axis_suffixes
from rtl.interfaces.card import StepPositions


POS_LOW_BITS = 2   # POS modulo 4: enough to tell a step up from a step down, POS moving one step a clock


def _word():
    return Signal(modbv(0)[COUNT_BITS:])


class EncoderPins:
    """One axis's encoder pins, levels as wired, asynchronous: ``a``, ``b``, ``index``."""

    def __init__(self, **given):
        adopt(self, given, a=Signal(bool(0)), b=Signal(bool(0)), index=Signal(bool(0)))


class EncoderPort:
    """The per-axis encoder unit's seam with the registers (``rtl/encoder/encoder.py``).

    The card drives ``filter`` (ENC_FILTER: a level is taken once seen
    ``filter`` + 1 clocks in a row), ``polarity`` (ENC_POLARITY: bit 0 A,
    1 B, 2 index; 1 inverts), ``mode`` (ENC_CONTROL.MODE: 0 quadrature, 1
    step/dir), ``index_zero`` (ENC_CONTROL.INDEX_ZERO), and the one-clock
    strobes ``arm`` (a write of INDEX_ARM) and ``clear_error`` (a write of 1
    to QUAD_ERROR), and ``coming`` (``Timestamp.coming``, given the card's
    signal); each strobe acts at the edge that ends its clock, on
    that edge's sample too.  The unit drives ``count`` (ENC_COUNT, wrapping),
    ``direction`` (1 after a count up), ``quad_error`` (sticky) and
    ``error_count`` (saturating), ``time`` (ENC_TIME: the time stamp of the
    last count edge), ``armed`` (INDEX_ARM as read), ``latch``
    (ENC_INDEX_LATCH), ``fired`` (one clock after the index latched) and
    ``zeroing`` (combinational: this clock's edge zeroes the count at the
    index, for the following error)."""

    def __init__(self, **given):
        adopt(self, given, filter=Signal(intbv(FILTER_RESET)[FILTER_BITS:]),
              polarity=Signal(intbv(0)[POLARITY_BITS:]), mode=Signal(bool(0)), index_zero=Signal(bool(0)),
              arm=Signal(bool(0)), clear_error=Signal(bool(0)), coming=_word(),
              count=_word(), direction=Signal(bool(1)), quad_error=Signal(bool(0)),
              error_count=Signal(intbv(0)[ERROR_COUNT_BITS:]), time=_word(), armed=Signal(bool(0)),
              latch=_word(), fired=Signal(bool(0)), zeroing=Signal(bool(0)))


class Timestamp:
    """The card's free-running clock count (``rtl/encoder/timestamp.py``):
    ``value`` (TIMESTAMP, 0 at reset, +1 every edge, wrapping) and ``coming``
    (combinational: the value it takes at the coming edge, what an encoder
    stores as ENC_TIME at a count edge)."""

    def __init__(self, **given):
        adopt(self, given, value=_word(), coming=_word())


class FollowingErrorPort:
    """One axis's following-error check (``rtl/encoder/following_error.py``).

    The card drives ``count`` and ``zeroing`` (``EncoderPort``'s),
    ``pos_low`` (the axis's step position modulo 4, its two low bits: the
    position changes by at most one step a clock), ``scale`` (ENC_SCALE, counts per step, unsigned 16.16; it
    changes only in a clock with ``align``), ``limit`` (FERROR_LIMIT,
    counts; 0 off), and the one-clock strobes ``align`` (re-align: a write
    of ENC_SCALE or the host's align) and ``clear_stop``.  The unit drives
    ``error`` (ENC_FERROR, 32 bits, read signed) and ``stop`` (latched while
    |``error``| > ``limit``, until ``clear_stop``)."""

    def __init__(self, **given):
        adopt(self, given, count=_word(), zeroing=Signal(bool(0)),
              pos_low=Signal(modbv(0)[POS_LOW_BITS:]), scale=Signal(intbv(0)[SCALE_BITS:]),
              limit=Signal(intbv(0)[LIMIT_BITS:]), align=Signal(bool(0)), clear_stop=Signal(bool(0)),
              error=_word(), stop=Signal(bool(0)))


class ProbePort:
    """The card's probe input and latch (``rtl/encoder/probe.py``) for ``axes`` axes.

    The card drives ``pin`` (PROBE as wired, asynchronous), ``invert`` (its
    polarity bit), ``filter`` (its filter setting, as ENC_FILTER), ``arm``
    (a one-clock strobe, acting at the edge that ends its clock), and per
    axis ``count_x``, ``count_y``, ... (ENC_COUNT) and ``pos_x``, ... (the
    step position, a 32-bit word); the unit drives ``armed``, ``fired`` (one clock
    after the latch) and per axis ``latched_count_x``, ... (PROBE_ENC) and
    ``latched_pos_x``, ... (PROBE_POS)."""

    def __init__(self, axes=AXES.default):
        self.axes = axes
        self.pin, self.invert, self.arm = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
        self.filter = Signal(intbv(FILTER_RESET)[FILTER_BITS:])
        self.armed, self.fired = Signal(bool(0)), Signal(bool(0))
        for suffix in axis_suffixes(axes):
            setattr(self, f"count_{suffix}", _word())
            setattr(self, f"pos_{suffix}", _word())
            setattr(self, f"latched_count_{suffix}", _word())
            setattr(self, f"latched_pos_{suffix}", _word())

    def signals(self, prefix, axis):
        """Axis ``axis``'s signal ``prefix`` (``count``, ``pos``, ``latched_count``, ``latched_pos``)."""
        return getattr(self, f"{prefix}_{axis_suffixes(self.axes)[axis]}")


class EncoderRegisters:
    """The encoder registers' seam with the card (``rtl/regs/encoder_block.py``) for ``axes`` axes.

    ``words``: {register name: ``RegisterWord``} holding TIMESTAMP,
    PROBE_CONTROL and every axis's block registers (ENC_COUNT_X, ...,
    PROBE_POS_X, ENC_COUNT_Y, ...); ``positions`` (``StepPositions``, the
    live step counts).  The card drives ``realign`` (bit i: axis i's
    position was set at the last edge: CLEAR_POSITION, or homing's zero)
    and ``clear_stop`` (COMMAND.CLEAR_STOP, one clock); the unit drives the
    words' ``hw``, ``ferror`` (bit i: axis i's following error is beyond
    its limit, latched until ``clear_stop``), ``index_fired`` and
    ``probe_fired`` (one clock each: INT_STATUS.INDEX and PROBE)."""

    def __init__(self, axes, words, positions=None, **given):
        self.axes, self.words = axes, words
        self.positions = StepPositions(axes) if positions is None else positions
        adopt(self, given, realign=Signal(intbv(0)[axes:]), clear_stop=Signal(bool(0)),
              ferror=Signal(intbv(0)[axes:]), index_fired=Signal(bool(0)), probe_fired=Signal(bool(0)))

    def word(self, name, axis=None):
        """The ``RegisterWord`` of ``name`` (of axis ``axis``'s block when given)."""
        return self.words[name if axis is None else f"{name}_{axis_suffixes(self.axes)[axis].upper()}"]
