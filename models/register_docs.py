"""``docs/registers.md`` and the C header's register part, made from the
register table (``models/registers.py``); ``python -m models.register_docs``
rewrites the docs."""
from pathlib import Path

from models import instructions
from models.registers import IO_BAR_BITS, REGISTERS, VERSION, VERSIONS, build_word


def markdown():
    """``docs/registers.md``."""
    lines = [
        "# Function registers (I/O BAR0, memory BAR2)",
        "",
        "Generated from `models/registers.py` by `python -m models.register_docs`; do not edit.",
        "",
        f"The I/O BAR (BAR0) is {1 << IO_BAR_BITS} bytes (`io_bar_bits` = {IO_BAR_BITS}); registers are",
        "32-bit, dword aligned.  Unlisted offsets read 0 and ignore writes.  BAR2, a",
        "32-bit non-prefetchable memory BAR of the same size, holds the same registers at the",
        "same offsets with the same behaviour (byte enables, clamping, write 1 to clear, read",
        "side effects), for hosts without port I/O; a burst into it moves one dword and is",
        "disconnected (docs/pci.md).",
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
        "| offset | name | access | reset | min | max | SET index | description |",
        "| --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for reg in REGISTERS:
        lines.append(
            f"| {reg.offset:#04x} | {reg.name} | {reg.access} | {reg.reset:#x} | "
            f"{_blank(reg.minimum)} | {_blank(reg.maximum)} | {_blank(reg.set_index)} | {reg.text} |")
    lines.append("")
    for reg in REGISTERS:
        lines += [f"## {reg.name} ({reg.offset:#04x}, {reg.access})", "", reg.text, "",
                  "| bits | field | description |", "| --- | --- | --- |"]
        for item in reg.fields:
            bits = f"{item.lsb + item.width - 1}:{item.lsb}" if item.width > 1 else f"{item.lsb}"
            kind = " (signed)" if item.signed else ""
            if item.cleared is not None:
                kind += f"; cleared by the hardware {item.cleared}"
            lines.append(f"| {bits} | {item.name} | {item.text}{kind} |")
        lines.append("")
    return "\n".join(lines)


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
    for reg in REGISTERS:
        name = f"{prefix}_{reg.name}"
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
    if extra:
        lines += [extra.rstrip("\n"), ""]
    lines += [f"#endif /* {guard} */", ""]
    return "\n".join(lines)


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
