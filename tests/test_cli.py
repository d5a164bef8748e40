"""Command line of ``python -m rtl.top``: help, one-line errors, ``--out``."""
import subprocess
import sys

import pytest

from rtl.top import PARAMETERS, UNITS
from sim.paths import ROOT

PROG = "python -m rtl.top"


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "rtl.top", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=600)


def assert_one_line_error(result):
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert result.returncode != 0, "a bad command line must exit non-zero"
    assert len(lines) == 1, f"expected a one-line error, got:\n{result.stderr}"
    assert lines[0].startswith(f"{PROG}: error: "), lines[0]


def test_help_names_every_option():
    result = run_cli("--help")
    assert result.returncode == 0, result.stderr
    for option in ["--convert", "--out", *(f"--{n.replace('_', '-')}" for n in PARAMETERS)]:
        assert option in result.stdout, f"{option} missing from --help"


def test_unknown_option_is_a_one_line_error(tmp_path):
    assert_one_line_error(run_cli("--convert", "--out", str(tmp_path), "--no-such-option"))


def test_nothing_to_do_is_a_one_line_error():
    assert_one_line_error(run_cli())


@pytest.mark.parametrize("name", sorted(PARAMETERS))
@pytest.mark.parametrize("value", ["abc", "-1"])
def test_bad_parameter_value_is_a_one_line_error(name, value, tmp_path):
    option = f"--{name.replace('_', '-')}"
    assert_one_line_error(run_cli("--convert", "--out", str(tmp_path), option, value))


def test_out_writes_every_unit_there_and_says_so(tmp_path):
    out = tmp_path / "verilog"
    result = run_cli("--convert", "--out", str(out))
    assert result.returncode == 0, result.stderr
    written = {path.name for path in out.iterdir()}
    assert {f"{unit}.v" for unit in UNITS} <= written
    for name in written:
        assert str(out / name) in result.stdout, f"{name} written but not reported"
