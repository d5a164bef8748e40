"""What the PCI host's scenarios and its transaction log are made of: the bus
commands (C/BE# in the address phase), a transaction to run (``Request``),
the wait object ``Clocks``, how a transaction ended (``Termination``), its
record (``BusTransaction``) and the host's error (``HostError``).  Plain
Python; ``sim.pci.host_core`` runs the requests."""
import enum
from dataclasses import dataclass, field

from models.pci import (CONFIG_READ, CONFIG_WRITE,  # noqa: F401 (the bus; commands, offered; with the requests)
                        DUAL_ADDRESS, INTERRUPT_ACK, IO_READ, IO_WRITE, MEM_READ, MEM_READ_LINE, MEM_READ_MULTIPLE,
                        MEM_WRITE, MEM_WRITE_INVALIDATE, MEMORY_READS, MEMORY_WRITES, SPECIAL_CYCLE)


class Termination(enum.Enum):
    NORMAL = "normal"
    RETRY = "retry"
    DISCONNECT = "disconnect"
    MASTER_ABORT = "master abort"
    TARGET_ABORT = "target abort"
    RESET = "reset"  # RST# came during the transaction


class HostError(RuntimeError):
    """The target left the host stuck, or an access ran out of its budget;
    ``transactions`` is the log of the bus transactions of the access."""

    def __init__(self, message, transactions=()):
        super().__init__(message)
        self.transactions = list(transactions)


@dataclass
class BusTransaction:
    """One transaction on the bus, from FRAME# to the end of the last phase.

    ``devsel_clock`` / ``first_trdy_clock``: edges after the address edge at
    which DEVSEL# / the first TRDY# were sampled asserted (None: never).
    ``parity_errors``: indices (in ``data``) of read data with bad PAR.
    ``start`` / ``end``: times of the address edge and of the last data phase.
    """

    command: int
    address: int
    requested: int
    data: list = field(default_factory=list)
    termination: Termination = Termination.NORMAL
    devsel_clock: int = None
    first_trdy_clock: int = None
    start: int = 0
    end: int = 0
    parity_errors: list = field(default_factory=list)


class Request:
    """One bus transaction to run: ``phases`` [(byte enables, data or None)],
    ``waits`` (IRDY# wait states: int or function of the phase index),
    parity-error injection.  A scenario yields it to wait until ``done``;
    ``transaction`` is then its ``BusTransaction``."""

    __slots__ = ("command", "address", "phases", "waits", "bad_address_parity",
                 "bad_data_parity", "done", "transaction")

    def __init__(self, command, address, phases, waits=0, bad_address_parity=False,
                 bad_data_parity=frozenset()):
        self.command, self.address, self.phases, self.waits = command, address, phases, waits
        self.bad_address_parity = bad_address_parity
        self.bad_data_parity = frozenset(bad_data_parity)
        self.done = False
        self.transaction = None


class Clocks:
    """Wait object: resume the scenario after ``count`` rising edges."""

    __slots__ = ("count",)

    def __init__(self, count):
        if count < 0:
            raise ValueError(f"cannot wait {count} clocks")
        self.count = count
