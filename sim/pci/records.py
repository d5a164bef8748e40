"""What the PCI protocol checker (``sim.pci.checker``) reports: the rules by
number (``RULES``), a broken rule (``ProtocolViolation``, raised; ``Violation``,
recorded) and the summary of one transaction (``TransactionRecord``, for
figures).  Plain Python, no simulator."""
from dataclasses import dataclass, field

RULES = {
    1: "write data held while the target waits",
    2: "read data held while the master waits",
    3: "C/BE# held through the data phase",
    4: "FRAME# asserted while IRDY# is still asserted",
    5: "IRDY# asserted without FRAME#",
    6: "FRAME# deasserted without IRDY#",
    7: "FRAME# held until the data phase completes",
    8: "IRDY# held until the data phase completes",
    9: "STOP# held while FRAME# is asserted",
    10: "STOP# deasserted once FRAME# is gone",
    11: "DEVSEL#, TRDY#, STOP# held while the master waits",
    12: "TRDY#/STOP# only with DEVSEL# (target abort excepted)",
    13: "DEVSEL# held until the last data phase, then deasserted",
    14: "PAR correct, PERR#/SERR# exactly when due",
    15: "latency (IRDY# 8, first TRDY#/STOP# 16, later 8, DEVSEL# by clock 5)",
    16: "no contention, a turnaround clock between drivers",
    17: "sustained tri-state lines driven high before release",
    18: "lines released during reset",
    19: "no X or Z on a line while it is driven",
    20: "no X or Z in read data the master takes (data corruption)",
}

class ProtocolViolation(AssertionError):
    """A PCI rule was broken: ``rule`` (number), ``time``, ``detail``;
    ``clock``: the checker's edge count; ``violations``: every recorded one
    (record mode)."""

    def __init__(self, rule, time, detail, clock=None, violations=()):
        self.rule, self.time, self.detail, self.clock = rule, time, detail, clock
        self.violations = list(violations)
        at = f"t={time}" if clock is None else f"t={time} (clock {clock})"
        super().__init__(f"PCI rule {rule} ({RULES[rule]}) broken at {at}: {detail}")


@dataclass(frozen=True)
class Violation:
    """One recorded violation: the bus as sampled at that edge."""

    rule: int
    time: int
    clock: int
    detail: str
    values: dict
    drivers: dict

    def __str__(self):
        lines = " ".join(f"{line}={hex_word(value)}" for line, value in self.values.items())
        return f"clock {self.clock} t={self.time} rule {self.rule} ({RULES[self.rule]}): {self.detail} [{lines}]"


@dataclass
class TransactionRecord:
    """What the monitor saw of one transaction (clocks are edge counts
    after the address edge)."""

    start: int                 # time of the address edge
    command: int
    address: int
    start_edge: int = 0
    devsel_clock: int = None
    first_trdy_clock: int = None
    first_stop_clock: int = None
    data_phases: int = 0        # data transferred (IRDY# and TRDY#)
    end: int = None
    end_edge: int = None
    target_abort: bool = False
    last_completion_edge: int = None
    ended: bool = False
    phase_start_edge: int = 0
    completions: list = field(default_factory=list)

    @property
    def write(self):
        return bool(self.command & 1)

    @property
    def master_abort(self):
        return self.devsel_clock is None


def hex_word(value):
    """A line's value for a message: hex, or z when nobody drove it."""
    return "z" if value is None else f"{value:#x}"
