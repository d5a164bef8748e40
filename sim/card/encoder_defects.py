"""Defects put by hand into the encoder units' converted Verilog, for the
benches (``sim/card/test_encoder_units.py``) and the proofs
(``tests/formal/test_encoder_proofs.py``) to reject."""
import re
from pathlib import Path

# Defects put by hand into the units' converted Verilog, for the benches and
# the proofs to reject: name -> (unit, [(pattern, replacement), ...]).
DEFECTS = {
    "a_double_change_counted": ("encoder", [(r"\(decoder_changed_a && \(!decoder_changed_b\) && "
                                             r"\(conditioner_a_level != conditioner_b_level\)\)",
                                             "(decoder_changed_a && (conditioner_a_level != conditioner_b_level))")]),
    "the_filter_one_clock_short": ("encoder", [(r"\((conditioner_\w+)_run >= port_filter\)",
                                                r"((\1_run + 1) >= port_filter)")]),
    "the_index_not_disarmed": ("encoder", [(r"port_armed <= \(index_latch_armed_now && \(!index_latch_fire\)\);",
                                            "port_armed <= index_latch_armed_now;")]),
    "step_dir_counting_both_edges_of_a": ("encoder", [(r"\(conditioner_a_level && \(!decoder_seen_a\) && "
                                                       r"conditioner_b_level\)",
                                                       "(decoder_changed_a && conditioner_b_level)")]),
    "the_stop_at_the_limit": ("following_error", [(r"\(folded > check_limit\)", "(folded >= check_limit)")]),
    "the_steps_scaled_one_late": ("following_error", [(r"rounded = scaled_now\[", "rounded = scaled[")]),
    "the_probe_on_its_level": ("probe", [(r"\(armed_now && level && \(!seen\)\)", "(armed_now && level)")]),
}


def with_defect(defect, source, folder):
    """A copy of ``source`` (the unit's Verilog) in ``folder`` with ``defect`` put in; its path."""
    text = Path(source).read_text()
    for pattern, replacement in DEFECTS[defect][1]:
        text, count = re.subn(pattern, replacement, text)
        assert count, f"{Path(source).name} no longer has {pattern!r}: pick the defect {defect} anew"
    mutant = Path(folder) / Path(source).name
    mutant.parent.mkdir(parents=True, exist_ok=True)
    mutant.write_text(text)
    return mutant
