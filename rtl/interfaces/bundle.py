"""How bundles take signals a block already has, and the card's reset."""
from myhdl import ResetSignal


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
