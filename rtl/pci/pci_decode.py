"""The PCI target's address decoder: which address phase it claims, and where.

PCI Local Bus 2.3, 3.2.2: an address phase names configuration space (IDSEL
asserted, AD[1:0] = 00, function 0: AD[10:8] = 0), the I/O BAR (all 32 bits
compared, BAR0 in the lower 64 KB) or a memory BAR (BAR1, the FIFO window;
BAR2, the registers' alias; BAR1 wins where a host made them overlap), by
its command.  The input registers hold the address phase, so the claim and
the offset come from flip-flops through this logic (DEVSEL# medium).
"""
from myhdl import always_comb, block, intbv

from rtl.pci.pci_slave_build import (CMD_CONFIG_READ, CMD_CONFIG_WRITE, CMD_IO_READ, CMD_IO_WRITE, CMD_MEM_READ,
                                      CMD_MEM_READ_LINE, CMD_MEM_READ_MULTIPLE, CMD_MEM_WRITE, CMD_MEM_WRITE_INVALIDATE,
                                      CONFIG_DWORDS, alias_bar_bits, alias_repeats, last_dword)


@block
def pci_decode(decode, *, io_bits, mem_bits, reg_bits):
    """Ports: ``decode`` a ``TargetDecode`` (``idle`` its state enum's idle
    item; ``start_addr`` as wide as the target's dword counters).

    Parameters: ``io_bits``, ``mem_bits``, ``reg_bits`` (BAR0 is 2**io_bits
    bytes, BAR1 2**mem_bits bytes, BAR2 ``alias_bar_bits(io_bits, reg_bits)``).

        edge        A        A+1
        AD, C/BE#   <adr>              on the pins, sampled at A
        claim       ____/~~~~~~\\___     with start_addr; taken at A+1
    """
    idle = decode.idle
    width = len(decode.start_addr)
    ad, cbe, bar0, bar1, bar2 = decode.ad, decode.cbe, decode.bar0, decode.bar1, decode.bar2
    alias_bits = alias_bar_bits(io_bits, reg_bits)
    config_mask, io_mask, mem_mask = CONFIG_DWORDS - 1, last_dword(io_bits), last_dword(mem_bits)
    alias_mask = io_mask if alias_repeats(io_bits, reg_bits) else last_dword(alias_bits)

    @always_comb
    def decode_address():
        code = cbe
        config_hit = (decode.idsel and not ad[0] and not ad[1] and ad[11:8] == 0
                      and (code == CMD_CONFIG_READ or code == CMD_CONFIG_WRITE))
        io_hit = (decode.io_enable and (code == CMD_IO_READ or code == CMD_IO_WRITE)
                  and ad[32:16] == 0 and ad[16:io_bits] == bar0[16:io_bits])
        mem_command = (decode.mem_enable
                       and (code == CMD_MEM_READ or code == CMD_MEM_WRITE
                            or code == CMD_MEM_READ_MULTIPLE or code == CMD_MEM_READ_LINE
                            or code == CMD_MEM_WRITE_INVALIDATE))
        mem_hit = mem_command and ad[32:mem_bits] == bar1[32:mem_bits]
        alias_hit = mem_command and ad[32:alias_bits] == bar2[32:alias_bits] and not mem_hit
        decode.claim.next = decode.state == idle and decode.address_phase and (
            config_hit or io_hit or mem_hit or alias_hit)
        decode.claim_config.next = config_hit
        decode.claim_io.next = io_hit
        decode.claim_alias.next = alias_hit
        decode.read_command.next = not cbe[0]

    @always_comb
    def start_offset():
        # the dword inside the BAR, or of the configuration header; chosen by
        # the command (it counts only with a claim, which has the same
        # command) and, in memory space, by BAR2's compare, as the back end
        # sees the registers at BAR0's offsets whichever BAR reached them
        # (a BAR0 under 16 bytes repeats in BAR2's 16; a BAR2 that reg_bits
        # makes larger than BAR0 passes its offsets whole: BAR0's registers
        # below BAR0's size, the registers only BAR2 has above it)
        code = cbe
        if code == CMD_CONFIG_READ or code == CMD_CONFIG_WRITE:
            decode.start_addr.next = ad[width + 2:2] & intbv(config_mask)[width:]
        elif code == CMD_IO_READ or code == CMD_IO_WRITE:
            decode.start_addr.next = ad[width + 2:2] & intbv(io_mask)[width:]
        elif decode.claim_alias:
            decode.start_addr.next = ad[width + 2:2] & intbv(alias_mask)[width:]
        else:
            decode.start_addr.next = ad[width + 2:2] & intbv(mem_mask)[width:]

    return decode_address, start_offset
