"""The register table's types: a ``Register`` of ``Field``s, with its access
kind, reset, range and the build parameters it reports or needs
(``models/registers.py`` has the table and says what the access kinds mean).
"""
from dataclasses import dataclass, field

from models import parameters

ACCESS_KINDS = ("RO", "RW", "W1C", "W1S", "WP")
WORD_BYTES = 4
BAR0_AXES = 2   # X and Y: their block registers are BAR0's (POS_X, ...), their inputs the first XY_INPUTS


@dataclass(frozen=True)
class Field:
    name: str
    lsb: int
    width: int
    text: str
    signed: bool = False
    build: str = None  # the build parameter whose value the field holds (RO only)
    cleared: str = None  # RW only: what clears the field and holds it at 0 (the hardware's ``hw`` bits)

    @property
    def mask(self):
        return ((1 << self.width) - 1) << self.lsb


@dataclass(frozen=True)
class Register:
    name: str
    offset: int
    access: str
    reset: int
    text: str
    fields: tuple = field(default_factory=tuple)
    minimum: int = None
    maximum: int = None
    set_index: int = None
    option: str = None  # the build parameter (0 or 1) a card must be built with for the register to exist

    @property
    def width(self):
        return max(f.lsb + f.width for f in self.fields)

    @property
    def signed(self):
        return len(self.fields) == 1 and self.fields[0].signed

    def field(self, name):
        for item in self.fields:
            if item.name == name:
                return item
        raise ValueError(f"register {self.name} has no field {name}")


def one_value(name, width, text, signed=False):
    """A register that holds one value in its low bits."""
    return (Field(name, 0, width, text, signed),)


def build_word(reg, values):
    """The value of ``reg`` in a card built with ``values`` ({build parameter:
    value}; the defaults of ``models/parameters.py`` for the rest): its reset
    value with every ``build`` field holding its parameter's code."""
    word = reg.reset
    for item in reg.fields:
        if item.build is None:
            continue
        value = values.get(item.build, parameters.PARAMETERS[item.build].default)
        code = parameters.encode(item.build, value)
        if not 0 <= code < 1 << item.width:
            raise ValueError(f"{reg.name}.{item.name}: {item.build} = {value} does not fit {item.width} bits")
        word = (word & ~item.mask) | code << item.lsb
    return word


def capability(name, offset, text, fields):
    """A read-only register of build facts; its reset value is that of the
    default build's top (``gen/top.v``, built for iCE40)."""
    constants = sum(value << item.lsb for item, value in fields)
    reg = Register(name, offset, "RO", constants, text, tuple(item for item, _ in fields))
    top = {item.build: parameters.PARAMETERS[item.build].default_for("top") for item in reg.fields if item.build}
    return Register(name, offset, "RO", build_word(reg, top), text, reg.fields)
