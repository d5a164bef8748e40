"""What the sequencer of a two-axis card hands on from a command's operands."""
from myhdl import Signal, always_comb, always_seq, block

from models import instructions as isa
from models.axes import XY_MASK


@block
def two_axis_operands(clock, reset, word, header_in, operands, pulses, line_in):
    """The operands of a two-axis card's commands as the sequencer
    (``rtl/regs/sequencer.py``) keeps them in its four operand registers: an
    ARC's XS .. YE in 0..3, a LINE's or PULSE's X and Y in 0 and 1.

    Ports: ``word`` (the FIFO's output), ``header_in`` (a header arrives in
    ``word``), ``operands`` (the registers), ``pulses`` (out: a PULSE's
    counts from registers 0 (X) and 1 (Y), and its AXES mask taken with its
    header: AXES 0, the two-axis form, is X and Y; bits beyond Y are RANGE,
    ``command_header``), ``line_in`` (out: a LINE header arrives: it clears
    registers 0 and 1, so an axis it does not name moves by 0).

        word        ==X=PULSE hdr=X=count X=X=count Y=X
        header_in   __/~~~~~~~~~~~\\_____________________
        pulses.mask ==============X=AXES (or X|Y)========
    """
    axes = pulses.axes
    count_bits = len(pulses.count_x)
    line_op, pulse_op = isa.BY_NAME["LINE"].code, isa.BY_NAME["PULSE"].code
    mask_lsb = next(lsb for name, lsb, _, _ in isa.BY_NAME["PULSE"].axis_fields if name == "AXES")
    x_word, y_word = operands[:2]
    pulse_in = Signal(bool(0))

    @always_comb
    def headers():
        line_in.next = header_in and word[32:isa.OPCODE_LSB] == line_op
        pulse_in.next = header_in and word[32:isa.OPCODE_LSB] == pulse_op

    @always_seq(clock.posedge, reset=reset)
    def pulse_axes():
        if pulse_in:
            pulses.mask.next = XY_MASK
            if word[mask_lsb + axes:mask_lsb] != 0:
                pulses.mask.next = word[mask_lsb + axes:mask_lsb]

    @always_comb
    def pulse_counts():
        pulses.count_x.next = x_word[count_bits:].signed()
        pulses.count_y.next = y_word[count_bits:].signed()

    return headers, pulse_axes, pulse_counts
