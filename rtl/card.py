"""The whole card with split PCI ports: PCI target + registers, FIFO, sequencer, pulses, DDA."""
from myhdl import Signal, block

from rtl import registers as regmap
from rtl.card_core import card_core
from rtl.dda_build import COORD_WIDTH, DEFAULT_VARIANTS
from rtl.interfaces import LocalBus, MotorPins, PciBus, card_reset
from rtl.pci_slave import local_addr_width, pci_slave

MEM_BAR_BITS = 12  # 4 KiB FIFO window: a host burst of up to 1024 words


def slave_params(**slave):
    """``pci_slave`` parameters of the card: the BAR sizes follow the register table."""
    return dict(slave, io_bar_bits=regmap.IO_BAR_BITS, mem_bar_bits=MEM_BAR_BITS)


@block
def card(clock, reset, pci, pins, *, fifo_depth=512, coord_width=COORD_WIDTH, variants=DEFAULT_VARIANTS, **slave):
    """The paper's figure 1 in the FPGA, PCI lines still split in / out / enable.

    Ports: ``clock`` PCI CLK, ``reset`` RST# (``card_reset()``), ``pci``
    (``PciBus``), ``pins`` (``MotorPins``).  Parameters: ``fifo_depth``,
    ``coord_width``, ``variants`` (the DDA's build) and those of ``pci_slave``
    but the BAR sizes (``vendor_id``,
    ``device_id``, ..., ``io_registers``).  BAR0 (I/O) is ``2**IO_BAR_BITS`` bytes, the size the
    register table needs; BAR1 (memory, the FIFO window) is 4 KiB.

        PCI --> pci_slave --LocalBus--> card_core --> STEP/DIR
                    ^                       |
                    +---------- irq --------+
    """
    params = slave_params(**slave)
    local = LocalBus(local_addr_width(params["io_bar_bits"], params["mem_bar_bits"]))
    irq = Signal(bool(0))
    target = pci_slave(clock, reset, pci, local, irq, **params)
    core = card_core(clock, reset, local, irq, pins, fifo_depth=fifo_depth, coord_width=coord_width,
                     variants=variants)
    return target, core


def card_ports(fifo_depth=512, coord_width=COORD_WIDTH, variants=DEFAULT_VARIANTS, **slave):
    """Fresh ports of ``card`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), pci=PciBus(), pins=MotorPins())
