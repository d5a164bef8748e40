"""The formal proofs (formal/, docs/formal.md) in the test suite.

The fast groups run by default (each a k-induction or a bounded check of
one unit's generated Verilog); the rest, and the mutation campaign, carry
the ``slow`` marker.  A few fixed mutants of the PCI target and the back end check that the
proofs can fail: each one changes the unit's outputs (a miter says so)
and each must be rejected by a proof; so must a few defects put by hand
into a copy of the whole card (gen/card.v).
"""
import re

import pytest

from formal import groups as catalogue
from formal import mutation, trace
from formal.proof_group import has_write_credit
from formal.sby import Task, run, tools_available
from rtl.convert import GEN_DIR

pytestmark = [pytest.mark.formal,
              pytest.mark.skipif(tools_available() is not None, reason=str(tools_available()))]

FAST = [group.name for group in catalogue.GROUPS if group.fast]
# the FIFO path has its own test below
SLOW = [group.name for group in catalogue.GROUPS if not group.fast and group.name != "pci_fifo_path"]


def _prove(name, tmp_path):
    group = catalogue.group(name)
    result = run(group.task(GEN_DIR), tmp_path)
    detail = f"{result.status}: failed {result.failed}, missed covers {result.missed}, trace {result.trace}"
    if group.mode == "cover":
        assert result.passed and not result.missed, detail
    else:
        assert result.passed, detail


@pytest.mark.parametrize("name", FAST)
def test_fast_group_proves(name, tmp_path):
    _prove(name, tmp_path)


@pytest.mark.slow(reason="proofs of minutes (docs/formal.md lists them with their seconds)")
@pytest.mark.parametrize("name", SLOW)
def test_slow_group_proves(name, tmp_path):
    _prove(name, tmp_path)


@pytest.mark.slow(reason="an unbounded proof of several minutes")
def test_fifo_path(tmp_path):
    """Nothing acknowledged is dropped; register access never waits behind the FIFO.

    A target without the LocalBus write credit (``room``) acknowledges
    posted dwords the FIFO then refuses while it is full (issue 10): the
    basecase finds a run from reset with an acknowledged dword not taken
    for 8 clocks.  With the credit the group is a proof."""
    result = run(catalogue.group("pci_fifo_path").task(GEN_DIR), tmp_path)
    if has_write_credit(GEN_DIR / "pci_slave.v"):
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
    # the shortest counterexample counts from reset, one step per clock, to 9
    rows = trace.table(result.trace, ["count"])
    assert rows[0].split() == ["step", "count"]
    assert [int(row.split()[1], 16) for row in rows[1:11]] == list(range(10))


# Mutants of the generated files (yosys `mutate -list N -seed 1`, the lists
# `python -m formal.mutation` scores; indices into them) that change the
# unit's outputs; each must be rejected by the group named, bounded to its
# depth.  pci_slave (20 mutants): m000 (bit 14 of the parity fold inverted:
# PAR wrong), m001 (the Signaled System Error status bit stuck at 1), m010
# (a bit of the next bus state stuck at 0) by the protocol rules.
# regs_fifo (16 mutants; the list follows the netlist, so a change of
# regs_fifo.v picks them anew): m002 (bit 8 of LOW_WATER's write decode
# inverted: it takes writes at 0x118, not 0x018), m010 (a bit of the
# register read chain stuck at 0 after reg_word7) by the register table's
# rules.  (Picked anew on the gen/ of the N-axis card: its m006 and m015
# passed while the table failed on gen/ itself at X's block offsets; with
# the aliases modelled m015, a homing mux, survives.)
MUTANT_LISTS = {"pci_slave": 20, "regs_fifo": 16}
FIXED_MUTANTS = (("pci_slave", 0, "pci_protocol", 12), ("pci_slave", 1, "pci_protocol", 12),
                 ("pci_slave", 10, "pci_protocol", 12), ("regs_fifo", 2, "regs_fifo_table", 10),
                 ("regs_fifo", 10, "regs_fifo_table", 10))
MITER_DEPTH = 12


@pytest.fixture(scope="module")
def mutation_lists(tmp_path_factory):
    lists = {}
    for unit, count in MUTANT_LISTS.items():
        work = tmp_path_factory.mktemp(f"mutants_{unit}")
        unit_file = GEN_DIR / f"{unit}.v"
        commands = mutation.list_mutations(unit_file, work, count, 1)
        lists[unit] = (work, unit_file, commands, mutation.ports(work, unit_file))
    return lists


# one fixed mutant per unit by default; the others judge the same way (slow set)
DEFAULT_MUTANTS = (("pci_slave", 0), ("regs_fifo", 2))


@pytest.mark.parametrize("unit, index, judge, depth", [
    pytest.param(*mutant, id=f"{mutant[0]}-m{mutant[1]:03d}", marks=[] if mutant[:2] in DEFAULT_MUTANTS else [
        pytest.mark.slow(reason="another mutant judged by the same group")]) for mutant in FIXED_MUTANTS])
def test_fixed_mutant_is_rejected(unit, index, judge, depth, mutation_lists):
    work, unit_file, commands, port_list = mutation_lists[unit]
    mutant = mutation.Mutant(index, commands[index])
    folder = work / f"m{index:03d}"
    renamed = folder / "renamed" / f"{unit}_mutant.v"
    mutation.write_mutant(work, unit_file, mutant.command, renamed, module_name=f"{unit}_mutant")
    assert mutation.is_observable(work, unit_file, renamed, port_list, MITER_DEPTH), mutant.command
    same_name = folder / f"{unit}.v"
    mutation.write_mutant(work, unit_file, mutant.command, same_name)
    mutation.judge(mutant, [catalogue.group(judge)], GEN_DIR, same_name, work, depth)
    assert mutant.verdict == "rejected", mutant.command


def assert_defect_rejected(judge, source, pattern, replacement, rules, tmp_path):
    """Put one defect into a copy of ``source`` (``pattern`` must match once)
    and check that group ``judge`` fails on it with one of ``rules``."""
    text, count = re.subn(pattern, replacement, source.read_text())
    assert count == 1, f"{source.name} no longer has {pattern!r} once: pick the defect anew"
    mutant = tmp_path / "mutant" / source.name
    mutant.parent.mkdir()
    mutant.write_text(text)
    result = run(catalogue.group(judge).task(GEN_DIR, unit_file=mutant), tmp_path)
    assert result.status == "FAIL" and set(result.failed) & rules, (result.status, result.failed)


# Defects put by hand into the 6-bit DDA the DDA groups convert (a line's X
# steps going the wrong way; X stepping whenever Y does): each must fail
# `dda_lines` with a rule named.  Patterns, since the converter numbers the
# instance prefix (dda_run0_...) by the conversions before it in the process.
DDA_DEFECTS = {
    "line_x_backwards": (r"steps_dir_x <= (dda_run0\w*_right);", r"steps_dir_x <= (!\1);",
                         {"dda_line_x_towards_end", "dda_ends_at_end_point"}),
    "x_steps_with_y": (r"steps_step_x <= (dda_run0\w*)_go_x;", r"steps_step_x <= (\1_go_x | \1_go_y);",
                       {"dda_line_x_towards_end", "dda_ends_at_end_point"}),
}


@pytest.mark.parametrize("name", DDA_DEFECTS)
def test_dda_defect_is_caught(name, tmp_path):
    pattern, replacement, rules = DDA_DEFECTS[name]
    assert_defect_rejected("dda_lines", catalogue.narrow_dda(), pattern, replacement, rules, tmp_path)


# Defects put by hand into a copy of gen/card.v, the whole card: the FIFO's
# read pointer advancing twice per word (a word skipped, the next taken out
# of order); STATUS.FIFO_LEVEL one more than the words in the FIFO.  Each must
# fail its card group with a rule named.
CARD_DEFECTS = {
    "read_pointer_twice": ("card_fifo_order",
                           r"(sync_fifo1_read_addr <= \(card_core0_regs_fifo1_sync_fifo1_read_addr \+ )1\);",
                           r"\g<1>2);", {"card_fifo_in_order", "card_fifo_taken_was_written"}),
    "level_off_by_one": ("card_status", r"(word\[32-1:16\] = card_core0_regs_fifo1_level_wide);",
                         r"\1 + 1;", {"card_status_level", "card_status_empty"}),
}


@pytest.mark.parametrize("name", CARD_DEFECTS)
def test_card_defect_is_caught(name, tmp_path):
    judge, pattern, replacement, rules = CARD_DEFECTS[name]
    assert_defect_rejected(judge, GEN_DIR / "card.v", pattern, replacement, rules, tmp_path)


@pytest.mark.slow(reason="the whole card at depth 28: minutes")
def test_card_error_defect_is_caught(tmp_path):
    """STATUS.ERROR stuck at NONE on the whole card: a malformed first
    command is not reported, and `card_status_error` rejects it."""
    assert_defect_rejected("card_status_error", GEN_DIR / "card.v",
                           r"word\[4\+:4\] = card_core0_regs_fifo1_error_code;", "word[4+:4] = 4'h0;",
                           {"card_status_error_bad_opcode", "card_status_error_reserved_bits"}, tmp_path)


# Defects put by hand into a copy of gen/regs_fifo.v's machine side: each must
# fail its machine group with the rule named (docs/machine.md).
MACHINE_DEFECTS = {
    "clear_stop_during_estop": ("machine_stop", "else if ((clear_stop && (!machine_guard0_estop))) begin",
                                "else if (clear_stop) begin", {"ms_estop_clear_refused"}),
    "zero_while_seeking": ("machine_homing", "released = (homing0_releasing && (!homing0_switch));",
                           "released = (homing0_seeking && (!homing0_switch));",
                           {"hm_zero_at_release"}),
    "held_at_any_rate": ("machine_hold", "    settled = (feed_held && (!tick) && (!outputs_busy));",
                         "    settled = ((!tick) && (!outputs_busy));", {"fh_held_rate_zero"}),
    # issue 28: DRIVE_ENABLE falling under a STEP pulse; CLEAR_STOP re-energising
    # (MACHINE_CONTROL.DRIVE_ENABLE not cleared by the stop); WATCHDOG cut to 24 bits
    "drive_falls_under_a_pulse": ("machine_drive", " || (pins_drive_enable && pulse_out0_control_pulsing));",
                                  ");", {"md_drive_holds_pulse"}),
    "clear_stop_reenergises": ("machine_drive", "drive_cleared = 1;", "drive_cleared = 0;",
                               {"md_drive_needs_write", "minv_drive_rearmed"}),
    "watchdog_cut_to_24_bits": ("machine_watchdog_write", "reg_word30_honoured = 16777215;",
                                "reg_word30_honoured = reg_word30_written[24-1:0];",
                                {"mwl_write_loads_clamped", "mwl_only_zero_turns_off"}),
}


@pytest.mark.parametrize("name", MACHINE_DEFECTS)
def test_machine_defect_is_caught(name, tmp_path):
    judge, original, defect, rules = MACHINE_DEFECTS[name]
    assert_defect_rejected(judge, GEN_DIR / "regs_fifo.v", re.escape(original), lambda _: defect,
                           rules, tmp_path)


# Defects put by hand into a copy of the 3-axis regs_fifo.v the `_3axes` groups
# convert: Z's step requests granted while the card is stopped or Z steps
# towards an active limit (its grant without the guard's gate).  The rules
# loop over the build's axes (formal/axes_props.py), so Z's gate is judged.
MORE_AXES_DEFECTS = {
    "z_ungated": ("machine_stop_3axes",
                  "assign machine_guard0_grant_z_granted_step = (machine_guard0_grant_z_request_step && machine_guard0_passes);",
                  "assign machine_guard0_grant_z_granted_step = machine_guard0_grant_z_request_step;",
                  {"ms_limit_dropped", "ms_stopped_no_step", "mr_estop_no_step"}),
}


@pytest.mark.slow(reason="a k-induction of a minute on the 3-axis build")
@pytest.mark.parametrize("name", MORE_AXES_DEFECTS)
def test_more_axes_defect_is_caught(name, tmp_path):
    judge, original, defect, rules = MORE_AXES_DEFECTS[name]
    assert_defect_rejected(judge, catalogue.built_unit("regs_fifo", catalogue.MORE_AXES), re.escape(original),
                           lambda _: defect, rules, tmp_path)


# A defect put by hand into a copy of the ECP5 build's regs_fifo.v, whose FIFO
# delivers its word from a fabric register (rtl/regs/sync_fifo.py, output_register):
# the word written where the head is read taken from the RAM's read register,
# which still holds the old word; `regs_fifo_order_ecp5` must reject it.
ECP5_DEFECTS = {
    "fresh_word_from_ram": ("regs_fifo_order_ecp5", "fifo_dout <= sync_fifo0_written;", "fifo_dout <= sync_fifo0_head;",
                            {"rf_fifo_in_order"}),
}


@pytest.mark.slow(reason="a bounded check of a minute on the ECP5 build")
@pytest.mark.parametrize("name", ECP5_DEFECTS)
def test_ecp5_defect_is_caught(name, tmp_path):
    judge, original, defect, rules = ECP5_DEFECTS[name]
    assert_defect_rejected(judge, catalogue.built_unit("regs_fifo", catalogue.ECP5_BUILD), re.escape(original),
                           lambda _: defect, rules, tmp_path)


# Defects put by hand into a copy of the regs_fifo.v of the encoders build
# (`machine_following_error`): Y's following error latched as X's (the
# guard's table of the lowest flagged axis, wrong for Y alone); the stop
# latched as LIMIT, not FOLLOWING_ERROR; X's flag raised at the limit, not
# beyond it.  Each must fail the group with a rule named.
FERROR_GUARD_DEFECTS = {
    "axis_of_y_as_x": ("2: machine_guard0_lagging_axis = 1;", "2: machine_guard0_lagging_axis = 0;",
                       {"fg_stops_on_a_flag", "fg_stop_only_on_a_flag"}),
    "reason_limit": ("machine_guard0_guard_reason <= 4;", "machine_guard0_guard_reason <= 3;",
                     {"fg_stops_on_a_flag"}),
    "x_flag_at_the_limit": ("(encoder_block0_axis_x_following_error_folded > encoder_block0_axis_x_check_limit)",
                            "(encoder_block0_axis_x_following_error_folded >= encoder_block0_axis_x_check_limit)",
                            {"fg_flags_as_errors"}),
}


@pytest.mark.slow(reason="a bounded check of a minute or more on the encoders build")
@pytest.mark.parametrize("name", FERROR_GUARD_DEFECTS)
def test_following_error_guard_defect_is_caught(name, tmp_path):
    original, defect, rules = FERROR_GUARD_DEFECTS[name]
    assert_defect_rejected("machine_following_error", catalogue.built_unit("regs_fifo", catalogue.ENCODERS),
                           re.escape(original), lambda _: defect, rules, tmp_path)
