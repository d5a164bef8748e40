"""``python -m fpgaflow --table``: every logic cell and flip-flop lands in one unit and register group.

A two-unit design, on iCE40 and ECP5, named as MyHDL names things (``<block><index>_<name>``):
``wide1`` holds a 16-bit accumulator (a carry chain and 16 flip-flops),
``narrow1`` a 2-bit counter.  The flip-flop counts come from the Verilog,
the logic-cell total from nextpnr's own utilisation report.
"""
import json

import pytest

from fpgaflow.table import Hierarchy, cell_table, format_table, register_group

pytestmark = pytest.mark.synth

TWO_UNITS = """module two_units (clock, reset, a, total, count);
input clock;
input reset;
input [15:0] a;
output [15:0] total;
output [1:0] count;
reg [15:0] wide1_acc;
reg [1:0] narrow1_count;
assign total = wide1_acc;
assign count = narrow1_count;
always @(posedge clock, negedge reset) begin: wide1_sum
    if (reset == 0) wide1_acc <= 0;
    else wide1_acc <= wide1_acc + a;
end
always @(posedge clock, negedge reset) begin: narrow1_step
    if (reset == 0) narrow1_count <= 0;
    else narrow1_count <= narrow1_count + 1;
end
endmodule
"""
BLOCKS = {"wide": True, "narrow": True, "_helper": False}


@pytest.fixture(scope="module", params=["ice40", "ecp5"])
def table(request, tmp_path_factory):
    gen = tmp_path_factory.mktemp("gen")
    (gen / "two_units.v").write_text(TWO_UNITS)
    build = tmp_path_factory.mktemp("cells")
    return cell_table("two_units", family=request.param, gen_dir=gen, build=build, blocks=BLOCKS), build


def test_names_split_into_units_and_leaves():
    hierarchy = Hierarchy({"card": True, "dda_arc": True, "reg_word": True, "_store": False})
    assert hierarchy.split("card1_dda_arc2_x_inward") == ([("card", 1), ("dda_arc", 2)], "x_inward")
    assert hierarchy.unit("card1_reg_word62__store47_pulse_on") == "card/reg_word"
    assert hierarchy.instance("card1_reg_word62__store47_pulse_on") == "card1/reg_word62"
    assert hierarchy.unit("motor_step_x") == "top"
    assert register_group("card1_dda_arc2_acc[12]") == "card1_dda_arc2_acc"
    assert register_group("card1_fifo2_storage.0.3_WADDR_SB_LUT4_I2_O[0]") == "card1_fifo2_storage.0.3_WADDR*"


def test_every_cell_is_counted_once(table):
    cells, build = table
    report = json.loads((build / "two_units" / "report.json").read_text())
    lcs, ffs, _ = cells.totals()
    assert lcs == report["utilization"][cells.family.utilisation["logic"]]["used"]
    assert ffs == 16 + 2


def test_registers_land_in_their_units(table):
    cells, _ = table
    groups = {group: (unit, bits, lcs, ffs) for group, unit, bits, lcs, ffs in cells.by_group()}
    assert groups["wide1_acc"][0] == "wide" and groups["wide1_acc"][1:2] == (16,) and groups["wide1_acc"][3] == 16
    assert groups["narrow1_count"][0] == "narrow" and groups["narrow1_count"][3] == 2
    units = {unit: (lcs, ffs) for unit, _, lcs, ffs, _ in cells.by_unit()}
    # the accumulator (16 sum bits and their carries) outweighs the 2-bit counter
    assert units["wide"][0] >= 16 > units["narrow"][0] >= 2
    assert cells.by_unit()[0][0] == "wide"


def test_the_table_prints_largest_first(table):
    cells, _ = table
    text = format_table(cells, "two_units", rows=1)
    lines = text.splitlines()
    assert lines[0].startswith("== two_units:")
    unit_rows = [line.split()[0] for line in lines[3:] if line.strip().split()[0] in ("wide", "narrow")]
    assert unit_rows == ["wide", "narrow"]
    assert "more groups" in text
