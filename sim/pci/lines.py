"""The PCI lines as plain Python data: names, widths, pull-ups, parity, a
bus sample.  No simulator in here: the MyHDL bus model (``sim.pci.bus``),
the protocol checker and every other front end share these.

Values are the electrical levels: the active-low control lines (FRAME#,
IRDY#, TRDY#, DEVSEL#, STOP#, PERR#, SERR#, INTA#) read 0 when asserted and
1 when idle (the system board pulls them up); AD, C/BE# and PAR have no
pull-ups and float when nobody drives them (``None`` in a ``BusSample``).
"""
# Line name -> width.  Order is the order of the VCD and of the samples.
LINE_WIDTHS = {
    "ad": 32, "cbe": 4, "par": 1, "frame": 1, "irdy": 1, "trdy": 1,
    "devsel": 1, "stop": 1, "perr": 1, "serr": 1, "inta": 1,
}
PULLED_UP = ("frame", "irdy", "trdy", "devsel", "stop", "perr", "serr", "inta")
FLOATING = ("ad", "cbe", "par")
OPEN_DRAIN = ("serr", "inta")
SUSTAINED_TRISTATE = ("frame", "irdy", "trdy", "devsel", "stop", "perr")


def even_parity(ad, cbe):
    """PAR that makes the number of ones over AD[31:0], C/BE#[3:0] and PAR even."""
    return ((int(ad) & 0xFFFFFFFF) | ((int(cbe) & 0xF) << 32)).bit_count() & 1


class BusSample:
    """The segment as sampled at one rising edge: ``values[line]`` (``None``
    for a floating AD, C/BE# or PAR, also readable as ``sample.<line>``) and
    ``drivers[line]`` (the set of agent names that drove the line in the
    clock that ended at this edge).  ``unknown``: the lines a four-state
    simulator saw as X or Z while an agent drove them (an X/Z detector's
    report; empty for two-state simulators)."""

    __slots__ = ("time", "values", "drivers", "unknown", *LINE_WIDTHS)

    def __init__(self, time, values, drivers, unknown=frozenset()):
        self.time, self.values, self.drivers, self.unknown = time, values, drivers, unknown
        for line in LINE_WIDTHS:
            setattr(self, line, values.get(line))

    def __repr__(self):
        return f"BusSample(time={self.time}, values={self.values}, unknown={set(self.unknown)})"
