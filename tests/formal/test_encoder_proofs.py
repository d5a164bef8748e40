"""The encoder's proofs (formal/props/encoder_harness.sv,
following_error_harness.sv, probe_harness.sv; run with the other groups by test_formal.py)
can fail: each defect put by hand into a copy of a unit's Verilog (the
benches' ``DEFECTS``) is rejected by the group named, with a rule of its
kind."""
import pytest

from formal import groups as catalogue
from formal.sby import run, tools_available
from rtl.convert import GEN_DIR
from sim.card.encoder_defects import with_defect

pytestmark = [pytest.mark.formal,
              pytest.mark.skipif(tools_available() is not None, reason=str(tools_available()))]

# defect -> (the group that rejects it, the rules of which one must fail)
JUDGES = {
    "a_double_change_counted": ("encoder_count", {"enc_count_only_legal_moves"}),
    "step_dir_counting_both_edges_of_a": ("encoder_count", {"enc_count_only_legal_moves"}),
    "the_filter_one_clock_short": ("encoder_pins", {"enc_pins_every_legal_edge_counted"}),
    "the_index_not_disarmed": ("encoder_index", {"idx_disarms_as_it_fires", "idx_once_per_arm",
                                                 "idx_inv_fired_means_disarmed"}),
    "the_stop_at_the_limit": ("following_error", {"fe_never_within_the_limit"}),
    "the_probe_on_its_level": ("probe_latch", {"prb_fires_at_an_armed_rise", "prb_once_per_arm",
                                               "prb_inv_fired_means_disarmed"}),
}


@pytest.mark.parametrize("defect", sorted(JUDGES))
def test_a_defect_put_in_by_hand_is_rejected_by_its_proof(defect, tmp_path):
    judge, rules = JUDGES[defect]
    group = catalogue.group(judge)
    mutant = with_defect(defect, group.convert(), tmp_path / "mutant")
    result = run(group.task(GEN_DIR, unit_file=mutant), tmp_path)
    assert result.status == "FAIL" and set(result.failed) & rules, (result.status, result.failed)
