"""Whether a register access falls in an axis block of BAR2 whose registers are BAR0's."""
from myhdl import always_comb, block


@block
def alias_block(bus, block_hit):
    """The block test of X's or Y's per-axis block in BAR2, made once for the
    registers it holds (their BAR0 offsets are their own; ``reg_word``
    compares only the address's low bits with their offset in the block).

    Ports: ``bus`` (``RegisterBus``: ``addr`` of reads, ``write_addr`` of
    writes), ``block_hit`` (``AliasBlock``: out ``read`` and ``write``, the
    address's bits above the block's ``size`` equal to its ``base``'s).
    All combinational:

        bus.addr        ==X=0x104=X==     (X's block: base 0x100, 64 bytes)
        block_hit.read  __/~~~~~~~\\__
    """
    low = (block_hit.size - 1).bit_length()
    top = len(bus.addr)
    index = block_hit.base >> low
    if block_hit.base >> top:
        raise ValueError(f"the block at {block_hit.base:#x} is beyond the {top}-bit register address")

    @always_comb
    def decode():
        block_hit.read.next = bus.addr[top:low] == index
        block_hit.write.next = bus.write_addr[top:low] == index

    return decode
