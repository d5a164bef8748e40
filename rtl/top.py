"""The card as synthesised: the PCI pads around the card (``top``).

``python -m rtl.top --convert`` writes the card's Verilog into ``gen/``; the
converter and its command line are ``rtl/convert.py``.
"""
import sys

from myhdl import Signal, block

from models.parameters import Build
from rtl.card import card
from rtl.interfaces import MotorPins, PciBus, PciPins, card_reset
from rtl.pci.pci_pads import pci_pads


# ``build``: one ``Build`` (``models/parameters.py``; ``Build.for_unit("top")``
# unless given), passed to ``card`` whole (the docstring is gen/top.v's header).
@block
def top(clock, reset, pci_pins, motor, *, build=Build.for_unit("top")):
    """The card as synthesised: PCI pads (the only tri-states) around the card.

    Ports: ``clock`` PCI CLK, ``reset`` RST# (``card_reset()``), ``pci_pins``
    (``PciPins``: AD, C/BE#, PAR, FRAME#, IRDY#, TRDY#, DEVSEL#, STOP#, IDSEL,
    PERR#, SERR#, INTA# as on the bus), ``motor`` (``MotorPins``: STEP/DIR of
    every axis of the build, the machine's inputs).
    Parameters: those of ``card`` (``models/parameters.py``).  ``device``
    ``ice40`` (the top's default): the PCI boundary flip-flops are the iCE40
    I/O cells' registers (``rtl/pci/pci_pads.py``; the target is told so) and
    the target's pin paths are iCE40 LUTs; ``ecp5``: plain tri-states, the
    pin paths ECP5 LUTs; ``generic``: plain tri-states and plain logic.  ``rtl/card.py`` is the same card with split ports, for
    benches.

        pins <-> pci_pads <-> card (pci_slave, regs_fifo, dda_arc) --> STEP/DIR
    """
    io_registers = build.device == "ice40"
    pci = PciBus()
    pads = pci_pads(clock, pci_pins, pci, io_registers=io_registers)
    core = card(clock, reset, pci, motor, build=build, io_registers=io_registers)
    return pads, core


def top_ports(axes=Build.axes, encoders=Build.encoders):
    """Fresh ports of ``top`` for conversion and benches: ``motor`` of ``axes`` axes (the build
    parameter; no other changes a port)."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), pci_pins=PciPins(), motor=MotorPins(axes, encoders))


if __name__ == "__main__":
    from rtl.convert import main

    sys.exit(main())
