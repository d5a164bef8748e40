"""The card's units behind the registers: FIFO, sequencer, register words, feed rate, pulse outputs."""
from myhdl import Signal, intbv, modbv

from models import instructions as isa
from models import registers as regmap
from models.axes import XY_MASK
from models.dda_build import COORD_WIDTH
from models.parameters import AXES, ENCODERS
from rtl.interfaces.bundle import adopt, axis_suffixes
from rtl.interfaces.dda import DdaPort


class MotorPins:
    """The machine's pins: STEP and DIR of each of the ``axes`` axes as they
    leave the card (``step_x``, ``dir_x``, ``step_y``, ``dir_y``, then
    ``step_z``, ``dir_z``, ... as ``models/axes.py`` names them; levels,
    straight from flip-flops; ``dir_*`` already carries the polarity),
    ``drive_enable`` (out, from a flip-flop: the drives may run), and the
    machine's inputs of its axes, in the order of ``MACHINE_INPUTS`` (E-stop, X's
    and Y's limit and home switches, then ``limit_pos_z``, ``limit_neg_z``,
    ``home_z``, ... of every further axis: pin levels as wired, asynchronous;
    ``rtl/machine/input_filter.py`` conditions them); with ``encoders`` (the
    build parameter) also every axis's encoder inputs ``enc_a_x``,
    ``enc_b_x``, ``enc_index_x``, ``enc_a_y``, ... and the card's ``probe``
    (levels as wired, asynchronous; ``rtl/regs/encoder_block.py``)."""

    def __init__(self, axes=AXES.default, encoders=ENCODERS.default):
        self.axes, self.encoders = axes, encoders
        for suffix in axis_suffixes(axes):
            setattr(self, f"step_{suffix}", Signal(bool(0)))
            setattr(self, f"dir_{suffix}", Signal(bool(0)))
        self.drive_enable = Signal(bool(0))
        for name in machine_inputs(axes):
            setattr(self, name, Signal(bool(0)))
        if encoders:
            for suffix in axis_suffixes(axes):
                for pin in ENCODER_PINS:
                    setattr(self, f"{pin}_{suffix}", Signal(bool(0)))
            self.probe = Signal(bool(0))

    def encoder(self, axis, pin):
        """Encoder pin ``pin`` (one of ``ENCODER_PINS``) of axis ``axis``."""
        return getattr(self, f"{pin}_{axis_suffixes(self.axes)[axis]}")

    def step(self, axis):
        """The STEP pin of axis ``axis`` (0 X, 1 Y, ...)."""
        return getattr(self, f"step_{axis_suffixes(self.axes)[axis]}")

    def dir(self, axis):
        """The DIR pin of axis ``axis``."""
        return getattr(self, f"dir_{axis_suffixes(self.axes)[axis]}")

    def inputs(self):
        """The input pins, in the order of ``MACHINE_INPUTS``."""
        return [getattr(self, name) for name in machine_inputs(self.axes)]


ENCODER_PINS = ("enc_a", "enc_b", "enc_index")   # an axis's encoder pins, with encoders

# The machine's inputs of the largest build, bit n of INPUT_POLARITY, INPUT_RAW and INPUT_ACTIVE is input n.
MACHINE_INPUTS = tuple(name.lower() for name in regmap.INPUT_NAMES)
INPUT_ESTOP = regmap.INPUT_NAMES.index("ESTOP")


def machine_inputs(axes):
    """The input pins' names of a card of ``axes`` axes, in the order of ``MACHINE_INPUTS``."""
    return MACHINE_INPUTS[:len(regmap.input_names(axes))]


# Widths of the bundles below, each from the table that defines it.
def _header_width(op_name, field_name):
    return {name: width for name, _, width, _ in isa.BY_NAME[op_name].header_fields}[field_name]


SET_INDEX_BITS = _header_width("SET", "INDEX")


MARK_TAG_BITS = _header_width("MARK", "TAG")


ERROR_BITS = regmap.register("STATUS").field("ERROR").width


PULSE_COUNT_BITS = regmap.register("PULSE_COUNT_X").width


TIMING_BITS = regmap.register("STEP_WIDTH").width
STEP_MODE_BITS = regmap.register("STEP_MODE").width


class FifoRead:
    """The read side of the data FIFO: the FIFO drives ``dout`` (the word
    popped the clock before) and ``empty``; the reader (the sequencer) drives
    ``pop`` (one word per clock while high)."""

    def __init__(self, **given):
        adopt(self, given, dout=Signal(intbv(0)[32:]), empty=Signal(bool(1)), pop=Signal(bool(0)))


class SequencerControl:
    """The sequencer's controls and status, seen from the registers.

    The registers drive ``enable`` (CONTROL.ENABLE outside direct mode),
    ``clear`` (COMMAND.SOFT_RESET, one clock) and ``clear_error`` (COMMAND.CLEAR_ERROR,
    one clock); the sequencer drives ``error_code`` (STATUS.ERROR), ``busy``
    (a command runs or is queued), ``motion_run`` (a path is under way: the
    feed-rate ramp runs) and ``discard_on_clear`` (the FIFO empties itself on
    the next CLEAR_ERROR).
    """

    def __init__(self, **given):
        adopt(self, given, enable=Signal(bool(0)), clear=Signal(bool(0)), clear_error=Signal(bool(0)),
               error_code=Signal(intbv(0)[ERROR_BITS:]), busy=Signal(bool(0)), motion_run=Signal(bool(0)),
               discard_on_clear=Signal(bool(0)))


class CommandHeader:
    """A header word as ``rtl/regs/command_header.py`` reads it, for the
    sequencer, which keeps what it needs when the word arrives: ``known``
    (the opcode is in the table), ``moves`` (LINE or ARC), ``operands`` (the
    operand words that follow it, N-axis form), ``reserved`` (a bit outside
    the N-axis form's fields: RESERVED_BITS), ``has_operands`` (any
    operand follows, from the opcode alone: a short path to the FIFO's
    pop), ``out_of_range`` (the axis
    fields break the card's rules: RANGE), the plane ``u``, ``v`` (axis
    indices; X, Y for the 0/0 form and for every other command) and
    ``slots`` (the operand registers its operands go to, in order: a LINE's
    axes, all of them for the others).  ``axes``: the card's; ``slots``: how
    many operand registers the sequencer has."""

    def __init__(self, axes, slots, operands_max):
        bits = max(1, (axes - 1).bit_length())
        self.axes, self.slot_count = axes, slots
        self.known, self.moves, self.has_operands = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
        self.operands = Signal(intbv(0, min=0, max=operands_max + 1))
        self.reserved, self.out_of_range = Signal(bool(0)), Signal(bool(0))
        self.u, self.v = Signal(intbv(0)[bits:]), Signal(intbv(1)[bits:])
        self.slots = Signal(intbv(0)[slots:])


class PulseCommand:
    """The PULSE command's seam for ``axes`` axes: the sequencer drives ``load``
    (one clock) with ``mask`` (bit i: axis i takes its count; the others go on
    as they were; its reset, X and Y, is today's PULSE) and the signed counts
    ``count_x``, ``count_y``, ... (``count(axis)``); the direct pulse
    generators drive ``busy`` (pulses still to go on any axis) and the pulse
    outputs ``outputs_busy`` (a step request is pending or the last step has
    not yet left the pins)."""

    def __init__(self, axes=AXES.default, **given):
        self.axes = axes
        bounds = dict(min=-(1 << (PULSE_COUNT_BITS - 1)), max=1 << (PULSE_COUNT_BITS - 1))
        counts = {f"count_{suffix}": Signal(intbv(0, **bounds)) for suffix in axis_suffixes(axes)}
        adopt(self, given, load=Signal(bool(0)), mask=Signal(intbv(XY_MASK)[axes:]), **counts,
               busy=Signal(bool(0)), outputs_busy=Signal(bool(0)))

    def count(self, axis):
        """Axis ``axis``'s count (0 X, 1 Y, ...)."""
        return getattr(self, f"count_{axis_suffixes(self.axes)[axis]}")


class SetPort:
    """The SET command's write port into the registers: the sequencer drives
    ``strobe`` (one clock) with ``index`` (the register's SET index) and
    ``value``; the register of that index takes ``value`` like a bus write."""

    def __init__(self, **given):
        adopt(self, given, strobe=Signal(bool(0)), index=Signal(intbv(0)[SET_INDEX_BITS:]),
               value=Signal(intbv(0)[32:]))


class MarkPort:
    """The MARK command's report: the sequencer drives ``strobe`` (one clock,
    when the MARK is reached) with ``tag``; the registers latch it in
    MARK_TAG and raise INT_STATUS.MARK."""

    def __init__(self, **given):
        adopt(self, given, strobe=Signal(bool(0)), tag=Signal(intbv(0)[MARK_TAG_BITS:]))


class RegisterBus:
    """The function registers' side of the I/O BAR, driven by ``regs_fifo``:
    ``addr`` (byte offset of reads, straight from the local bus),
    ``write_addr`` (byte offset of the write), ``write`` (an I/O write
    happens at this clock edge), ``byte_mask`` (the write's byte enables as
    a bit mask, at least as wide as the registers that merge bytes) and
    ``wdata`` (the write's data, its bytes not enabled 0: masked before the
    write stage's flip-flops, so no register masks it again); every
    ``reg_word`` reads them."""

    def __init__(self, addr_width=16, mask_width=32, **given):
        adopt(self, given, addr=Signal(intbv(0)[addr_width:]), write_addr=Signal(intbv(0)[addr_width:]),
               write=Signal(bool(0)), byte_mask=Signal(intbv(0)[mask_width:]), wdata=Signal(intbv(0)[32:]))


class AliasBlock:
    """An axis block of BAR2 whose registers are BAR0's (X's, Y's:
    ``models.registers.axis_aliases``), decoded once for all of them by
    ``rtl/regs/alias_block.py``: ``read`` (``RegisterBus.addr`` is in the
    block) and ``write`` (``write_addr`` is); ``base`` (its first byte
    offset) and ``size`` (bytes, a power of two: the registers compare the
    address's low bits with their offset in the block)."""

    def __init__(self, base, size):
        if size & (size - 1) or base % size:
            raise ValueError(f"an alias block of {size} bytes at {base:#x} is not aligned to a power of two")
        self.base, self.size = base, size
        self.read, self.write = Signal(bool(0)), Signal(bool(0))


class RegisterWord:
    """One function register's signals to the hardware, as wide as the
    register ``spec`` (a ``models.registers.Register``): the hardware drives
    ``hw`` (RO and WP: what reads return; W1C: bits it sets; W1S: bits it
    clears; RW: the bits of its ``cleared`` fields it clears; ``hw_reset``: its value before the hardware drives it, the build
    word of a capability register); the register drives ``value``
    (RW/W1C/W1S: the register; WP: the last value written) and ``strobe``
    (WP: one clock per write)."""

    def __init__(self, spec, hw_reset=0):
        self.spec = spec
        self.hw = Signal(intbv(hw_reset)[spec.width:])
        self.value = Signal(intbv(spec.reset)[spec.width:])
        self.strobe = Signal(bool(0))


class ReadChain:
    """One link of the registers' read and clamp chain: each ``reg_word``
    drives the link after it with the link before it, its read data OR'ed
    into ``data`` when the bus reads it, and its one-clock flag into
    ``clamped`` when a write to it was out of range."""

    def __init__(self):
        self.data = Signal(intbv(0)[32:])
        self.clamped = Signal(bool(0))


class PulseControl:
    """Settings and status of the pulse outputs (``rtl/regs/pulse_out.py``) of ``axes`` axes.

    The registers drive ``clear`` (drop the queue), ``clear_position``
    (zero the positions), ``zero`` (bit i axis i: zero that axis's
    position, counting a step that rises in that clock), ``width``, ``space``, ``setup`` and ``hold``
    (STEP_WIDTH, STEP_SPACE, DIR_SETUP, DIR_HOLD, in clocks), ``mode`` (STEP_MODE) and
    ``polarity_x``, ``polarity_y``, ... one an axis (DIR_POLARITY); the pulse outputs drive ``ready``
    (the queue takes the steps on their way), ``active`` (a step is queued or on the pins) and
    ``pulsing`` (a STEP pulse starts at the coming edge, is high inside or is high on the pins: the
    machine guard keeps DRIVE_ENABLE for it).
    """

    def __init__(self, axes=AXES.default, **given):
        self.axes = axes
        polarities = {f"polarity_{suffix}": Signal(bool(0)) for suffix in axis_suffixes(axes)}
        adopt(self, given, clear=Signal(bool(0)), clear_position=Signal(bool(0)), zero=Signal(intbv(0)[axes:]),
               width=Signal(intbv(1)[TIMING_BITS:]), space=Signal(intbv(1)[TIMING_BITS:]),
               setup=Signal(intbv(1)[TIMING_BITS:]), hold=Signal(intbv(1)[TIMING_BITS:]),
               mode=Signal(intbv(0)[STEP_MODE_BITS:]), **polarities,
               ready=Signal(bool(1)), active=Signal(bool(0)), pulsing=Signal(bool(0)))

    def polarity(self, axis):
        """Axis ``axis``'s DIR polarity (1 inverts its DIR pin)."""
        return getattr(self, f"polarity_{axis_suffixes(self.axes)[axis]}")


class StepPositions:
    """The step counters of the ``axes`` axes, driven by the pulse outputs:
    ``x``, ``y``, ``z``, ... (signed 32 bits, wrapping), counted at the edge
    where a STEP pin rises."""

    def __init__(self, axes=AXES.default):
        self.axes = axes
        for suffix in axis_suffixes(axes):
            setattr(self, suffix, Signal(modbv(0, min=-(1 << 31), max=1 << 31)))

    def of(self, axis):
        """The step counter of axis ``axis``."""
        return getattr(self, axis_suffixes(self.axes)[axis])


class AxisBlock:
    """The per-axis register blocks' seam (``rtl/regs/axis_block.py``) for
    ``axes`` axes and a local bus of ``addr_width`` address bits.

    The card drives ``addr`` (the register access's byte offset), ``read`` (a
    register read is taken at this edge) and ``positions`` (``StepPositions``,
    the live step counts); the unit drives ``held``
    (``StepPositions``: every axis's count but X's as the last POS_X read
    captured it) and ``pos_words`` (the words POS_Z, POS_A, ... read: one
    32-bit signal per axis from Z on)."""

    def __init__(self, axes=AXES.default, addr_width=16, positions=None, pos_words=None, **given):
        self.axes = axes
        adopt(self, given, addr=Signal(intbv(0)[addr_width:]), read=Signal(bool(0)))
        self.positions = StepPositions(axes) if positions is None else positions
        self.held = StepPositions(axes)
        self.pos_words = [Signal(intbv(0)[32:]) for _ in range(2, axes)] if pos_words is None else list(pos_words)
        if len(self.pos_words) != max(0, axes - 2):
            raise ValueError(f"AxisBlock: {len(self.pos_words)} POS words for the {axes - 2} axes from Z on")


class RampSettings:
    """The feed rate's settings, driven by the registers FEED_RATE
    (``target``), RAMP_START (``ramp_start``) and RAMP_STEP (``ramp_step``);
    the feed rate (``rtl/regs/feed_rate.py``) reads them."""

    def __init__(self, **given):
        def rate(name):
            spec = regmap.register(name)
            return Signal(intbv(spec.reset)[spec.width:])
        adopt(self, given, target=rate("FEED_RATE"), ramp_start=rate("RAMP_START"), ramp_step=rate("RAMP_STEP"))


class FeedPort:
    """The feed rate's seam with the motion: the card drives ``run`` (a path
    is under way), ``hold`` (the pulse outputs are full) and ``pause`` (feed
    hold: MACHINE_CONTROL.HOLD or a decelerated stop), the DDA
    ``stop_left`` (``DdaPort.stop_left`` of ``coord_width``); the feed rate
    drives ``tick`` (one clock per iteration) and ``held`` (the rate is zero
    on a ``pause``)."""

    def __init__(self, coord_width=COORD_WIDTH, **given):
        adopt(self, given, run=Signal(bool(0)), hold=Signal(bool(0)), pause=Signal(bool(0)),
               stop_left=DdaPort(coord_width).stop_left, tick=Signal(bool(0)), held=Signal(bool(0)))


class DirectPulseCommand:
    """One axis's direct pulses, seen from the card: it drives ``load`` (one
    clock) with ``count`` (signed pulses, the sign their direction) and
    ``asked`` (``load`` as the sequencer and homing count it: the E-stop in
    place of the guard's halt, see ``rtl/regs/pulse_source.py``),
    ``period`` (clocks between pulses, PULSE_PERIOD_*), ``clear`` (soft
    reset) and ``retarget`` (one clock: ``count``'s size becomes the pulses
    still to go, in the direction under way, the period's timing goes on:
    homing's back-off); the generator drives ``remaining`` (pulses still to
    go), ``busy`` (from ``load`` until the last request) and ``running``
    (``busy`` but for the clock of ``load``: from registers only)."""

    def __init__(self, **given):
        bounds = dict(min=-(1 << (PULSE_COUNT_BITS - 1)), max=1 << (PULSE_COUNT_BITS - 1))
        period = regmap.register("PULSE_PERIOD_X")
        adopt(self, given, load=Signal(bool(0)), count=Signal(intbv(0, **bounds)),
               period=Signal(intbv(period.reset)[period.width:]), clear=Signal(bool(0)), retarget=Signal(bool(0)),
               remaining=Signal(intbv(0)[PULSE_COUNT_BITS:]), busy=Signal(bool(0)),
               running=Signal(bool(0)), asked=Signal(bool(0)))


class StepRequest:
    """One axis's step requests into the pulse outputs: the source drives
    ``step`` (one clock per step) with ``dir`` (1: positive); the pulse
    outputs drive ``ready`` (they take a step now)."""

    def __init__(self, **given):
        adopt(self, given, step=Signal(bool(0)), dir=Signal(bool(0)), ready=Signal(bool(1)))


class StatusWords:
    """What the status registers read (``rtl/regs/status_words.py``), each as wide
    as its register in ``models/registers.py``.

    The card drives ``busy`` (a command queued or running, a direct pulse,
    a step on its way, a move or a HOME under way), ``quadrant`` (the
    DDA's), ``error_code`` (the sequencer's), ``fifo_empty``, ``fifo_full``
    and ``fifo_level`` (words), ``clamped`` (one clock: a register write was
    clamped), ``home_ended`` (one clock as a HOME ends), ``index_fired`` and
    ``probe_fired`` (one clock as an index or the probe latched), ``low_water``,
    ``int_status`` and ``int_enable`` (the registers' values), ``position_x``
    (the live X count) and ``position_y`` (the Y count captured with the last
    POS_X read); the unit drives ``status`` (STATUS), ``int_set`` (the
    INT_STATUS bits to set), ``mark_tag``, ``machine_status``,
    ``stop_reason``, ``pos_x``, ``pos_y``, ``input_raw``, ``input_active`` (what those registers
    read; the input words as wide as a card of ``axes`` axes has inputs) and ``irq`` (INTA#, active
    high: an enabled INT_STATUS bit is set)."""

    def __init__(self, axes=AXES.default, **given):
        inputs = len(machine_inputs(axes))
        def word(name):
            return Signal(intbv(0)[regmap.register(name).width:])
        step_count = dict(min=-(1 << 31), max=1 << 31)
        adopt(self, given, busy=Signal(bool(0)), quadrant=Signal(intbv(0)[2:]),
               error_code=Signal(intbv(0)[ERROR_BITS:]), fifo_empty=Signal(bool(1)), fifo_full=Signal(bool(0)),
               fifo_level=Signal(intbv(0)[regmap.register("STATUS").field("FIFO_LEVEL").width:]),
               clamped=Signal(bool(0)), home_ended=Signal(bool(0)), index_fired=Signal(bool(0)),
               probe_fired=Signal(bool(0)), low_water=word("LOW_WATER"),
               int_status=word("INT_STATUS"), int_enable=word("INT_ENABLE"),
               position_x=Signal(modbv(0, **step_count)), position_y=Signal(modbv(0, **step_count)),
               status=word("STATUS"), int_set=word("INT_STATUS"), mark_tag=word("MARK_TAG"),
               machine_status=word("MACHINE_STATUS"), stop_reason=word("STOP_REASON"), pos_x=word("POS_X"),
               pos_y=word("POS_Y"), input_raw=Signal(intbv(0)[inputs:]), input_active=Signal(intbv(0)[inputs:]),
               irq=Signal(bool(0)))
