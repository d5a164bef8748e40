"""A PCI target written elsewhere, in Verilog, on the bench: the example of
docs/verification.md (``docs/example/scratch_target.v``: tri-state ports in
ANSI style, parameters in port ranges, a Latin-1 byte in a comment, an
include folder, a define).  Enumeration, bursts through its one-dword
disconnects and first-attempt retries, data checked, monitor quiet; with
``X_ON_RETRY`` defined the X/Z detector reports the X it drives on AD."""
import pytest

from sim.pci.bench import PciBench
from sim.pci.checker import ProtocolViolation
from sim.pci.example_target import CLASS, DEVICE, VENDOR, WORDS, scenario, scratch_target
from sim.pci.host import Termination


def test_a_foreign_verilog_target_enumerates_and_moves_bursts():
    out = {}
    bench = PciBench(target=scratch_target())
    bench.run(scenario(out), "verilog_target_scratch")
    device = out["device"]
    assert (device.vendor_id, device.device_id, device.class_code) == (VENDOR, DEVICE, CLASS)
    assert [(bar["io"], bar["size"]) for bar in device.bars] == [(False, 4 * WORDS)]
    assert out["read"].data == out["values"]
    terminations = [t.termination for t in out["read"].transactions]
    assert terminations.count(Termination.RETRY) == WORDS // 2   # odd dwords: first attempt retried
    assert terminations.count(Termination.DISCONNECT) == WORDS  # STOP# with every datum
    assert out["word1"].value == (out["values"][1] & ~0xFF00) | 0xAB00
    assert bench.checker.unknown_clocks == 0


def test_the_x_detector_reports_x_driven_during_retries():
    out = {}
    bench = PciBench(target=scratch_target(defines=["X_ON_RETRY"]), monitor="record")
    with pytest.raises(ProtocolViolation) as failure:
        bench.run(scenario(out), "verilog_target_scratch_x")
    violations = failure.value.violations
    assert {v.rule for v in violations} == {19}
    assert all(v.detail.split(" X or Z")[0] in ("AD", "AD, PAR", "PAR") for v in violations)  # PAR of X
    assert any(v.detail.startswith("AD") for v in violations)
    assert len(violations) == bench.checker.unknown_clocks > 0
    assert out["read"].data == out["values"]   # the host still moved every datum
    assert "rule 19" in bench.checker.summary()
