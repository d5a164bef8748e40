"""The card's function registers (I/O BAR0, and memory BAR2 at the same
offsets, then BAR2's per-axis blocks), described once.

``REGISTERS`` is the single table of BAR0, ``AXIS_REGISTERS`` the list every
axis of the build has in BAR2 (``axis_offset``: ``AXIS_BLOCK_BASE +
AXIS_STRIDE * axis`` plus the register's offset in the block); for X and Y
they are BAR0's own registers (POS_X, PULSE_PERIOD_X, ...), reached at both
offsets, and for Z, A, B, C registers of their own (``axis_registers``).  From it come the RTL decoder
(``rtl/regs_fifo.py`` builds one ``reg_word`` per entry), ``docs/registers.md``
and the C header the converter writes into ``gen/`` (both
``models/register_docs.py``) and the map the host benches use (``offset``, ``field_value``,
``field_of``).

Access kinds:

- ``RO``: read only; writes are ignored.  The value comes from the hardware.
- ``RW``: read/write, byte enables honoured.  A value outside the register's
  ``minimum``/``maximum`` is clamped to the nearest bound (the register reads
  back what the hardware honours) and ``INT_STATUS.CLAMPED`` is set.  A
  field with ``cleared`` (the event, in words) is cleared by the hardware
  and held at 0 while that holds: a write of 1 meanwhile is not kept.
- ``W1C``: hardware sets bits, writing 1 clears them.
- ``W1S``: writing 1 sets bits, the hardware clears them when it has acted.
- ``WP`` (write pulse): a write gives a one-clock pulse of the written value
  to the hardware; reads return a hardware value (e.g. what is left to do).

Registers with a ``set_index`` can also be written from the command stream by
the ``SET`` instruction (``docs/instructions.md``).

The capability registers (CLOCK_HZ, FIFO_SIZE, BUILD) are RO fields whose
``build`` names the build parameter (``models/parameters.py``) they hold, so a
host reads what it needs instead of knowing the build; ``build_word`` gives
their value for a build, and the ``reset`` of the table is the default
build's top.

ID.VERSION: the major version (bits 15:8) changes when a register or field
moves or changes meaning, the minor version (bits 7:0) when registers or
fields are added; ``VERSIONS`` says what each version added.
"""
from dataclasses import replace

from models import parameters
from models import register_checks as checks
from models.axes import AXIS_NAMES
# The map's names live in these modules and are read through this one (``regmap.X``).
from models.axis_registers import (AXIS_BLOCK_BASE, AXIS_FREE, AXIS_REGISTERS, AXIS_STRIDE,  # noqa: F401
                                   ENCODER_REGISTERS, REG_BAR_BITS)
from models.machine_inputs import (INPUT_NAMES, INPUT_TEXT, INPUTS_PER_AXIS, LIMIT_NAMES, XY_INPUTS,  # noqa: F401
                                   home_input, input_names, limit_bit, limit_input)
from models.register_types import (ACCESS_KINDS, BAR0_AXES, WORD_BYTES, Field, Register,  # noqa: F401
                                   build_word, capability, one_value)

ID_MAGIC = 0xDDAC
# What each register-map version added (docs/registers.md lists it).
VERSIONS = (
    (0x0100, "the register map"),
    (0x0101, "CLOCK_HZ, FIFO_SIZE and BUILD"),
    (0x0102, "the machine inputs and the guard (MACHINE_CONTROL .. WATCHDOG, COMMAND.CLEAR_STOP, "
             "STATUS.STOPPED, INT_STATUS.STOPPED and INPUT; docs/machine.md)"),
    (0x0103, "feed hold and the decelerated stop (MACHINE_CONTROL.HOLD, MACHINE_STATUS.HELD and "
             "STOPPING); homing (HOME .. HOME_SEARCH, INT_STATUS.HOMED; docs/machine.md)"),
    (0x0200, "a stop clears MACHINE_CONTROL.DRIVE_ENABLE (CLEAR_STOP no longer re-energises the drives: "
             "the host writes it again); WATCHDOG, LOW_WATER, RAMP_STEP and HOME_BACKOFF clamp a write "
             "above their range instead of cutting it; a refused CLEAR_STOP keeps the FIFO; "
             "DRIVE_ENABLE stays high until a STEP pulse under way has ended (docs/machine.md)"),
    (0x0201, "STEP_SPACE (the STEP low time; STEP_WIDTH is the high time only) and STEP_MODE (step/dir, "
             "up/down, quadrature); the registers also in memory space, BAR2 (docs/pci.md)"),
    (0x0202, "BAR2 grows to 4 KiB: a register block per axis at 0x100 + 0x40 * axis (POS, PULSE_PERIOD, "
             "PULSE_COUNT; X's and Y's are POS_X, PULSE_PERIOD_X, ... again), direct pulses on every axis; "
             "a POS_X read snapshots every other axis's position; DIR_POLARITY.Z .. C"),
    (0x0203, "the limit and home inputs of every axis (INPUT_POLARITY bits 7..18: LIMIT_POS_Z, LIMIT_NEG_Z, "
             "HOME_Z, then A, B, C's), INPUT_RAW and INPUT_ACTIVE (every input; MACHINE_STATUS keeps X's and "
             "Y's), STOP_REASON.LIMITS widened to bits 15:4; HOME.AXIS_INDEX homes any axis (docs/machine.md)"),
    (0x0204, "encoder inputs on a build with encoders (build parameter encoders, BUILD.ENCODERS): per axis "
             "ENC_COUNT .. PROBE_POS in the block, TIMESTAMP and PROBE_CONTROL, INT_STATUS.INDEX and PROBE, "
             "STOP_REASON.REASON FOLLOWING_ERROR and STOP_REASON.AXIS (docs/encoders.md)"),
    (0x0300, "a helical ARC's axes follow the area the arc sweeps: its operand ITERATIONS becomes AREA_LO, "
             "AREA_HI (docs/axes.md); the registers are 2.4's"),
)
VERSION = VERSIONS[-1][0]
RATE_ONE = 1 << 16  # feed rate of one iteration per clock
RATE_MAX = RATE_ONE // 2  # the DDA takes an iteration at most every other clock
STEP_WIDTH_RESET = 1      # STEP_WIDTH's reset, and STEP_SPACE's: the timing of the cards before STEP_SPACE
STEP_MODES = ("STEP_DIR", "UP_DOWN", "QUADRATURE")   # STEP_MODE.MODE codes


_VARIANT_CODES = ", ".join(f"{code} {name}" for code, name in enumerate(parameters.VARIANT_NAMES))
_DEVICE_CODES = ", ".join(f"{code} {name}" for code, name in enumerate(parameters.DEVICES))


_INT_FIELDS = (
    Field("DONE", 0, 1, "motion done: the command queue ran empty after motion"),
    Field("LOW_WATER", 1, 1, "FIFO level fell below LOW_WATER"),
    Field("ERROR", 2, 1, "a command was rejected (STATUS.ERROR says why)"),
    Field("MARK", 3, 1, "a MARK command was reached (MARK_TAG says which)"),
    Field("CLAMPED", 4, 1, "a register write was out of range and was clamped"),
    Field("STOPPED", 5, 1, "the machine guard stopped the card (STOP_REASON says why)"),
    Field("INPUT", 6, 1, "a filtered machine input changed (INPUT_ACTIVE)"),
    Field("HOMED", 7, 1, "a HOME ended: done, not found or refused (HOME_STATUS says which)"),
    Field("INDEX", 8, 1, "an armed encoder index latched ENC_INDEX_LATCH, on any axis (a build with encoders)"),
    Field("PROBE", 9, 1, "the armed probe latched PROBE_ENC and PROBE_POS (a build with encoders)"),
)

STOP_REASONS = ("NONE", "ESTOP", "WATCHDOG", "LIMIT", "FOLLOWING_ERROR")  # STOP_REASON.REASON codes
_REASON_CODES = ", ".join(f"{code} {name}" for code, name in enumerate(STOP_REASONS))
WATCHDOG_BITS = 24
HOME_SEARCH_BITS = 23  # a search fits a signed 24-bit direct-pulse count
HOME_PHASES = ("IDLE", "SEEK", "RELEASE", "BACKOFF")  # HOME_STATUS.PHASE codes

REGISTERS = (
    Register("ID", 0x00, "RO", (ID_MAGIC << 16) | VERSION, "identity and version", (
        Field("VERSION", 0, 16, "register-map version, major in bits 15:8"),
        Field("MAGIC", 16, 16, "0xDDAC: this card"),
    )),
    Register("CONTROL", 0x04, "RW", 0, "operating mode", (
        Field("ENABLE", 0, 1, "1: execute commands (0 holds the queue; words still enter the FIFO)"),
        Field("MODE", 1, 1, "0: DDA interpolation from the FIFO, 1: direct pulses from PULSE_COUNT_*"),
    )),
    Register("COMMAND", 0x08, "WP", 0, "one-shot actions (read as 0)", (
        Field("SOFT_RESET", 0, 1, "stop motion at once, empty the FIFO, reset the DDA, clear the error"),
        Field("CLEAR_ERROR", 1, 1, "clear STATUS.ERROR; execution resumes with the next queued word"),
        Field("CLEAR_POSITION", 2, 1, "zero POS_X and POS_Y"),
        Field("CLEAR_STOP", 3, 1, "release the machine guard's stop (not while the E-stop input is "
              "active); written while stopped, it empties the FIFO of the words written before it"),
    )),
    # after reset: idle, no error, the FIFO empty
    Register("STATUS", 0x0C, "RO", 1 << 8, "what the card is doing", (
        Field("BUSY", 0, 1, "a command is executing or queued"),
        Field("DONE", 1, 1, "the queue ran empty after motion (cleared when a command starts)"),
        Field("QUADRANT", 2, 2, "quadrant of the arc's moving point, 0..3 for I..IV"),
        Field("ERROR", 4, 4, "error code, 0: none (docs/instructions.md lists them)"),
        Field("FIFO_EMPTY", 8, 1, "the FIFO holds no word"),
        Field("FIFO_FULL", 9, 1, "the FIFO is full: memory writes are retried"),
        Field("STOPPED", 10, 1, "the machine guard holds the card stopped (STOP_REASON says why)"),
        Field("FIFO_LEVEL", 16, 16, "words in the FIFO"),
    )),
    Register("INT_ENABLE", 0x10, "RW", 0, "interrupt enables (INTA# = any enabled status bit)", _INT_FIELDS),
    Register("INT_STATUS", 0x14, "W1C", 0, "interrupt status, write 1 to clear", _INT_FIELDS),
    Register("LOW_WATER", 0x18, "RW", 0, "FIFO low-water mark",
             one_value("LEVEL", 16, "LOW_WATER interrupt when the FIFO level falls below this"), minimum=0, maximum=0xFFFF),
    Register("MARK_TAG", 0x1C, "RO", 0, "tag of the last MARK reached",
             one_value("TAG", 16, "the MARK command's tag")),
    Register("POS_X", 0x20, "RO", 0, "X position in steps; reading it snapshots POS_Y (and every other axis's POS)",
             one_value("STEPS", 32, "steps that left the X pins, signed", signed=True)),
    Register("POS_Y", 0x24, "RO", 0, "Y position captured by the last POS_X read",
             one_value("STEPS", 32, "steps that left the Y pins, signed", signed=True)),
    Register("FEED_RATE", 0x28, "RW", 4096,
             "target iteration rate, in 1/65536 per clock (ramps: docs/instructions.md)",
             one_value("RATE", 16, "iterations per clock times 65536 (32768: one every other clock, the most)"),
             minimum=1, maximum=RATE_MAX, set_index=0),
    Register("RAMP_START", 0x2C, "RW", 4096,
             "iteration rate a move starts with, and ends with unless it blends, when RAMP_STEP is not 0",
             one_value("RATE", 16, "iterations per clock times 65536 (at most 32768)"),
             minimum=1, maximum=RATE_MAX, set_index=1),
    Register("RAMP_STEP", 0x30, "RW", 0,
             "rate change per iteration: up towards FEED_RATE, down to RAMP_START before a stop (0: no ramp)",
             one_value("STEP", 16, "added to the rate each iteration until FEED_RATE; subtracted as the end nears"),
             minimum=0, maximum=0xFFFF, set_index=2),
    Register("STEP_WIDTH", 0x34, "RW", STEP_WIDTH_RESET,
             "STEP high time in clocks (the low time between steps: STEP_SPACE)",
             one_value("CLOCKS", 8, "1..255"), minimum=1, maximum=255, set_index=3),
    Register("DIR_SETUP", 0x38, "RW", 1, "DIR stable before the STEP leading edge, in clocks",
             one_value("CLOCKS", 8, "1..255"), minimum=1, maximum=255, set_index=4),
    Register("DIR_HOLD", 0x3C, "RW", 1, "DIR stable after the STEP trailing edge, in clocks",
             one_value("CLOCKS", 8, "1..255"), minimum=1, maximum=255, set_index=5),
    Register("DIR_POLARITY", 0x40, "RW", 0, "DIR pin polarity (bit n: axis n; a card of fewer axes keeps the "
             "bits of those it lacks, unused)",
             tuple(Field(name, bit, 1, f"1: invert the {name} DIR pin") for bit, name in enumerate(AXIS_NAMES))),
    Register("PULSE_PERIOD_X", 0x44, "RW", 2, "clocks between direct X pulses",
             one_value("CLOCKS", 16, "1..65535"), minimum=1, maximum=0xFFFF, set_index=6),
    Register("PULSE_PERIOD_Y", 0x48, "RW", 2, "clocks between direct Y pulses",
             one_value("CLOCKS", 16, "1..65535"), minimum=1, maximum=0xFFFF, set_index=7),
    Register("PULSE_COUNT_X", 0x4C, "WP", 0, "direct mode: write a signed count of X pulses; read what is left",
             one_value("COUNT", 24, "signed pulses (sign: direction); reads the pulses still to go",
                  signed=True), minimum=-(1 << 23), maximum=(1 << 23) - 1),
    Register("PULSE_COUNT_Y", 0x50, "WP", 0, "direct mode: write a signed count of Y pulses; read what is left",
             one_value("COUNT", 24, "signed pulses (sign: direction); reads the pulses still to go",
                  signed=True), minimum=-(1 << 23), maximum=(1 << 23) - 1),
    capability("CLOCK_HZ", 0x54, "clock the card was built for (build parameter clock_hz)", (
        (Field("HZ", 0, 32, "PCI clock in Hz: the host converts times (DWELL, STEP_WIDTH, DIR_*, "
               "rates) with it", build="clock_hz"), 0),
    )),
    capability("FIFO_SIZE", 0x58, "size of the data FIFO (build parameter fifo_depth)", (
        (Field("WORDS", 0, 16, "32-bit words the FIFO holds", build="fifo_depth"), 0),
    )),
    capability("BUILD", 0x5C, "options the card was built with", (
        (Field("COORD_WIDTH", 0, 8, "signed coordinate width of LINE and ARC operands, in bits "
               "(build parameter coord_width)", build="coord_width"), 0),
        (Field("AXES", 8, 4, "axes with STEP/DIR pins, X, Y, Z, A, B, C in that order (build parameter "
               "axes; docs/axes.md)", build="axes"), 0),
        (Field("DDA_VARIANTS", 16, 4, f"bit n set: ARC.VARIANT n is built ({_VARIANT_CODES}; "
               "build parameter variants)", build="variants"), 0),
        (Field("DEVICE", 24, 4, f"FPGA family of the Verilog ({_DEVICE_CODES}; build parameter device)",
               build="device"), 0),
        (Field("ENCODERS", 28, 1, "1: every axis has encoder inputs, the probe input and their registers "
               "(build parameter encoders; docs/encoders.md)", build="encoders"), 0),
    )),
    Register("MACHINE_CONTROL", 0x60, "RW", 0, "the machine's outputs", (
        Field("DRIVE_ENABLE", 0, 1, "1: raise the DRIVE_ENABLE pin (a pulse under way keeps it high to its end); "
              "after a stop the host writes 1 again once CLEAR_STOP has released it",
              cleared="at a stop of the guard, and held at 0 while STATUS.STOPPED"),
        Field("HOLD", 1, 1, "feed hold: 1 ramps the path's rate down to zero (RAMP_STEP) and waits, "
              "0 ramps it up again; the path continues exactly"),
    )),
    Register("MACHINE_STATUS", 0x64, "RO", 0, "the machine's inputs and the guard", (
        Field("RAW", 0, XY_INPUTS, "ESTOP and X's and Y's input pins after the synchroniser, as wired (bit n: "
              "input n of INPUT_POLARITY; every input: INPUT_RAW)"),
        Field("ACTIVE", 8, XY_INPUTS, "ESTOP and X's and Y's inputs filtered, polarity applied: 1 active "
              "(bit n: input n; every input: INPUT_ACTIVE)"),
        Field("STOPPED", 16, 1, "the guard holds the card stopped (STOP_REASON says why)"),
        Field("DRIVE_ENABLE", 17, 1, "the DRIVE_ENABLE pin"),
        Field("HELD", 18, 1, "the path's rate is zero on a feed hold or a decelerated stop and its last "
              "step has left the pins"),
        Field("STOPPING", 19, 1, "a decelerated stop (WATCHDOG or LIMIT with RAMP_STEP not 0) ramps down; "
              "STOPPED follows once HELD"),
    )),
    Register("STOP_REASON", 0x68, "RO", 0,
             "why the guard stops or stopped the card (0 when neither STOPPING nor STOPPED)", (
        Field("REASON", 0, 3, f"{_REASON_CODES}"),
        Field("LIMITS", 4, len(LIMIT_NAMES), "LIMIT: the limits stepped towards (bit n: " + ", ".join(
            f"{bit} {name}" for bit, name in enumerate(LIMIT_NAMES)) + ")"),
        Field("AXIS", 16, 3, "FOLLOWING_ERROR: the axis whose following error went beyond its FERROR_LIMIT "
              "(0 X, 1 Y, ...; the lowest of several in the same clock)"),
    )),
    Register("INPUT_POLARITY", 0x6C, "RW", 0, "input polarity: 1 makes that input active low (a card of "
             "fewer axes has the bits of its axes' inputs only: the others read 0, writes to them are ignored)",
             tuple(Field(name, bit, 1, f"1: the {text} input is active low")
                   for bit, (name, text) in enumerate(INPUT_TEXT))),
    Register("INPUT_FILTER", 0x70, "RW", 3,
             "glitch filter: an input's new level counts once it held for this many samples",
             one_value("SAMPLES", 4, "1..15 samples, INPUT_TICK clocks apart (1: the first sample takes it)"),
             minimum=1, maximum=15),
    Register("INPUT_TICK", 0x74, "RW", 1, "clocks between the input filter's samples",
             one_value("CLOCKS", 16, "1..65535"), minimum=1, maximum=0xFFFF),
    Register("WATCHDOG", 0x78, "WP", 0,
             "host watchdog: write the timeout in clocks (0: off) at least that often; reads the clocks left",
             one_value("CLOCKS", WATCHDOG_BITS, "clocks until the guard stops the card (reason WATCHDOG); a write "
                  f"above {(1 << WATCHDOG_BITS) - 1} loads {(1 << WATCHDOG_BITS) - 1}"),
             minimum=0, maximum=(1 << WATCHDOG_BITS) - 1),
    Register("HOME", 0x7C, "WP", 0, "home one axis (docs/machine.md); reads what the last HOME asked", (
        Field("AXIS", 0, 1, "written with AXIS_INDEX 0 (as a two-axis host writes it): 0 homes X, 1 Y; reads the "
              "low bit of the axis asked"),
        Field("NEGATIVE", 1, 1, "1: the switch is towards negative positions"),
        Field("AXIS_INDEX", 4, 3, "the axis to home, 1 Y, 2 Z, 3 A, 4 B, 5 C (0: the one AXIS names); an axis the "
              "card lacks is REFUSED; reads the axis asked"),
    )),
    Register("HOME_STATUS", 0x80, "RO", 0, "the homing's state", (
        Field("BUSY", 0, 1, "homing under way (from the clock the HOME write is taken)"),
        Field("DONE", 1, 1, "the last HOME ended with the position zeroed at the release point"),
        Field("NOT_FOUND", 2, 1, "the switch did not trip (or release) within HOME_SEARCH steps"),
        Field("REFUSED", 3, 1, "a HOME came while the card was not idle, was stopped, or was homing, or named "
              "an axis the card lacks"),
        Field("PHASE", 4, 2, ", ".join(f"{code} {name}" for code, name in enumerate(HOME_PHASES))),
    )),
    Register("HOME_SEEK_PERIOD", 0x84, "RW", 100, "clocks between steps towards the home switch",
             one_value("CLOCKS", 16, "1..65535"), minimum=1, maximum=0xFFFF),
    Register("HOME_RELEASE_PERIOD", 0x88, "RW", 1000,
             "clocks between steps off the switch and of the back-off",
             one_value("CLOCKS", 16, "1..65535"), minimum=1, maximum=0xFFFF),
    Register("HOME_BACKOFF", 0x8C, "RW", 0, "steps on past the release point once the position is zeroed there",
             one_value("STEPS", 16, "0..65535"), minimum=0, maximum=0xFFFF),
    Register("HOME_SEARCH", 0x90, "RW", 0xFFFF,
             "steps the switch must trip within, and release within after it tripped",
             one_value("STEPS", HOME_SEARCH_BITS, f"1..{(1 << HOME_SEARCH_BITS) - 1}"),
             minimum=1, maximum=(1 << HOME_SEARCH_BITS) - 1),
    Register("STEP_SPACE", 0x94, "RW", STEP_WIDTH_RESET, "minimum STEP low time between two steps, in clocks",
             one_value("CLOCKS", 8, "1..255 (reset: STEP_WIDTH's reset, so one value times both as before)"),
             minimum=1, maximum=255, set_index=8),
    Register("STEP_MODE", 0x98, "RW", 0, "what the STEP and DIR pins of every axis carry (hostmot2's step_type)",
             one_value("MODE", 2, "0 step/dir; 1 up/down: STEP pulses the steps whose DIR would be high, DIR the "
                  "others; 2 quadrature: STEP, DIR an A/B pair, one change per step (A leads while DIR would "
                  "be high, a change a step period after the last); every mode keeps STEP_WIDTH, "
                  "STEP_SPACE, and DIR_HOLD + DIR_SETUP at a reversal; change it only while no step is "
                  "queued"), minimum=0, maximum=2),
    Register("INPUT_RAW", 0x9C, "RO", 0, "every input pin after the synchroniser, as wired (the bits of "
             "inputs the card lacks read 0)",
             tuple(Field(name, bit, 1, f"the {text} pin") for bit, (name, text) in enumerate(INPUT_TEXT))),
    Register("INPUT_ACTIVE", 0xA0, "RO", 0, "every input filtered, polarity applied: 1 active (the bits of "
             "inputs the card lacks read 0)",
             tuple(Field(name, bit, 1, f"1: the {text} input is active")
                   for bit, (name, text) in enumerate(INPUT_TEXT))),
)


IO_BAR_BITS = max(2, (max(r.offset for r in REGISTERS + ENCODER_REGISTERS) + WORD_BYTES - 1).bit_length())
SET_TARGETS = {r.set_index: r for r in REGISTERS if r.set_index is not None}
_BY_NAME = {r.name: r for r in REGISTERS + ENCODER_REGISTERS}
_AXIS_BY_NAME = {r.name: r for r in AXIS_REGISTERS}


def present(reg, values):
    """Whether a card built with ``values`` ({build parameter: value}; the defaults for the rest) has ``reg``."""
    return reg.option is None or bool(values.get(reg.option, parameters.PARAMETERS[reg.option].default))


def bar0_registers(values=None):
    """BAR0's registers of a card built with ``values`` (default: the default build), by offset."""
    return tuple(sorted((r for r in REGISTERS + ENCODER_REGISTERS if present(r, values or {})),
                        key=lambda r: r.offset))


def axis_spec(name):
    """The block register ``name`` (POS, ENC_COUNT, ...) as the block describes it (offset inside the block)."""
    try:
        return _AXIS_BY_NAME[name]
    except KeyError:
        raise ValueError(f"no per-axis register {name}") from None


def in_bar0(name):
    """Whether the block register ``name`` is BAR0's for X and Y (BAR0 has <name>_X)."""
    return f"{axis_spec(name).name}_{AXIS_NAMES[0]}" in _BY_NAME


def axis_offset(name, axis):
    """Byte offset in BAR2 of the per-axis register ``name`` (POS, ...) of axis ``axis`` (0: X)."""
    if not 0 <= axis < len(AXIS_NAMES):
        raise ValueError(f"axis {axis} is not 0..{len(AXIS_NAMES) - 1}")
    return AXIS_BLOCK_BASE + AXIS_STRIDE * axis + axis_spec(name).offset


def axis_register(name, axis):
    """The per-axis register ``name`` of axis ``axis``: for X and Y BAR0's own
    (POS_X, ...) where BAR0 has it, else one named POS_Z, ENC_COUNT_X, ... at its BAR2 offset."""
    full = f"{axis_spec(name).name}_{AXIS_NAMES[axis]}"
    if axis < BAR0_AXES and in_bar0(name):
        return register(full)
    return replace(axis_spec(name), name=full, offset=axis_offset(name, axis))


def axis_registers(axes, values=None):
    """The registers a card of ``axes`` axes built with ``values`` (build parameters; default: the
    defaults) has in BAR2's blocks only (not BAR0's), by offset."""
    return tuple(axis_register(spec.name, axis) for axis in range(axes) for spec in AXIS_REGISTERS
                 if present(spec, values or {}) and not (axis < BAR0_AXES and in_bar0(spec.name)))


def axis_aliases():
    """{BAR2 offset: BAR0 offset} of X's and Y's block registers that are BAR0's."""
    return {axis_offset(spec.name, axis): axis_register(spec.name, axis).offset
            for axis in range(BAR0_AXES) for spec in AXIS_REGISTERS if in_bar0(spec.name)}


_INPUT_REGISTERS = ("INPUT_POLARITY", "INPUT_RAW", "INPUT_ACTIVE")


def built_register(reg, axes):
    """``reg`` as a card of ``axes`` axes builds it: the input registers keep the fields of its
    inputs only (the others read 0 and ignore writes), every other register is the table's."""
    if reg.name not in _INPUT_REGISTERS:
        return reg
    names = input_names(axes)
    return replace(reg, fields=tuple(item for item in reg.fields if item.name in names))


def register(name):
    """The BAR0 register called ``name`` (of every build, or of those with encoders)."""
    try:
        return _BY_NAME[name]
    except KeyError:
        raise ValueError(f"no register {name}") from None


def offset(name):
    """Byte offset of register ``name`` in the I/O BAR (and in BAR2)."""
    return register(name).offset


def field_value(reg_name, field_name, word):
    """The value of one field in a word read from ``reg_name``."""
    item = register(reg_name).field(field_name)
    value = (word >> item.lsb) & ((1 << item.width) - 1)
    if item.signed and value >> (item.width - 1):
        value -= 1 << item.width
    return value


def field_of(reg_name, **values):
    """The word that puts ``values`` ({field: value}) into ``reg_name``."""
    reg = register(reg_name)
    word = 0
    for name, value in values.items():
        item = reg.field(name)
        word |= (value << item.lsb) & item.mask
    return word


def check_table(registers=None):
    """Raise ValueError when the table (``registers``; default: ``REGISTERS`` and
    ``ENCODER_REGISTERS``) contradicts itself (``models/register_checks.py``)."""
    checks.check_table(REGISTERS + ENCODER_REGISTERS if registers is None else registers, ACCESS_KINDS, WORD_BYTES)


def check_axis_block(axis_registers=None):
    """Raise ValueError when the per-axis block (``axis_registers``; default: ``AXIS_REGISTERS``)
    contradicts itself, differs from X's and Y's BAR0 registers or does not fit BAR2."""
    layout = dict(ACCESS_KINDS=ACCESS_KINDS, WORD_BYTES=WORD_BYTES, AXIS_BLOCK_BASE=AXIS_BLOCK_BASE,
                  AXIS_STRIDE=AXIS_STRIDE, AXIS_FREE=AXIS_FREE, BAR0_AXES=BAR0_AXES, IO_BAR_BITS=IO_BAR_BITS,
                  REG_BAR_BITS=REG_BAR_BITS)
    checks.check_axis_block(AXIS_REGISTERS if axis_registers is None else axis_registers,
                            REGISTERS + ENCODER_REGISTERS, layout)


# the table is checked as it loads
check_table()
check_axis_block()
