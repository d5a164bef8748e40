"""X/Z that the master takes as read data (rule 20) against X/Z in a clock
that moves none (rule 19): the checker on the plain-Python bus loop with a
delayed-transaction target whose AD drive is reported as X whenever it
drives it, and the example Verilog target reading a dword it never wrote."""
import pytest

from sim.pci.bench import PciBench
from sim.pci.checker import ProtocolChecker, ProtocolViolation
from sim.pci.delayed_target import DelayedTarget
from sim.pci.example_target import scratch_target
from sim.pci.lines import BusSample
from sim.pci.loop import PythonBus
from sim.pci.master import PciMaster
from sim.pci.records import RULES

BASE = 0x80000000


class AdReportedUnknown:
    """Feeds ``checker`` every sample with AD reported X/Z in each clock the
    target drove it (a four-state detector's report); counts those clocks."""

    def __init__(self, checker):
        self.checker = checker
        self.target_ad_clocks = 0

    def step(self, sample, in_reset=False):
        unknown = frozenset({"ad"}) if "target" in sample.drivers["ad"] else frozenset()
        self.target_ad_clocks += bool(unknown)
        self.checker.step(BusSample(sample.time, sample.values, sample.drivers, unknown), in_reset)


@pytest.mark.parametrize("irdy_waits", [0, 2])
def test_x_taken_as_read_data_is_rule_20_and_other_x_rule_19(irdy_waits):
    checker = ProtocolChecker(mode="record")
    feed = AdReportedUnknown(checker)
    # no retries: AD is driven only in data phases; IRDY# waits add clocks that move no data
    bus = PythonBus(PciMaster(irdy_waits=irdy_waits), {"target": DelayedTarget(base=BASE, read_retries=0)},
                    checker=feed)
    bus.reset()
    bus.run(bus.host.mem_write(BASE, [1, 2, 3]))
    dwords = sum(len(bus.run(bus.host.mem_read(BASE, count)).data) for count in (1, 3))
    by_rule = {rule: [v for v in checker.violations if v.rule == rule] for rule in (19, 20)}
    assert {v.rule for v in checker.violations} <= {19, 20}
    assert len(by_rule[20]) == checker.corrupt_read_clocks == dwords == 4
    # every other clock with the target on AD moves no data: turnaround, IRDY# waits
    assert len(by_rule[19]) == feed.target_ad_clocks - dwords > 0
    assert checker.unknown_clocks == feed.target_ad_clocks
    assert all(v.detail.startswith("AD X or Z taken as read data") for v in by_rule[20])
    assert all(v.detail == "AD X or Z while driven" for v in by_rule[19])
    summary = checker.summary()
    assert f"rule 20 ({RULES[20]}): 4," in summary and f"rule 19 ({RULES[19]}): {len(by_rule[19])}," in summary


def test_a_never_written_dword_read_from_a_verilog_target_is_rule_20():
    """``scratch_target`` reads its RAM as it is: X where nothing was written."""
    out = {}

    def scenario(bench):
        (device,) = yield from bench.host.enumerate_bus(devices=[0])
        base = out["base"] = device.bars[0]["base"]
        yield from bench.host.mem_write(base, [0x11111111])
        out["read"] = yield from bench.host.mem_read(base, 3)   # dword 0 written, 1 and 2 never

    bench = PciBench(target=scratch_target(), monitor="record")
    with pytest.raises(ProtocolViolation) as failure:
        bench.run(scenario, "x_read_data", trace=False)
    violations = failure.value.violations
    rule_20 = [v for v in violations if v.rule == 20]
    assert len(rule_20) == 2 == bench.checker.corrupt_read_clocks   # dwords 1 and 2, once each
    assert [v.detail.split(" at ")[1].split(",")[0] for v in rule_20] == [
        f"{out['base'] + 4:#x}", f"{out['base'] + 8:#x}"]
    assert out["read"].data[0] == 0x11111111
    # the X stays on AD while the target disconnects, and PAR covers it a
    # clock later: clocks that move no data, rule 19
    assert {v.rule for v in violations} == {19, 20}
    assert not {v.clock for v in violations if v.rule == 19} & {v.clock for v in rule_20}
