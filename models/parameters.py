"""The card's build parameters, each defined once: default, range or choices, help.

``PARAMETERS`` is the single table.  The converter's command line
(``rtl/convert.py``) is made from it, every check of a value goes through
``check``, so a range is stated in one place, with its reason.  A limit that
holds only for one device names the part it is for (``device_maximum``).

``Build`` is the build record made from the table: one frozen dataclass with
a field per parameter and the table's defaults, checked whole when it is
made (``Build.for_unit`` gives a unit's defaults, ``replace`` a changed
copy).  The top makes or receives one ``Build`` and passes it down,
``top -> card -> card_core -> regs_fifo`` and ``card -> pci_slave ->
pci_config``, as the keyword ``build``; no block re-declares a parameter or
its default.  Leaf units that take a value or two keep plain keywords
(``sync_fifo(depth=...)``, ``pin_lut(device=...)``), and blocks whose build
shapes their ports read it from the interface they receive (``dda_arc``
from its ``DdaPort``).  Which parameters a unit converted alone takes from
the command line is said in one place: the converter's ``UNITS``.

Values are Python ints and strings; ``encode`` turns ``device`` and
``variants`` into the codes the capability registers report
(``models/registers.py``).
"""
import dataclasses
from dataclasses import dataclass, field

from models.axes import AXIS_NAMES, MAX_AXES

DEVICES = ("generic", "ice40", "ecp5")  # BUILD.DEVICE codes 0, 1, 2
# ARC.VARIANT codes 0..3 (models/instructions.py); BUILD.DDA_VARIANTS has bit n for code n
VARIANT_NAMES = ("traditional", "weighted", "improved", "precise")
VARIANT_SETS = {"improved,precise": ("improved", "precise"), "all": VARIANT_NAMES}


class ParameterError(ValueError):
    """A build parameter outside its range, or an unknown one: ``problem``
    says what is wrong with ``parameter`` (None: no parameter in particular)."""

    def __init__(self, problem, parameter=None):
        self.problem, self.parameter = problem, parameter
        super().__init__(problem if parameter is None else f"{parameter.name} {problem}")


@dataclass(frozen=True)
class Parameter:
    """One build parameter.

    ``minimum``/``maximum`` (ints) or ``choices`` (strings) bound it;
    ``power_of_two`` asks for one; ``reason`` says why the bounds are what
    they are; ``device_maximum`` maps a device to ``(maximum, reason)`` for a
    tighter limit of that device's part; ``unit_defaults`` maps a unit to a
    default of its own (the top is built for iCE40 unless told otherwise).
    """

    name: str
    default: object
    text: str
    minimum: int = None
    maximum: int = None
    choices: tuple = None
    power_of_two: bool = False
    reason: str = ""
    device_maximum: dict = field(default_factory=dict)
    unit_defaults: dict = field(default_factory=dict)
    hex_digits: int = 0  # shown in hexadecimal with this many digits
    flag: bool = False   # 0 or 1, given on the command line as a bare option (``--encoders``: 1)

    @property
    def option(self):
        return f"--{self.name.replace('_', '-')}"

    def default_for(self, unit):
        """The default of ``unit`` (most units: ``default``)."""
        return self.unit_defaults.get(unit, self.default)

    def shown(self, value):
        """``value`` as the help and the messages write it."""
        if self.choices is not None:
            return str(value)
        if value < 0:
            return f"-{self.shown(-value)}"
        return f"0x{value:0{self.hex_digits}X}" if self.hex_digits else f"{value:,}"

    def bounds(self):
        """The range or the choices, as text."""
        if self.choices is not None:
            return " or ".join(filter(None, (", ".join(self.choices[:-1]), self.choices[-1])))
        kind = "a power of two, " if self.power_of_two else ""
        return f"{kind}{self.shown(self.minimum)}..{self.shown(self.maximum)}"

    def describe(self):
        """Help text: what it is, its bounds and why, device limits, default."""
        text = f"{self.text}: {self.bounds()}"
        if self.reason:
            text += f" ({self.reason})"
        for device, (maximum, why) in self.device_maximum.items():
            text += f"; {device}: at most {self.shown(maximum)} ({why})"
        if self.unit_defaults:
            others = ", ".join(f"{value} for the {unit}" for unit, value in self.unit_defaults.items())
            return f"{text} (default: {self.default}; {others})"
        return f"{text} (default: {self.shown(self.default)})"

    def parse(self, text):
        """The value of the command-line word ``text``; ParameterError if bad."""
        if self.choices is not None:
            return self.check(text)
        try:
            value = int(text, 0)
        except ValueError:
            raise ParameterError(f"must be an integer ({self.bounds()}), not {text!r}", self) from None
        return self.check(value)

    def check(self, value, device=None):
        """``value`` if it is within bounds (and within ``device``'s limit)."""
        if self.choices is not None:
            if value not in self.choices:
                raise ParameterError(f"must be {self.bounds()}, not {value!r}", self)
            return value
        if isinstance(value, bool) or not isinstance(value, int):
            raise ParameterError(f"must be an integer ({self.bounds()}), not {value!r}", self)
        if (not self.minimum <= value <= self.maximum
                or (self.power_of_two and value & (value - 1))):
            why = f" ({self.reason})" if self.reason else ""
            raise ParameterError(f"must be {self.bounds()}{why}, not {self.shown(value)}", self)
        if device in self.device_maximum:
            maximum, why = self.device_maximum[device]
            if value > maximum:
                raise ParameterError(f"must be at most {self.shown(maximum)} for {device} ({why}), "
                                     f"not {self.shown(value)}", self)
        return value


def _id(name, bits, default, text, maximum=None, reason=""):
    """A PCI configuration-header field of ``bits`` bits."""
    return Parameter(name, default, text, 0, (1 << bits) - 1 if maximum is None else maximum,
                     reason=reason, hex_digits=bits // 4)


_TABLE = (
    Parameter("device", "generic", "FPGA family the Verilog is for", choices=DEVICES,
              reason="generic: plain Verilog, no vendor primitive; ice40: SB_IO pads that hold the PCI "
              "registers, hand-placed SB_LUT4 cells on the PCI pin paths; ecp5: hand-placed LUT4 cells on the PCI "
              "pin paths, the FIFO's read word from a fabric flip-flop (its block RAM's clock-to-output kept out of the "
              "sequencer's logic), the pads as in the generic build", unit_defaults={"top": "ice40"}),
    Parameter("variants", "improved,precise", "DDA variants built, reported in BUILD.DDA_VARIANTS",
              choices=tuple(VARIANT_SETS), reason="improved,precise: the paper's improved DDA and the "
              "precise mode; all: the paper's traditional and weighted DDA as well, to reproduce its "
              "figures"),
    Parameter("axes", 2, f"axes with STEP/DIR outputs, reported in BUILD.AXES: the first N of "
              f"{' '.join(AXIS_NAMES)} (docs/axes.md)", 2, MAX_AXES,
              reason=f"2: an arc needs a plane of two axes; {MAX_AXES}: the axis names "
              f"{' '.join(AXIS_NAMES)} and the {MAX_AXES}-bit axis masks of LINE.AXES, ARC.HELIX and PULSE.AXES"),
    Parameter("encoders", 0, "1: encoder inputs on every axis, the probe input, the following-error stop "
              "and their registers, reported in BUILD.ENCODERS (docs/encoders.md; the command line's bare "
              "--encoders)", 0, 1, flag=True,
              reason="an option: one axis's encoder and following error is about 790 iCE40 cells, more "
              "than the two-axis HX8K card has left"),
    Parameter("coord_width", 24, "signed coordinate width of the DDA, in bits", 14, 29,
              reason="14: STOP_LEFT, coord_width + 3 bits, must be wider than the feed-rate ramp's "
              "16-bit count; 29: wider coordinates give STOP_LEFT a reset value above 32 bits, which "
              "MyHDL writes as an unsized Verilog number"),
    Parameter("fifo_depth", 512, "data FIFO depth in 32-bit words", 4, 32768, power_of_two=True,
              reason="4: the FIFO promises the PCI target three free places (LocalBus.room) before it "
              "acknowledges a posted dword; STATUS.FIFO_LEVEL, 16 bits, counts 0..depth",
              device_maximum={"ice40": (4096, "the iCE40 HX8K has 32 block RAMs of 4 Kbit, "
                                                "4,096 32-bit words in all"),
                              "ecp5": (16384, "the ECP5 LFE5U-25F has 56 block RAMs of 512 36-bit words, "
                                              "28,672 32-bit words in all")}),
    Parameter("clock_hz", 33_333_333, "PCI clock the card runs at, in Hz, reported in CLOCK_HZ "
              "(the host converts times with it)", 1, 33_333_333,
              reason="PCI 2.3 clocks a device that does not claim 66 MHz at up to 33.33 MHz"),
    _id("vendor_id", 16, 0x1234, "PCI Vendor ID (placeholder: use your own)", 0xFFFE,
        reason="0xFFFF reads as no device"),
    _id("device_id", 16, 0xDDA0, "PCI Device ID"),
    _id("revision_id", 8, 0x01, "PCI Revision ID"),
    _id("class_code", 24, 0x088000, "PCI class code (0x088000: base system peripheral, other)"),
    _id("subsystem_vendor_id", 16, 0x1234, "PCI Subsystem Vendor ID"),
    _id("subsystem_id", 16, 0x0001, "PCI Subsystem ID"),
    Parameter("io_bar_bits", 6, "BAR0 (I/O) of the stand-alone pci_slave unit is 2**bits bytes; "
              "the card sizes it from its register map", 2, 8,
              reason="PCI: I/O BARs of 4 to 256 bytes"),
    Parameter("reg_bar_bits", 4, "BAR2 (memory) of the stand-alone pci_slave unit is 2**bits bytes, or BAR0's "
              "size if larger; BAR0's registers sit at their offsets in it, the rest reaches the back end too; "
              "the card's is 4 KiB (its per-axis register blocks, docs/pci.md)", 4, 16,
              reason="16 bytes, PCI's smallest memory BAR, to 64 KiB"),
    Parameter("mem_bar_bits", 12, "BAR1 (memory) of the stand-alone pci_slave unit is 2**bits bytes; "
              "the card's is 4 KiB", 4, 24, reason="16 bytes, PCI's smallest memory BAR, to 16 MiB"),
)
PARAMETERS = {p.name: p for p in _TABLE}
PCI_IDS = ("vendor_id", "device_id", "revision_id", "class_code", "subsystem_vendor_id", "subsystem_id")
DEVICE, VARIANTS, AXES, ENCODERS, COORD_WIDTH, FIFO_DEPTH, CLOCK_HZ = (
    PARAMETERS[name] for name in ("device", "variants", "axes", "encoders", "coord_width", "fifo_depth", "clock_hz"))


def _known(values):
    """``values`` if it names build parameters only; ParameterError else."""
    unknown = sorted(set(values) - set(PARAMETERS))
    if unknown:
        raise ParameterError(f"unknown build parameters {unknown}")
    return values


def check(values, device=None):
    """``values`` ({name: value}) if every one is within its bounds; the
    device limits of ``device`` (or of ``values["device"]``) apply too."""
    device = _known(values).get("device", device)
    if device is not None:
        DEVICE.check(device)
    for name, value in values.items():
        PARAMETERS[name].check(value, device)
    return dict(values)


class _BuildRecord:
    """What ``Build`` does besides holding its fields (they come from the table)."""

    def __post_init__(self):
        check(self.as_dict())

    @classmethod
    def for_unit(cls, unit, **values):
        """The build of ``unit``: its defaults (``Parameter.default_for``), ``values`` replacing them."""
        _known(values)
        return cls(**{name: values.get(name, PARAMETERS[name].default_for(unit)) for name in PARAMETERS})

    def replace(self, **values):
        """A copy with ``values`` ({name: value}) replaced, checked; ParameterError on an unknown name."""
        return dataclasses.replace(self, **_known(values))

    def as_dict(self):
        """``{name: value}`` of every parameter, in the table's order."""
        return {name: getattr(self, name) for name in PARAMETERS}

    def view(self, names):
        """``{name: value}`` of the parameters ``names`` (a unit's share of the build)."""
        return {name: getattr(self, name) for name in names}


Build = dataclasses.make_dataclass(
    "Build", [(p.name, type(p.default), field(default=p.default)) for p in _TABLE],
    bases=(_BuildRecord,), frozen=True, namespace={"__module__": __name__})
Build.__doc__ = """The build record: one field per build parameter of ``PARAMETERS``, its
default the table's; every value is checked (ranges, choices, device limits)
when a ``Build`` is made, so a block that receives one checks nothing again."""


def variant_codes(variants):
    """ARC.VARIANT codes of the variants ``variants`` names, ascending."""
    return tuple(VARIANT_NAMES.index(name) for name in VARIANT_SETS[VARIANTS.check(variants)])


def encode(name, value):
    """The number a capability register field holds for parameter ``name``."""
    if name == "device":
        return DEVICES.index(DEVICE.check(value))
    if name == "variants":
        return sum(1 << code for code in variant_codes(value))
    return PARAMETERS[name].check(value)
