"""The interface every transport implements, and what they share.

A ``Transport`` offers what the card API needs of a PCI card, and nothing
about which card it is:

| call | what |
| --- | --- |
| ``read(offset, size=4)`` / ``write(offset, value, size=4)`` | the function registers, 1, 2 or 4 bytes, naturally aligned: BAR0's offsets (I/O, or BAR2 where it aliases them), and beyond BAR0 BAR2's per-axis blocks |
| ``fifo_write(words)`` | BAR1 (memory, the FIFO window): 32-bit words, each a single aligned store |
| ``mem_read(offset, count=1)`` | BAR1 dwords (the FIFO window reads 0) |
| ``config_read(register, size=4)`` | configuration space |
| ``wait_interrupt(seconds)`` | True when INTA# is asserted within ``seconds``, else False |
| ``sleep(seconds)`` / ``now()`` | let card time pass / card time since opening, in seconds |
| ``clocks`` | card clocks since opening (simulations; None on a real card) |
| ``pins`` | the STEP/DIR pin log (simulations; None on a real card) |
| ``machine`` | the simulated machine on the card's inputs (``SimTransport(..., machine=...)``; else None) |

The implementations are listed in ``host/transports/__init__.py``, whose
``open_transport`` picks one.
"""

SIM_KINDS = ("myhdl", "icarus", "verilator")
POLL_SECONDS = 50e-6  # card time between two looks at a status register when no interrupt is enabled


class TransportError(RuntimeError):
    """An access the card did not complete, or a card that cannot be reached."""


class Transport:
    """The interface (see the module docstring); ``name`` says which card."""

    name = "transport"
    clock_hz = None  # the clock simulated time counts in (None: wall-clock time)

    def read(self, offset, size=4):
        raise NotImplementedError

    def write(self, offset, value, size=4):
        raise NotImplementedError

    def fifo_write(self, words):
        raise NotImplementedError

    def mem_read(self, offset, count=1):
        raise NotImplementedError

    def config_read(self, register, size=4):
        raise NotImplementedError

    def wait_interrupt(self, seconds):
        raise NotImplementedError

    def sleep(self, seconds):
        raise NotImplementedError

    def now(self):
        raise NotImplementedError

    @property
    def clocks(self):
        return None

    @property
    def pins(self):
        return None

    machine = None   # a simulated card's machine (switches, E-stop, drives), when it has one

    def close(self):
        """Release the card; the transport is unusable afterwards."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
