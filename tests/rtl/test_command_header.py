"""``rtl/regs/command_header.py`` against the instruction table's own reading of a header
(``models.instructions.header_fields_of`` and ``operand_names``): which words are known,
which set a reserved bit, and how many operand words follow, on cards of two and three axes.

The words are seeded: every opcode value (the six commands and the unknown ones) with
random low bits, each bit outside the opcode's form set alone, and the command's own
fields at random, so every class of header bit is tried with every opcode."""
import random

import pytest
from myhdl import Signal, block, delay, instance, intbv

from models import instructions as isa
from rtl.interfaces import CommandHeader
from rtl.regs.axis_operands import AXIS_SLOT
from rtl.regs.command_header import command_header
from rtl.regs.instruction_tables import OPERANDS_MAX


def _words(seed):
    rng = random.Random(seed)
    words = []
    for code in range(16):
        head = code << isa.OPCODE_LSB
        words += [head, head | rng.getrandbits(isa.OPCODE_LSB)]
        op = isa.BY_CODE.get(code)
        if op is None:
            continue
        allowed = op.axis_header_mask & ((1 << isa.OPCODE_LSB) - 1)
        words += [head | (rng.getrandbits(isa.OPCODE_LSB) & allowed) for _ in range(8)]
        words += [head | (rng.getrandbits(isa.OPCODE_LSB) & allowed) | 1 << bit
                  for bit in range(isa.OPCODE_LSB) if not allowed >> bit & 1]
    return words


def _expected(word):
    """(known, reserved, operand words) as the instruction table reads ``word``."""
    op = isa.BY_CODE.get(word >> isa.OPCODE_LSB)
    if op is None:
        return False, None, None
    reserved = bool(word & ~op.axis_header_mask & 0xFFFFFFFF)
    fields = {name: word >> lsb & ((1 << width) - 1) for name, lsb, width, _ in op.fields}
    return True, reserved, len(isa.operand_names(op, fields))


@block
def _bench(words, axes, seen):
    word = Signal(intbv(0)[32:])
    header = CommandHeader(axes, 4 if axes == 2 else AXIS_SLOT + axes, OPERANDS_MAX)
    unit = command_header(word, header)

    @instance
    def drive():
        for value in words:
            word.next = value
            yield delay(1)
            seen.append((bool(header.known), bool(header.reserved), int(header.operands)))

    return unit, drive


@pytest.mark.parametrize("axes, seed", [(2, 3), (3, 4)])
def test_header_reading_matches_the_instruction_table(axes, seed):
    words, seen = _words(seed), []
    _bench(words, axes, seen).run_sim(quiet=True)
    for word, (known, reserved, operands) in zip(words, seen, strict=True):
        want_known, want_reserved, want_operands = _expected(word)
        assert known == want_known, f"{word:#010x}"
        if want_known:   # an unknown opcode is BAD_OPCODE whatever else the word holds
            assert (reserved, operands) == (want_reserved, want_operands), f"{word:#010x}"
