"""Seeded random PCI traffic against a scoreboard on the PCI target alone,
MyHDL and the generated Verilog (the generator: ``sim/card/pci_slave_traffic.py``)."""
import pytest

from sim.card.pci_slave_traffic import run_random


@pytest.mark.parametrize("target", ["myhdl", "verilog"])
def test_random_traffic_short(target):
    bench, board = run_random(target, 300, seed=7)
    assert board.stats["dwords checked"] > 500 and board.stats["write dwords"] > 500
    assert bench.memory.retries > 0 and bench.memory.abandoned > 0  # the stalls happened
    assert board.stats["retry"] > 0 and board.stats["disconnect"] > 0
    records = bench.checker.transactions
    assert any(r.master_abort for r in records) and any(r.target_abort for r in records)


@pytest.mark.slow(reason="10,000 random transactions; the short run is in the default suite")
@pytest.mark.parametrize("target", ["myhdl", "verilog"])
def test_random_traffic_long(target):
    bench, board = run_random(target, 10_000, seed=2026)
    assert len(bench.checker.transactions) >= 10_000
    assert board.stats["dwords checked"] > 20_000
    assert board.stats["retry"] > 100 and board.stats["disconnect"] > 100
