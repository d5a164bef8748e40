"""What the sequencer of a card of more than two axes hands on from an N-axis command's operands."""
from myhdl import Signal, always_comb, always_seq, block, concat, intbv

from models import instructions as isa
from models.axes import XY_MASK
from models.helix_area import area_width
from rtl.regs.operand_register import signed_low

ARC = isa.BY_NAME["ARC"]
AREA_SLOT = len(ARC.fixed_operands)   # ARC's AREA_LO, AREA_HI: the operand registers after XS .. YE
AXIS_SLOT = AREA_SLOT + len(ARC.axis_operands.lead)   # axis i's displacement or count: AXIS_SLOT + i


def area_operand_bits(coord_width):
    """The bits the AREA_LO and AREA_HI registers keep: W's ``area_width`` bits, AREA_LO's 32 first."""
    bits = area_width(coord_width)
    return min(32, bits), max(1, bits - 32)


@block
def axis_operands(clock, reset, word, arriving, header_in, operand_in, position, operands, axes_cmd, pulses,
                  clear_area, clear_axes, bad_helix):
    """The N-axis operands of a card of more than two axes (``axes_cmd.axes``),
    as the sequencer (``rtl/regs/sequencer.py``) keeps them: XS .. YE in
    operand registers 0..3, ARC's AREA_LO and AREA_HI in registers
    ``AREA_SLOT`` and the one after, and the displacement (LINE, ARC's
    HELIX) or count (PULSE) of axis i in register ``AXIS_SLOT + i``
    (``command_header`` gives these slots).

    Ports: ``word`` (the FIFO's output), ``arriving`` (``CommandHeader``:
    ``word`` read as a header), ``header_in`` (a header arrives in
    ``word``), ``operand_in`` (an operand arrives), ``position`` (its
    index + 1), ``operands`` (the registers), ``axes_cmd`` (out: the plane,
    taken with the header; each axis's displacement and the AREA, read
    with the DDA's start; ``largest``, a LINE's largest |displacement|: the
    largest magnitude of the command's operands, each registered as it
    arrives (``arrived``) and compared with the largest so far the clock
    after: final in the second clock after the last operand's, the first
    in which the sequencer can give the start), ``pulses`` (out: each axis's count, and the mask
    of a PULSE, taken with its header), ``clear_area`` (out: an ARC header
    clears the AREA registers: no helix), ``clear_axes`` (out: a LINE, ARC
    or PULSE header clears the axes' registers: an axis it does not name
    moves by 0), ``bad_helix`` (out: an ARC's helix breaks the RANGE rules
    on its operands: AREA_LO or AREA_HI with a bit above W's
    ``area_width``, or AREA 0 with a helix displacement;
    ``models.dda_axes.check_move``).

        word        ==X=ARC hdr=X=XS=X ... X=AREA_LO=X=AREA_HI=X=DZ=X
        header_in   __/~~~~~~~\\_____________________________________
        bad_helix   ____________________________________________/~~~     AREA 0

        word        =X=hdr=X==DX=X==DY=X==DZ=X=====X=====
        arrived     =X=====X=====X=|DX|X=|DY|X=|DZ|X=====
        largest     =X=====X==0==X==0==X==a==X==b==X==c==    a = |DX|, c = max |d|
        dda.start   _______________________________/~~~~~\\   at the earliest
    """
    axes = axes_cmd.axes
    width = len(axes_cmd.delta(0))
    area_bits = len(axes_cmd.area)
    low_bits, high_bits = area_operand_bits(width)
    area_low, area_high = operands[AREA_SLOT], operands[AREA_SLOT + 1]
    mask_lsb = next(lsb for name, lsb, _, _ in ARC.axis_fields if name == "HELIX")
    opcode_of = {op.name: op.code for op in isa.OPCODES}
    line_op, arc_op, pulse_op = opcode_of["LINE"], opcode_of["ARC"], opcode_of["PULSE"]
    is_arc = Signal(bool(0))
    magnitude, arrived = Signal(intbv(0)[width:]), Signal(intbv(0)[width:])
    comparing = Signal(bool(0))
    # the arriving word's bits above what its AREA register keeps (zero tests only: the word comes
    # from the FIFO's block RAM late in the clock)
    low_beyond, high_beyond = Signal(bool(0)), Signal(bool(0))
    deltas = [signed_low(operands[AXIS_SLOT + axis], axes_cmd.delta(axis)) for axis in range(axes)]
    counts = [signed_low(operands[AXIS_SLOT + axis], pulses.count(axis)) for axis in range(axes)]

    @always_comb
    def clearing():
        clear_area.next = header_in and word[32:isa.OPCODE_LSB] == arc_op
        clear_axes.next = header_in and (word[32:isa.OPCODE_LSB] == line_op or word[32:isa.OPCODE_LSB] == arc_op
                                         or word[32:isa.OPCODE_LSB] == pulse_op)

    if area_bits > 32:
        @always_comb
        def hand_on():
            axes_cmd.area.next = concat(area_high, area_low)

        @always_comb
        def area_fits():
            low_beyond.next = False
            high_beyond.next = word[32:high_bits] != 0
    else:
        @always_comb
        def hand_on():
            axes_cmd.area.next = area_low

        @always_comb
        def area_fits():
            low_beyond.next = word[32:low_bits] != 0
            high_beyond.next = word != 0

    @always_comb
    def arriving_magnitude():
        # |the arriving word| as a coordinate (a word that does not fit is refused anyway)
        if word[width - 1]:
            magnitude.next = -word[width:].signed()
        else:
            magnitude.next = word[width:]

    @always_seq(clock.posedge, reset=reset)
    def take_header():
        if header_in:
            axes_cmd.u.next = arriving.u
            axes_cmd.v.next = arriving.v
            is_arc.next = word[32:isa.OPCODE_LSB] == arc_op
            bad_helix.next = 0
            if word[32:isa.OPCODE_LSB] == pulse_op:
                pulses.mask.next = XY_MASK
                if word[mask_lsb + axes:mask_lsb] != 0:
                    pulses.mask.next = word[mask_lsb + axes:mask_lsb]
        elif operand_in and is_arc:
            # AREA's words fit W's bits; a helix displacement needs an AREA (taken before it) not 0
            if position == AREA_SLOT + 1 and low_beyond:
                bad_helix.next = 1
            if position == AREA_SLOT + 2 and high_beyond:
                bad_helix.next = 1
            if position > AXIS_SLOT and axes_cmd.area == 0:
                bad_helix.next = 1

    @always_seq(clock.posedge, reset=reset)
    def keep_largest():
        # one comparison a clock: the arriving operand's magnitude is registered first
        comparing.next = operand_in
        if operand_in:
            arrived.next = magnitude
        if header_in:
            axes_cmd.largest.next = 0
        elif comparing and arrived > axes_cmd.largest:
            axes_cmd.largest.next = arrived

    return deltas, counts, clearing, hand_on, area_fits, arriving_magnitude, take_header, keep_largest
