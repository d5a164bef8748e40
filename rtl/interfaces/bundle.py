"""How bundles take signals a block already has, the card's reset, and the axes' names in signal names."""
from myhdl import ResetSignal

from models.axes import AXIS_NAMES
from models.parameters import AXES


def card_reset():
    """The card's reset: PCI RST#, asynchronous, active low."""
    return ResetSignal(1, active=0, isasync=True)


def adopt(bundle, given, **fresh):
    """Set the signals ``fresh`` on ``bundle``, each one replaced by the signal
    of its name in ``given`` (the card wires signals it already has into a
    bundle); a given signal must be as wide as the fresh one."""
    unknown = set(given) - set(fresh)
    if unknown:
        raise TypeError(f"{type(bundle).__name__} has no signal {', '.join(sorted(unknown))}")
    for name, signal in fresh.items():
        if name in given:
            if len(given[name]) != len(signal):
                raise ValueError(f"{type(bundle).__name__}.{name}: {len(signal)} bits, not {len(given[name])}")
            signal = given[name]
        setattr(bundle, name, signal)


def axis_suffixes(axes):
    """The suffixes of the per-axis signals of a card of ``axes`` axes (``x``,
    ``y``, ``z``, ``a``, ...: ``models/axes.py``), checked against the build
    parameter's range."""
    return tuple(name.lower() for name in AXIS_NAMES[:AXES.check(axes)])


def named(name, instance):
    """``instance`` (a block instance) named ``name``: the converted signals
    and the traces call its signals ``<parent>_<name>_<signal>`` (one
    instance per axis: ``axis_x``, ``axis_y``, ... rather than numbered)."""
    instance.name = name
    return instance
