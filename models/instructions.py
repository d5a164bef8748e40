"""The command words the host writes into the data FIFO, described once.

Every command is a header word followed by a fixed number of operand words.
Header: opcode in bits 31:28, opcode-specific fields below, every other bit
must be 0.  The sequencer (``rtl/regs/sequencer.py``) decodes from these
constants, the host benches encode with ``encode``, ``docs/instructions.md``
and the C header are written from them.
"""
from dataclasses import dataclass

OPCODE_LSB = 28


@dataclass(frozen=True)
class Opcode:
    name: str
    code: int
    operands: tuple  # names of the operand words, in order
    header_fields: tuple  # (name, lsb, width, text)
    text: str

    @property
    def header_mask(self):
        mask = 0xF << OPCODE_LSB
        for _, lsb, width, _ in self.header_fields:
            mask |= ((1 << width) - 1) << lsb
        return mask


BLEND_FIELD = ("BLEND", 16, 1, "1: go on into the next LINE/ARC at speed; 0: slow down to RAMP_START "
               "at the end of this move")

OPCODES = (
    Opcode("LINE", 0x1, ("DX", "DY"), (BLEND_FIELD,),
           "straight move by (DX, DY) steps (signed, must fit the coordinate width)"),
    Opcode("ARC", 0x2, ("XS", "YS", "XE", "YE"),
           (("CCW", 0, 1, "1: counter-clockwise"),
            ("VARIANT", 1, 2, "0 traditional, 1 weighted, 2 improved, 3 precise (a card has the variants it "
                              "was built with, by default improved and precise; another is refused: RANGE)"),
            ("LAMBDA", 3, 5, "weighting factor 2**-LAMBDA"),
            ("ACC_BITS", 8, 5, "paper variants: accumulator width n (0: normalised to the radius)"),
            BLEND_FIELD),
           "arc about the centre from (XS, YS) to (XE, YE), centre-relative signed steps"),
    Opcode("PULSE", 0x3, ("COUNT_X", "COUNT_Y"), (),
           "direct pulses: signed counts per axis at PULSE_PERIOD_X / _Y, both axes at once"),
    Opcode("SET", 0x4, ("VALUE",), (("INDEX", 0, 4, "which register (SET index in docs/registers.md)"),),
           "write VALUE into a register at this point of the stream (clamped like a bus write)"),
    Opcode("DWELL", 0x5, ("CLOCKS",), (), "wait CLOCKS clocks (32-bit) before the next command"),
    Opcode("MARK", 0x6, (), (("TAG", 0, 16, "copied into MARK_TAG"),),
           "set INT_STATUS.MARK and MARK_TAG when reached"),
)

# operands that are signed steps (the others, SET's VALUE and DWELL's CLOCKS, are unsigned)
SIGNED_OPERANDS = ("DX", "DY", "XS", "YS", "XE", "YE", "COUNT_X", "COUNT_Y")
MAX_OPERANDS = max(len(op.operands) for op in OPCODES)
BY_NAME = {op.name: op for op in OPCODES}
BY_CODE = {op.code: op for op in OPCODES}

# Error codes (STATUS.ERROR).
ERRORS = (
    (0, "NONE", "no error"),
    (1, "BAD_OPCODE", "the header's opcode is not in the table (CLEAR_ERROR then empties the FIFO)"),
    (2, "RESERVED_BITS", "a header bit outside the opcode's fields is set"),
    (3, "RANGE", "an operand does not fit (coordinate outside the DDA's width, SET index unknown), "
                 "or an ARC's VARIANT is not built into this card"),
    (4, "DDA_REJECTED", "the DDA refused the arc (end not on the circle, radius too large)"),
)
ERROR_CODE = {name: code for code, name, _ in ERRORS}


def encode(name, *operands, **header):
    """The words of command ``name``: header then operands (masked to 32 bits)."""
    try:
        op = BY_NAME[name]
    except KeyError:
        raise ValueError(f"unknown command {name}") from None
    if len(operands) != len(op.operands):
        raise ValueError(f"{name} takes {len(op.operands)} operands, got {len(operands)}")
    word = op.code << OPCODE_LSB
    fields = {f[0]: f for f in op.header_fields}
    for key, value in header.items():
        if key not in fields:
            raise ValueError(f"{name} has no header field {key}")
        _, lsb, width, _ = fields[key]
        if not 0 <= value < (1 << width):
            raise ValueError(f"{name}.{key} = {value} does not fit {width} bits")
        word |= value << lsb
    return [word] + [value & 0xFFFFFFFF for value in operands]


def markdown():
    """``docs/instructions.md`` (encoding part)."""
    lines = ["## Encoding", "",
             "Generated from `models/instructions.py`.  Opcode in header bits 31:28; header bits",
             "outside the listed fields must be 0.", "",
             "| opcode | name | header fields | operand words | meaning |",
             "| --- | --- | --- | --- | --- |"]
    for op in OPCODES:
        fields = ", ".join(f"{n} [{lsb + w - 1}:{lsb}]" for n, lsb, w, _ in op.header_fields) or "-"
        operands = ", ".join(op.operands) or "-"
        lines.append(f"| {op.code:#x} | {op.name} | {fields} | {operands} | {op.text} |")
    lines += ["", "Header fields:", ""]
    for op in OPCODES:
        for n, lsb, w, text in op.header_fields:
            lines.append(f"- {op.name}.{n}: {text}")
    lines += ["", "## Error codes (STATUS.ERROR)", "", "| code | name | meaning |", "| --- | --- | --- |"]
    lines += [f"| {code} | {name} | {text} |" for code, name, text in ERRORS]
    return "\n".join(lines) + "\n"


def c_defines(prefix="DDA"):
    """C ``#define`` lines for opcodes, header fields and error codes."""
    lines = [f"#define {prefix}_OPCODE_SHIFT {OPCODE_LSB}u"]
    for op in OPCODES:
        lines.append(f"#define {prefix}_CMD_{op.name} 0x{op.code:X}u")
        lines.append(f"#define {prefix}_CMD_{op.name}_OPERANDS {len(op.operands)}u")
        lines.append(f"#define {prefix}_CMD_{op.name}_WORDS {1 + len(op.operands)}u")
        for n, lsb, w, _ in op.header_fields:
            lines.append(f"#define {prefix}_CMD_{op.name}_{n}_SHIFT {lsb}u")
            lines.append(f"#define {prefix}_CMD_{op.name}_{n}_MASK 0x{((1 << w) - 1) << lsb:08X}u")
    for code, name, _ in ERRORS:
        lines.append(f"#define {prefix}_ERROR_{name} {code}u")
    return "\n".join(lines) + "\n"


def c_builders(prefix="DDA"):
    """C ``static inline`` command builders, one per opcode, as ``encode`` builds them.

    ``<prefix>_cmd_<name>(words, operands..., header fields...)`` writes the
    header and the operand words into ``words`` and returns their number
    (``<prefix>_CMD_<NAME>_WORDS``), or returns 0 and writes nothing when a
    header field does not fit its width.
    """
    lines = ["#include <stdint.h>", "",
             "/* Command builders: each writes a command's words (header, then operands) into",
             " * words[] and returns how many; it returns 0 and writes nothing when a header",
             " * field does not fit its width.  Signed operands are steps (two's complement). */"]
    for op in OPCODES:
        macro = f"{prefix}_CMD_{op.name}"
        params = [f"uint32_t words[{macro}_WORDS]"]
        params += [f"{'int32_t' if name in SIGNED_OPERANDS else 'uint32_t'} {name.lower()}" for name in op.operands]
        params += [f"uint32_t {name.lower()}" for name, _, _, _ in op.header_fields]
        checks = " || ".join(f"{name.lower()} > 0x{(1 << width) - 1:X}u" for name, _, width, _ in op.header_fields)
        header = " | ".join([f"({macro} << {prefix}_OPCODE_SHIFT)"] + [
            f"({name.lower()} << {macro}_{name}_SHIFT)" for name, _, _, _ in op.header_fields])
        lines += ["", f"/* {op.name}: {op.text}. */",
                  f"static inline unsigned {prefix.lower()}_cmd_{op.name.lower()}(" + ",\n    ".join(params) + ")",
                  "{"]
        if checks:
            lines.append(f"    if ({checks})\n        return 0u;")
        lines.append(f"    words[0] = {header};")
        lines += [f"    words[{index + 1}] = (uint32_t){name.lower()};" for index, name in enumerate(op.operands)]
        lines += [f"    return {macro}_WORDS;", "}"]
    return "\n".join(lines) + "\n"
