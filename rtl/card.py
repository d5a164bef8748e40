"""The whole card with split PCI ports: PCI target + registers, FIFO, sequencer, pulses, DDA."""
from myhdl import Signal, block

from models import parameters
from models import registers as regmap
from models.parameters import CLOCK_HZ, COORD_WIDTH, DEVICE, FIFO_DEPTH, PCI_IDS, VARIANTS
from rtl.card_core import CORE_PARAMETERS, card_core
from rtl.interfaces import LocalBus, MotorPins, PciBus, card_reset
from rtl.pci.pci_slave_build import local_addr_width
from rtl.pci_slave import pci_slave

MEM_BAR_BITS = 12  # 4 KiB FIFO window: a host burst of up to 1024 words
CARD_PARAMETERS = (*CORE_PARAMETERS, *PCI_IDS)


def slave_params(**slave):
    """``pci_slave`` parameters of the card: the BAR sizes follow the register table."""
    return dict(slave, io_bar_bits=regmap.IO_BAR_BITS, mem_bar_bits=MEM_BAR_BITS)


@block
def card(clock, reset, pci, pins, *, fifo_depth=FIFO_DEPTH.default, coord_width=COORD_WIDTH.default,
         clock_hz=CLOCK_HZ.default, variants=VARIANTS.default, device=DEVICE.default, io_registers=False,
         **ids):
    """The paper's figure 1 in the FPGA, PCI lines still split in / out / enable.

    Ports: ``clock`` PCI CLK, ``reset`` RST# (``card_reset()``), ``pci``
    (``PciBus``), ``pins`` (``MotorPins``).  Parameters
    (``models/parameters.py``): ``fifo_depth``, ``coord_width``, ``clock_hz``,
    ``variants``, ``device`` (the PCI target's one-LUT paths: plain logic or
    iCE40 cells) and the PCI IDs (``vendor_id``, ``device_id``, ...);
    ``io_registers`` (``pci_slave``'s: True when the top's pads hold the PCI
    registers).  BAR0 (I/O) is ``2**IO_BAR_BITS`` bytes, the size the
    register table needs; BAR1 (memory, the FIFO window) is 4 KiB.

        PCI --> pci_slave --LocalBus--> card_core --> STEP/DIR
                    ^                       |
                    +---------- irq --------+
    """
    core = dict(fifo_depth=fifo_depth, coord_width=coord_width, clock_hz=clock_hz, variants=variants,
                device=device)
    parameters.check_unit("card", CARD_PARAMETERS, dict(core, **ids))
    params = slave_params(**ids, device=device, io_registers=io_registers)
    local = LocalBus(local_addr_width(params["io_bar_bits"], params["mem_bar_bits"]))
    irq = Signal(bool(0))
    target = pci_slave(clock, reset, pci, local, irq, **params)
    interior = card_core(clock, reset, local, irq, pins, **core)
    return target, interior


def card_ports(io_registers=False, **build):
    """Fresh ports of ``card`` for conversion and benches (``build``: its
    parameters, checked; none of them changes a port)."""
    parameters.check_unit("card", CARD_PARAMETERS, build)
    if not isinstance(io_registers, bool):
        raise ValueError(f"card: io_registers must be True or False, not {io_registers!r}")
    return dict(clock=Signal(bool(0)), reset=card_reset(), pci=PciBus(), pins=MotorPins())
