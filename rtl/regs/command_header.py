"""A command's header word read as the sequencer needs it: framing, checks and the plane."""
from myhdl import ConcatSignal, Signal, always_comb, block, concat, intbv

from models import instructions as isa
from models.axes import XY_MASK, axes_of
from rtl.regs.axis_operands import AREA_SLOT, AXIS_SLOT
from rtl.regs.instruction_tables import opcode_rom


def _axis_field(op_name, field_name):
    for name, lsb, width, _ in isa.BY_NAME[op_name].axis_fields:
        if name == field_name:
            return lsb, lsb + width
    raise ValueError(f"{op_name} has no axis field {field_name}")


def _zero_mask_operands(op):
    spec = op.axis_operands
    return len(axes_of(spec.zero_mask)) if spec else 0


def _fewest_operands(op):
    """The fewest operands a header of ``op`` frames: its axis mask 0, or one axis in it."""
    spec = op.axis_operands
    return len(op.fixed_operands) + (min(_zero_mask_operands(op), len(spec.lead) + 1) if spec else 0)


@block
def command_header(word, header):
    """Reads the header word ``word`` (32 bits, the FIFO's output) into
    ``header`` (``CommandHeader``), combinationally: the sequencer keeps
    what it needs in the clock the word arrives.

    Framing by the N-axis form (``models/instructions.py``,
    ``operand_names``): the fixed operands, then for an axis mask (LINE.AXES,
    PULSE.AXES, ARC.HELIX at the same bits) of 0 the operands it stands for
    (LINE, PULSE: two), otherwise the lead operands (ARC: AREA_LO, AREA_HI) and one
    per axis in the mask.  So a stream the host's encoder writes is framed
    whatever the card does with it.

    RANGE (``out_of_range``, docs/axes.md): a LINE axis the card
    (``header.axes``) lacks; an ARC plane axis it lacks, or U_AXIS = V_AXIS
    other than 0/0, or on a card of two axes a plane other than X, Y; a HELIX
    axis the card lacks or that is u or v (on a card of two axes every HELIX
    axis); a PULSE axis the card lacks.  The rules on a helix's operands are the
    sequencer's (``rtl/regs/axis_operands.py``).  The plane ``u``, ``v``:
    U_AXIS, V_AXIS, or X, Y when both are 0.  ``slots``: the operand
    registers its operands go to (the sequencer puts each into the lowest
    slot left): on a card of two axes a LINE's or PULSE's axes (0: X and
    Y), all ones otherwise; on more axes XS .. YE in slots 0..3, AREA_LO, AREA_HI in 4, 5 and an
    axis i's displacement or count in 6 + i (``axis_operands``).

        word      ==X=ARC hdr=X=XS=X=YS=X ...
        operands  ==X====4====X==?=X ...       valid while word is a header
    """
    axes, slot_count = header.axes, header.slot_count
    mask_lsb, mask_msb = _axis_field("LINE", "AXES")
    for name in ("PULSE", "ARC"):
        if isa.BY_NAME[name].axis_operands.field != ("AXES" if name == "PULSE" else "HELIX"):
            raise ValueError(f"{name}'s axis operands follow an unexpected field")
    if _axis_field("PULSE", "AXES") != (mask_lsb, mask_msb) or _axis_field("ARC", "HELIX") != (mask_lsb, mask_msb):
        raise ValueError("LINE.AXES, PULSE.AXES and ARC.HELIX must share their bits")
    u_lsb, u_msb = _axis_field("ARC", "U_AXIS")
    v_lsb, v_msb = _axis_field("ARC", "V_AXIS")
    mask_width = mask_msb - mask_lsb
    known = opcode_rom(lambda op: 1)
    moves = opcode_rom(lambda op: int(op.name in ("LINE", "ARC")))
    fixed = opcode_rom(lambda op: len(op.fixed_operands))
    has_mask = opcode_rom(lambda op: int(op.axis_operands is not None))
    zero_mask = opcode_rom(_zero_mask_operands)
    lead = opcode_rom(lambda op: len(op.axis_operands.lead) if op.axis_operands else 0)
    some = opcode_rom(lambda op: int(_fewest_operands(op) > 0))
    code = {op.name: op.code for op in isa.OPCODES}
    line_op, arc_op, pulse_op = code["LINE"], code["ARC"], code["PULSE"]
    index_bits = len(header.u)
    all_slots = (1 << slot_count) - 1
    ones_in = tuple(bin(mask).count("1") for mask in range(1 << mask_width))
    beyond = ((1 << mask_width) - 1) & ~((1 << axes) - 1)   # the mask bits of axes the card lacks
    xy_only = axes == 2   # a card of two axes turns arcs in X, Y only (models.dda_axes.check_move)
    # a card of more axes: XS .. YE, AREA_LO, AREA_HI, then one slot per axis (rtl/regs/axis_operands.py)
    arc_slots = (1 << AREA_SLOT) - 1
    xy_slots = XY_MASK << AXIS_SLOT
    helix_slots = (1 << AXIS_SLOT) - 1   # XS .. YE and AREA
    plane_axes = Signal(intbv(0)[axes:])
    helix_on_plane = Signal(bool(0))

    fixed_count, zero_count, lead_count, ones = (Signal(intbv(0)[4:]) for _ in range(4))
    has_axes = Signal(bool(0))
    lookups = [_lookup(word(32, isa.OPCODE_LSB), rom, signal)
               for rom, signal in ((fixed, fixed_count), (zero_mask, zero_count), (lead, lead_count),
                                   (has_mask, has_axes), (known, header.known), (moves, header.moves), (some, header.has_operands))]
    lookups.append(_lookup(word(mask_msb, mask_lsb), ones_in, ones))

    @always_comb
    def frame():
        header.operands.next = fixed_count
        if has_axes:
            if word[mask_msb:mask_lsb] == 0:
                header.operands.next = fixed_count + zero_count
            else:
                header.operands.next = fixed_count + lead_count + ones

    if xy_only:   # a card of two axes turns arcs in X, Y only: no plane to read, no helix
        @always_comb
        def check_axes():
            header.out_of_range.next = False
            if word[32:isa.OPCODE_LSB] == line_op or word[32:isa.OPCODE_LSB] == pulse_op:
                header.out_of_range.next = (word[mask_msb:mask_lsb] & beyond) != 0
            elif word[32:isa.OPCODE_LSB] == arc_op:
                header.out_of_range.next = (word[u_msb:u_lsb] >= axes or word[v_msb:v_lsb] >= axes
                                            or (word[u_msb:u_lsb] == word[v_msb:v_lsb] and word[u_msb:u_lsb] != 0)
                                            or word[mask_msb:mask_lsb] != 0
                                            or (xy_only and word[u_msb:u_lsb] != 0))

        @always_comb
        def slots():
            header.slots.next = all_slots
            if word[32:isa.OPCODE_LSB] == line_op or word[32:isa.OPCODE_LSB] == pulse_op:
                if word[mask_msb:mask_lsb] == 0:
                    header.slots.next = XY_MASK
                else:
                    header.slots.next = word[mask_lsb + slot_count:mask_lsb]

        checks = [check_axes, slots]
    else:
        @always_comb
        def check_axes_n():
            header.out_of_range.next = False
            if word[32:isa.OPCODE_LSB] == line_op or word[32:isa.OPCODE_LSB] == pulse_op:
                header.out_of_range.next = (word[mask_msb:mask_lsb] & beyond) != 0
            elif word[32:isa.OPCODE_LSB] == arc_op:
                header.out_of_range.next = (word[u_msb:u_lsb] >= axes or word[v_msb:v_lsb] >= axes
                                            or (word[u_msb:u_lsb] == word[v_msb:v_lsb] and word[u_msb:u_lsb] != 0)
                                            or (word[mask_msb:mask_lsb] & beyond) != 0 or helix_on_plane)

        @always_comb
        def slots_n():
            header.slots.next = all_slots
            if word[32:isa.OPCODE_LSB] == line_op or word[32:isa.OPCODE_LSB] == pulse_op:
                if word[mask_msb:mask_lsb] == 0:
                    header.slots.next = xy_slots
                else:
                    header.slots.next = concat(word[mask_lsb + axes:mask_lsb], intbv(0)[AXIS_SLOT:])
            elif word[32:isa.OPCODE_LSB] == arc_op:
                header.slots.next = arc_slots
                if word[mask_msb:mask_lsb] != 0:
                    header.slots.next = concat(word[mask_lsb + axes:mask_lsb], intbv(helix_slots)[AXIS_SLOT:])

        @always_comb
        def plane():
            header.u.next = word[u_lsb + index_bits:u_lsb]
            header.v.next = word[v_lsb + index_bits:v_lsb]
            if word[u_msb:u_lsb] == 0 and word[v_msb:v_lsb] == 0:
                header.v.next = 1

        @always_comb
        def helix_plane():
            # a HELIX axis that is the plane's u or v
            helix_on_plane.next = (word[mask_lsb + axes:mask_lsb] & plane_axes) != 0

        # the plane's axes as a mask, by (V_AXIS, U_AXIS): X, Y for 0, 0
        plane_rom = tuple(((1 << (index & 7)) | (1 << (index >> 3)) if index else XY_MASK) & ((1 << axes) - 1)
                          for index in range(64))
        checks = [check_axes_n, slots_n, plane, helix_plane,
                  _lookup(ConcatSignal(word(v_msb, v_lsb), word(u_msb, u_lsb)), plane_rom, plane_axes)]
    return lookups, frame, checks, _reserved_bits(word, header.reserved)


@block
def _reserved_bits(word, reserved):
    """``reserved``: ``word`` read as a header sets a bit its opcode's form does not
    have (``axis_header_mask``; every bit but the opcode's own for an unknown one).

    The bits are grouped by the opcodes that allow them (the header's bit
    classes: the opcode, BLEND, LINE's and PULSE's AXES, ARC's fields, SET's
    INDEX, MARK's TAG, never-used bits), so the test is one OR of each class's
    bits and one opcode lookup per class instead of one per bit."""
    allowed_by = tuple(opcode_rom(lambda op, bit=bit: (op.axis_header_mask >> bit) & 1) for bit in range(32))
    classes = {}
    for bit, allowed in enumerate(allowed_by):
        classes.setdefault(allowed, []).append(bit)
    flags = [Signal(bool(0)) for _ in classes]
    units = [_reserved_class(word, bits, tuple(1 - a for a in allowed), flag)
             for (allowed, bits), flag in zip(classes.items(), flags)]
    any_flag = ConcatSignal(*flags) if len(flags) > 1 else flags[0]

    @always_comb
    def either():
        reserved.next = any_flag != 0

    return units, either


@block
def _reserved_class(word, bits, refused, flag):
    """``flag``: ``word`` sets one of ``bits`` (bit indices) and its opcode refuses them
    (``refused``, by opcode)."""
    refusing = Signal(bool(0))
    members = ConcatSignal(*(word(bit) for bit in bits)) if len(bits) > 1 else word(bits[0])

    @always_comb
    def look_up():
        refusing.next = refused[word[32:isa.OPCODE_LSB]]

    @always_comb
    def test():
        flag.next = refusing and members != 0

    return look_up, test


@block
def _lookup(index, rom, value):
    """``value`` is ``rom[index]`` (a case statement)."""

    @always_comb
    def look_up():
        value.next = rom[index]

    return look_up
