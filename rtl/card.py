"""The whole card with split PCI ports: PCI target + registers, FIFO, sequencer, pulses, DDA."""
from myhdl import Signal, block

from models import registers as regmap
from models.parameters import Build
from rtl.card_core import card_core
from rtl.interfaces import LocalBus, MotorPins, PciBus, card_reset
from rtl.pci.pci_slave_build import local_addr_width
from rtl.pci_slave import pci_slave

MEM_BAR_BITS = 12  # 4 KiB FIFO window: a host burst of up to 1024 words


def slave_build(build):
    """The build of the card's ``pci_slave``: ``build`` with the BAR sizes the register table needs."""
    return build.replace(io_bar_bits=regmap.IO_BAR_BITS, mem_bar_bits=MEM_BAR_BITS, reg_bar_bits=regmap.REG_BAR_BITS)


# ``build``: one ``Build`` (``models/parameters.py``), passed down whole; the
# parameters the docstring names are its fields (the docstring is gen/card.v's header).
@block
def card(clock, reset, pci, pins, *, build=Build(), io_registers=False):
    """The paper's figure 1 in the FPGA, PCI lines still split in / out / enable.

    Ports: ``clock`` PCI CLK, ``reset`` RST# (``card_reset()``), ``pci``
    (``PciBus``), ``pins`` (``MotorPins`` of the build's ``axes``).  Parameters
    (``models/parameters.py``): ``fifo_depth``, ``coord_width``, ``clock_hz``,
    ``variants``, ``device`` (the PCI target's one-LUT paths: plain logic or
    iCE40 cells) and the PCI IDs (``vendor_id``, ``device_id``, ...);
    ``io_registers`` (``pci_slave``'s: True when the top's pads hold the PCI
    registers).  BAR0 (I/O) is ``2**IO_BAR_BITS`` bytes, the size the
    register table needs; BAR1 (memory, the FIFO window) is 4 KiB; BAR2
    (memory) is ``2**REG_BAR_BITS`` bytes: BAR0's registers at their offsets,
    then the per-axis register blocks.

        PCI --> pci_slave --LocalBus--> card_core --> STEP/DIR
                    ^                       |
                    +---------- irq --------+
    """
    slave = slave_build(build)
    local = LocalBus(local_addr_width(slave.io_bar_bits, slave.mem_bar_bits, slave.reg_bar_bits))
    irq = Signal(bool(0))
    target = pci_slave(clock, reset, pci, local, irq, build=slave, io_registers=io_registers)
    interior = card_core(clock, reset, local, irq, pins, build=build)
    return target, interior


def card_ports(axes=Build.axes, encoders=Build.encoders):
    """Fresh ports of ``card`` for conversion and benches: ``pins`` of ``axes`` axes (the build
    parameter; no other changes a port)."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), pci=PciBus(), pins=MotorPins(axes, encoders))
