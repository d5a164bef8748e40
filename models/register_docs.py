"""``docs/registers.md`` and the C header's register part, made from the
register table (``models/registers.py``); ``python -m models.register_docs``
rewrites the docs."""
from pathlib import Path

from models import instructions
from models.axes import AXIS_NAMES
from models.registers import (AXIS_BLOCK_BASE, AXIS_FREE, AXIS_REGISTERS, AXIS_STRIDE, BAR0_AXES, ENCODER_REGISTERS,
                              IO_BAR_BITS, REG_BAR_BITS, REGISTERS, VERSION, VERSIONS, axis_offset, axis_register,
                              build_word, in_bar0)

ALL_BAR0 = tuple(sorted(REGISTERS + ENCODER_REGISTERS, key=lambda r: r.offset))


def _text(reg):
    """The register's description, with the build option it needs."""
    return reg.text if reg.option is None else f"{reg.text} (a build with {reg.option} only)"


def markdown():
    """``docs/registers.md``."""
    lines = [
        "# Function registers (I/O BAR0, memory BAR2)",
        "",
        "Generated from `models/registers.py` by `python -m models.register_docs`; do not edit.",
        "",
        f"The I/O BAR (BAR0) is {1 << IO_BAR_BITS} bytes (`io_bar_bits` = {IO_BAR_BITS}); registers are",
        "32-bit, dword aligned.  Unlisted offsets read 0 and ignore writes.  BAR2, a",
        f"32-bit non-prefetchable memory BAR of {(1 << REG_BAR_BITS) // 1024} KiB, holds the same registers at the",
        "same offsets with the same behaviour (byte enables, clamping, write 1 to clear, read",
        "side effects), for hosts without port I/O, and after them the per-axis register",
        "blocks (below: [Per-axis register blocks](#per-axis-register-blocks-bar2)); a burst into",
        "it moves one dword and is disconnected (docs/pci.md).",
        "",
        "CLOCK_HZ, FIFO_SIZE and BUILD hold the parameters the card was built with",
        "(`python -m rtl.top --help` lists them); their reset column shows the default build's",
        "top, `gen/top.v`, built for iCE40 (the generic `gen/card.v` reads BUILD.DEVICE = 0).",
        "",
        f"ID.VERSION is {_version(VERSION)}: the major version (bits 15:8) changes when a",
        "register or field moves or changes meaning, the minor version (bits 7:0) when",
        "registers or fields are added:",
        "",
        *(f"- {_version(number)}: {text}" for number, text in VERSIONS),
        "",
        "Access: RO read only; RW read/write (byte enables honoured; a value outside",
        "min..max is clamped to the nearest bound, reads back clamped, and sets",
        "INT_STATUS.CLAMPED); W1C write 1 to clear; W1S write 1 to set; WP write",
        "pulse (the write acts once, reads return the hardware's value).",
        "",
        "Registers marked \"a build with encoders only\" exist on a card built with the build",
        "parameter `encoders` (BUILD.ENCODERS = 1, `python -m rtl.top --convert --encoders`); a card",
        "without reads 0 there and ignores writes, as at every unlisted offset.",
        "",
        "| offset | name | access | reset | min | max | SET index | description |",
        "| --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for reg in ALL_BAR0:
        lines.append(
            f"| {reg.offset:#04x} | {reg.name} | {reg.access} | {reg.reset:#x} | "
            f"{_blank(reg.minimum)} | {_blank(reg.maximum)} | {_blank(reg.set_index)} | {_text(reg)} |")
    lines.append("")
    for reg in ALL_BAR0:
        lines += [f"## {reg.name} ({reg.offset:#04x}, {reg.access})", "", _text(reg), "",
                  "| bits | field | description |", "| --- | --- | --- |"]
        lines += [_field_row(item) for item in reg.fields]
        lines.append("")
    return "\n".join(lines + _axis_markdown())


def _axis_markdown():
    """The per-axis blocks' part of ``docs/registers.md``."""
    lines = [
        "## Per-axis register blocks (BAR2)",
        "",
        f"Every axis the card has (BUILD.AXES; {', '.join(AXIS_NAMES)} are axes 0 to {len(AXIS_NAMES) - 1}) has a block of",
        f"registers in BAR2 at {AXIS_BLOCK_BASE:#05x} + {AXIS_STRIDE:#04x} * axis (`DDA_AXIS_BLOCK_BASE`,",
        "`DDA_AXIS_STRIDE`, `DDA_AXIS_<REG>_OFFSET(axis)` in `gen/dda_card.h`); the offsets below are",
        "inside the block.  The blocks of X and Y hold BAR0's own registers where BAR0 has them (the",
        "same flip-flops, reached at both offsets, with the same side effects): " + ", ".join(
            f"{spec.name} = {'/'.join(axis_register(spec.name, axis).name for axis in range(BAR0_AXES))}"
            for spec in AXIS_REGISTERS if in_bar0(spec.name)) + ".",
        "The other block registers (" + ", ".join(spec.name for spec in AXIS_REGISTERS if not in_bar0(spec.name))
        + ") are the blocks' only, for every axis, named <REG>_X, <REG>_Y, <REG>_Z, ...; the blocks",
        "of Z, A, B and C are BAR2's only (the I/O BAR keeps to PCI's 256 bytes).",
        "A block offset no register uses, and the block of an axis the build lacks, read 0",
        "and ignore writes, as every unlisted offset does; block offset " + ", ".join(
            f"{free:#04x}" for free in AXIS_FREE) + " is kept for the axis's homing registers, the rest",
        "for more.",
        "",
        "Positions at one instant: a read of X's POS (POS_X, in BAR0 or at",
        f"{axis_offset('POS', 0):#05x}) returns X's position and captures every other axis's in the same",
        "clock; POS of Y, Z, ... (POS_Y included) read what that read captured.  Read X's",
        "first, then the others.",
        "",
        "| block offset | name | access | reset | min | max | description |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for reg in AXIS_REGISTERS:
        lines.append(f"| {reg.offset:#04x} | {reg.name} | {reg.access} | {reg.reset:#x} | {_blank(reg.minimum)} | "
                     f"{_blank(reg.maximum)} | {_text(reg)} |")
    lines += ["", "| axis | block | " + " | ".join(reg.name for reg in AXIS_REGISTERS) + " |",
              "| --- | --- | " + " | ".join("---" for _ in AXIS_REGISTERS) + " |"]
    for axis, name in enumerate(AXIS_NAMES):
        cells = [f"{axis_offset(reg.name, axis):#05x} ({axis_register(reg.name, axis).name})" for reg in AXIS_REGISTERS]
        lines.append(f"| {axis} {name} | {AXIS_BLOCK_BASE + AXIS_STRIDE * axis:#05x} | " + " | ".join(cells) + " |")
    lines.append("")
    for reg in AXIS_REGISTERS:
        lines += [f"### {reg.name} (block {reg.offset:#04x}, {reg.access})", "", _text(reg), "",
                  "| bits | field | description |", "| --- | --- | --- |"]
        lines += [_field_row(item) for item in reg.fields]
        lines.append("")
    return lines


def _field_row(item):
    bits = f"{item.lsb + item.width - 1}:{item.lsb}" if item.width > 1 else f"{item.lsb}"
    kind = " (signed)" if item.signed else ""
    if item.cleared is not None:
        kind += f"; cleared by the hardware {item.cleared}"
    return f"| {bits} | {item.name} | {item.text}{kind} |"


def _version(number):
    return f"{number >> 8}.{number & 0xFF}"


def _blank(value):
    return "" if value is None else str(value)


def c_header(prefix="DDA", extra="", values=None):
    """The C header with offsets, field masks and shifts, the SET indexes and
    the clamping bounds (``_MIN``, ``_MAX``) (``extra``: more
    definitions placed inside the include guard); the ``_RESET`` values are
    those of a card built with ``values`` (build parameters; default: the
    defaults)."""
    guard = f"{prefix}_REGISTERS_H"
    lines = [
        "/* Host interface of the PCI DDA card: function registers (I/O BAR0, memory BAR2) and more.",
        " * Generated from rtl/ by python -m rtl.top --convert; do not edit. */",
        f"#ifndef {guard}",
        f"#define {guard}",
        "",
        f"#define {prefix}_IO_BAR_SIZE {1 << IO_BAR_BITS}u",
        "",
    ]
    for reg in ALL_BAR0:
        name = f"{prefix}_{reg.name}"
        if reg.option is not None:
            lines.append(f"/* {reg.name}: a build with {reg.option} only ({prefix}_BUILD_{reg.option.upper()}) */")
        lines.append(f"#define {name} 0x{reg.offset:02X}u")
        lines.append(f"#define {name}_RESET 0x{build_word(reg, values or {}):08X}u")
        for item in reg.fields:
            lines.append(f"#define {name}_{item.name}_SHIFT {item.lsb}u")
            lines.append(f"#define {name}_{item.name}_MASK 0x{item.mask:08X}u")
        if reg.set_index is not None:
            lines.append(f"#define {name}_SET_INDEX {reg.set_index}u")
        if reg.minimum is not None:
            # a write outside MIN..MAX is clamped (and flags INT_STATUS.CLAMPED)
            lines.append(f"#define {name}_MIN ({reg.minimum})")
            lines.append(f"#define {name}_MAX ({reg.maximum})")
        lines.append("")
    lines += _axis_c_lines(prefix)
    if extra:
        lines += [extra.rstrip("\n"), ""]
    lines += [f"#endif /* {guard} */", ""]
    return "\n".join(lines)


def _axis_c_lines(prefix):
    """The per-axis blocks' C macros: the block's place, and per register its
    offset inside the block, ``_OFFSET(axis)`` in BAR2, reset, fields, bounds."""
    name = f"{prefix}_AXIS"
    lines = ["/* Per-axis register blocks, BAR2 only: axis i (0 X, 1 Y, 2 Z, 3 A, 4 B, 5 C; BUILD.AXES of them)",
             " * at BLOCK_BASE + STRIDE * i.  X's and Y's hold BAR0's registers where BAR0 has them",
             " * (POS = POS_X / POS_Y, ...); ENC_* and the rest are the blocks' only (builds with encoders).",
             " * A read of X's POS captures the other axes' POS: read it first. */",
             f"#define {name}_BLOCK_BASE 0x{AXIS_BLOCK_BASE:03X}u",
             f"#define {name}_STRIDE 0x{AXIS_STRIDE:02X}u",
             f"#define {name}_BLOCK(axis) ({name}_BLOCK_BASE + {name}_STRIDE * (unsigned)(axis))", ""]
    for reg in AXIS_REGISTERS:
        reg_name = f"{name}_{reg.name}"
        note = "" if reg.option is None else f"; a build with {reg.option} only"
        lines += [f"#define {reg_name} 0x{reg.offset:02X}u /* inside the block{note} */",
                  f"#define {reg_name}_OFFSET(axis) ({name}_BLOCK(axis) + {reg_name})",
                  f"#define {reg_name}_RESET 0x{reg.reset:08X}u"]
        for item in reg.fields:
            lines += [f"#define {reg_name}_{item.name}_SHIFT {item.lsb}u",
                      f"#define {reg_name}_{item.name}_MASK 0x{item.mask:08X}u"]
        if reg.minimum is not None:
            lines += [f"#define {reg_name}_MIN ({reg.minimum})", f"#define {reg_name}_MAX ({reg.maximum})"]
        lines.append("")
    return lines


DOCS_BEGIN = "<!-- generated from models/instructions.py: begin -->"
DOCS_END = "<!-- generated from models/instructions.py: end -->"


def refreshed_instructions_doc(text):
    """``docs/instructions.md`` with its generated part replaced by the current table."""
    head, rest = text.split(DOCS_BEGIN, 1)
    _, tail = rest.split(DOCS_END, 1)
    return f"{head}{DOCS_BEGIN}\n{instructions.markdown()}{DOCS_END}{tail}"


def write_docs(docs_dir):
    """Write ``registers.md`` and refresh the generated part of ``instructions.md``."""
    docs_dir = Path(docs_dir)
    (docs_dir / "registers.md").write_text(markdown() + "\n")
    guide = docs_dir / "instructions.md"
    guide.write_text(refreshed_instructions_doc(guide.read_text()))


if __name__ == "__main__":
    write_docs(Path(__file__).resolve().parent.parent / "docs")
