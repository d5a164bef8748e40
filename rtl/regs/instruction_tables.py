"""What the sequencer reads of the instruction set (``models/instructions.py``)
while it is built: per-opcode tables made into case statements, the header
fields' bits, the most operands a header frames; and ``fits_width``, the
check that an arriving operand fits a width."""
from myhdl import always_comb, block

from models import instructions as isa


def opcode_rom(value_of):
    """A 16-entry tuple, indexed by opcode, converted to a case statement."""
    return tuple(value_of(isa.BY_CODE[code]) if code in isa.BY_CODE else 0 for code in range(16))


def operand_mask(op, kind):
    """Bit i: operand i of ``op`` is ``kind`` ("coord": signed steps of a move,
    "count": a PULSE count), whatever the axis mask (the longest form)."""
    spec = op.axis_operands
    names = isa.operand_names(op, {spec.field: (1 << isa.AXIS_MASK_WIDTH) - 1}) if spec else op.operands
    is_kind = (lambda name: name.startswith("COUNT_")) if kind == "count" else (
        lambda name: name in isa.SIGNED_OPERANDS and not name.startswith("COUNT_"))
    return sum(1 << i for i, name in enumerate(names) if is_kind(name))


# the most operand words a header frames: the fixed ones, the lead ones and one per bit of a full axis mask
OPERANDS_MAX = max(len(op.fixed_operands) + (len(op.axis_operands.lead) + isa.AXIS_MASK_WIDTH
                                             if op.axis_operands else 0) for op in isa.OPCODES)


def header_field(op_name, field_name):
    for name, lsb, width, _ in isa.BY_NAME[op_name].header_fields:
        if name == field_name:
            return lsb, lsb + width
    raise ValueError(f"{op_name} has no field {field_name}")


@block
def fits_width(operand, fits, width):
    """``fits``: the 32-bit ``operand`` is a ``width``-bit signed number (its top
    bits are copies of bit ``width - 1``)."""
    ones = (1 << (33 - width)) - 1

    @always_comb
    def sign_extension():
        fits.next = operand[32:width - 1] == 0 or operand[32:width - 1] == ones

    return sign_extension
