"""Every Verilog file in ``gen/`` is clean under ``verilator --lint-only -Wall`` and compiles in Icarus.

Waivers live in ``tests/verilator.vlt``, each with its reason.  The iCE40
I/O cell (``SB_IO``, instantiated by ``rtl/pci_pads.py``) is given to both
tools as an empty black box with its real ports and parameters.
"""
import shutil
import subprocess

import pytest

from sim.paths import GEN, ROOT

WAIVERS = ROOT / "tests" / "verilator.vlt"
SOURCES = sorted(GEN.glob("*.v"))

SB_IO_BLACKBOX = """\
`timescale 1ns/10ps
module SB_IO (inout PACKAGE_PIN, input LATCH_INPUT_VALUE, input CLOCK_ENABLE,
              input INPUT_CLK, input OUTPUT_CLK, input OUTPUT_ENABLE,
              input D_OUT_0, input D_OUT_1, output D_IN_0, output D_IN_1);
  parameter [5:0] PIN_TYPE = 6'b000000;
  parameter [0:0] PULLUP = 1'b0;
  parameter [0:0] NEG_TRIGGER = 1'b0;
  parameter IO_STANDARD = "SB_LVCMOS";
endmodule
"""


@pytest.fixture
def blackbox(tmp_path):
    path = tmp_path / "sb_io_blackbox.v"
    path.write_text(SB_IO_BLACKBOX)
    return path


def _tool(name):
    path = shutil.which(name)
    assert path, f"{name} not found: install it (Debian package {name})"
    return path


@pytest.mark.parametrize("source", SOURCES, ids=lambda path: path.stem)
def test_verilator_lint_is_clean(source, blackbox):
    result = subprocess.run([_tool("verilator"), "--lint-only", "-Wall", str(WAIVERS), str(source),
                             str(blackbox), "--top-module", source.stem],
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr


@pytest.mark.parametrize("source", SOURCES, ids=lambda path: path.stem)
def test_icarus_compiles(source, blackbox, tmp_path):
    result = subprocess.run([_tool("iverilog"), "-g2005", "-Wall", "-o", str(tmp_path / "out.vvp"),
                             "-s", source.stem, str(source), str(blackbox)],
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
