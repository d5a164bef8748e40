"""One operand register of the sequencer's instruction register."""
from myhdl import always, always_comb, block


@block
def operand_register(clock, word, take, clear, register):
    """An operand register of ``rtl/regs/sequencer.py``: takes the low bits
    of ``word`` (the FIFO's output) at ``take``, else 0 at ``clear`` (a LINE
    header: the registers of the card's axes; None: never).  Ports: ``take``,
    ``clear`` (bits), ``word`` (32 bits), ``register`` (as wide as the bits
    its operands need).  Parameters: none.  No reset: an operand is written
    before it is read (the sequencer reads a command once all its words have
    arrived), and a register without one clears with its flip-flops' own
    synchronous reset (iCE40 SB_DFFESR), no logic per bit.

        clock     _/~\\_/~\\_/~\\_
        take      _/~~~\\_______
        register  =====X=word==
    """
    width = len(register)
    if clear is None:
        @always(clock.posedge)
        def hold():
            if take:
                register.next = word[width:]
    else:
        @always(clock.posedge)
        def hold():
            if take:
                register.next = word[width:]
            elif clear:
                register.next = 0

    return hold


@block
def signed_low(register, value):
    """``value`` (signed) is the low bits of ``register``."""
    width = len(value)

    @always_comb
    def copy():
        value.next = register[width:].signed()

    return copy
