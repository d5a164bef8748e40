"""The formal proofs (formal/, docs/formal.md) in the test suite.

The fast groups run by default (each a k-induction or a bounded check of
one unit's generated Verilog); the rest, and the mutation campaign, carry
the ``slow`` marker.  A few fixed mutants of the PCI target check that the
proofs can fail: each one changes the target's outputs (a miter says so)
and each must be rejected by a proof.
"""
import pytest

from formal import groups as catalogue
from formal import mutation
from formal.sby import Task, run, tools_available

pytestmark = [pytest.mark.formal,
              pytest.mark.skipif(tools_available() is not None, reason=str(tools_available()))]

FAST = [group.name for group in catalogue.GROUPS if group.fast]
# the FIFO path has its own test below
SLOW = [group.name for group in catalogue.GROUPS if not group.fast and group.name != "pci_fifo_path"]


def _prove(name, tmp_path):
    group = catalogue.group(name)
    result = run(group.task(catalogue.GEN_DIR), tmp_path)
    detail = f"{result.status}: failed {result.failed}, missed covers {result.missed}, trace {result.trace}"
    if group.mode == "cover":
        assert result.passed and not result.missed, detail
    else:
        assert result.passed, detail


@pytest.mark.parametrize("name", FAST)
def test_fast_group_proves(name, tmp_path):
    _prove(name, tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("name", SLOW)
def test_slow_group_proves(name, tmp_path):
    _prove(name, tmp_path)


@pytest.mark.slow
def test_fifo_path(tmp_path):
    """Nothing acknowledged is dropped; register access never waits behind the FIFO.

    A target without the LocalBus write credit (``room``) acknowledges
    posted dwords the FIFO then refuses while it is full (issue 10): the
    basecase finds a run from reset with an acknowledged dword not taken
    for 8 clocks.  With the credit the group is a proof."""
    result = run(catalogue.group("pci_fifo_path").task(catalogue.GEN_DIR), tmp_path)
    if catalogue.has_write_credit(catalogue.GEN_DIR / "pci_slave.v"):
        assert result.passed, f"{result.status}: failed {result.failed}, trace {result.trace}"
    else:
        assert result.status == "FAIL" and "acknowledged_write_drains" in result.failed, result.status
        assert result.trace is not None and result.trace.name == "trace.vcd", result.trace


def test_a_broken_rule_is_caught(tmp_path):
    """The runner reports a failing assertion by name, with a trace."""
    source = tmp_path / "counter.sv"
    source.write_text("""module counter(input clock, input reset_n);
    reg [3:0] count = 0;
    always @(posedge clock) count <= reset_n ? count + 1 : 0;
    always @(posedge clock) never_nine: assert(count != 9);
endmodule
""")
    result = run(Task(name="counter", mode="bmc", depth=12, top="counter", sources=[source]), tmp_path)
    assert result.status == "FAIL"
    assert result.failed == ["never_nine"]
    assert result.trace is not None and result.trace.exists()


# Mutants of gen/pci_slave.v (yosys `mutate -list 20 -seed 1`, the list
# `python -m formal.mutation` scores; indices into it) that change the
# target's outputs; each must be rejected by the protocol group, bounded.
FIXED_MUTANTS = (1, 2, 4)
JUDGES = ("pci_protocol",)
JUDGE_DEPTH = 12


@pytest.fixture(scope="module")
def pci_mutations(tmp_path_factory):
    work = tmp_path_factory.mktemp("mutants")
    unit_file = catalogue.GEN_DIR / "pci_slave.v"
    commands = mutation.list_mutations(unit_file, work, 20, 1)
    return work, unit_file, commands, mutation.ports(work, unit_file)


@pytest.mark.parametrize("index", FIXED_MUTANTS)
def test_fixed_mutant_is_rejected(index, pci_mutations):
    work, unit_file, commands, port_list = pci_mutations
    mutant = mutation.Mutant(index, commands[index])
    folder = work / f"m{index:03d}"
    renamed = folder / "renamed" / "pci_slave_mutant.v"
    mutation.write_mutant(work, unit_file, mutant.command, renamed, module_name="pci_slave_mutant")
    assert mutation.is_observable(work, unit_file, renamed, port_list, 12), mutant.command
    same_name = folder / "pci_slave.v"
    mutation.write_mutant(work, unit_file, mutant.command, same_name)
    judges = [catalogue.group(name) for name in JUDGES]
    mutation.judge(mutant, judges, catalogue.GEN_DIR, same_name, work, JUDGE_DEPTH)
    assert mutant.verdict == "rejected", mutant.command
