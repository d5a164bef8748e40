"""Foreign Verilog targets on ``PciBench``, as a new user brings them
(``docs/verification.md``): ports declared in the module body next to
functions and tasks, one output enable per bit, a back end in a clock
domain of its own with outputs to watch.  The targets are the small ones
of ``docs/example/`` (``split_core.v`` and its wrappers), written for
these tests; golden values are the data the host wrote and what each
target's comment says it does."""
import pytest

from sim.backends.icarus import CosimError, CosimWarning
from sim.pci.bench import PciBench
from sim.pci.checker import ProtocolViolation
from sim.pci.example_target import SPLIT_DEVICE, SPLIT_PINS, SPLIT_VENDOR, SPLIT_WORDS, split_scenario, split_target
from sim.pci.host import Termination

WB_CLOCK_RATIO = 30 / 40   # two_clock_top's back end: 40 ns clocks against PCI's 30 ns


def run(target, name, **options):
    out = {}
    bench = PciBench(target=target, **options)
    bench.run(split_scenario(out), name, trace=False)
    return bench, out


def check_moved(bench, out):
    device = out["device"]
    assert (device.vendor_id, device.device_id) == (SPLIT_VENDOR, SPLIT_DEVICE)
    assert [bar["size"] for bar in device.bars] == [4 * SPLIT_WORDS]
    assert out["read"].data == out["values"]
    # one data phase per transaction: STOP# with TRDY# on every dword
    assert [t.termination for t in out["write"].transactions] == [Termination.DISCONNECT] * SPLIT_WORDS
    assert bench.checker.unknown_clocks == 0 and not bench.checker.violations


@pytest.mark.parametrize("top", ["split_core", "body_ports_top"])
def test_a_target_runs_whatever_its_port_style(top):
    # body_ports_top: ports in the body, beside functions and a task with inputs
    # (e, v, code) that a port reader must not take for ports
    check_moved(*run(split_target(top), f"foreign_{top}"))


def test_per_bit_enables_bring_no_icarus_warning(recwarn):
    run(split_target("split_core"), "foreign_per_bit_quiet")
    assert not [w for w in recwarn if issubclass(w.category, CosimWarning)]


def test_a_line_driven_only_in_part_is_reported():
    # LATE_RELEASE: AD[15:0] stays enabled one clock after the end of every read
    out = {}
    bench = PciBench(target=split_target("split_core", defines=["LATE_RELEASE"]), monitor="record")
    with pytest.raises(ProtocolViolation) as failure:
        bench.run(split_scenario(out), "foreign_late_release", trace=False)
    violations = failure.value.violations
    assert {v.rule for v in violations} == {19}
    claimed_reads = [r for r in bench.checker.transactions if not r.write and not r.master_abort]
    assert len(claimed_reads) > len(out["values"])   # enumeration's and the scenario's
    ends = [r.end_edge for r in claimed_reads]
    assert [v.clock for v in violations if v.detail == "AD X or Z while driven"] == [end + 1 for end in ends]
    # PAR follows AD's enables a clock later, and then covers the C/BE# the
    # host has released: X
    assert [v.clock for v in violations if v.detail == "PAR X or Z while driven"] == [end + 2 for end in ends]
    assert len(violations) == 2 * len(ends)
    assert out["read"].data == out["values"]


def test_an_enable_of_another_width_is_refused():
    with pytest.raises(CosimError, match=r"output enable ad_oe of AD is 16 bits; give one enable \(1 bit\) "
                                         r"or one per bit \(32 bits\)"):
        run(split_target("split_core", defines={"AD_OE_BITS": 16}), "foreign_narrow_enable")


def test_a_port_of_another_width_is_refused():
    target = split_target("split_core")
    target.pins = dict(SPLIT_PINS, par=("par_in", "wr_word", "par_oe"))
    with pytest.raises(CosimError, match="port wr_word is 2 bits, PCI's PAR has 1"):
        run(target, "foreign_wide_par")


def test_icarus_warnings_are_passed_on():
    # INNER_WIDTH_BUG: the target's own wiring is a bit short; Icarus says so
    with pytest.warns(CosimWarning, match=r"Port \d+ \(wr_word\) of split_core expects 2 bits, got 1"):
        bench, out = run(split_target("body_ports_top", defines=["INNER_WIDTH_BUG"]), "foreign_inner_width")
    check_moved(bench, out)


def test_a_second_clock_domain_and_watched_outputs():
    """two_clock_top clocks its back end itself (# delays in its wrapper);
    the bench watches the back end's outputs by name."""
    value, seen = 0xC0FFEE42, {}

    def scenario(bench):
        host = bench.host
        (device,) = yield from host.enumerate_bus(devices=[0])
        mailbox, ticks = bench.outputs["wb_mailbox"], bench.outputs["wb_ticks"]
        start_ticks, start_edge = int(ticks), host.core.edge
        yield from host.mem_write(device.bars[0]["base"] + 8, value)
        for clocks in range(1, 20):
            yield bench.clock.posedge
            if int(mailbox) == value:
                seen["clocks"] = clocks
                break
        yield from bench.clocks(200)
        seen["ratio"] = (int(ticks) - start_ticks) / (host.core.edge - start_edge)

    bench = PciBench(target=split_target("two_clock_top", outputs=["wb_mailbox", "wb_ticks"]))
    bench.run(scenario, "foreign_two_clocks", trace=False)
    assert set(bench.outputs) == {"wb_mailbox", "wb_ticks"} and len(bench.outputs["wb_ticks"]) == 16
    # the toggle crosses two back-end flip-flops and an edge detector: at most
    # four 40 ns clocks, five PCI clocks
    assert 1 <= seen["clocks"] <= 5
    assert seen["ratio"] == pytest.approx(WB_CLOCK_RATIO, abs=0.01)


def test_an_output_the_target_has_not_is_refused():
    with pytest.raises(CosimError, match="two_clock_top has no output wb_nothing"):
        PciBench(target=split_target("two_clock_top", outputs=["wb_nothing"]))


class FakePort:
    """A DUT port as cocotb shows it: its value as a string of 0/1/x/z."""

    def __init__(self, text):
        self.value = text

    def __len__(self):
        return len(self.value)


@pytest.mark.parametrize("enables, level, expected", [
    ("1" * 32, "0" * 16 + "1" * 16, (0xFFFF, True, False)),         # all enabled
    ("0" * 32, "x" * 32, (0, False, False)),                        # released: its X does not count
    ("0" * 16 + "1" * 16, "1" * 32, (0xFFFF, True, True)),          # driven only in part
    ("1" * 31 + "z", "1" * 32, (0xFFFFFFFE, True, True)),           # an enable bit Z
    ("1" * 32, "x" + "0" * 31, (0, True, True)),                    # X on an enabled bit
])
def test_the_cocotb_front_end_reads_per_bit_enables_alike(enables, level, expected):
    from sim.pci.cocotb_bus import _drive

    assert _drive(FakePort(level), FakePort(enables), False, 32) == expected
    inverted = "".join({"0": "1", "1": "0"}.get(c, c) for c in enables)
    assert _drive(FakePort(level), FakePort(inverted), True, 32) == expected
