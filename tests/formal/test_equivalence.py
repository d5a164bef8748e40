"""The equivalence miter (``python -m formal.equivalence``) on a small unit:
the feed-rate ramp converted on its own, against copies of its Verilog with
an equivalent rewrite and with defects put in by hand."""
import re

import pytest

from formal import equivalence
from formal.sby import tools_available
from rtl.convert import convert_unit

pytestmark = [pytest.mark.formal,
              pytest.mark.skipif(tools_available() is not None, reason=str(tools_available()))]

UNIT = "feed_rate"


@pytest.fixture(scope="module")
def original(tmp_path_factory):
    return convert_unit(UNIT, {}, tmp_path_factory.mktemp("original"))


def changed(original, tmp_path, *edits):
    """A copy of ``original`` with each (pattern, replacement) applied; each pattern must match."""
    text = original.read_text()
    for pattern, replacement in edits:
        text, count = re.subn(pattern, replacement, text)
        assert count, f"{original.name} no longer has {pattern!r}: pick the change anew"
    copy = tmp_path / "changed" / original.name
    copy.parent.mkdir()
    copy.write_text(text)
    return copy


def test_an_equivalent_rewrite_is_proved(original, tmp_path):
    """Operands of a compare swapped and a register renamed (``decelerate``,
    which the register correspondence then cannot pair: it is reloaded every
    clock, so an induction of two clocks gets past it) prove equivalent,
    unbounded."""
    new = changed(original, tmp_path, (r"assign above = \(rate > target_s\);", "assign above = (target_s < rate);"),
                  (r"\bdecelerate\b", "end_near"))
    verdict = equivalence.check(UNIT, original, new, mode="prove", depth=2, work=tmp_path / "work")
    assert verdict.status == "PASS" and verdict.equivalent, verdict.text()
    assert "rate" in verdict.matched and "decelerate" not in verdict.matched, verdict.matched


def test_a_deep_defect_is_not_proved(original, tmp_path):
    """The ramp's last step one count late (``count_last`` at 3 ticks, not 2):
    from a common state the rate soon differs, so the induction fails on a
    register and the change is not accepted."""
    new = changed(original, tmp_path, (r"assign count_last = \(count == \(2 \+ 1\)\);",
                                       "assign count_last = (count == (2 + 2));"))
    verdict = equivalence.check(UNIT, original, new, mode="prove", depth=3, work=tmp_path / "work")
    assert not verdict.equivalent, verdict.text()
    assert verdict.status in ("FAIL", "UNKNOWN")
    assert set(verdict.outputs + verdict.registers) & {"rate", "feed_tick", "feed_held", "count"}, verdict.text()


def test_a_visible_defect_gives_a_counterexample(original, tmp_path):
    """``step_zero`` set for a step of 1 instead of 0: after the reset a run
    with ramp_step 0 or 1 starts at the wrong rate, and the outputs-only
    bounded miter shows the tick that differs, from a reset."""
    new = changed(original, tmp_path, (r"step_zero <= \(settings_ramp_step == 0\);",
                                       "step_zero <= (settings_ramp_step == 1);"))
    verdict = equivalence.check(UNIT, original, new, mode="bmc", depth=8, match_registers=False,
                                work=tmp_path / "work")
    assert verdict.status == "FAIL" and not verdict.equivalent
    assert verdict.outputs and set(verdict.outputs) <= {"feed_tick", "feed_held"}, verdict.text()
    assert verdict.trace is not None and verdict.trace.exists()


def test_a_folder_of_other_files_is_refused(original, tmp_path):
    """``--work`` naming a folder that holds something else is refused before
    anything in it is touched."""
    kept = tmp_path / "notes.txt"
    kept.write_text("not a miter's")
    with pytest.raises(ValueError, match="holds files of something else"):
        equivalence.check(UNIT, original, original, work=tmp_path)
    assert kept.read_text() == "not a miter's"


def test_a_renamed_register_is_paired_by_name(original, tmp_path):
    """``rate`` renamed ``path_rate``: it holds its value between ticks, so
    unpaired the induction of one clock starts the two copies from different
    rates and fails; paired (``pairs``) the same k = 1 closes."""
    new = changed(original, tmp_path, (r"\brate\b", "path_rate"))
    unpaired = equivalence.check(UNIT, original, new, mode="prove", depth=1, work=tmp_path / "unpaired")
    assert not unpaired.equivalent and "rate" not in unpaired.matched, unpaired.text()
    paired = equivalence.check(UNIT, original, new, mode="prove", depth=1, work=tmp_path / "paired",
                               pairs=[("rate", "path_rate")])
    assert paired.equivalent and "rate" in paired.matched, paired.text()
