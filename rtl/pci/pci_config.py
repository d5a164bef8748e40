"""The PCI target's configuration header (type 0, one function).

Dwords implemented (PCI Local Bus 2.3, section 6.1; docs/pci.md):

    0  Device ID | Vendor ID                 read only, from the build
    1  Status | Command                      Command: I/O Space, Memory Space,
                                             Parity Error Response, SERR# Enable,
                                             Interrupt Disable; Status: write 1
                                             to clear, DEVSEL timing medium
    2  Class Code | Revision ID              read only, from the build
    4  BAR0: I/O, 2**io_bar_bits bytes       bits above the size writable
    5  BAR1: memory, 2**mem_bar_bits bytes   32-bit, not prefetchable
    6  BAR2: memory, BAR0's size (16 bytes   32-bit, not prefetchable: the
       at least)                             registers of BAR0 again
    11 Subsystem ID | Subsystem Vendor ID    read only, from the build
    15 Interrupt Pin (INTA#) | Line           Line read/write
    every other dword reads 0, writes are ignored

A write lands at the edge after its data phase (``write`` is registered by
the target); the byte enables choose the lanes.  Status bits are set one
clock after their event::

    edge            k     k+1   k+2
    TRDY#,IRDY#   __/~~\\__               data phase of a configuration write
    write         ______/~~\\__
    io_enable     ------------< new >
"""
from myhdl import Signal, always_comb, always_seq, block, concat, instances, intbv

from models.parameters import Build
from rtl.pci.pci_slave_build import alias_bar_bits

CONFIG_ID, CONFIG_COMMAND_STATUS, CONFIG_CLASS, CONFIG_BAR0, CONFIG_BAR1, CONFIG_BAR2 = 0, 1, 2, 4, 5, 6
CONFIG_SUBSYSTEM, CONFIG_INTERRUPT = 11, 15
STATUS_DEVSEL_MEDIUM = 0b01   # Status[10:9]
INTERRUPT_PIN_INTA = 1
BAR_IO_SPACE = 1              # BAR bit 0: I/O space (BAR1, BAR2: 0, memory, 32-bit, non-prefetchable)


@block
def pci_config(clock, reset, config, *, build=Build()):
    """Ports: ``clock``, ``reset``; ``config`` a ``ConfigSpace``.

    Parameters: ``build`` (a ``Build``, ``models/parameters.py``), of which
    the header reads the IDs of ``models.parameters.PCI_IDS``, io_bar_bits
    and mem_bar_bits (the BAR sizes).
    """
    id_word = build.device_id << 16 | build.vendor_id
    class_word = build.class_code << 8 | build.revision_id
    subsystem_word = build.subsystem_id << 16 | build.subsystem_vendor_id
    io_bar_writable = (0xFFFF << build.io_bar_bits) & 0xFFFF   # BAR0[31:16] hardwired to 0 (PC I/O)
    mem_bar_writable = (0xFFFFFFFF << build.mem_bar_bits) & 0xFFFFFFFF
    alias_bar_writable = (0xFFFFFFFF << alias_bar_bits(build.io_bar_bits, build.reg_bar_bits)) & 0xFFFFFFFF

    # the writable bits of each byte lane of BAR0, BAR1, BAR2
    io_0, io_1 = ((io_bar_writable >> (8 * lane)) & 0xFF for lane in range(2))
    mem_0, mem_1, mem_2, mem_3 = ((mem_bar_writable >> (8 * lane)) & 0xFF for lane in range(4))
    alias_0, alias_1, alias_2, alias_3 = ((alias_bar_writable >> (8 * lane)) & 0xFF for lane in range(4))

    signaled_target_abort = Signal(bool(0))
    signaled_system_error = Signal(bool(0))
    detected_parity_error = Signal(bool(0))
    interrupt_line = Signal(intbv(0)[8:])
    bar0_read = Signal(intbv(0)[16:])  # BAR0 as read: base bits and the I/O flag
    data, cbe_n = config.data, config.cbe_n

    @always_seq(clock.posedge, reset=reset)
    def config_registers():
        clear_target_abort = False
        clear_system_error = False
        clear_parity_error = False
        if config.write:
            if config.index == CONFIG_COMMAND_STATUS:
                if not cbe_n[0]:
                    config.io_enable.next = data[0]
                    config.mem_enable.next = data[1]
                    config.parity_response.next = data[6]
                if not cbe_n[1]:
                    config.serr_enable.next = data[8]
                    config.interrupt_disable.next = data[10]
                if not cbe_n[3]:   # Status: write 1 to clear
                    clear_target_abort = data[27]
                    clear_system_error = data[30]
                    clear_parity_error = data[31]
            elif config.index == CONFIG_BAR0:
                # only the writable bits are stored; the others stay 0 (no flip-flop)
                if not cbe_n[0]:
                    config.bar0.next[8:0] = data[8:0] & io_0
                if not cbe_n[1]:
                    config.bar0.next[16:8] = data[16:8] & io_1
            elif config.index == CONFIG_BAR1:
                if not cbe_n[0]:
                    config.bar1.next[8:0] = data[8:0] & mem_0
                if not cbe_n[1]:
                    config.bar1.next[16:8] = data[16:8] & mem_1
                if not cbe_n[2]:
                    config.bar1.next[24:16] = data[24:16] & mem_2
                if not cbe_n[3]:
                    config.bar1.next[32:24] = data[32:24] & mem_3
            elif config.index == CONFIG_BAR2:
                if not cbe_n[0]:
                    config.bar2.next[8:0] = data[8:0] & alias_0
                if not cbe_n[1]:
                    config.bar2.next[16:8] = data[16:8] & alias_1
                if not cbe_n[2]:
                    config.bar2.next[24:16] = data[24:16] & alias_2
                if not cbe_n[3]:
                    config.bar2.next[32:24] = data[32:24] & alias_3
            elif config.index == CONFIG_INTERRUPT:
                if not cbe_n[0]:
                    interrupt_line.next = data[8:0]
        signaled_target_abort.next = config.target_abort or (signaled_target_abort and not clear_target_abort)
        signaled_system_error.next = config.system_error or (signaled_system_error and not clear_system_error)
        detected_parity_error.next = config.parity_error or (detected_parity_error and not clear_parity_error)

    @always_comb
    def io_bar_read():
        bar0_read.next = (config.bar0 & intbv(io_bar_writable)[16:]) | intbv(BAR_IO_SPACE)[16:]

    @always_comb
    def config_read():
        if config.index == CONFIG_ID:
            config.rdata.next = intbv(id_word)[32:]
        elif config.index == CONFIG_COMMAND_STATUS:
            config.rdata.next = concat(
                detected_parity_error, signaled_system_error, intbv(0)[2:],
                signaled_target_abort, intbv(STATUS_DEVSEL_MEDIUM)[2:], intbv(0)[5:], config.irq,
                intbv(0)[8:], config.interrupt_disable, False, config.serr_enable, False,
                config.parity_response, intbv(0)[4:], config.mem_enable, config.io_enable)
        elif config.index == CONFIG_CLASS:
            config.rdata.next = intbv(class_word)[32:]
        elif config.index == CONFIG_BAR0:
            config.rdata.next = concat(intbv(0)[16:], bar0_read)
        elif config.index == CONFIG_BAR1:
            config.rdata.next = config.bar1 & intbv(mem_bar_writable)[32:]
        elif config.index == CONFIG_BAR2:
            config.rdata.next = config.bar2 & intbv(alias_bar_writable)[32:]
        elif config.index == CONFIG_SUBSYSTEM:
            config.rdata.next = intbv(subsystem_word)[32:]
        elif config.index == CONFIG_INTERRUPT:
            config.rdata.next = concat(intbv(0)[16:], intbv(INTERRUPT_PIN_INTA)[8:], interrupt_line)
        else:
            config.rdata.next = 0

    return instances()
