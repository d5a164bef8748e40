"""Passive PCI protocol monitor, MyHDL front end.

The rules live in ``sim.pci.checker`` (``ProtocolChecker``: plain Python, one
``BusSample`` per rising edge); ``pci_monitor`` feeds it the bench's bus
model at every rising edge.
"""
from myhdl import block, instance

from sim.pci.checker import RULES, ProtocolChecker, ProtocolViolation, TransactionRecord  # noqa: F401


@block
def pci_monitor(clock, reset, segment, checker):
    """Feed ``checker`` (a ProtocolChecker) one sample of ``segment`` per
    rising edge of ``clock``; ``reset`` (RST#, or None) marks reset clocks.

        clock   _/~\\_/~\\_/~\\_
        sample    ^   ^   ^     lines and drivers of the clock that ended
    """

    @instance
    def watch():
        while True:
            yield clock.posedge
            in_reset = reset is not None and reset.val == reset.active
            checker.step(segment.sample(), in_reset)

    return watch
