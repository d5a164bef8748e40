"""The encoder units (``rtl/encoder/``, not yet in the card's ``gen/``),
each converted alone, are clean under ``verilator --lint-only -Wall`` and
compile in Icarus, as the card's files are (``test_lint.py``)."""
import shutil
import subprocess

import pytest

from rtl.convert import ROOT, convert_unit

UNITS = ("encoder", "following_error", "probe", "timestamp")
WAIVERS = ROOT / "tests" / "verilator.vlt"


@pytest.fixture(scope="module")
def converted(tmp_path_factory):
    folder = tmp_path_factory.mktemp("encoder_units")
    return {unit: convert_unit(unit, {}, folder) for unit in UNITS}


@pytest.mark.parametrize("unit", UNITS)
def test_encoder_unit_lints_clean_and_compiles(unit, converted, tmp_path):
    for tool in ("verilator", "iverilog"):
        assert shutil.which(tool), f"{tool} not found: install it (Debian package {tool})"
    source = converted[unit]
    lint = subprocess.run(["verilator", "--lint-only", "-Wall", str(WAIVERS), str(source), "--top-module", unit],
                          capture_output=True, text=True, timeout=600)
    assert lint.returncode == 0, lint.stderr
    compiled = subprocess.run(["iverilog", "-g2005", "-Wall", "-o", str(tmp_path / "out.vvp"), "-s", unit,
                               str(source)], capture_output=True, text=True, timeout=600)
    assert compiled.returncode == 0 and not compiled.stderr.strip(), compiled.stderr
