"""DEVSEL# and first TRDY# of the card's accesses, one of each kind, as a
host sees them: counted as the docs count, in clocks after the address
phase (the edge that samples DEVSEL# or TRDY# asserted, less the edge that
samples the address: ``BusTransaction.devsel_clock`` and
``first_trdy_clock`` of the host's records).

The card runs as a ``PciBench`` target: ``gen/card.v`` in Icarus as a
foreign ``VerilogTarget`` (``card_verilog``; its split ports, the machine
inputs tied at rest), or the benches' MyHDL card and generated top level
(``sim.card.fifo_scoreboard.card_target``).  ``measure`` enumerates it and
makes one access of each kind in ``ACCESSES``: configuration space, a
function register over I/O (STATUS read, FEED_RATE written), the FIFO
window over memory (BAR1) and the same registers over memory (BAR2).  ``bench/pci_figures.py`` prints the figures and
``tests/sim/test_register_latency.py`` holds the docs to them."""
from models import instructions as isa
from models import registers as regmap
from rtl.convert import GEN_DIR
from models.parameters import AXES
from rtl.interfaces import machine_inputs
from sim.card.card_bench import PinLog
from sim.card.card_e2e import card_bars
from sim.card.fifo_scoreboard import DEFAULT_FIFO, card_target
from sim.pci.bench import TARGET_DEVICE, PciBench
from sim.pci.verilog_target import VerilogTarget, split_pins

ACCESSES = ("configuration read", "configuration write", "I/O read", "I/O write", "memory read",
            "memory write", "BAR2 read", "BAR2 write")
KINDS = ("card.v", "myhdl", "top.v")


def card_verilog():
    """``gen/card.v`` as a ``VerilogTarget``."""
    card = GEN_DIR / "card.v"
    return VerilogTarget([card], "card", split_pins([card], "card"), clock="clock", reset="reset",
                         idsel="pci_idsel_in", ties={f"pins_{name}": "1'b0" for name in machine_inputs(AXES.default)})


def card(kind):
    """The card as a ``PciBench`` target: ``kind`` one of ``KINDS``."""
    if kind == "card.v":
        return card_verilog()
    if kind == "myhdl":
        return card_target("myhdl", DEFAULT_FIFO, PinLog(), taken=[])
    if kind == "top.v":
        return card_target("verilog", DEFAULT_FIFO, PinLog(), taken=None)
    raise ValueError(f"unknown card kind {kind!r}: use one of {', '.join(KINDS)}")


def measure(kind="card.v"):
    """``{access: (DEVSEL# clock, first TRDY# clock)}`` for ``ACCESSES``
    on the card of ``kind``; each access must complete in one transaction
    without retry."""
    results = {}

    def scenario(bench):
        host = bench.host
        (device,) = yield from host.enumerate_bus(devices=[TARGET_DEVICE])
        bars = card_bars(device)
        io, mem, alias = (bars[role]["base"] for role in ("io", "mem", "alias"))
        results["configuration read"] = yield from host.config_read(TARGET_DEVICE, 0x00)
        results["configuration write"] = yield from host.config_write(TARGET_DEVICE, 0x3C, 0x0B, be=0x1)
        results["I/O read"] = yield from host.io_read(io + regmap.offset("STATUS"))
        results["I/O write"] = yield from host.io_write(io + regmap.offset("FEED_RATE"), 1)
        results["memory read"] = yield from host.mem_read(mem)
        results["memory write"] = yield from host.mem_write(mem, isa.encode("MARK", TAG=1))  # moves nothing
        results["BAR2 read"] = yield from host.mem_read(alias + regmap.offset("STATUS"))
        results["BAR2 write"] = yield from host.mem_write(alias + regmap.offset("FEED_RATE"), 1)

    PciBench(target=card(kind)).run(scenario, f"register_latency_{kind}", trace=False)
    figures = {}
    for access in ACCESSES:
        result = results[access]
        if len(result.transactions) != 1 or not result.complete:
            raise RuntimeError(f"{kind}: {access} took {[t.termination.value for t in result.transactions]}")
        (transaction,) = result.transactions
        figures[access] = (transaction.devsel_clock, transaction.first_trdy_clock)
    return figures

