"""Instruction register: fetches commands from the FIFO and executes them."""
from myhdl import Signal, always_comb, always_seq, block, downrange, enum, intbv

from models import instructions as isa
from models.parameters import AXES, COORD_WIDTH
from rtl.interfaces import (AxesCommand, CommandHeader, DdaPort, FifoRead, MarkPort, PulseCommand, SequencerControl,
                            SetPort, card_reset)
from rtl.regs.axis_operands import AREA_SLOT, AXIS_SLOT, area_operand_bits, axis_operands
from rtl.regs.command_header import command_header
from rtl.regs.instruction_tables import OPERANDS_MAX, fits_width, header_field, opcode_rom, operand_mask
from rtl.regs.operand_register import operand_register
from rtl.regs.two_axis_operands import two_axis_operands


@block
def sequencer(clock, reset, fifo, control, dda, axes_cmd, pulses, set_port, mark, *, set_indices=(0,)):
    """Fetch, check and execute the FIFO's commands (``docs/instructions.md``).

    Ports (``rtl/interfaces/``): ``fifo`` (``FifoRead``), ``control``
    (``SequencerControl``), ``dda`` (``DdaPort``), ``axes_cmd``
    (``AxesCommand``: on a card of more than two axes the plane, a LINE's or
    helix's displacements and an ARC's AREA), ``pulses`` (``PulseCommand``), ``set_port``
    (``SetPort``), ``mark`` (``MarkPort``).
    Fetch: the FIFO is read one word per clock (``fifo.pop``; the word
    arrives in ``fifo.dout`` the next clock) into the next-instruction
    register while the current command runs; ``command_header`` frames it
    by the N-axis form (docs/axes.md) and each operand goes to the lowest
    operand register left of those the header names (two axes: a LINE's
    and a PULSE's its axes', a LINE's others are cleared, otherwise in
    order, so a LINE's displacement or a PULSE's count of axis i is in
    register i; more axes: ``axis_operands``'
    slots, XS .. YE, AREA_LO, AREA_HI, then axis i's displacement or count in
    register 6 + i).  Execute: LINE/ARC drive
    ``dda`` (a one-clock ``start`` with the operands and BLEND) as soon as
    the DDA is ``ready``, also while the move before still runs, so chained
    segments leave no gap; PULSE loads the direct pulse generators of its
    axes (``pulses.load``, ``pulses.count_*``, ``pulses.mask``, taken with
    its header: AXES, or X and Y for 0) and waits while ``pulses.busy``;
    DWELL counts clocks once the pulse outputs are quiet
    (``pulses.outputs_busy`` low: no step request pending and the last step
    has left the pins); SET gives a ``set_port.strobe`` with its index and
    value; MARK a ``mark.strobe`` with its tag.  An ARC whose VARIANT the DDA
    was not built with (``dda.variants``) is malformed (RANGE), as is a
    command whose axis fields break the card's rules (``command_header``).
    SET, DWELL, MARK, PULSE and
    a malformed command wait until the motion before them has ended (DDA
    idle, outputs quiet), so a MARK means "reached" and the moves before a
    bad command complete.  A malformed command, or a move the DDA rejects,
    sets ``control.error_code`` and nothing more executes until
    ``control.clear_error``; after BAD_OPCODE the stream cannot be framed
    any more, so ``control.discard_on_clear`` tells the FIFO to empty itself
    on that clear (the fetch restarts at a header).  ``control.enable`` low
    holds the queue; ``control.clear`` (soft reset) drops everything.
    ``control.busy``: something is running or queued;
    ``control.motion_run``: a path is under way (feed-rate ramp; high across
    chained segments).  ARC/LINE operands must fit ``dda.coord_width``,
    PULSE counts ``pulses.count_x``'s width.  Parameter: ``set_indices`` (SET
    indices that exist); the card's axes are ``axes_cmd.axes``.

        clock     _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        fifo_pop  _/~~~~~~~~~~~\\_______________     LINE: 3 words
        next ok   _____________/~~~\\___________
        dda.start _________________/~~~\\_______     (dda.ready high)
    """
    coord_width, count_bits, error_bits = dda.coord_width, len(pulses.count_x), len(control.error_code)
    axes = axes_cmd.axes
    seq_t = enum("S_IDLE", "S_MOTION", "S_PULSE", "S_DWELL", "S_ERROR")
    state = Signal(seq_t.S_IDLE)
    # the instruction register keeps the bits something reads: the opcode, the
    # two-axis form's header fields, the plane, SET's and DWELL's 32-bit operand 0,
    # and of the other operands the coordinate and count bits (their checks read
    # the arriving word); a card of two axes has four operand registers (an ARC's
    # four, a LINE's two), a card of N > 2 axes AXIS_SLOT + N: XS .. YE, an ARC's
    # AREA_LO and AREA_HI, and one per axis for a LINE's or helix's displacement or a PULSE's count
    field_bits = max(lsb + width for op in isa.OPCODES for _, lsb, width, _ in op.header_fields)
    if field_bits > isa.OPCODE_LSB:
        raise ValueError("the header's fields overlap the opcode")
    header = Signal(intbv(0)[field_bits:])
    wide = max(coord_width, count_bits)
    if axes == 2:
        slot_count = len(isa.BY_NAME["ARC"].fixed_operands)
        operands = ([Signal(intbv(0)[32:]), Signal(intbv(0)[wide:])]
                    + [Signal(intbv(0)[coord_width:]) for _ in range(2, slot_count)])
    else:
        slot_count = AXIS_SLOT + axes
        operands = ([Signal(intbv(0)[32:]), Signal(intbv(0)[wide:])]
                    + [Signal(intbv(0)[coord_width:]) for _ in range(2, AREA_SLOT)]
                    + [Signal(intbv(0)[bits:]) for bits in area_operand_bits(coord_width)]
                    + [Signal(intbv(0)[wide:]) for _ in range(axes)])
    operand_0, operand_1, operand_2, operand_3 = operands[:4]
    arriving = CommandHeader(axes, slot_count, OPERANDS_MAX)
    slots_left, slot_taken = Signal(intbv(0)[slot_count:]), Signal(intbv(0)[slot_count:])
    fetched = Signal(intbv(0, min=0, max=OPERANDS_MAX + 1))
    word_due = Signal(bool(0))
    next_valid = Signal(bool(0))
    next_error = Signal(intbv(0)[len(control.error_code):])
    next_motion = Signal(bool(0))
    issue = Signal(bool(0))
    finishing = Signal(bool(0))
    state_over = Signal(bool(0))
    motion_done = Signal(bool(0))
    discard = Signal(bool(0))
    dwell_left = Signal(intbv(0)[32:])
    line_in = Signal(bool(0))

    next_count = Signal(intbv(0, min=0, max=OPERANDS_MAX + 1))
    opcode = Signal(intbv(0)[32 - isa.OPCODE_LSB:])
    # which operands must fit: those the registers keep (a command with more operands is refused anyway)
    coord_mask = Signal(intbv(0)[slot_count:])
    count_mask = Signal(intbv(0)[slot_count:])
    set_known = Signal(bool(0))
    variant_built = Signal(bool(0))  # the arriving header's ARC.VARIANT is one the DDA has
    # the checks, made as the words arrive and kept beside them (no deep logic before the issue)
    bad_opcode, bad_header_bits, bad_set_index, bad_operand, bad_variant, bad_axes = (
        Signal(bool(0)) for _ in range(6))
    # the axis fields' RANGE rules: the header's, and on more than two axes a helix's operands'
    bad_helix = Signal(bool(0))
    bad_fields = bad_axes if axes == 2 else Signal(bool(0))

    arriving_coord_fits, arriving_count_fits = Signal(bool(0)), Signal(bool(0))
    kept = (1 << slot_count) - 1
    coord_operands = opcode_rom(lambda op: operand_mask(op, "coord") & kept)
    count_operands = opcode_rom(lambda op: operand_mask(op, "count") & kept)
    set_ok = tuple(int(i in set_indices) for i in range(1 << len(set_port.index)))
    built = tuple(int(code in dda.variants) for code in range(1 << len(dda.variant)))
    code = {op.name: op.code for op in isa.OPCODES}
    line_op, arc_op, pulse_op, set_op, dwell_op, mark_op = (
        code["LINE"], code["ARC"], code["PULSE"], code["SET"], code["DWELL"], code["MARK"])
    E_NONE, E_BAD_OPCODE, E_RESERVED_BITS, E_RANGE, E_DDA_REJECTED = (
        isa.ERROR_CODE[name] for name in ("NONE", "BAD_OPCODE", "RESERVED_BITS", "RANGE", "DDA_REJECTED"))
    ccw_lsb = header_field("ARC", "CCW")[0]
    blend_lsb = header_field("ARC", "BLEND")[0]
    if header_field("LINE", "BLEND")[0] != blend_lsb:
        raise ValueError("LINE and ARC must have BLEND in the same header bit")
    variant_lsb, variant_msb = header_field("ARC", "VARIANT")
    lambda_lsb, lambda_msb = header_field("ARC", "LAMBDA")
    acc_lsb, acc_msb = header_field("ARC", "ACC_BITS")
    index_lsb, index_msb = header_field("SET", "INDEX")
    tag_lsb, tag_msb = header_field("MARK", "TAG")
    reading = command_header(fifo.dout, arriving)
    # an operand goes to the lowest register left; a LINE header clears those of its card's axes (two
    # axes), an ARC header the AREA registers and a move's or PULSE's header the axes' (more axes)
    clear_area, clear_axes = Signal(bool(0)), Signal(bool(0))
    if axes == 2:
        clears = [line_in if index < axes else None for index in range(slot_count)]
    else:
        clears = [None] * AREA_SLOT + [clear_area] * (AXIS_SLOT - AREA_SLOT) + [clear_axes] * axes
    registers = [operand_register(clock, fifo.dout, slot_taken(index), clear, register)
                 for index, (clear, register) in enumerate(zip(clears, operands))]

    @always_comb
    def lookup_coords():
        coord_mask.next = coord_operands[opcode]

    @always_comb
    def lookup_counts():
        count_mask.next = count_operands[opcode]

    @always_comb
    def lookup_set():
        set_known.next = set_ok[fifo.dout[index_msb:index_lsb]]

    @always_comb
    def lookup_variant():
        variant_built.next = built[fifo.dout[variant_msb:variant_lsb]]

    @always_comb
    def fetch_request():
        more = True
        if word_due:
            if fetched == 0:
                more = arriving.has_operands == 1
            else:
                more = fetched < next_count
        fifo.pop.next = (not fifo.empty and not next_valid and more and not control.clear
                         and state != seq_t.S_ERROR)

    @always_comb
    def operand_routing():
        # the lowest register left takes an arriving operand word; the loop runs whatever the
        # condition, so its variable is assigned in every pass and no tool reads it as a latch
        taken = intbv(0)[slot_count:]
        for index in downrange(slot_count):
            if slots_left[index]:
                taken[:] = 0
                taken[index] = 1
        if not word_due or fetched == 0 or control.clear or discard:
            taken[:] = 0
        slot_taken.next = taken

    @always_comb
    def discarding():
        control.discard_on_clear.next = state == seq_t.S_ERROR and control.error_code == E_BAD_OPCODE
        discard.next = control.clear_error and state == seq_t.S_ERROR and control.error_code == E_BAD_OPCODE

    @always_seq(clock.posedge, reset=reset)
    def fetch():
        word_due.next = fifo.pop
        if control.clear or discard:
            word_due.next = 0
            fetched.next = 0
            next_valid.next = 0
        else:
            if issue:
                next_valid.next = 0
            if word_due:
                if fetched == 0:
                    opcode.next = fifo.dout[32:isa.OPCODE_LSB]
                    header.next = fifo.dout[field_bits:]
                    next_motion.next = arriving.moves
                    next_count.next = arriving.operands
                    slots_left.next = arriving.slots
                    bad_opcode.next = not arriving.known
                    bad_header_bits.next = arriving.reserved
                    bad_axes.next = arriving.out_of_range
                    bad_set_index.next = fifo.dout[32:isa.OPCODE_LSB] == set_op and not set_known
                    bad_variant.next = fifo.dout[32:isa.OPCODE_LSB] == arc_op and not variant_built
                    bad_operand.next = 0
                    if not arriving.has_operands:
                        next_valid.next = 1
                    else:
                        fetched.next = 1
                else:
                    slots_left.next = slots_left & ~slot_taken
                    if fetched <= slot_count and ((coord_mask[fetched - 1] and not arriving_coord_fits)
                                                  or (count_mask[fetched - 1] and not arriving_count_fits)):
                        bad_operand.next = 1
                    if fetched == next_count:
                        next_valid.next = 1
                        fetched.next = 0
                    else:
                        fetched.next = fetched + 1

    @always_comb
    def check():
        result = intbv(0)[error_bits:]
        result[:] = E_NONE
        if bad_opcode:
            result[:] = E_BAD_OPCODE
        elif bad_header_bits:
            result[:] = E_RESERVED_BITS
        elif bad_set_index or bad_operand or bad_variant or bad_fields:
            result[:] = E_RANGE
        next_error.next = result

    @always_comb
    def motion_status():
        # every move handed to the DDA has ended (a start is not yet seen as busy)
        motion_done.next = not dda.start and not dda.busy and not dda.done

    @always_comb
    def completion():
        state_over.next = False
        if state == seq_t.S_IDLE:
            state_over.next = True
        elif state == seq_t.S_MOTION:
            state_over.next = motion_done
        elif state == seq_t.S_PULSE:
            state_over.next = not pulses.busy
        elif state == seq_t.S_DWELL:
            state_over.next = dwell_left <= 1 and not pulses.outputs_busy
        else:
            state_over.next = False

    @always_comb
    def readiness():
        if next_motion and next_error == E_NONE:
            if state == seq_t.S_MOTION:
                # chain: the DDA sets the move up while the one before runs
                finishing.next = dda.ready and not dda.start and not dda.error
            else:
                finishing.next = state_over
        else:
            finishing.next = state_over and not pulses.outputs_busy

    @always_comb
    def issuing():
        issue.next = next_valid and control.enable and finishing and not control.clear

    @always_seq(clock.posedge, reset=reset)
    def execute():
        dda.start.next = 0
        pulses.load.next = 0
        set_port.strobe.next = 0
        mark.strobe.next = 0
        if control.clear:
            state.next = seq_t.S_IDLE
            control.error_code.next = E_NONE
        elif state == seq_t.S_ERROR:
            if control.clear_error:
                state.next = seq_t.S_IDLE
                control.error_code.next = E_NONE
        elif state == seq_t.S_MOTION and dda.error and not dda.start:
            state.next = seq_t.S_ERROR
            control.error_code.next = E_DDA_REJECTED
        elif issue:
            if next_error != E_NONE:
                state.next = seq_t.S_ERROR
                control.error_code.next = next_error
            elif opcode == line_op or opcode == arc_op:
                state.next = seq_t.S_MOTION
                dda.start.next = 1
            elif opcode == pulse_op:
                state.next = seq_t.S_PULSE
                pulses.load.next = 1
            elif opcode == dwell_op:
                state.next = seq_t.S_DWELL
            else:
                state.next = seq_t.S_IDLE
                if opcode == set_op:
                    set_port.strobe.next = 1
                elif opcode == mark_op:
                    mark.strobe.next = 1
        elif state_over:
            state.next = seq_t.S_IDLE

    @always_seq(clock.posedge, reset=reset)
    def dwell_count():
        # The count only matters in DWELL, so it takes the operand whenever
        # a DWELL can begin at this edge (outside DWELL or at its end; the
        # operand is the next instruction's) and counts down inside it: the
        # issue and the clear (STOP) stay out of its 32-bit enable.
        if state != seq_t.S_DWELL or state_over:
            dwell_left.next = operand_0
        elif not pulses.outputs_busy and dwell_left != 0:
            dwell_left.next = dwell_left - 1

    @always_comb
    def present():
        # The receivers take these in the clock of their strobe (start, load,
        # set, mark), one clock after the issue and before the next fetched
        # word can overwrite the instruction register: no copy is needed.
        dda.line.next = opcode == line_op
        dda.ccw.next = header[ccw_lsb]
        dda.blend.next = header[blend_lsb]
        dda.variant.next = header[variant_msb:variant_lsb]
        dda.lambda_shift.next = header[lambda_msb:lambda_lsb]
        dda.acc_bits.next = header[acc_msb:acc_lsb]
        if opcode == line_op:
            dda.xs.next = 0
            dda.ys.next = 0
            dda.xe.next = operand_0[coord_width:].signed()
            dda.ye.next = operand_1[coord_width:].signed()
        else:
            dda.xs.next = operand_0[coord_width:].signed()
            dda.ys.next = operand_1[coord_width:].signed()
            dda.xe.next = operand_2[coord_width:].signed()
            dda.ye.next = operand_3[coord_width:].signed()
        set_port.index.next = header[index_msb:index_lsb]
        set_port.value.next = operand_0
        mark.tag.next = header[tag_msb:tag_lsb]

    @always_comb
    def report():
        control.busy.next = (state == seq_t.S_MOTION or state == seq_t.S_PULSE or state == seq_t.S_DWELL
                             or next_valid or word_due or fetched != 0 or not fifo.empty)
        control.motion_run.next = state == seq_t.S_MOTION

    fits = [fits_width(fifo.dout, arriving_coord_fits, coord_width), fits_width(fifo.dout, arriving_count_fits, count_bits)]
    header_in = Signal(bool(0))   # a header word arrives and is kept (no clear drops it)

    @always_comb
    def arriving_header():
        header_in.next = word_due and fetched == 0 and not control.clear and not discard

    if axes == 2:
        axis_units = [two_axis_operands(clock, reset, fifo.dout, header_in, operands, pulses, line_in)]
    else:
        # the plane and a PULSE's mask, taken with the header; a LINE's or helix's displacement of axis i
        # and a PULSE's count of axis i in operand register AXIS_SLOT + i; a helix's RANGE rules
        operand_in = Signal(bool(0))

        @always_comb
        def arriving_operand():
            operand_in.next = word_due and fetched != 0 and not control.clear and not discard

        @always_comb
        def field_checks():
            bad_fields.next = bad_axes or bad_helix

        axis_units = [arriving_operand, field_checks,
                      axis_operands(clock, reset, fifo.dout, arriving, header_in, operand_in, fetched, operands,
                                    axes_cmd, pulses, clear_area, clear_axes, bad_helix)]
    return (fits, reading, registers, arriving_header, axis_units, lookup_coords, lookup_counts, lookup_set, lookup_variant, fetch_request,
            operand_routing, discarding, fetch, check, motion_status, completion, readiness, issuing, execute,
            dwell_count, present, report)


def sequencer_ports(coord_width=COORD_WIDTH.default, axes=AXES.default):
    """Fresh ports of ``sequencer`` for conversion and benches (a card of ``axes`` axes)."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), fifo=FifoRead(), control=SequencerControl(),
                dda=DdaPort(coord_width), axes_cmd=AxesCommand(axes, coord_width), pulses=PulseCommand(axes),
                set_port=SetPort(), mark=MarkPort())
