"""Every Verilog file of every build is clean under ``verilator --lint-only -Wall``
and compiles in Icarus; the ``generic`` build has no vendor primitive.

Builds: ``gen/`` (the default: units and card generic, the top for iCE40,
two axes), and, converted into a work folder by the command line,
``generic`` at the top of the parameter ranges (six axes), ``ice40`` at
the bottom (but three axes: the smallest card with more than X and Y) and
``ecp5`` with four axes (the build docs/synthesis.md measures on ECP5).  Files
with vendor LUTs are linted twice: for simulators and with ``SYNTHESIS``
defined (the ``SB_LUT4`` or ``LUT4`` branch).  Waivers live in
``tests/verilator.vlt``, each with its reason.  The vendor cells (``SB_IO``,
``SB_LUT4``, ECP5's ``LUT4``) are given to both tools as empty black boxes
with their real ports and parameters.
"""
import re
import shutil
import subprocess
import sys

import pytest

from rtl.convert import GEN_DIR, ROOT, UNITS

WAIVERS = ROOT / "tests" / "verilator.vlt"

BUILDS = {
    "gen": None,
    "generic": ["--device", "generic", "--coord-width", "29", "--fifo-depth", "32768", "--variants", "all",
                "--clock-hz", "1", "--vendor-id", "0xFFFE", "--axes", "6"],
    "ice40": ["--device", "ice40", "--coord-width", "14", "--fifo-depth", "4", "--clock-hz", "33333333",
              "--axes", "3", "--encoders"],   # Z's encoder registers are block-only as X's and Y's
    "ecp5": ["--device", "ecp5", "--axes", "4"],
}
# build -> the suffixes of its STEP/DIR pins, as docs/axes.md names the axes
AXIS_PINS = {"gen": "xy", "generic": "xyzabc", "ice40": "xyz", "ecp5": "xyza"}
SOURCES = [(build, unit) for build in BUILDS for unit in UNITS]
# Each build is converted once per worker: the module's tests share one.
pytestmark = pytest.mark.xdist_group("lint")

# the SB_IO black box of the FuseSoC lint target, and the LUT cells of the ice40 and ecp5 builds
SB_IO_BLACKBOX = ROOT / "tests" / "verilog" / "sb_io_blackbox.v"
SB_LUT4_BLACKBOX = """\
module SB_LUT4 (output O, input I0, input I1, input I2, input I3);
  parameter [15:0] LUT_INIT = 16'h0000;
endmodule
module LUT4 (input A, input B, input C, input D, output Z);
  parameter [15:0] INIT = 16'h0000;
endmodule
"""


@pytest.fixture(scope="module")
def blackbox(tmp_path_factory):
    path = tmp_path_factory.mktemp("cells") / "sb_io_blackbox.v"
    path.write_text(SB_IO_BLACKBOX.read_text() + SB_LUT4_BLACKBOX)
    return path


@pytest.fixture(scope="module")
def build_folders(tmp_path_factory):
    """Build name -> folder, converted on first use."""
    folders = {"gen": GEN_DIR}
    work = tmp_path_factory.mktemp("builds")

    def folder(build):
        if build not in folders:
            out = work / build
            result = subprocess.run([sys.executable, "-m", "rtl.top", "--convert", "--out", str(out),
                                     *BUILDS[build]], cwd=ROOT, capture_output=True, text=True, timeout=1800)
            assert result.returncode == 0, result.stderr
            folders[build] = out
        return folders[build]

    return folder


def _tool(name):
    path = shutil.which(name)
    assert path, f"{name} not found: install it (Debian package {name})"
    return path


@pytest.mark.parametrize("build, unit", SOURCES, ids=[f"{b}-{u}" for b, u in SOURCES])
def test_verilator_lint_is_clean(build, unit, build_folders, blackbox):
    source = build_folders(build) / f"{unit}.v"
    has_luts = "`ifdef SYNTHESIS" in source.read_text()
    for defines in ([], ["-DSYNTHESIS"]) if has_luts else ([],):
        result = subprocess.run([_tool("verilator"), "--lint-only", "-Wall", *defines, str(WAIVERS),
                                 str(source), str(blackbox), "--top-module", unit],
                                capture_output=True, text=True, timeout=600)
        assert result.returncode == 0, f"{' '.join(defines)}\n{result.stderr}"


@pytest.mark.parametrize("build, unit", SOURCES, ids=[f"{b}-{u}" for b, u in SOURCES])
def test_icarus_compiles(build, unit, build_folders, blackbox, tmp_path):
    source = build_folders(build) / f"{unit}.v"
    result = subprocess.run([_tool("iverilog"), "-g2005", "-Wall", "-o", str(tmp_path / "out.vvp"),
                             "-s", unit, str(source), str(blackbox)],
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr


# unit -> the vendor cells its Verilog instantiates, per build
VENDOR_CELLS = {
    "gen": {"top": {"SB_IO", "SB_LUT4"}},
    "generic": {},
    "ice40": {"pci_slave": {"SB_LUT4"}, "card": {"SB_LUT4"}, "top": {"SB_IO", "SB_LUT4"}},
    "ecp5": {"pci_slave": {"LUT4"}, "card": {"LUT4"}, "top": {"LUT4"}},   # no ECP5 pad cell: generic pads
}
# an instance of a parameterised cell (vendor cells are written in capitals; the converter's modules are not)
_CELL = re.compile(r"^\s*(?:\(\*.*?\*\)\s*)?([A-Z][A-Z0-9_]*)\s*#\s*\(", re.MULTILINE)


@pytest.mark.parametrize("build", sorted(BUILDS))
def test_vendor_primitives_only_where_the_device_asks_and_every_axis_has_pins(build, build_folders):
    folder = build_folders(build)
    for unit in UNITS:
        text = (folder / f"{unit}.v").read_text()
        cells = set(_CELL.findall(text))
        assert cells == VENDOR_CELLS[build].get(unit, set()), f"{build}/{unit}.v: {sorted(cells)}"
        assert ("`ifdef SYNTHESIS" in text) == bool(cells & {"SB_LUT4", "LUT4"}), f"{build}/{unit}.v"
    # the top's motor outputs: STEP and DIR of each axis of the build, in axis order, and the drive enable
    outputs = re.findall(r"^output (motor_\w+);", (folder / "top.v").read_text(), re.MULTILINE)
    assert outputs == [f"motor_{kind}_{axis}" for axis in AXIS_PINS[build] for kind in ("step", "dir")] + [
        "motor_drive_enable"], outputs
