"""The code examples of ``docs/verification.md`` run as they are written
there: every fenced Python block that starts with ``# example: <name>``,
from the project's root (their file names are relative to it)."""
import re

import pytest

from rtl.convert import ROOT
from sim.pci.records import RULES

DOC = ROOT / "docs" / "verification.md"
EXAMPLES = ("host options", "a second clock domain and watched outputs")


def examples():
    """``{name: code}`` of the doc's named examples."""
    blocks = re.findall(r"```python\n(# example: ([^\n]+)\n.*?)```", DOC.read_text(), re.S)
    return {name: code for code, name in blocks}


def test_every_named_example_is_run_here():
    assert sorted(examples()) == sorted(EXAMPLES)


@pytest.mark.parametrize("name", EXAMPLES)
def test_the_example_runs(name, monkeypatch):
    monkeypatch.chdir(ROOT)
    exec(compile(examples()[name], f"docs/verification.md ({name})", "exec"), {})


def test_the_rules_table_is_the_checkers():
    table = DOC.read_text().split("| rule | what it holds the bus to |")[1].split("\n\n")[0]
    rows = re.findall(r"^\| (\d+) \| (.+?) \|$", table, re.M)
    assert {int(number): text for number, text in rows} == RULES
