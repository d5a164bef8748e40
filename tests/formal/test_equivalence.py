"""``python -m formal.equivalence``: two versions of a unit compared at their ports.

Small hand-written units: a counter whose process is split in two (the
same circuit), the same split with an off-by-one (a different one), and a
pair with the same outputs but an internal register that drifts, which
only ``--registers`` tells apart.
"""
import pytest

from formal import equivalence
from formal.sby import tools_available

pytestmark = [pytest.mark.formal,
              pytest.mark.skipif(tools_available() is not None, reason=str(tools_available()))]

ONE_PROCESS = """module unit(input clock, input reset, input step, output reg [3:0] count, output reg wrapped);
    always @(posedge clock or negedge reset)
        if (!reset) begin count <= 0; wrapped <= 0; end
        else if (step) begin count <= count + 1; wrapped <= count == 15; end
endmodule
"""
TWO_PROCESSES = """module unit(input clock, input reset, input step, output reg [3:0] count, output reg wrapped);
    always @(posedge clock or negedge reset)
        if (!reset) count <= 0; else if (step) count <= count + 1;
    always @(posedge clock or negedge reset)
        if (!reset) wrapped <= 0; else if (step) wrapped <= &count;
endmodule
"""
OFF_BY_ONE = TWO_PROCESSES.replace("wrapped <= &count", "wrapped <= count == 14")
# the same outputs; the hidden register differs from the second clock on
HIDDEN = """module unit(input clock, input reset, input step, output reg [3:0] count, output reg wrapped);
    (* keep *) reg [1:0] spare;
    always @(posedge clock or negedge reset)
        if (!reset) begin count <= 0; wrapped <= 0; spare <= 0; end
        else begin
            spare <= spare + SPARE_STEP;
            if (step) begin count <= count + 1; wrapped <= count == 15; end
        end
endmodule
"""


def _files(tmp_path, old_text, new_text):
    (tmp_path / "old").mkdir()
    (tmp_path / "new").mkdir()
    old, new = tmp_path / "old" / "unit.v", tmp_path / "new" / "unit.v"
    old.write_text(old_text)
    new.write_text(new_text)
    return old, new


def test_a_split_process_is_proved_equivalent(tmp_path):
    old, new = _files(tmp_path, ONE_PROCESS, TWO_PROCESSES)
    verdict = equivalence.check(old, new, "unit", depth=2, registers=True, work=tmp_path / "work")
    assert verdict.status == "equivalent", verdict.text()
    assert ("register", "count") not in verdict.compared   # outputs are compared as outputs
    assert ("output", "wrapped") in verdict.compared


def test_an_off_by_one_is_found_with_its_trace(tmp_path):
    old, new = _files(tmp_path, ONE_PROCESS, OFF_BY_ONE)
    verdict = equivalence.check(old, new, "unit", depth=2, bmc_depth=20, work=tmp_path / "work")
    assert verdict.status == "different", verdict.text()
    # the shortest run: the reset clock, 14 steps to count 14, the wrong flag
    # a clock later, seen by the clocked assertion at the next edge
    assert verdict.result.step == 17 and verdict.result.trace.exists(), verdict.text()


@pytest.mark.slow   # four proofs (20 s); the option's use on the target is in docs/formal.md
def test_registers_compares_what_the_outputs_hide(tmp_path):
    old, new = _files(tmp_path, HIDDEN.replace("SPARE_STEP", "1"), HIDDEN.replace("SPARE_STEP", "2"))
    outputs_only = equivalence.check(old, new, "unit", depth=2, work=tmp_path / "outputs")
    with_registers = equivalence.check(old, new, "unit", depth=2, registers=True, work=tmp_path / "registers")
    assert outputs_only.status == "equivalent", outputs_only.text()
    assert with_registers.status == "different", with_registers.text()


@pytest.mark.parametrize("problem, args, message", [
    ("no file", ["missing.v", "unit.v", "--top", "unit"], "no file"),
    ("other ports", ["old/unit.v", "ports/unit.v", "--top", "unit"], "different ports"),
    ("no reset", ["old/unit.v", "new/unit.v", "--top", "unit", "--reset", "rst_n"], "no input 'rst_n'"),
])
def test_bad_input_is_refused_with_a_message(problem, args, message, tmp_path, monkeypatch, capsys):
    _files(tmp_path, ONE_PROCESS, TWO_PROCESSES)
    (tmp_path / "ports").mkdir()
    (tmp_path / "ports" / "unit.v").write_text(TWO_PROCESSES.replace("input step,", "input step, input hold,"))
    monkeypatch.chdir(tmp_path)
    try:
        code = equivalence.main(args)
    except SystemExit as stop:
        code = stop.code
    assert code != 0
    assert message in capsys.readouterr().err, problem
