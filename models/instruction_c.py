"""The command set in C (``gen/dda_card.h``): defines and builders, from ``models/instructions.py``.

``c_defines`` gives the opcodes, header fields (both forms), word counts,
axis indices and error codes; ``c_builders`` one builder per opcode for the
two-axis form (``dda_cmd_line``, ...) and one per opcode with axis operands
for the N-axis form (``dda_cmd_line_axes``, ``dda_cmd_arc_helix``,
``dda_cmd_pulse_axes``), each giving the words ``instructions.encode`` gives.
"""
from models.axes import AXIS_NAMES, MAX_AXES, axes_of, names
from models.instructions import ERRORS, MAX_WORDS, OPCODE_LSB, OPCODES, SIGNED_OPERANDS, max_words


def c_defines(prefix="DDA"):
    """C ``#define`` lines for axes, opcodes, header fields and error codes."""
    lines = [f"#define {prefix}_AXES_MAX {MAX_AXES}u /* axis index i: {' '.join(AXIS_NAMES)} */"]
    lines += [f"#define {prefix}_AXIS_{name} {index}u" for index, name in enumerate(AXIS_NAMES)]
    lines += [f"#define {prefix}_OPCODE_SHIFT {OPCODE_LSB}u",
              f"#define {prefix}_CMD_MAX_WORDS {MAX_WORDS}u /* the longest command of the N-axis form */"]
    for op in OPCODES:
        lines.append(f"#define {prefix}_CMD_{op.name} 0x{op.code:X}u")
        lines.append(f"#define {prefix}_CMD_{op.name}_OPERANDS {len(op.operands)}u")
        lines.append(f"#define {prefix}_CMD_{op.name}_WORDS {1 + len(op.operands)}u")
        if op.axis_operands:
            lines.append(f"#define {prefix}_CMD_{op.name}_MAX_WORDS {max_words(op)}u")
        for n, lsb, w, _ in op.fields:
            lines.append(f"#define {prefix}_CMD_{op.name}_{n}_SHIFT {lsb}u")
            lines.append(f"#define {prefix}_CMD_{op.name}_{n}_MASK 0x{((1 << w) - 1) << lsb:08X}u")
    for code, name, _ in ERRORS:
        lines.append(f"#define {prefix}_ERROR_{name} {code}u")
    return "\n".join(lines) + "\n"


def _operand_type(name):
    return "int32_t" if name in SIGNED_OPERANDS else "uint32_t"


def _checks(fields):
    return " || ".join(f"{name.lower()} > 0x{(1 << width) - 1:X}u" for name, _, width, _ in fields)


def _header(prefix, op, fields):
    macro = f"{prefix}_CMD_{op.name}"
    return " | ".join([f"({macro} << {prefix}_OPCODE_SHIFT)"] + [
        f"({name.lower()} << {macro}_{name}_SHIFT)" for name, _, _, _ in fields])


def _plain(prefix, op, params, body):
    lines = ["", f"/* {op.name}: {op.text}. */",
             f"static inline unsigned {prefix.lower()}_cmd_{op.name.lower()}(" + ",\n    ".join(params) + ")", "{"]
    checks = _checks(op.header_fields)
    if checks:
        lines.append(f"    if ({checks})\n        return 0u;")
    lines.append(f"    words[0] = {_header(prefix, op, op.header_fields)};")
    return lines + body + ["}"]


def _axis_builder(prefix, op):
    """The N-axis builder of ``op``: the axis operands come from an array indexed by axis."""
    spec = op.axis_operands
    macro = f"{prefix}_CMD_{op.name}"
    array = spec.prefix.rstrip("_").lower()
    mask = spec.field.lower()
    others = [f for f in op.fields if f[0] != spec.field]
    params = [f"uint32_t words[{macro}_MAX_WORDS]"]
    params += [f"{_operand_type(name)} {name.lower()}" for name in op.fixed_operands + spec.lead]
    params += [f"uint32_t {mask}", f"const int32_t {array}[{prefix}_AXES_MAX]"]
    params += [f"uint32_t {name.lower()}" for name, _, _, _ in others]
    fields = [f for f in op.fields if f[0] == spec.field] + others
    lines = ["", f"/* {op.name}, N-axis form (docs/axes.md): {array}[i] is axis i's operand, read for the axes",
             f" * in {spec.field} only ({spec.field} = 0: "
             + (f"{names(axes_of(spec.zero_mask))}" if spec.zero_mask else "no axis operands") + "). */",
             f"static inline unsigned {prefix.lower()}_cmd_{spec.builder}(" + ",\n    ".join(params) + ")", "{"]
    chosen = "chosen" if spec.zero_mask else mask
    if spec.zero_mask:
        lines.append(f"    uint32_t chosen = {mask} ? {mask} : 0x{spec.zero_mask:X}u;")
    lines.append("    unsigned length = 1u;")
    lines.append(f"    if ({_checks(fields)})\n        return 0u;")
    lines.append(f"    words[0] = {_header(prefix, op, fields)};")
    lines += [f"    words[length++] = (uint32_t){name.lower()};" for name in op.fixed_operands]
    if spec.lead:
        lines.append(f"    if ({mask} != 0u) {{")
        lines += [f"        words[length++] = (uint32_t){name.lower()};" for name in spec.lead]
        lines.append("    }")
    lines += [f"    for (unsigned axis = 0u; axis < {prefix}_AXES_MAX; axis++)",
              f"        if (({chosen} >> axis) & 1u)",
              f"            words[length++] = (uint32_t){array}[axis];",
              "    return length;", "}"]
    return lines


def c_builders(prefix="DDA"):
    """C ``static inline`` command builders, as ``instructions.encode`` builds the words.

    ``<prefix>_cmd_<name>(words, operands..., header fields...)``: the
    two-axis form; ``<prefix>_cmd_line_axes``, ``_arc_helix``, ``_pulse_axes``
    (words, fixed operands..., mask, array indexed by axis, other header
    fields...): the N-axis form.  Each writes the header and the operand words
    into ``words`` and returns their number, or returns 0 and writes nothing
    when a header field does not fit its width.
    """
    lines = ["#include <stdint.h>", "",
             "/* Command builders: each writes a command's words (header, then operands) into",
             " * words[] and returns how many; it returns 0 and writes nothing when a header",
             " * field does not fit its width.  Signed operands are steps (two's complement). */"]
    for op in OPCODES:
        macro = f"{prefix}_CMD_{op.name}"
        params = [f"uint32_t words[{macro}_WORDS]"]
        params += [f"{_operand_type(name)} {name.lower()}" for name in op.operands]
        params += [f"uint32_t {name.lower()}" for name, _, _, _ in op.header_fields]
        body = [f"    words[{index + 1}] = (uint32_t){name.lower()};" for index, name in enumerate(op.operands)]
        lines += _plain(prefix, op, params, body + [f"    return {macro}_WORDS;"])
    for op in OPCODES:
        if op.axis_operands:
            lines += _axis_builder(prefix, op)
    return "\n".join(lines) + "\n"
