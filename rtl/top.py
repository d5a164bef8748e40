"""The card as synthesised: the PCI pads around the card (``top``).

``python -m rtl.top --convert`` writes the card's Verilog into ``gen/``; the
converter and its command line are ``rtl/convert.py``.
"""
import sys

from myhdl import Signal, block

from models import parameters
from models.parameters import DEVICE
from rtl.card import CARD_PARAMETERS, card
from rtl.interfaces import MotorPins, PciBus, PciPins, card_reset
from rtl.pci.pci_pads import pci_pads


@block
def top(clock, reset, pci_pins, motor, *, device=DEVICE.default_for("top"), **build):
    """The card as synthesised: PCI pads (the only tri-states) around the card.

    Ports: ``clock`` PCI CLK, ``reset`` RST# (``card_reset()``), ``pci_pins``
    (``PciPins``: AD, C/BE#, PAR, FRAME#, IRDY#, TRDY#, DEVSEL#, STOP#, IDSEL,
    PERR#, SERR#, INTA# as on the bus), ``motor`` (``MotorPins``: STEP/DIR).
    Parameters: those of ``card`` (``models/parameters.py``).  ``device``
    ``ice40`` (the top's default): the PCI boundary flip-flops are the iCE40
    I/O cells' registers (``rtl/pci/pci_pads.py``; the target is told so) and
    the target's pin paths are iCE40 LUTs; ``generic``: plain tri-states
    and plain logic.  ``rtl/card.py`` is the same card with split ports, for
    benches.

        pins <-> pci_pads <-> card (pci_slave, regs_fifo, dda_arc) --> STEP/DIR
    """
    io_registers = DEVICE.check(device) == "ice40"
    pci = PciBus()
    pads = pci_pads(clock, pci_pins, pci, io_registers=io_registers)
    core = card(clock, reset, pci, motor, device=device, io_registers=io_registers, **build)
    return pads, core


def top_ports(**build):
    """Fresh ports of ``top`` for conversion and benches (``build``: its
    parameters, checked; none of them changes a port)."""
    parameters.check_unit("top", CARD_PARAMETERS, build)
    return dict(clock=Signal(bool(0)), reset=card_reset(), pci_pins=PciPins(), motor=MotorPins())


if __name__ == "__main__":
    from rtl.convert import main

    sys.exit(main())
