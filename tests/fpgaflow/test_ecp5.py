"""The ECP5 flow (``python -m fpgaflow --family ecp5``) on a small unit.

The flow's own figures must agree with nextpnr-ecp5's report: the worst
register-to-register path with its fmax, the worst pin-to-register and
register-to-pin paths with the ``<async>`` paths of the report.
"""
import json
import subprocess
import sys

import pytest

import fpgaflow
from rtl.convert import ROOT

pytestmark = pytest.mark.synth
TOOL_TIMEOUT_S = 600

ACCUMULATOR_UNIT = """module accumulator_unit (clock, reset, a, b, y, carry);
input clock;
input reset;
input [15:0] a;
input [15:0] b;
output reg [15:0] y;
output carry;
assign carry = y[15] & a[15];
always @(posedge clock, negedge reset) begin: accumulator_unit_add
    if (reset == 0) y <= 0;
    else y <= y + (a ^ b);
end
endmodule
"""

ICE40_CELL_UNIT = """module ice40_cell_unit (clock, a, y);
input clock;
input a;
output y;
SB_LUT4 #(.LUT_INIT(16'h5555)) invert (.O(y), .I0(a), .I1(1'b0), .I2(1'b0), .I3(1'b0));
endmodule
"""

# As the ecp5 build writes a pin LUT (rtl/ecp5.py): the register's next value is a kept
# LUT4 of the pin and of a register, which must reach the placed netlist as one cell.
ECP5_CELL_UNIT = """module ecp5_cell_unit (clock, reset, pin, e, y);
input clock;
input reset;
input pin;
input e;
output reg y;
reg held;
wire next;
`ifdef SYNTHESIS
(* keep *) LUT4 #(.INIT(16'h6666)) pin_lut (.A(pin), .B(held), .C(1'b0), .D(1'b0), .Z(next));
`else
assign next = pin ^ held;
`endif
always @(posedge clock, negedge reset) begin: ecp5_cell_unit_step
    if (reset == 0) begin y <= 0; held <= 0; end
    else begin held <= e ^ y; if (e) y <= next; end
end
endmodule
"""


@pytest.fixture(scope="module")
def figures(tmp_path_factory):
    gen = tmp_path_factory.mktemp("gen")
    (gen / "accumulator_unit.v").write_text(ACCUMULATOR_UNIT)
    return fpgaflow.synthesize("accumulator_unit", family="ecp5", gen_dir=gen, paths=3,
                               build=tmp_path_factory.mktemp("ecp5"), timeout=TOOL_TIMEOUT_S)


def test_places_with_the_units_registers(figures):
    assert figures["family"] == "ecp5" and figures["placed"]
    assert figures["fabric_ffs"] == 16 and figures["io_ffs"] == 0
    assert 16 <= figures["lcs"] <= figures["lcs_available"] == 24288
    assert figures["ios"] == 1 + 1 + 16 + 16 + 16 + 1


def test_worst_path_is_nextpnrs(figures):
    worst = figures["paths"][0]
    assert abs(worst["ns"] - 1000.0 / figures["fmax_mhz"]) < 0.012
    assert worst["end"][0].startswith("y[") and worst["end"][1] == "accumulator_unit_add"


def test_pin_figures_agree_with_nextpnrs_report(figures):
    pins = figures["pins"]
    worst_in = max(entry["in"] for entry in pins.values() if isinstance(entry["in"], float))
    worst_out = max(entry["out"] for entry in pins.values() if isinstance(entry["out"], float))
    assert abs(worst_in - figures["io_report"]["in"]) < 0.012
    assert abs(worst_out - figures["io_report"]["out"]) < 0.012
    # the inputs reach the accumulator through logic; carry leaves through a LUT from y[15] and a[15]
    assert pins["a[0]"]["in_cells"] >= 1 and pins["carry"]["out"] is not None


def test_refuses_ice40_cells(tmp_path):
    (tmp_path / "ice40_cell_unit.v").write_text(ICE40_CELL_UNIT)
    with pytest.raises(fpgaflow.SynthError, match="ECP5 takes the ecp5 build"):
        fpgaflow.synthesize("ice40_cell_unit", family="ecp5", gen_dir=tmp_path, build=tmp_path / "ecp5")


def test_ice40_refuses_ecp5_cells(tmp_path):
    (tmp_path / "ecp5_cell_unit.v").write_text(ECP5_CELL_UNIT)
    with pytest.raises(fpgaflow.SynthError, match="ECP5 cell LUT4: iCE40 takes the ice40 build"):
        fpgaflow.synthesize("ecp5_cell_unit", family="ice40", gen_dir=tmp_path, build=tmp_path / "ice40")


def test_ecp5_lut_cell_is_kept_and_its_pin_one_cell_from_the_register(tmp_path):
    (tmp_path / "ecp5_cell_unit.v").write_text(ECP5_CELL_UNIT)
    figures = fpgaflow.synthesize("ecp5_cell_unit", family="ecp5", gen_dir=tmp_path, build=tmp_path / "ecp5",
                                  timeout=TOOL_TIMEOUT_S)
    assert figures["placed"] and figures["pins"]["pin"]["in_cells"] == 1
    routed = json.loads((tmp_path / "ecp5" / "ecp5_cell_unit" / "ecp5_cell_unit_routed.json").read_text())
    (cells,) = [module["cells"] for module in routed["modules"].values()]   # the unit, as the flow's top
    assert cells["pin_lut"]["type"] == "TRELLIS_COMB", sorted(cells)


@pytest.mark.slow(reason="a conversion and about 1.5 minutes of place and route a seed; the ECP5 flow on a small unit runs by default")
def test_generic_top_places_on_ecp5_and_meets_the_pci_clock(tmp_path):
    # about 1.5 minutes of CPU a seed on top of the conversion: in the slow set
    gen = tmp_path / "gen"
    result = subprocess.run([sys.executable, "-m", "rtl.top", "--convert", "--device", "generic", "--out", str(gen)],
                            capture_output=True, text=True, cwd=ROOT, timeout=TOOL_TIMEOUT_S)
    assert result.returncode == 0, result.stderr
    figures = fpgaflow.synthesize_closing("top", range(1, 1 + fpgaflow.SWEEP_SEEDS), family="ecp5", gen_dir=gen,
                                          build=tmp_path / "ecp5", timeout=TOOL_TIMEOUT_S)
    assert figures["placed"] and figures["meets"], figures["critical"]
    assert figures["lcs"] <= figures["lcs_available"]
