"""The registers of a build with encoders in BAR0, and the per-axis blocks
in BAR2 (docs/axes.md, docs/encoders.md): tables only, looked up through
``models/registers.py``.

The per-axis blocks are in BAR2 only (the I/O BAR0 keeps to PCI's 256
bytes): block i, for axis i, at AXIS_BLOCK_BASE + AXIS_STRIDE * i; offsets
in ``AXIS_REGISTERS`` are inside the block, the axis's own registers first,
the rest of the block free for more (reads 0, writes ignored).  A block
register whose <REG>_X and <REG>_Y BAR0 has is BAR0's for X and Y; the
others are the block's only, for every axis.
"""
from models.encoder_model import (ERROR_COUNT_BITS, FILTER_BITS, FILTER_RESET, LIMIT_BITS, POLARITY_BITS, SCALE_BITS,
                                  SCALE_MAX)
from models.register_types import Field, Register, one_value

_ENCODERS = "encoders"   # the build parameter the encoder registers need
_FILTER_TEXT = ("a level is taken once seen FILTER + 1 clocks in a row (0..15; docs/encoders.md has the glitch "
                "widths each rejects)")
# Card-wide registers of a build with encoders, in BAR0 (a build without them reads 0 there, ignores writes).
ENCODER_REGISTERS = (
    Register("TIMESTAMP", 0xA4, "RO", 0, "the card's time stamp: clocks since reset (ENC_TIME is one of its values)",
             one_value("CLOCKS", 32, "counts every clock, wrapping"), option=_ENCODERS),
    Register("PROBE_CONTROL", 0xA8, "WP", FILTER_RESET << 8,
             "the probe input: arm it, its polarity and filter (a write sets every field: write the word "
             "read back with the fields changed)", (
                 Field("ARM", 0, 1, "write 1 to arm: the next probe edge latches every axis's PROBE_ENC and "
                       "PROBE_POS once; reads 1 while armed"),
                 Field("INVERT", 1, 1, "1: the probe input is active low"),
                 Field("FILTER", 8, FILTER_BITS, f"the probe's filter: {_FILTER_TEXT}"),
             ), option=_ENCODERS),
)

REG_BAR_BITS = 12   # BAR2: 4 KiB, BAR0's registers at 0x000..0x0FF, then the blocks
AXIS_BLOCK_BASE = 0x100
AXIS_STRIDE = 0x40
AXIS_FREE = (0x0C,)   # kept for the axis's homing registers (AXIS_HOME)
_COUNT_TEXT = "counts, signed, wrapping modulo 2**32"
AXIS_REGISTERS = (
    Register("POS", 0x00, "RO", 0, "the axis's position in steps: X's live, the others' as a read of X's "
             "(POS_X, in BAR0 or block 0) captured them, one instant for all",
             one_value("STEPS", 32, "steps that left the axis's pins, signed", signed=True)),
    Register("PULSE_PERIOD", 0x04, "RW", 2, "clocks between the axis's direct pulses",
             one_value("CLOCKS", 16, "1..65535"), minimum=1, maximum=0xFFFF),
    Register("PULSE_COUNT", 0x08, "WP", 0, "direct mode: write a signed count of the axis's pulses; read what is left",
             one_value("COUNT", 24, "signed pulses (sign: direction); reads the pulses still to go",
                  signed=True), minimum=-(1 << 23), maximum=(1 << 23) - 1),
    Register("ENC_COUNT", 0x10, "RO", 0, "the encoder's count (4x quadrature, or step/dir)",
             one_value("COUNT", 32, _COUNT_TEXT, signed=True), option=_ENCODERS),
    Register("ENC_STATUS", 0x14, "WP", 0, "the encoder's errors and direction; write 1 to QUAD_ERROR to clear it "
             "and ERROR_COUNT (W1C in effect)", (
                 Field("QUAD_ERROR", 0, 1, "sticky: a sample where A and B both changed (not counted); write 1 "
                       "clears it and ERROR_COUNT"),
                 Field("DIRECTION", 1, 1, "1: the last count was up"),
                 Field("ERROR_COUNT", 8, ERROR_COUNT_BITS, "illegal transitions since the last clear, saturating"),
             ), option=_ENCODERS),
    Register("ENC_CONTROL", 0x18, "WP", FILTER_RESET << 8,
             "the encoder's mode, index, polarity and filter (a write sets every field: write the word read "
             "back with the fields changed)", (
                 Field("MODE", 0, 1, "0 quadrature (4x), 1 step/dir (A step, counted on its rising edge, B direction)"),
                 Field("INDEX_ZERO", 1, 1, "1: the index edge that latches also zeroes ENC_COUNT (index-enable)"),
                 Field("INDEX_ARM", 2, 1, "write 1 to arm: the next index edge latches ENC_COUNT into "
                       "ENC_INDEX_LATCH once (INT_STATUS.INDEX); reads 1 while armed"),
                 Field("POLARITY", 4, POLARITY_BITS, "bit 0 A, 1 B, 2 index: 1 inverts that input"),
                 Field("FILTER", 8, FILTER_BITS, f"the A, B and index filter: {_FILTER_TEXT}"),
             ), option=_ENCODERS),
    Register("ENC_INDEX_LATCH", 0x1C, "RO", 0, "ENC_COUNT as it was at the last armed index edge",
             one_value("COUNT", 32, _COUNT_TEXT, signed=True), option=_ENCODERS),
    Register("ENC_TIME", 0x20, "RO", 0, "TIMESTAMP at the last count edge (velocity: docs/encoders.md)",
             one_value("CLOCKS", 32, "the time stamp, clocks"), option=_ENCODERS),
    Register("ENC_SCALE", 0x24, "WP", 0, "encoder counts per step, unsigned 16.16; a write re-aligns the "
             "following error (reads the value written)",
             one_value("SCALE", SCALE_BITS, "counts per step times 65536 (0: the step position is taken as 0)"),
             minimum=0, maximum=SCALE_MAX, option=_ENCODERS),
    Register("FERROR_LIMIT", 0x28, "RW", 0, "following-error limit: |ENC_FERROR| beyond it stops the card "
             "(STOP_REASON FOLLOWING_ERROR)", one_value("COUNTS", LIMIT_BITS, "counts (0: off)"),
             minimum=0, maximum=(1 << LIMIT_BITS) - 1, option=_ENCODERS),
    Register("ENC_FERROR", 0x2C, "RO", 0, "the following error: ENC_COUNT - round(POS * ENC_SCALE), both "
             "from their last alignment (docs/encoders.md)", one_value("COUNTS", 32, "counts, signed", signed=True),
             option=_ENCODERS),
    Register("PROBE_ENC", 0x30, "RO", 0, "ENC_COUNT at the last armed probe edge (PROBE_CONTROL)",
             one_value("COUNT", 32, _COUNT_TEXT, signed=True), option=_ENCODERS),
    Register("PROBE_POS", 0x34, "RO", 0, "the axis's step position (POS) at the last armed probe edge",
             one_value("STEPS", 32, "steps, signed", signed=True), option=_ENCODERS),
)
