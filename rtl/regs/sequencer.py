"""Instruction register: fetches commands from the FIFO and executes them."""
from myhdl import Signal, always_comb, always_seq, block, enum, intbv

from models import instructions as isa
from models.parameters import COORD_WIDTH
from rtl.interfaces import DdaPort, FifoRead, MarkPort, PulseCommand, SequencerControl, SetPort, card_reset


def _opcode_rom(value_of):
    """A 16-entry tuple, indexed by opcode, converted to a case statement."""
    return tuple(value_of(isa.BY_CODE[code]) if code in isa.BY_CODE else 0 for code in range(16))


def _operand_mask(op, names):
    return sum(1 << i for i, name in enumerate(op.operands) if name in names)


def _field(op_name, field_name):
    for name, lsb, width, _ in isa.BY_NAME[op_name].header_fields:
        if name == field_name:
            return lsb, lsb + width
    raise ValueError(f"{op_name} has no field {field_name}")


@block
def sequencer(clock, reset, fifo, control, dda, pulses, set_port, mark, *, set_indices=(0,)):
    """Fetch, check and execute the FIFO's commands (``docs/instructions.md``).

    Ports (``rtl/interfaces/``): ``fifo`` (``FifoRead``), ``control``
    (``SequencerControl``), ``dda`` (``DdaPort``), ``pulses``
    (``PulseCommand``), ``set_port`` (``SetPort``), ``mark`` (``MarkPort``).
    Fetch: the FIFO is read one word per clock (``fifo.pop``; the word
    arrives in ``fifo.dout`` the next clock) into the next-instruction
    register while the current command runs.  Execute: LINE/ARC drive
    ``dda`` (a one-clock ``start`` with the operands and BLEND) as soon as
    the DDA is ``ready``, also while the move before still runs, so chained
    segments leave no gap; PULSE loads both direct pulse generators
    (``pulses.load``, ``pulses.count_*``) and waits while ``pulses.busy``;
    DWELL counts clocks once the pulse outputs are quiet
    (``pulses.outputs_busy`` low: no step request pending and the last step
    has left the pins); SET gives a ``set_port.strobe`` with its index and
    value; MARK a ``mark.strobe`` with its tag.  An ARC whose VARIANT the DDA
    was not built with (``dda.variants``) is malformed (RANGE).  SET, DWELL, MARK, PULSE and
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
    indices that exist).

        clock     _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        fifo_pop  _/~~~~~~~~~~~\\_______________     LINE: 3 words
        next ok   _____________/~~~\\___________
        dda.start _________________/~~~\\_______     (dda.ready high)
    """
    coord_width, count_bits, error_bits = dda.coord_width, len(pulses.count_x), len(control.error_code)
    seq_t = enum("S_IDLE", "S_MOTION", "S_PULSE", "S_DWELL", "S_ERROR")
    state = Signal(seq_t.S_IDLE)
    # the instruction register keeps the bits something reads: the opcode, the
    # header's fields, SET's and DWELL's 32-bit operand 0, and of the other
    # operands the coordinate and count bits (their checks read the arriving word)
    field_bits = max(lsb + width for op in isa.OPCODES for _, lsb, width, _ in op.header_fields)
    if field_bits > isa.OPCODE_LSB:
        raise ValueError("the header's fields overlap the opcode")
    header = Signal(intbv(0)[field_bits:])
    if isa.MAX_OPERANDS != 4:
        raise ValueError("the instruction register holds four operand words")
    operand_0 = Signal(intbv(0)[32:])
    operand_1 = Signal(intbv(0)[max(coord_width, count_bits):])
    operand_2, operand_3 = Signal(intbv(0)[coord_width:]), Signal(intbv(0)[coord_width:])
    operand_1_bits = len(operand_1)
    fetched = Signal(intbv(0, min=0, max=isa.MAX_OPERANDS + 2))
    word_due = Signal(bool(0))
    next_valid = Signal(bool(0))
    next_error = Signal(intbv(0)[len(control.error_code):])
    next_motion, arriving_moves = Signal(bool(0)), Signal(bool(0))
    issue = Signal(bool(0))
    finishing = Signal(bool(0))
    state_over = Signal(bool(0))
    motion_done = Signal(bool(0))
    discard = Signal(bool(0))
    dwell_left = Signal(intbv(0)[32:])

    arriving_count = Signal(intbv(0, min=0, max=isa.MAX_OPERANDS + 1))
    next_count = Signal(intbv(0, min=0, max=isa.MAX_OPERANDS + 1))
    next_known = Signal(bool(0))  # of the arriving word, like the masks and set_known
    opcode = Signal(intbv(0)[32 - isa.OPCODE_LSB:])
    mask_high = Signal(intbv(0)[16:])
    mask_low = Signal(intbv(0)[16:])
    coord_mask = Signal(intbv(0)[isa.MAX_OPERANDS:])
    count_mask = Signal(intbv(0)[isa.MAX_OPERANDS:])
    set_known = Signal(bool(0))
    variant_built = Signal(bool(0))  # the arriving header's ARC.VARIANT is one the DDA has
    # the checks, made as the words arrive and kept beside them (no deep logic before the issue)
    bad_opcode, bad_header_bits, bad_set_index, bad_operand, bad_variant = (Signal(bool(0)) for _ in range(5))
    arriving_coord_fits, arriving_count_fits = Signal(bool(0)), Signal(bool(0))
    opcode_known = _opcode_rom(lambda op: 1)
    opcode_moves = _opcode_rom(lambda op: int(op.name in ("LINE", "ARC")))
    operand_count = _opcode_rom(lambda op: len(op.operands))
    header_mask_high = _opcode_rom(lambda op: op.header_mask >> 16)
    header_mask_low = _opcode_rom(lambda op: op.header_mask & 0xFFFF)
    coord_operands = _opcode_rom(lambda op: _operand_mask(op, ("DX", "DY", "XS", "YS", "XE", "YE")))
    count_operands = _opcode_rom(lambda op: _operand_mask(op, ("COUNT_X", "COUNT_Y")))
    set_ok = tuple(int(i in set_indices) for i in range(1 << len(set_port.index)))
    built = tuple(int(code in dda.variants) for code in range(1 << len(dda.variant)))
    code = {op.name: op.code for op in isa.OPCODES}
    line_op, arc_op, pulse_op, set_op, dwell_op, mark_op = (
        code["LINE"], code["ARC"], code["PULSE"], code["SET"], code["DWELL"], code["MARK"])
    E_NONE, E_BAD_OPCODE, E_RESERVED_BITS, E_RANGE, E_DDA_REJECTED = (
        isa.ERROR_CODE[name] for name in ("NONE", "BAD_OPCODE", "RESERVED_BITS", "RANGE", "DDA_REJECTED"))
    ccw_lsb = _field("ARC", "CCW")[0]
    blend_lsb = _field("ARC", "BLEND")[0]
    if _field("LINE", "BLEND")[0] != blend_lsb:
        raise ValueError("LINE and ARC must have BLEND in the same header bit")
    variant_lsb, variant_msb = _field("ARC", "VARIANT")
    lambda_lsb, lambda_msb = _field("ARC", "LAMBDA")
    acc_lsb, acc_msb = _field("ARC", "ACC_BITS")
    index_lsb, index_msb = _field("SET", "INDEX")
    tag_lsb, tag_msb = _field("MARK", "TAG")

    @always_comb
    def lookup_arriving():
        arriving_count.next = operand_count[fifo.dout[32:isa.OPCODE_LSB]]

    @always_comb
    def lookup_arriving_kind():
        arriving_moves.next = opcode_moves[fifo.dout[32:isa.OPCODE_LSB]]

    @always_comb
    def lookup_count():
        next_count.next = operand_count[opcode]

    @always_comb
    def lookup_valid():
        next_known.next = opcode_known[fifo.dout[32:isa.OPCODE_LSB]]

    @always_comb
    def lookup_mask_high():
        mask_high.next = header_mask_high[fifo.dout[32:isa.OPCODE_LSB]]

    @always_comb
    def lookup_mask_low():
        mask_low.next = header_mask_low[fifo.dout[32:isa.OPCODE_LSB]]

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
                more = arriving_count != 0
            else:
                more = fetched < next_count
        fifo.pop.next = (not fifo.empty and not next_valid and more and not control.clear
                         and state != seq_t.S_ERROR)

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
                    next_motion.next = arriving_moves
                    bad_opcode.next = not next_known
                    bad_header_bits.next = (fifo.dout[32:16] & ~mask_high) != 0 or (fifo.dout[16:] & ~mask_low) != 0
                    bad_set_index.next = fifo.dout[32:isa.OPCODE_LSB] == set_op and not set_known
                    bad_variant.next = fifo.dout[32:isa.OPCODE_LSB] == arc_op and not variant_built
                    bad_operand.next = 0
                    if arriving_count == 0:
                        next_valid.next = 1
                    else:
                        fetched.next = 1
                else:
                    if fetched == 1:
                        operand_0.next = fifo.dout
                    elif fetched == 2:
                        operand_1.next = fifo.dout[operand_1_bits:]
                    elif fetched == 3:
                        operand_2.next = fifo.dout[coord_width:]
                    else:
                        operand_3.next = fifo.dout[coord_width:]
                    if ((coord_mask[fetched - 1] and not arriving_coord_fits)
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
        elif bad_set_index or bad_operand or bad_variant:
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
        pulses.count_x.next = operand_0[count_bits:].signed()
        pulses.count_y.next = operand_1[count_bits:].signed()
        set_port.index.next = header[index_msb:index_lsb]
        set_port.value.next = operand_0
        mark.tag.next = header[tag_msb:tag_lsb]

    @always_comb
    def report():
        control.busy.next = (state == seq_t.S_MOTION or state == seq_t.S_PULSE or state == seq_t.S_DWELL
                             or next_valid or word_due or fetched != 0 or not fifo.empty)
        control.motion_run.next = state == seq_t.S_MOTION

    fits = [_fits(fifo.dout, arriving_coord_fits, coord_width), _fits(fifo.dout, arriving_count_fits, count_bits)]
    return (fits, lookup_arriving, lookup_arriving_kind, lookup_count, lookup_valid, lookup_mask_high, lookup_mask_low,
            lookup_coords, lookup_counts, lookup_set, lookup_variant, fetch_request, discarding, fetch, check, motion_status,
            completion, readiness, issuing, execute, dwell_count, present, report)


@block
def _fits(operand, fits, width):
    """``fits``: the 32-bit ``operand`` is a ``width``-bit signed number (its top
    bits are copies of bit ``width - 1``)."""
    ones = (1 << (33 - width)) - 1

    @always_comb
    def sign_extension():
        fits.next = operand[32:width - 1] == 0 or operand[32:width - 1] == ones

    return sign_extension


def sequencer_ports(coord_width=COORD_WIDTH.default):
    """Fresh ports of ``sequencer`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), fifo=FifoRead(), control=SequencerControl(),
                dda=DdaPort(coord_width), pulses=PulseCommand(), set_port=SetPort(), mark=MarkPort())
