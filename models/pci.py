"""Facts of PCI Local Bus 2.3 that the card, its benches and the host share, stated once.

The bus commands (C/BE# in the address phase, section 3.1.1), the
configuration header's registers and Command bits (section 6.2), and the
rule every register access keeps (1, 2 or 4 bytes, naturally aligned,
inside its BAR).  ``rtl/pci/`` decodes with them, the verification IP
(``sim/pci/``) drives and checks with them, the host transports refuse an
access that breaks them.
"""

INTERRUPT_ACK = 0x0
SPECIAL_CYCLE = 0x1
IO_READ = 0x2
IO_WRITE = 0x3
MEM_READ = 0x6
MEM_WRITE = 0x7
CONFIG_READ = 0xA
CONFIG_WRITE = 0xB
MEM_READ_MULTIPLE = 0xC
DUAL_ADDRESS = 0xD
MEM_READ_LINE = 0xE
MEM_WRITE_INVALIDATE = 0xF
MEMORY_READS = (MEM_READ, MEM_READ_LINE, MEM_READ_MULTIPLE)
MEMORY_WRITES = (MEM_WRITE, MEM_WRITE_INVALIDATE)

# Configuration header (type 0): byte offsets of the registers the card implements.
CONFIG_ID = 0x00            # Device ID | Vendor ID
CONFIG_COMMAND = 0x04       # Status | Command
CONFIG_CLASS = 0x08         # Class Code | Revision ID
CONFIG_HEADER_TYPE = 0x0C   # BIST | Header Type | Latency Timer | Cache Line Size
CONFIG_BAR0 = 0x10          # I/O: the function registers
CONFIG_BAR1 = 0x14          # memory: the data FIFO
CONFIG_BAR2 = 0x18          # memory: the function registers again
CONFIG_SUBSYSTEM = 0x2C     # Subsystem ID | Subsystem Vendor ID
CONFIG_INTERRUPT = 0x3C     # Max_Lat | Min_Gnt | Interrupt Pin | Interrupt Line
CONFIG_BYTES = 256

# Command register bits.
COMMAND_IO = 1 << 0
COMMAND_MEMORY = 1 << 1
COMMAND_PARITY_RESPONSE = 1 << 6
COMMAND_SERR_ENABLE = 1 << 8
COMMAND_INTERRUPT_DISABLE = 1 << 10

ACCESS_SIZES = (1, 2, 4)


def check_access(offset, size, bar_size, what="BAR0"):
    """ValueError unless ``size`` bytes at ``offset`` are a naturally aligned access inside the BAR."""
    if size not in ACCESS_SIZES:
        raise ValueError(f"{what} accesses are 1, 2 or 4 bytes, not {size}")
    if offset % size or not 0 <= offset <= bar_size - size:
        raise ValueError(f"{what}: {size}-byte access at {offset:#x} is misaligned or outside its {bar_size} bytes")


def check_value(value, size):
    """ValueError unless ``value`` fits ``size`` bytes."""
    if not 0 <= value < 1 << (8 * size):
        raise ValueError(f"{value:#x} does not fit {size} bytes")
