"""``rtl/pci/pin_lut.py``: the one-LUT paths as Verilog, judged in Icarus against truth tables.

Every function (the PCI target's pin codings, every two-input function,
seeded random ones of up to four inputs) is written by ``lut_verilog`` for
each device and driven with every combination of 0, 1, X and Z on its
inputs.  The expected output comes from the Python function alone: where
every way of reading the X/Z inputs as 0/1 gives the same value, the output
must be that value (a floating input the output does not depend on must
not make it X); where they disagree, X (never Z: a LUT does not float).
The ``ice40`` build's ``SB_LUT4`` branch and the ``ecp5`` build's ``LUT4``
branch (``ifdef SYNTHESIS``) are checked against yosys's own cell models.
"""
import itertools
import random
import shutil
import subprocess

import pytest

from rtl.pci.pin_lut import lut_expression, lut_verilog
from rtl.pci.pin_pick import PIN_CODINGS

LEVELS = "01xz"


def _functions():
    functions = [(4, lambda x, y, frame, irdy, pick=pick: pick(frame, irdy, x, y))
                 for _, _, pick, _ in PIN_CODINGS.values()]
    functions += [(2, lambda a, b, table=table: table >> (a | b << 1) & 1) for table in range(16)]
    functions += [(1, lambda a: a), (1, lambda a: 1 - a), (3, lambda a, b, c: a ^ b ^ c)]
    rng = random.Random(7)
    for inputs in (1, 2, 3, 4, 4, 4, 4, 4, 4):
        table = rng.getrandbits(1 << inputs)
        functions.append((inputs, lambda *bits, table=table: table >> sum(b << k for k, b in enumerate(bits)) & 1))
    return functions


FUNCTIONS = _functions()


def expected(function, inputs, levels):
    """The output for input ``levels`` ('0', '1', 'x', 'z'; input 0 first): the
    common value of every 0/1 reading of the unknown inputs, else 'x'."""
    choices = [(int(level),) if level in "01" else (0, 1) for level in levels[:inputs]]
    values = {function(*bits) for bits in itertools.product(*choices)}
    return str(values.pop()) if len(values) == 1 else "x"


def bench(device):
    """A test bench: ``out[k]`` is function k of ``in[0..]``; prints ``out`` for
    every combination of input levels."""
    lines = ["`timescale 1ns/1ps", "module tb;", "reg [3:0] in;", f"wire [{len(FUNCTIONS) - 1}:0] out;"]
    for k, (inputs, function) in enumerate(FUNCTIONS):
        lines += lut_verilog(f"out[{k}]", f"lut_{k}", [f"in[{i}]" for i in range(inputs)], function,
                             device=device)
    lines.append("initial begin")
    for levels in itertools.product(LEVELS, repeat=4):
        lines.append(f"    in = 4'b{''.join(reversed(levels))}; #1 $display(\"%b\", out);")
    lines += ["    $finish;", "end", "endmodule", ""]
    return "\n".join(lines)


def run_icarus(tmp_path, text, *extra):
    source = tmp_path / "tb.v"
    source.write_text(text)
    iverilog = shutil.which("iverilog")
    assert iverilog, "iverilog not found: install it (Debian package iverilog)"
    compiled = subprocess.run([iverilog, "-g2012", "-s", "tb", "-o", str(tmp_path / "tb.vvp"), *extra,
                               str(source)], capture_output=True, text=True, timeout=300)
    assert compiled.returncode == 0, compiled.stderr
    run = subprocess.run(["vvp", "-n", str(tmp_path / "tb.vvp")], capture_output=True, text=True, timeout=300)
    return [line for line in run.stdout.splitlines() if set(line) <= set("01xz")]


@pytest.mark.parametrize("device", ["generic", "ice40", "ecp5"])
def test_simulation_model_is_x_only_where_the_output_depends_on_x(device, tmp_path):
    rows = run_icarus(tmp_path, bench(device))
    combinations = list(itertools.product(LEVELS, repeat=4))
    assert len(rows) == len(combinations)
    for levels, row in zip(combinations, rows):
        for k, (inputs, function) in enumerate(FUNCTIONS):
            got, want = row[len(FUNCTIONS) - 1 - k], expected(function, inputs, levels)
            assert got == want, f"function {k} ({inputs} inputs), inputs {levels[:inputs]}: {got}, not {want}"


def test_generic_lut_is_plain_logic_and_ice40_a_cell_under_synthesis():
    generic = lut_verilog("o", "o_lut", ["a", "b"], lambda a, b: a & b, device="generic")
    assert generic == ["assign o = (b ? (a ? 1'b1 : 1'b0) : 1'b0);"]
    ice40 = lut_verilog("o", "o_lut", ["a", "b"], lambda a, b: a & b, device="ice40")
    assert ice40[0] == "`ifdef SYNTHESIS" and ice40[2:] == ["`else", generic[0], "`endif"]
    assert ice40[1] == "SB_LUT4 #(.LUT_INIT(16'h8888)) o_lut (.O(o), .I0(a), .I1(b), .I2(1'b0), .I3(1'b0));"


def test_ecp5_lut_is_a_kept_lut4_cell_under_synthesis_in0_on_a():
    generic = lut_verilog("o", "o_lut", ["a", "b"], lambda a, b: a & b, device="generic")
    ecp5 = lut_verilog("o", "o_lut", ["a", "b"], lambda a, b: a & b, device="ecp5")
    assert ecp5[0] == "`ifdef SYNTHESIS" and ecp5[2:] == ["`else", generic[0], "`endif"]
    # INIT bit D*8 + C*4 + B*2 + A: a AND b is 1 at 3, 7, 11, 15 (C, D tied to 0 but filled alike)
    assert ecp5[1] == "(* keep *) LUT4 #(.INIT(16'h8888)) o_lut (.A(a), .B(b), .C(1'b0), .D(1'b0), .Z(o));"
    # PCI's SERR# enable: (PAR XOR bus parity) AND armed is 1 at A^B & C: 5, 6, 13, 14
    serr = lut_verilog("o", "o_lut", ["par", "parity", "armed"], lambda p, q, armed: (p ^ q) & armed,
                       device="ecp5")
    assert serr[1] == ("(* keep *) LUT4 #(.INIT(16'h6060)) o_lut (.A(par), .B(parity), .C(armed), .D(1'b0), "
                       ".Z(o));")


def test_expression_leaves_out_inputs_the_function_ignores():
    assert lut_expression(["a", "b", "c"], lambda a, b, c: b) == "(b ? 1'b1 : 1'b0)"
    assert lut_expression(["a", "b"], lambda a, b: 1) == "1'b1"
    assert lut_expression(["a", "b"], lambda a, b: 1 - a) == "(a ? 1'b0 : 1'b1)"


def _cell_model(device):
    """Icarus options for yosys's cell model of ``device``'s LUT."""
    from sim.card.top_harness import ICE40_DEFINES, ecp5_lut_model, ice40_cell_model

    if device == "ice40":
        return [*(f"-D{name}" for name in ICE40_DEFINES), "-l", str(ice40_cell_model())]
    return ["-l", str(ecp5_lut_model())]


@pytest.mark.parametrize("device", ["ice40", "ecp5"])
def test_lut_cells_compute_the_truth_table(device, tmp_path):
    """The ``ifdef SYNTHESIS`` branch, with yosys's cell model (``SB_LUT4``, ``LUT4``): every 0/1 input."""
    rows = run_icarus(tmp_path, bench(device), "-DSYNTHESIS", *_cell_model(device))
    combinations = list(itertools.product(LEVELS, repeat=4))
    assert len(rows) == len(combinations)
    for levels, row in zip(combinations, rows):
        if set(levels) <= set("01"):
            for k, (inputs, function) in enumerate(FUNCTIONS):
                want = function(*(int(level) for level in levels[:inputs]))
                assert row[len(FUNCTIONS) - 1 - k] == str(want), f"function {k}, inputs {levels}"
