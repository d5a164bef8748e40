"""Signal bundles shared between the card's blocks.

Every interface is a plain class whose attributes are MyHDL ``Signal``s.
Widths are constructor arguments.  When a block with an interface argument is
the top of a conversion, MyHDL names each port ``<argument>_<attribute>``.

Shared PCI lines are split into ``*_in`` / ``*_out`` / ``*_oe`` so that the
cores co-simulate and convert cleanly; only the pad wrapper at the top level
has tri-states.  All PCI ``*_out`` values keep the bus polarity (active-low
lines are 0 when asserted).
"""
from myhdl import ResetSignal, Signal, intbv


class PciBus:
    """The target's view of a 32-bit PCI bus.

    ``*_in`` is what the target samples from the line, ``*_out`` what it would
    drive and ``*_oe`` whether it drives.  SERR# and INTA# are open-drain: the
    target drives them low (``*_oe`` high, ``*_out`` low) or not at all.
    """

    def __init__(self):
        self.ad_in = Signal(intbv(0)[32:])
        self.ad_out = Signal(intbv(0)[32:])
        self.ad_oe = Signal(bool(0))
        self.cbe_in = Signal(intbv(0xF)[4:])
        self.par_in = Signal(bool(0))
        self.par_out = Signal(bool(0))
        self.par_oe = Signal(bool(0))
        self.frame_in = Signal(bool(1))
        self.irdy_in = Signal(bool(1))
        self.idsel_in = Signal(bool(0))
        self.trdy_out = Signal(bool(1))
        self.trdy_oe = Signal(bool(0))
        self.devsel_out = Signal(bool(1))
        self.devsel_oe = Signal(bool(0))
        self.stop_out = Signal(bool(1))
        self.stop_oe = Signal(bool(0))
        self.perr_out = Signal(bool(1))
        self.perr_oe = Signal(bool(0))
        self.serr_out = Signal(bool(1))
        self.serr_oe = Signal(bool(0))
        self.inta_out = Signal(bool(1))
        self.inta_oe = Signal(bool(0))


class LocalBus:
    """The PCI target's back-end bus (one per card, both BARs).

    A request (``we`` or ``re``) with ``space``, ``addr``, ``be`` and, for a
    write, ``wdata`` is held until the clock edge at which the back end answers
    ``ready`` (the transfer happens at that edge; ``rdata`` is valid while
    ``ready`` is high) or ``retry`` (nothing happens: the back end cannot serve
    the request now and the target terminates with retry or disconnect).

    ``space`` 0 is the I/O BAR (function registers), 1 the memory BAR (data
    FIFO window).  ``addr`` is the byte offset inside the BAR, dword aligned.
    ``be`` are active-high byte enables.

        clock    _/~\\_/~\\_/~\\_/~\\_
        we       __/~~~~~~~~~~~\\___
        addr     --<  A0 >< A1 >---
        ready    ________/~~~~~\\___     A0 waits one clock, A1 none
    """

    def __init__(self, addr_width=16):
        self.addr_width = addr_width
        self.space = Signal(bool(0))
        self.addr = Signal(intbv(0)[addr_width:])
        self.be = Signal(intbv(0)[4:])
        self.wdata = Signal(intbv(0)[32:])
        self.we = Signal(bool(0))
        self.re = Signal(bool(0))
        self.rdata = Signal(intbv(0)[32:])
        self.ready = Signal(bool(0))
        self.retry = Signal(bool(0))


class AxisPulses:
    """Step and direction requests for the two axes, one clock per step."""

    def __init__(self):
        self.step_x = Signal(bool(0))
        self.step_y = Signal(bool(0))
        self.dir_x = Signal(bool(0))
        self.dir_y = Signal(bool(0))


def card_reset():
    """The card's reset: PCI RST#, asynchronous, active low."""
    return ResetSignal(1, active=0, isasync=True)
