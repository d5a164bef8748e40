"""The N-axis form of the command words (``models/instructions.py``, ``models/commands.py``).

Expected words are assembled here from the bit positions docs/axes.md fixes
(LINE.AXES 25:20, ARC.U_AXIS 15:13, V_AXIS 19:17, HELIX 25:20, PULSE.AXES 25:20;
operands per axis ascending, AREA_LO and AREA_HI before a helix's displacements), not
from the encoder.
"""
import random

import pytest

from models import instructions as isa
from models.commands import (DwellCommand, MarkCommand, PulseCommand, SetCommand, command_words, decode_words,
                             stream_words)
from models.dda_plan import ArcCommand, AxesLineCommand, LineCommand

LINE, ARC, PULSE = 0x1 << 28, 0x2 << 28, 0x3 << 28
BLEND = 1 << 16


def u32(value):
    return value & 0xFFFFFFFF


@pytest.mark.parametrize("command, words", [
    # the two-axis form, word for word what a two-axis host writes
    (LineCommand(5, -3), [LINE, 5, u32(-3)]),
    (AxesLineCommand((5, -3)), [LINE, 5, u32(-3)]),
    (AxesLineCommand((5, -3, 0, 0)), [LINE, 5, u32(-3)]),
    (AxesLineCommand((0, 7), blend=True), [LINE | BLEND, 0, 7]),
    (ArcCommand(10, 0, 0, 10), [ARC | 0b111, 10, 0, 0, 10]),
    (PulseCommand((4, -1)), [PULSE, 4, u32(-1)]),
    # the N-axis form
    (AxesLineCommand((5, 0, -2)), [LINE | 0b101 << 20, 5, u32(-2)]),
    (AxesLineCommand((0, 0, 0, 9, 0, -1), blend=True), [LINE | BLEND | 0b101000 << 20, 9, u32(-1)]),
    (ArcCommand(-4, 3, 3, -4, ccw=False, plane=(2, 0)), [ARC | 0b110 | 2 << 13, u32(-4), 3, 3, u32(-4)]),
    (ArcCommand(6, 8, 6, 8, plane=(1, 2), helix=(-40, 0, 0, 0, 7), area=60),
     [ARC | 0b111 | 1 << 13 | 2 << 17 | 0b10001 << 20, 6, 8, 6, 8, 60, 0, u32(-40), 7]),
    # AREA in two words: bits 31:0, then the bits above
    (ArcCommand(6, 8, 6, 8, helix=(0, 0, 12), area=0x1_2345_6789_ABCD),
     [ARC | 0b111 | 0b100 << 20, 6, 8, 6, 8, 0x6789_ABCD, 0x1_2345, 12]),
    (PulseCommand((0, 0, 3, 0, 0, 2)), [PULSE | 0b100100 << 20, 3, 2]),
])
def test_words_of_both_forms(command, words):
    assert command_words(command) == words


def test_a_helix_without_its_area_is_refused():
    with pytest.raises(ValueError, match="AREA"):
        command_words(ArcCommand(6, 8, 6, 8, helix=(0, 0, 12)))


def random_command(rng):
    kind = rng.randrange(7)
    steps = [rng.randint(-(1 << 20), 1 << 20) if rng.random() < 0.7 else 0 for _ in range(rng.randint(2, 6))]
    if kind == 0:
        return LineCommand(steps[0], steps[1], rng.random() < 0.5)
    if kind == 1:
        return AxesLineCommand(tuple(steps), rng.random() < 0.5)
    if kind == 2:
        u, v = rng.sample(range(6), 2)
        helix = tuple(0 if axis in (u, v) else s for axis, s in enumerate(steps))
        return ArcCommand(*(rng.randint(-999, 999) for _ in range(4)), rng.random() < 0.5, rng.randrange(4),
                          rng.randrange(32), rng.randrange(32), rng.random() < 0.5, (u, v), helix,
                          rng.randrange(1, 1 << 49) if any(helix) else None)
    if kind == 3:
        return PulseCommand(tuple(steps))
    if kind == 4:
        return SetCommand("FEED_RATE", rng.randrange(1, 32768))
    if kind == 5:
        return DwellCommand(rng.randrange(1 << 32))
    return MarkCommand(rng.randrange(1 << 16))


def same_meaning(a, b):
    """Commands that move the same: per-axis tuples compared with their zeros dropped at the end."""
    def trimmed(values):
        values = list(values)
        while len(values) > 2 and values[-1] == 0:
            values.pop()
        return tuple(values)
    if isinstance(a, (AxesLineCommand, LineCommand)):
        return isinstance(b, (AxesLineCommand, LineCommand)) and trimmed(_deltas(a)) == trimmed(_deltas(b)) \
            and a.blend == b.blend
    if isinstance(a, PulseCommand):
        return trimmed(a.counts) == trimmed(b.counts)
    if isinstance(a, ArcCommand):
        helix = trimmed(a.helix) if any(a.helix) else ()
        return b == ArcCommand(a.xs, a.ys, a.xe, a.ye, a.ccw, a.variant, a.lambda_shift, a.acc_bits, a.blend,
                               a.plane, helix, a.area if helix else None)
    return a == b


def _deltas(command):
    return (command.dx, command.dy) if isinstance(command, LineCommand) else command.deltas


@pytest.mark.parametrize("seed", range(3))
def test_decode_reads_back_what_the_encoder_wrote(seed):
    rng = random.Random(seed)
    commands = [random_command(rng) for _ in range(300)]
    decoded = decode_words(stream_words(commands))
    assert len(decoded) == len(commands)
    for original, back in zip(commands, decoded):
        assert same_meaning(original, back), (original, back)
        assert command_words(back) == command_words(original)


@pytest.mark.parametrize("header, names", [
    ({}, ("DX", "DY")), ({"AXES": 0b11}, ("DX", "DY")), ({"AXES": 0b100100}, ("DZ", "DC")),
])
def test_line_operands_follow_the_axes_field(header, names):
    assert isa.operand_names("LINE", header) == names


def test_arc_operands_follow_the_helix_field():
    assert isa.operand_names("ARC", {"U_AXIS": 2}) == ("XS", "YS", "XE", "YE")
    assert isa.operand_names("ARC", {"HELIX": 0b1100}) == ("XS", "YS", "XE", "YE", "AREA_LO", "AREA_HI", "DZ",
                                                             "DA")


def test_the_longest_command_and_the_two_axis_table_the_card_in_gen_decodes():
    # an arc with a helix on the four axes outside its plane: header, four, AREA_LO, AREA_HI, four
    assert isa.MAX_WORDS == 11 and isa.max_words(isa.BY_NAME["ARC"]) == 11
    assert isa.MAX_OPERANDS == 4  # the two-axis form: what rtl/regs/sequencer.py holds
    assert isa.BY_NAME["LINE"].header_mask == 0xF << 28 | BLEND
    assert isa.BY_NAME["LINE"].axis_header_mask == 0xF << 28 | BLEND | 0x3F << 20


@pytest.mark.parametrize("words, message", [
    ([0xF << 28], "BAD_OPCODE"),
    ([LINE | 1 << 26, 1, 2], "RESERVED_BITS"),
    ([LINE | 0b111 << 20, 1, 2], "needs 3 operands"),
    ([ARC | 0b100 << 20, 1, 0, 0, 1, 5, 0], "needs 7 operands"),
])
def test_a_stream_that_cannot_be_framed_is_refused(words, message):
    with pytest.raises(ValueError, match=message):
        decode_words(words)


def test_encode_refuses_a_wrong_operand_count_and_a_field_too_wide():
    with pytest.raises(ValueError, match="takes 3 operands"):
        isa.encode("LINE", 1, 2, AXES=0b111)
    with pytest.raises(ValueError, match="does not fit 3 bits"):
        isa.encode("ARC", 1, 0, 0, 1, U_AXIS=8)
