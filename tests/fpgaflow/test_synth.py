"""The card routes on iCE40 HX8K (ct256) and meets PCI's 33 MHz (``fpgaflow``).

Synthesises ``top`` once it is in ``gen/``, else every unit there.  PCI pins of
the top must also fit PCI 33's budgets: 7 ns from pin to register, 11 ns from
clock to pin, with the pad and clock-buffer delays nextpnr leaves out added
from the data sheet (``fpgaflow.ice40``, ``Ice40.at_the_pins``).
"""
import json
import shutil
import subprocess

import pytest

import fpgaflow
from fpgaflow.flow import netlist_figures
from fpgaflow.tools import run_yosys
from fpgaflow.wrapper import unit_ports

# In the default run: the top places and routes in about 90 s on a 2-core
# machine (plus 1-2 minutes once, while yowasp compiles its WebAssembly).
pytestmark = pytest.mark.synth
TOOL_TIMEOUT_S = 240  # CPU seconds per tool and seed: the top routes in about 60 s; a router
# that does not converge on a seed (it happens at 95 % of the logic cells) then costs 4 minutes

UNITS = fpgaflow.available_units()


# Timing closure with a seed sweep: the first of these placement seeds whose
# result meets the clock and the pin budgets (docs/synthesis.md).
PLACEMENT_SEEDS = range(1, 1 + fpgaflow.SWEEP_SEEDS)


@pytest.fixture(scope="module", params=UNITS)
def figures(request):
    return fpgaflow.synthesize_closing(request.param, PLACEMENT_SEEDS, timeout=TOOL_TIMEOUT_S)


def test_routes_and_meets_the_pci_clock(figures):
    if not figures["placed"]:
        pytest.skip(f"{figures['unit']} has more port bits than the package has pins: packed only")
    assert figures["lcs"] <= 7680
    assert figures["meets"], (f"{figures['unit']}: fmax {figures['fmax_mhz']} MHz "
                              f"< {fpgaflow.PCI_MHZ} MHz; {figures['critical']}")


def test_pci_pins_meet_pci33_budgets(figures):
    if figures["unit"] != "top":
        pytest.skip("pin budgets apply to the card's pins (gen/top.v)")
    late = fpgaflow.pin_budget_misses(figures, fpgaflow.ICE40)
    assert not late, f"PCI 33 budget missed at the balls (seed {figures['seed']}): " + "; ".join(late)


# --- standalone timing (--wrap) and the path list ----------------------------

ADDER_UNIT = """module adder_unit (clock, reset, a, b, y);
input clock;
input reset;
input [15:0] a;
input [15:0] b;
output reg [15:0] y;
always @(posedge clock, negedge reset) begin: adder_unit_add
    if (reset == 0) y <= 0;
    else y <= a + b;
end
endmodule
"""


def test_wrapper_feeds_and_folds_every_port_bit():
    ports = {"clock": ("input", 1), "reset": ("input", 1), "a": ("input", 8), "b": ("input", 3),
             "y": ("output", 10), "z": ("output", 1)}
    text = fpgaflow.wrapper_verilog("u", ports)
    assert "module u_timed (clock, reset, scan_in, scan_out);" in text
    assert "reg [10:0] scan_chain;" in text and "scan_chain <= {scan_chain[9:0], scan_in};" in text
    assert ".a(scan_chain[7:0])" in text and ".b(scan_chain[10:8])" in text
    assert ".y(unit_outputs[9:0])" in text and ".z(unit_outputs[10:10])" in text
    # 11 captured bits -> 3 -> 1, four bits (one LUT) per registered stage
    assert "reg [2:0] folded_1;" in text and "folded_1[2] <= ^captured[10:8];" in text
    assert "reg [0:0] folded_2;" in text and "assign scan_out = folded_2[0];" in text


@pytest.mark.parametrize("ports, message", [
    ({"clock": ("input", 1), "pad": ("inout", 4), "y": ("output", 1)}, "inout"),
    ({"clk": ("input", 1), "y": ("output", 1)}, "'clock'"),
    ({"clock": ("input", 1), "a": ("input", 2)}, "no outputs"),
])
def test_wrapper_refuses_what_it_cannot_time(ports, message):
    with pytest.raises(fpgaflow.SynthError, match=message):
        fpgaflow.wrapper_verilog("u", ports)


def test_wrapper_is_lint_clean(tmp_path):
    assert shutil.which("verilator"), "verilator not found: install it (Debian package verilator)"
    (tmp_path / "adder_unit.v").write_text("`timescale 1ns/10ps\n" + ADDER_UNIT)
    wrapper = tmp_path / "adder_unit_timed.v"
    wrapper.write_text(fpgaflow.wrapper_verilog("adder_unit", unit_ports("adder_unit", tmp_path, tmp_path)))
    result = subprocess.run(["verilator", "--lint-only", "-Wall", str(wrapper), str(tmp_path / "adder_unit.v"),
                             "--top-module", "adder_unit_timed"], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr


def test_wrapped_unit_paths_match_nextpnr(tmp_path):
    gen = tmp_path / "gen"
    gen.mkdir()
    (gen / "adder_unit.v").write_text(ADDER_UNIT)
    figures = fpgaflow.synthesize("adder_unit", gen_dir=gen, wrap=True, paths=5, build=tmp_path / "synth",
                               timeout=TOOL_TIMEOUT_S)
    assert figures["placed"] and figures["wrapped"]
    assert figures["wrapper_ffs"] == 32 + 16 + 4 + 1   # input chain, captures, two XOR stages
    worst = figures["paths"][0]
    # the SDF pass finds nextpnr's critical path (delays rounded to 10 ps, fmax to 0.1 MHz)
    assert abs(worst["ns"] - 1000.0 / figures["fmax_mhz"]) < 0.012
    # the 16-bit adder from the input chain into y sets it, not the wrapper
    assert worst["start"][0].startswith("scan_chain[") and worst["end"][0].startswith("unit.y[")
    assert worst["end"][1] == "adder_unit_add" and worst["carries"] >= 8
    assert not fpgaflow.wrapper_own(worst)
    ends = [path["end"][0].split("[")[0] for path in figures["paths"]]
    assert len(ends) == len(set(ends)), "one path per end register"


UNREAD_UNIT = """module unread_unit (clock, reset, a, y);
input clock;
input reset;
input [3:0] a;
output reg [3:0] y;
reg [2:0] spare;
always @(posedge clock, negedge reset) begin: unread_unit_store
    if (reset == 0) begin
        y <= 0;
        spare <= 0;
    end else begin
        y <= a ^ {1'b0, spare & ~spare};
        spare <= ~a[2:0];
    end
end
endmodule
"""


def test_registers_keep_their_names_and_unread_bits_are_counted(tmp_path):
    # ``spare`` is read until the logic optimisation drops the read (x & ~x):
    # the kept register stays, named, and counts as read by nothing
    gen = tmp_path / "gen"
    gen.mkdir()
    (gen / "unread_unit.v").write_text(UNREAD_UNIT)
    work = tmp_path / "synth"
    work.mkdir()
    netlist = run_yosys("unread_unit", [gen / "unread_unit.v"], work, fpgaflow.ICE40.synth, timeout=TOOL_TIMEOUT_S)
    cells = netlist_figures(netlist, "unread_unit", fpgaflow.ICE40)
    assert cells["fabric_ffs"] == 4 + 3 and cells["unread_ffs"] == 3
    names = set(json.loads(netlist.read_text())["modules"]["unread_unit"]["netnames"])
    assert "spare" in names
