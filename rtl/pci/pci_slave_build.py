"""The PCI target's build (``rtl/pci_slave.py``): the commands it claims, its
latency budget, the check of ``io_registers`` and the address width of its
back-end bus (its build parameters: a ``Build``, ``models/parameters.py``)."""
from models import pci
from models.parameters import PARAMETERS, Build

# Commands (C/BE# in the address phase) the target claims (``models/pci.py``).
CMD_IO_READ, CMD_IO_WRITE = pci.IO_READ, pci.IO_WRITE
CMD_MEM_READ, CMD_MEM_WRITE = pci.MEM_READ, pci.MEM_WRITE
CMD_CONFIG_READ, CMD_CONFIG_WRITE = pci.CONFIG_READ, pci.CONFIG_WRITE
CMD_MEM_READ_MULTIPLE, CMD_MEM_READ_LINE, CMD_MEM_WRITE_INVALIDATE = (
    pci.MEM_READ_MULTIPLE, pci.MEM_READ_LINE, pci.MEM_WRITE_INVALIDATE)

# Latency budget: clocks a data phase may wait for TRDY#, counted from the
# claim (first phase) or from the last completion.  STOP# then comes out so
# that it is sampled 14 clocks after FRAME# (PCI allows 16) or 7 clocks after
# the last completed phase (PCI allows 8).
INITIAL_WAIT_LIMIT = 11
SUBSEQUENT_WAIT_LIMIT = 5

CONFIG_DWORDS = 64   # the configuration header's 256 bytes


MEMORY_BAR_MIN_BITS = 4   # a memory BAR's bits [3:0] are its type: 16 bytes at least (PCI 2.3, 6.2.5.1)


def alias_bar_bits(io_bar_bits, reg_bar_bits=MEMORY_BAR_MIN_BITS):
    """Bits of BAR2, the registers in memory space: ``reg_bar_bits``, at least
    BAR0's size (and a memory BAR's 16 bytes: a smaller BAR0 then repeats in
    them, see ``alias_repeats``)."""
    return max(io_bar_bits, reg_bar_bits, MEMORY_BAR_MIN_BITS)


def alias_repeats(io_bar_bits, reg_bar_bits=MEMORY_BAR_MIN_BITS):
    """True when BAR2 holds BAR0's registers only, repeated to fill it (its
    offsets reach the back end cut to BAR0's size); False when ``reg_bar_bits``
    makes it larger than BAR0 (its offsets reach the back end whole)."""
    return reg_bar_bits <= io_bar_bits or reg_bar_bits == MEMORY_BAR_MIN_BITS


def last_dword(bar_bits):
    """The offset of the last dword of a BAR of 2**bar_bits bytes (a mask of dword offsets)."""
    return (1 << (bar_bits - 2)) - 1


def check_io_registers(io_registers):
    """``io_registers`` if it is True or False (where the boundary flip-flops are, see ``pci_slave``)."""
    if not isinstance(io_registers, bool):
        raise ValueError(f"pci_slave: io_registers must be True or False, not {io_registers!r}")
    return io_registers


def local_addr_width(io_bar_bits=Build.io_bar_bits, mem_bar_bits=Build.mem_bar_bits, reg_bar_bits=Build.reg_bar_bits):
    """Address bits of ``LocalBus`` the target drives: the largest BAR, and at
    least the 256 bytes of configuration space (one counter serves all);
    ParameterError if a size is outside its range."""
    return max(PARAMETERS["io_bar_bits"].check(io_bar_bits), PARAMETERS["mem_bar_bits"].check(mem_bar_bits),
               PARAMETERS["reg_bar_bits"].check(reg_bar_bits), 8)
