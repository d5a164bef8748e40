"""What the sequencer of a card of more than two axes hands on from an N-axis command's operands."""
from myhdl import Signal, always_comb, always_seq, block, concat, intbv

from models import instructions as isa
from models.axes import XY_MASK
from rtl.regs.operand_register import signed_low

ARC = isa.BY_NAME["ARC"]
ITERATIONS_SLOT = len(ARC.fixed_operands)   # ARC's ITERATIONS: the operand register after XS .. YE
AXIS_SLOT = ITERATIONS_SLOT + len(ARC.axis_operands.lead)   # axis i's displacement or count: AXIS_SLOT + i


@block
def axis_operands(clock, reset, word, arriving, header_in, operand_in, position, operands, axes_cmd, pulses,
                  clear_iterations, clear_axes, bad_helix):
    """The N-axis operands of a card of more than two axes (``axes_cmd.axes``),
    as the sequencer (``rtl/regs/sequencer.py``) keeps them: XS .. YE in
    operand registers 0..3, ARC's ITERATIONS in register ``ITERATIONS_SLOT``,
    and the displacement (LINE, ARC's HELIX) or count (PULSE) of axis i in
    register ``AXIS_SLOT + i`` (``command_header`` gives these slots).

    Ports: ``word`` (the FIFO's output), ``arriving`` (``CommandHeader``:
    ``word`` read as a header), ``header_in`` (a header arrives in
    ``word``), ``operand_in`` (an operand arrives), ``position`` (its
    index + 1), ``operands`` (the registers), ``axes_cmd`` (out: the plane,
    taken with the header; each axis's displacement and ITERATIONS, read
    with the DDA's start; ``largest``, a LINE's largest |displacement|: the
    largest magnitude of the command's operands, each registered as it
    arrives (``arrived``) and compared with the largest so far the clock
    after: final in the second clock after the last operand's, the first
    in which the sequencer can give the start), ``pulses`` (out: each axis's count, and the mask
    of a PULSE, taken with its header), ``clear_iterations`` (out: an ARC
    header clears the ITERATIONS register: no helix), ``clear_axes`` (out: a
    LINE, ARC or PULSE header clears the axes' registers: an axis it does
    not name moves by 0), ``bad_helix`` (out: an ARC's helix breaks the RANGE rules
    on its operands: ITERATIONS 0, or an axis moving more steps than
    ITERATIONS; ``models.dda_axes.check_move``).

        word        ==X=ARC hdr=X=XS=X ... X=ITER=X=DZ=X
        header_in   __/~~~~~~~\\_____________________
        bad_helix   ____________________________/~~~     |DZ| > ITER

        word        =X=hdr=X==DX=X==DY=X==DZ=X=====X=====
        arrived     =X=====X=====X=|DX|X=|DY|X=|DZ|X=====
        largest     =X=====X==0==X==0==X==a==X==b==X==c==    a = |DX|, c = max |d|
        dda.start   _______________________________/~~~~~\\   at the earliest
    """
    axes = axes_cmd.axes
    width = len(axes_cmd.delta(0))
    iterations = operands[ITERATIONS_SLOT]
    mask_lsb = next(lsb for name, lsb, _, _ in ARC.axis_fields if name == "HELIX")
    opcode_of = {op.name: op.code for op in isa.OPCODES}
    line_op, arc_op, pulse_op = opcode_of["LINE"], opcode_of["ARC"], opcode_of["PULSE"]
    is_arc = Signal(bool(0))
    magnitude, arrived = Signal(intbv(0)[width:]), Signal(intbv(0)[width:])
    comparing, steeper = Signal(bool(0)), Signal(bool(0))
    # |w| > K for the arriving word w, by comparisons of its bits (read unsigned: u) with K's low bits,
    # never of a sum or a negation: the word comes from the FIFO's block RAM late in the clock.
    # K >= 2^width: no word is steeper.  Else w >= 0: u > K; w < 0 (u = w + 2^width): K + w < 0,
    # that is u <= 2^width - 1 - K, the low bits of K inverted.
    k_small, k_inverted = Signal(bool(0)), Signal(intbv(0)[width:])
    above_k, above_inverted = Signal(bool(0)), Signal(bool(0))
    deltas = [signed_low(operands[AXIS_SLOT + axis], axes_cmd.delta(axis)) for axis in range(axes)]
    counts = [signed_low(operands[AXIS_SLOT + axis], pulses.count(axis)) for axis in range(axes)]

    @always_comb
    def clearing():
        clear_iterations.next = header_in and word[32:isa.OPCODE_LSB] == arc_op
        clear_axes.next = header_in and (word[32:isa.OPCODE_LSB] == line_op or word[32:isa.OPCODE_LSB] == arc_op
                                         or word[32:isa.OPCODE_LSB] == pulse_op)

    @always_comb
    def hand_on():
        axes_cmd.iterations.next = iterations

    @always_comb
    def arriving_magnitude():
        # |the arriving word| as a coordinate (a word that does not fit is refused anyway)
        if word[width - 1]:
            magnitude.next = -word[width:].signed()
        else:
            magnitude.next = word[width:]

    @always_comb
    def helix_bounds():
        k_small.next = iterations[len(iterations):width] == 0
        k_inverted.next = ~iterations[width:]

    @always_comb
    def helix_compares():
        above_k.next = word[width:] > iterations[width:]
        above_inverted.next = word[width:] > k_inverted

    @always_comb
    def helix_steeper():
        if word[width - 1]:
            steeper.next = k_small and not above_inverted
        else:
            steeper.next = k_small and above_k

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
        elif operand_in and is_arc and position > AXIS_SLOT:
            # a helix displacement: ITERATIONS (taken before it) is not 0 and at least its magnitude
            if iterations == 0 or steeper:
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

    return (deltas, counts, clearing, hand_on, arriving_magnitude, helix_bounds, helix_compares, helix_steeper, take_header,
            keep_largest)
