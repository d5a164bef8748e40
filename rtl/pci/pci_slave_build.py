"""The PCI target's build (``rtl/pci_slave.py``): the commands it claims, its
latency budget, its parameters, checked, and the address width of its
back-end bus."""
from models import parameters, pci
from models.parameters import PCI_IDS, ParameterError

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


def alias_bar_bits(io_bar_bits):
    """Bits of BAR2, the memory alias of BAR0's registers: BAR0's size, at
    least a memory BAR's 16 bytes (a smaller BAR0 then repeats in it)."""
    return max(io_bar_bits, MEMORY_BAR_MIN_BITS)


def last_dword(bar_bits):
    """The offset of the last dword of a BAR of 2**bar_bits bytes (a mask of dword offsets)."""
    return (1 << (bar_bits - 2)) - 1


# Build parameters of the stand-alone unit (defaults and ranges: models/parameters.py);
# ``io_registers`` says where the boundary flip-flops are (see ``pci_slave``).
SLAVE_PARAMETERS = (*PCI_IDS, "io_bar_bits", "mem_bar_bits", "device")


def check_params(params):
    """``params`` completed with the defaults; ValueError on a bad one."""
    unknown = set(params) - {*SLAVE_PARAMETERS, "io_registers"}
    if unknown:
        raise ValueError(f"pci_slave: unknown parameters {sorted(unknown)}")
    io_registers = params.get("io_registers", False)
    if not isinstance(io_registers, bool):
        raise ValueError(f"pci_slave: io_registers must be True or False, not {io_registers!r}")
    builds = {name: value for name, value in params.items() if name != "io_registers"}
    try:
        values = parameters.check(dict(parameters.defaults(SLAVE_PARAMETERS), **builds))
    except ParameterError as error:
        raise ValueError(f"pci_slave: {error}") from None
    return dict(values, io_registers=io_registers)


def local_addr_width(io_bar_bits=parameters.PARAMETERS["io_bar_bits"].default,
                     mem_bar_bits=parameters.PARAMETERS["mem_bar_bits"].default):
    """Address bits of ``LocalBus`` the target drives: the larger BAR, and at
    least the 256 bytes of configuration space (one counter serves all)."""
    return max(io_bar_bits, mem_bar_bits, 8)
