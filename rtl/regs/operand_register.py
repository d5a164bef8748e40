"""One operand register of the sequencer's instruction register."""
from myhdl import always_comb, always_seq, block


@block
def operand_register(clock, reset, word, take, clear, register):
    """An operand register of ``rtl/regs/sequencer.py``: takes the low bits
    of ``word`` (the FIFO's output) at ``take``, else 0 at ``clear`` (a LINE
    header: the registers of the card's axes; None: never).  Ports: ``take``,
    ``clear`` (bits), ``word`` (32 bits), ``register`` (as wide as the bits
    its operands need).  Parameters: none.

        clock     _/~\\_/~\\_/~\\_
        take      _/~~~\\_______
        register  =====X=word==
    """
    width = len(register)
    if clear is None:
        @always_seq(clock.posedge, reset=reset)
        def hold():
            if take:
                register.next = word[width:]
    else:
        @always_seq(clock.posedge, reset=reset)
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
