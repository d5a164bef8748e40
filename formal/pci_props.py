"""Constants of the PCI harnesses, generated from models/pci.py (the bus
commands, the configuration header's offsets and Command bits), as the
verification IP and the host read them.

``pci_constants()`` returns the body that ``props/pci_bus_model.vh`` reads
(``pci_table.vh``, included by ``pci_target_harness.sv`` and
``card_harness.sv``): one localparam per command and per configuration
dword, the Command register's bit numbers, and a function per command class
the target decodes (configuration, I/O, memory).
"""
from models import pci

COMMANDS = ("INTERRUPT_ACK", "SPECIAL_CYCLE", "IO_READ", "IO_WRITE", "MEM_READ", "MEM_WRITE", "CONFIG_READ",
            "CONFIG_WRITE", "MEM_READ_MULTIPLE", "DUAL_ADDRESS", "MEM_READ_LINE", "MEM_WRITE_INVALIDATE")
CONFIG_REGISTERS = ("ID", "COMMAND", "CLASS", "HEADER_TYPE", "BAR0", "BAR1", "BAR2", "SUBSYSTEM", "INTERRUPT")
COMMAND_BITS = ("IO", "MEMORY", "PARITY_RESPONSE", "SERR_ENABLE", "INTERRUPT_DISABLE")
# the command classes the target decodes (models/pci.py), as Verilog functions
CLASSES = {"config_command": (pci.CONFIG_READ, pci.CONFIG_WRITE),
           "io_command": (pci.IO_READ, pci.IO_WRITE),
           "memory_command": pci.MEMORY_READS + pci.MEMORY_WRITES}
WORD_BYTES = 4


def _bit(mask):
    if mask <= 0 or mask & (mask - 1):
        raise ValueError(f"{mask:#x} is not one bit")
    return mask.bit_length() - 1


def pci_constants():
    """The generated include ``pci_table.vh``."""
    lines = ["// Generated from models/pci.py by formal/pci_props.py; do not edit.",
             "// Included into pci_target_harness and card_harness (read by pci_bus_model.vh).",
             "    // bus commands (C/BE# in the address phase, 3.1.1)"]
    lines += [f"    localparam [3:0] CMD_{name} = 4'h{getattr(pci, name):X};" for name in COMMANDS]
    lines.append("    // configuration header (type 0, 6.1): dword of each register the card implements")
    for name in CONFIG_REGISTERS:
        offset = getattr(pci, f"CONFIG_{name}")
        lines.append(f"    localparam [5:0] CONFIG_{name} = 6'd{offset // WORD_BYTES};   // {offset:#04x}")
    lines.append("    // Command register bits (6.2.2)")
    lines += [f"    localparam COMMAND_{name} = {_bit(getattr(pci, f'COMMAND_{name}'))};" for name in COMMAND_BITS]
    names = {getattr(pci, name): name for name in COMMANDS}
    for function, codes in CLASSES.items():
        terms = " || ".join(f"command == CMD_{names[code]}" for code in codes)
        lines += [f"    function {function}(input [3:0] command);", f"        {function} = {terms};",
                  "    endfunction"]
    return "\n".join(lines) + "\n"
