"""Port declarations as third-party Verilog writes them (``sim.backends.icarus.port_directions``)."""
import pytest

from sim.backends.icarus import CosimError, port_directions, read_verilog

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
