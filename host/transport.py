"""How the host reaches a card: one interface, several implementations.

A ``Transport`` offers what the card API needs of a PCI card, and nothing
about which card it is:

| call | what |
| --- | --- |
| ``read(offset, size=4)`` / ``write(offset, value, size=4)`` | BAR0 (I/O, the function registers), 1, 2 or 4 bytes, naturally aligned |
| ``fifo_write(words)`` | BAR1 (memory, the FIFO window): 32-bit words, each a single aligned store |
| ``mem_read(offset, count=1)`` | BAR1 dwords (the FIFO window reads 0) |
| ``config_read(register, size=4)`` | configuration space |
| ``wait_interrupt(seconds)`` | True when INTA# is asserted within ``seconds``, else False |
| ``sleep(seconds)`` / ``now()`` | let card time pass / card time since opening, in seconds |
| ``clocks`` | card clocks since opening (simulations; None on a real card) |
| ``pins`` | the STEP/DIR pin log (simulations; None on a real card) |

Implementations: ``host.sim_transport.SimTransport`` (the simulated card on
MyHDL, Icarus or Verilator) and ``host.sysfs.SysfsTransport`` (a real card
on Linux, through sysfs and ``uio_pci_generic``).  ``open_transport(spec)``
picks one from a ``--card`` value.
"""

SIM_KINDS = ("myhdl", "icarus", "verilator")
ACCESS_SIZES = (1, 2, 4)
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

    def close(self):
        """Release the card; the transport is unusable afterwards."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def check_access(offset, size, bar_size, what="BAR0"):
    """ValueError unless ``size`` bytes at ``offset`` are a naturally aligned access inside the BAR."""
    if size not in ACCESS_SIZES:
        raise ValueError(f"{what} accesses are 1, 2 or 4 bytes, not {size}")
    if offset % size or not 0 <= offset <= bar_size - size:
        raise ValueError(f"{what}: {size}-byte access at {offset:#x} is misaligned or outside its {bar_size} bytes")


def check_value(value, size):
    if not 0 <= value < 1 << (8 * size):
        raise ValueError(f"{value:#x} does not fit {size} bytes")


def open_transport(spec, **options):
    """The transport a ``--card`` value names: ``myhdl``, ``icarus``,
    ``verilator`` (the simulated card), ``pci`` (the one real card) or
    ``pci:DDDD:BB:DD.F`` (that real card).  ``options`` go to the
    implementation's constructor."""
    if spec in SIM_KINDS:
        from host.sim_transport import SimTransport

        return SimTransport(spec, **options)
    if spec == "pci" or spec.startswith("pci:"):
        from host.sysfs import SysfsTransport

        return SysfsTransport(spec[4:] or None, **options)
    raise ValueError(f"unknown card {spec!r}: use one of {', '.join(SIM_KINDS)}, pci or pci:DDDD:BB:DD.F")
