"""FuseSoC runs the core's ``lint`` (Verilator) and ``sim`` (Icarus) targets (``pci_dda_card.core``).

``sim`` resets the card and reads configuration dword 0; it must return
{Device ID, Vendor ID} as the converter's parameter table sets them, and
fail (non-zero exit) when told to expect anything else.  ``lint`` must pass
on ``gen/top.v`` and fail on a top with one unused wire more.
"""
import shutil
import subprocess
import sys

import pytest
import yaml

from models.parameters import PARAMETERS
from rtl.convert import GEN_DIR, ROOT

CORE = ROOT / "pci_dda_card.core"
VLNV = "::pci_dda_card:0.1.0"
BENCH = ROOT / "tests" / "verilog" / "card_config_read_tb.v"
TIMEOUT_S = 300


def expected_id():
    """Configuration dword 0: Device ID in the upper half, Vendor ID in the lower (PCI 2.3, 6.2.1)."""
    return PARAMETERS["device_id"].default << 16 | PARAMETERS["vendor_id"].default


def fusesoc(cores_root, build_root, target, *arguments):
    return subprocess.run([sys.executable, "-m", "fusesoc.main", "--cores-root", str(cores_root), "run",
                           "--build-root", str(build_root), "--target", target, VLNV, *arguments],
                          capture_output=True, text=True, timeout=TIMEOUT_S, cwd=build_root.parent)


def _tool(name):
    assert shutil.which(name), f"{name} not found: install it (Debian package {name})"


def test_core_expects_the_ids_of_the_parameter_table():
    core = yaml.safe_load(CORE.read_text().split("\n", 1)[1])
    assert core["parameters"]["EXPECTED_ID"]["default"] == expected_id()


def test_sim_reads_the_configuration_id(tmp_path):
    _tool("iverilog")
    result = fusesoc(ROOT, tmp_path / "build", "sim", f"--EXPECTED_ID={expected_id()}")
    assert result.returncode == 0, result.stdout + result.stderr
    assert f"PASS: configuration dword 0 = {expected_id():08x}" in result.stdout


def test_sim_fails_on_another_id(tmp_path):
    _tool("iverilog")
    wrong = expected_id() ^ 0x00010000
    result = fusesoc(ROOT, tmp_path / "build", "sim", f"--EXPECTED_ID={wrong}")
    assert result.returncode != 0
    assert f"FAIL: configuration dword 0 is {expected_id():08x}, expected {wrong:08x}" in result.stdout


def test_lint_passes_on_the_top(tmp_path):
    _tool("verilator")
    result = fusesoc(ROOT, tmp_path / "build", "lint")
    assert result.returncode == 0, result.stdout + result.stderr
    assert "verilator -f" in result.stdout


def test_lint_fails_on_an_unused_wire(tmp_path):
    _tool("verilator")
    root = tmp_path / "cores"
    for path in (CORE, GEN_DIR / "top.v", ROOT / "tests" / "verilator.vlt", ROOT / "tests" / "verilog"):
        target = root / path.relative_to(ROOT)
        target.parent.mkdir(parents=True, exist_ok=True)
        (shutil.copytree if path.is_dir() else shutil.copy)(path, target)
    top = root / "gen" / "top.v"
    top.write_text(top.read_text().replace("endmodule", "wire lint_probe;\n\nendmodule", 1))
    result = fusesoc(root, tmp_path / "build", "lint")
    assert result.returncode != 0
    assert "lint_probe" in result.stdout + result.stderr


@pytest.mark.parametrize("tool", ["verilator", "iverilog"])
def test_bench_is_clean(tool, tmp_path):
    _tool(tool)
    if tool == "verilator":
        command = ["verilator", "--lint-only", "-Wall", "--timing", str(ROOT / "tests" / "verilator.vlt"),
                   str(BENCH), str(GEN_DIR / "card.v"), "--top-module", BENCH.stem]
    else:
        command = ["iverilog", "-g2005", "-Wall", "-o", str(tmp_path / "bench.vvp"), "-s", BENCH.stem,
                   str(BENCH), str(GEN_DIR / "card.v")]
    result = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT_S)
    assert result.returncode == 0 and not result.stderr.strip(), result.stderr
