"""Port declarations as third-party Verilog writes them: the text reader
(``sim.backends.icarus.port_directions``) and Icarus's own reading
(``elaborated_ports``)."""
import pytest

from sim.backends.icarus import CosimError, elaborated_ports, port_directions, read_verilog

ANSI = """
// header comment with a module word: module fake(input x);
module ansi #(parameter W = 8, parameter N = W * 2, parameter integer D = 4) (
    input wire clk, rst_n,          /* two names, one declaration */
    input [W-1:0] a,
    output reg signed [N-1:0] b,
    inout [D:0] c
);
endmodule
"""
BODY = """
module body (clk, a, b, c);
    parameter W = 3;
    input clk;
    input [W:0] a, b;
    output [7:0] c;
endmodule
"""


def test_ansi_ports_with_parameters_and_comments():
    assert port_directions(ANSI, "ansi") == [
        ("input", "", "clk"), ("input", "", "rst_n"), ("input", "[7:0] ", "a"),
        ("output", "signed [15:0] ", "b"), ("inout", "[4:0] ", "c")]


def test_ports_declared_in_the_body():
    assert port_directions(BODY, "body") == [
        ("input", "", "clk"), ("input", "[3:0] ", "a"), ("input", "[3:0] ", "b"), ("output", "[7:0] ", "c")]


def test_a_range_it_cannot_evaluate_is_refused():
    with pytest.raises(CosimError, match="cannot evaluate"):
        port_directions("module m(input [$clog2(8):0] a);\nendmodule\n", "m")


def test_any_encoding_reads(tmp_path):
    path = tmp_path / "latin1.v"
    path.write_bytes("// auteur: \xe9t\xe9\nmodule m(input a);\nendmodule\n".encode("latin-1"))
    assert port_directions(read_verilog(path), "m") == [("input", "", "a")]


# Ports named in the header and declared in the body, next to functions and a
# task whose inputs are not ports, attributes, and comments that look like
# declarations.
BODY_WITH_SUBROUTINES = """
module older (clk, rst_n, ad, ad_en, cbe, done);
    parameter WIDTH = 32;
    (* keep = "true" *) input clk;          // input fake; (a comment)
    input wire rst_n;                      /* output fake2; */
    input wire [WIDTH-1:0] ad, cbe;
    output ad_en;
    output reg [1:0] done;
    function en_all(input [WIDTH-1:0] e);
        en_all = &e;
    endfunction
    function [WIDTH-1:0] mixed;
        input [WIDTH-1:0] v;
        input [WIDTH-1:0] e;
        mixed = v & e;
    endfunction
    task report;
        input [3:0] code;
        $display("%h", code);
    endtask
    assign ad_en = en_all(mixed(ad, cbe));
    always @(*) done = {rst_n, clk};
endmodule
"""
OLDER_PORTS = [("input", "", "clk"), ("input", "", "rst_n"), ("input", "[31:0] ", "ad"),
               ("output", "", "ad_en"), ("input", "[31:0] ", "cbe"), ("output", "[1:0] ", "done")]  # header order


def test_function_and_task_inputs_are_not_ports():
    assert port_directions(BODY_WITH_SUBROUTINES, "older") == OLDER_PORTS


def test_icarus_reads_the_same_ports(tmp_path):
    # the simulator's own reading is the reference for the text reader
    path = tmp_path / "older.v"
    path.write_text(BODY_WITH_SUBROUTINES)
    assert elaborated_ports([path], "older") == OLDER_PORTS


def test_icarus_reads_ports_behind_macros_and_ifdefs(tmp_path):
    path = tmp_path / "macros.v"
    path.write_text("module m(input [`W-1:0] a\n`ifdef EXTRA\n, output [1:0] b\n`endif\n);\nendmodule\n")
    assert elaborated_ports([path], "m", defines={"W": 8, "EXTRA": None}) == [
        ("input", "[7:0] ", "a"), ("output", "[1:0] ", "b")]
    assert elaborated_ports([path], "m", defines=["W=4"]) == [("input", "[3:0] ", "a")]


def test_a_module_icarus_cannot_elaborate_is_named(tmp_path):
    path = tmp_path / "m.v"
    path.write_text("module m(input a);\nendmodule\n")
    with pytest.raises(CosimError, match="Icarus cannot elaborate other"):
        elaborated_ports([path], "other")
