"""Which card the host is talking to: ``identify(card)`` reads ID and the
capability registers (CLOCK_HZ, FIFO_SIZE, BUILD, the configuration IDs)
into an ``Identity``, or refuses another card or a register map this host
does not speak (``IdentityError``).
"""
from dataclasses import dataclass

from models import registers as regmap

# the major version this host speaks, every minor of it (3.0 holds every register 2.4 had; a 2.x card
# takes a helical ARC's operands otherwise, docs/axes.md)
MAJOR = regmap.VERSION >> 8


class IdentityError(RuntimeError):
    """Not this card, or a register map this host does not speak."""


@dataclass(frozen=True)


class Identity:
    version: tuple      # (major, minor)
    clock_hz: int
    fifo_words: int
    coord_width: int
    axes: int
    variants: tuple     # ARC.VARIANT values built
    device: int         # BUILD.DEVICE
    vendor_id: int
    device_id: int
    encoders: bool = False   # BUILD.ENCODERS: the card has encoder inputs and their registers


def identify(card):
    """``card``'s ``Identity`` (its ``read``, ``field`` and ``transport``); IdentityError for another
    card or major version."""
    word = card.read("ID")
    magic, version = regmap.field_value("ID", "MAGIC", word), regmap.field_value("ID", "VERSION", word)
    where = card.transport.name
    if magic != regmap.ID_MAGIC:
        raise IdentityError(f"{where}: ID reads {word:#010x}, not a DDA card (magic {regmap.ID_MAGIC:#x})")
    major, minor = version >> 8, version & 0xFF
    if major != MAJOR:
        raise IdentityError(f"{where}: register map {major}.{minor}; this host software speaks {MAJOR}.x")
    build = card.read("BUILD")
    ids = card.transport.config_read(0)
    variants = regmap.field_value("BUILD", "DDA_VARIANTS", build)
    return Identity((major, minor), card.read("CLOCK_HZ"), card.field("FIFO_SIZE", "WORDS"),
                    regmap.field_value("BUILD", "COORD_WIDTH", build), regmap.field_value("BUILD", "AXES", build),
                    tuple(v for v in range(4) if variants >> v & 1),
                    regmap.field_value("BUILD", "DEVICE", build), ids & 0xFFFF, ids >> 16,
                    bool(regmap.field_value("BUILD", "ENCODERS", build)))
