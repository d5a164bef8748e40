"""The command words the host writes into the data FIFO, described once.

Every command is a header word followed by operand words.  Header: opcode in
bits 31:28, opcode-specific fields below, every other bit must be 0.  The
sequencer (``rtl/regs/sequencer.py``) decodes from these constants, the host
benches encode with ``encode``, ``docs/instructions.md`` and the C header
are written from them.

Two forms (docs/axes.md):

* the two-axis form: ``Opcode.header_fields`` and ``Opcode.operands`` (a
  fixed number of words, ``MAX_OPERANDS`` at most), which the card in
  ``gen/`` decodes;
* the N-axis form adds ``Opcode.axis_fields`` (LINE.AXES, ARC.U_AXIS,
  V_AXIS, HELIX, PULSE.AXES) and operands that follow an axis mask
  (``Opcode.axis_operands``): ``operand_names`` lists a header's operands.
  With every axis field 0 it is the two-axis form, word for word.  The
  card frames every command by this form (``rtl/regs/command_header.py``)
  and refuses what its axes cannot run with RANGE (docs/axes.md).
"""
from dataclasses import dataclass

from models.axes import AXIS_NAMES, MAX_AXES, XY_MASK, axes_of

OPCODE_LSB = 28


@dataclass(frozen=True)
class AxisOperands:
    """Operands that follow the axis mask in header field ``field``: one per
    axis whose bit is set, ascending, named ``prefix`` + the axis name;
    ``lead``: operands before them, present only when the mask is not 0;
    ``zero_mask``: the axes a mask of 0 stands for (0: none, no operands);
    ``builder``: the name of the C builder that takes them as an array."""
    field: str
    prefix: str
    zero_mask: int
    builder: str
    lead: tuple = ()
    others: int = 0  # axes the mask can never hold (the plane's two, for HELIX)


@dataclass(frozen=True)
class Opcode:
    name: str
    code: int
    operands: tuple  # names of the operand words of the two-axis form, in order
    header_fields: tuple  # (name, lsb, width, text) of the two-axis form
    text: str
    axis_fields: tuple = ()  # (name, lsb, width, text) the N-axis form adds
    axis_operands: AxisOperands = None

    @property
    def header_mask(self):
        """The bits of the two-axis form's fields (and the opcode)."""
        return _mask(self.header_fields)

    @property
    def axis_header_mask(self):
        """The bits of every field of the N-axis form (and the opcode)."""
        return _mask(self.fields)

    @property
    def fields(self):
        """Every header field, the two-axis form's first."""
        return self.header_fields + self.axis_fields

    @property
    def fixed_operands(self):
        """The operands every header has (the rest follow the axis mask)."""
        if self.axis_operands is None:
            return self.operands
        return self.operands[:len(self.operands) - len(axes_of(self.axis_operands.zero_mask))]


def _mask(fields):
    mask = 0xF << OPCODE_LSB
    for _, lsb, width, _ in fields:
        mask |= ((1 << width) - 1) << lsb
    return mask


BLEND_FIELD = ("BLEND", 16, 1, "1: go on into the next LINE/ARC at speed; 0: slow down to RAMP_START "
               "at the end of this move")
AXIS_MASK_LSB, AXIS_MASK_WIDTH = 20, MAX_AXES
AXIS_INDEX_WIDTH = 3
_AXIS_BITS = ", ".join(f"{bit} {name}" for bit, name in enumerate(AXIS_NAMES))

OPCODES = (
    Opcode("LINE", 0x1, ("DX", "DY"), (BLEND_FIELD,),
           "straight move by (DX, DY) steps (signed, must fit the coordinate width); N-axis form: by "
           "one displacement per axis in AXES, all axes ending together (docs/axes.md)",
           (("AXES", AXIS_MASK_LSB, AXIS_MASK_WIDTH, f"the axes with a displacement operand, bit i axis i "
             f"({_AXIS_BITS}); 0: X and Y (the two-axis form)"),),
           AxisOperands("AXES", "D", XY_MASK, "line_axes")),
    Opcode("ARC", 0x2, ("XS", "YS", "XE", "YE"),
           (("CCW", 0, 1, "1: counter-clockwise"),
            ("VARIANT", 1, 2, "0 traditional, 1 weighted, 2 improved, 3 precise (a card has the variants it "
                              "was built with, by default improved and precise; another is refused: RANGE)"),
            ("LAMBDA", 3, 5, "weighting factor 2**-LAMBDA"),
            ("ACC_BITS", 8, 5, "paper variants: accumulator width n (0: normalised to the radius)"),
            BLEND_FIELD),
           "arc about the centre from (XS, YS) to (XE, YE), centre-relative signed steps; N-axis form: "
           "in the plane (U_AXIS, V_AXIS), XS .. YE its (u, v) coordinates, the HELIX axes moving linearly "
           "with the area the arc sweeps, AREA_HI:AREA_LO its total (docs/axes.md)",
           (("U_AXIS", 13, AXIS_INDEX_WIDTH, "the plane's first axis u (U_AXIS = V_AXIS = 0: X, Y, the "
             "two-axis form); CCW turns from +u towards +v"),
            ("V_AXIS", 17, AXIS_INDEX_WIDTH, "the plane's second axis v (not u)"),
            ("HELIX", AXIS_MASK_LSB, AXIS_MASK_WIDTH, f"the axes that move linearly with the arc, bit i "
             f"axis i ({_AXIS_BITS}; not u or v); 0: none, no AREA")),
           AxisOperands("HELIX", "D", 0, "arc_helix", lead=("AREA_LO", "AREA_HI"), others=2)),
    Opcode("PULSE", 0x3, ("COUNT_X", "COUNT_Y"), (),
           "direct pulses: signed counts per axis at PULSE_PERIOD_X / _Y, both axes at once; N-axis form: "
           "one count per axis in AXES, at that axis's PULSE_PERIOD",
           (("AXES", AXIS_MASK_LSB, AXIS_MASK_WIDTH, f"the axes with a count operand, bit i axis i "
             f"({_AXIS_BITS}); 0: X and Y (the two-axis form)"),),
           AxisOperands("AXES", "COUNT_", XY_MASK, "pulse_axes")),
    Opcode("SET", 0x4, ("VALUE",), (("INDEX", 0, 4, "which register (SET index in docs/registers.md)"),),
           "write VALUE into a register at this point of the stream (clamped like a bus write)"),
    Opcode("DWELL", 0x5, ("CLOCKS",), (), "wait CLOCKS clocks (32-bit) before the next command"),
    Opcode("MARK", 0x6, (), (("TAG", 0, 16, "copied into MARK_TAG"),),
           "set INT_STATUS.MARK and MARK_TAG when reached"),
)

# operands that are signed steps (the others, SET's VALUE, DWELL's CLOCKS and ARC's AREA, are unsigned)
SIGNED_OPERANDS = (("XS", "YS", "XE", "YE") + tuple(f"D{name}" for name in AXIS_NAMES)
                   + tuple(f"COUNT_{name}" for name in AXIS_NAMES))
MAX_OPERANDS = max(len(op.operands) for op in OPCODES)  # of the two-axis form
BY_NAME = {op.name: op for op in OPCODES}
BY_CODE = {op.code: op for op in OPCODES}

# Error codes (STATUS.ERROR).
ERRORS = (
    (0, "NONE", "no error"),
    (1, "BAD_OPCODE", "the header's opcode is not in the table (CLEAR_ERROR then empties the FIFO)"),
    (2, "RESERVED_BITS", "a header bit outside the opcode's fields is set"),
    (3, "RANGE", "an operand does not fit (coordinate outside the DDA's width, SET index unknown), "
                 "an ARC's VARIANT is not built into this card, or an axis field names an axis the card "
                 "does not have or breaks the N-axis form's rules (docs/axes.md)"),
    (4, "DDA_REJECTED", "the DDA refused the arc (end not on the circle, radius too large)"),
)
ERROR_CODE = {name: code for code, name, _ in ERRORS}


def opcode(name):
    """The ``Opcode`` called ``name``."""
    try:
        return BY_NAME[name]
    except KeyError:
        raise ValueError(f"unknown command {name}") from None


def operand_names(op, header=None):
    """The operand words of ``op`` (an ``Opcode`` or its name) with the header
    fields ``header`` ({field: value}; missing fields are 0), in order."""
    op = opcode(op) if isinstance(op, str) else op
    spec = op.axis_operands
    mask = (header or {}).get(spec.field, 0) if spec else 0
    if not mask:
        return op.operands
    return op.fixed_operands + spec.lead + tuple(spec.prefix + AXIS_NAMES[i] for i in axes_of(mask))


def max_words(op):
    """The most words a command ``op`` has in the N-axis form (header included)."""
    spec = op.axis_operands
    if spec is None:
        return 1 + len(op.operands)
    return 1 + len(op.fixed_operands) + len(spec.lead) + MAX_AXES - spec.others


MAX_WORDS = max(max_words(op) for op in OPCODES)  # of the N-axis form, header included


def encode(name, *operands, **header):
    """The words of command ``name``: header then operands (masked to 32 bits).

    ``header`` may hold the N-axis form's fields too; the operands are then
    those ``operand_names`` lists.  Only widths are checked here: whether the
    axes exist on a card, and the rest of the card's RANGE rules, are the
    card's (``models.dda_axes.check_move``)."""
    op = opcode(name)
    wanted = operand_names(op, header)
    if len(operands) != len(wanted):
        raise ValueError(f"{name} takes {len(wanted)} operands ({', '.join(wanted) or 'none'}) with this "
                         f"header, got {len(operands)}")
    word = op.code << OPCODE_LSB
    fields = {f[0]: f for f in op.fields}
    for key, value in header.items():
        if key not in fields:
            raise ValueError(f"{name} has no header field {key}")
        _, lsb, width, _ = fields[key]
        if not 0 <= value < (1 << width):
            raise ValueError(f"{name}.{key} = {value} does not fit {width} bits")
        word |= value << lsb
    return [word] + [value & 0xFFFFFFFF for value in operands]


def header_fields_of(word):
    """(``Opcode``, {field: value} of every field of the N-axis form) of a header
    word; ValueError for an unknown opcode or a bit outside the fields."""
    op = BY_CODE.get(word >> OPCODE_LSB)
    if op is None:
        raise ValueError(f"BAD_OPCODE: header {word:#010x}")
    if word & ~op.axis_header_mask & 0xFFFFFFFF:
        raise ValueError(f"RESERVED_BITS: {op.name} header {word:#010x}")
    return op, {name: word >> lsb & ((1 << width) - 1) for name, lsb, width, _ in op.fields}


def split_words(words):
    """[(``Opcode``, {field: value}, [operands])] of a word stream framed by the
    N-axis form; signed operands as Python ints.  ValueError for a bad header
    or a stream that ends inside a command."""
    commands, index = [], 0
    while index < len(words):
        op, fields = header_fields_of(words[index])
        names = operand_names(op, fields)
        operands = words[index + 1:index + 1 + len(names)]
        if len(operands) < len(names):
            raise ValueError(f"{op.name} at word {index} needs {len(names)} operands, the stream ends")
        commands.append((op, fields, [_signed(v) if n in SIGNED_OPERANDS else v for n, v in zip(names, operands)]))
        index += 1 + len(names)
    return commands


def _signed(word):
    return word - (1 << 32) if word >> 31 else word


def _axis_operand_text(op):
    spec = op.axis_operands
    choices = ", ".join(spec.prefix + name for name in AXIS_NAMES[:-1]) + f" or {spec.prefix}{AXIS_NAMES[-1]}"
    per_axis = f"{choices} for each {spec.field} bit, ascending"
    if spec.zero_mask:
        return f"{', '.join(op.operands)}; N-axis: {per_axis}"
    return f"{', '.join(op.operands)}; N-axis, {spec.field} not 0: then {', '.join(spec.lead)}, {per_axis}"


def markdown():
    """``docs/instructions.md`` (encoding part)."""
    lines = ["## Encoding", "",
             "Generated from `models/instructions.py`.  Opcode in header bits 31:28; header bits",
             "outside the listed fields must be 0.  The N-axis form's fields and operands",
             "([axes.md](axes.md)) are marked N-axis; with those fields 0 a command is the",
             "two-axis form.  The card frames every command by the N-axis form.", "",
             "| opcode | name | header fields | operand words | meaning |",
             "| --- | --- | --- | --- | --- |"]
    for op in OPCODES:
        fields = ", ".join(f"{n} [{lsb + w - 1}:{lsb}]" for n, lsb, w, _ in op.header_fields) or "-"
        if op.axis_fields:
            fields += "; N-axis: " + ", ".join(f"{n} [{lsb + w - 1}:{lsb}]" for n, lsb, w, _ in op.axis_fields)
        operands = _axis_operand_text(op) if op.axis_operands else ", ".join(op.operands) or "-"
        lines.append(f"| {op.code:#x} | {op.name} | {fields} | {operands} | {op.text} |")
    lines += ["", "Header fields:", ""]
    for op in OPCODES:
        for n, lsb, w, text in op.header_fields:
            lines.append(f"- {op.name}.{n}: {text}")
        for n, lsb, w, text in op.axis_fields:
            lines.append(f"- {op.name}.{n} (N-axis): {text}")
    lines += ["", "## Error codes (STATUS.ERROR)", "", "| code | name | meaning |", "| --- | --- | --- |"]
    lines += [f"| {code} | {name} | {text} |" for code, name, text in ERRORS]
    return "\n".join(lines) + "\n"
