"""What several tests of the converter share: one run of its command line on the default build."""
import subprocess
import sys

import pytest

from rtl.convert import ROOT

STALE = "stale_unit.v"


@pytest.fixture(scope="session")
def default_build_by_the_cli(tmp_path_factory):
    """``python -m rtl.top --convert --out DIR`` as a user runs it, DIR holding a stale file of an
    earlier build: (DIR, the finished process).  Converting takes half a minute, so the tests of
    ``gen/`` and of the command line share this run (their module is in one xdist group)."""
    out = tmp_path_factory.mktemp("default_build") / "verilog"
    out.mkdir()
    (out / STALE).write_text("module stale_unit; endmodule\n")
    result = subprocess.run([sys.executable, "-m", "rtl.top", "--convert", "--out", str(out)], cwd=ROOT,
                            capture_output=True, text=True, timeout=1800)
    assert result.returncode == 0, result.stderr
    return out, result
