"""The card's access latency as the docs state it, against the card: one
access of each kind on ``gen/card.v`` through the bench
(``sim/card/register_latency.py``), DEVSEL# and first TRDY# in clocks
after the address phase.  docs/pci.md holds the table; README and
docs/instructions.md name the first-TRDY# figures as "<access> A+n"."""
import re

import pytest

from rtl.convert import ROOT
from sim.card.register_latency import ACCESSES, measure

STATED = re.compile(r"\b(configuration read|configuration write|I/O read|I/O write|memory read|memory write|BAR2 read"
                    r"|BAR2 write) "
                    r"A\+(\d+)")
TABLE_ROW = re.compile(r"^\s*\| (configuration|I/O|memory|BAR2) (read|write)[^|]*\| A\+(\d+) \| A\+(\d+) \|$", re.M)


@pytest.fixture(scope="module")
def measured():
    return measure("card.v")


def test_the_table_in_pci_md_is_the_cards(measured):
    rows = TABLE_ROW.findall((ROOT / "docs" / "pci.md").read_text())
    assert {f"{space} {direction}": (int(devsel), int(trdy)) for space, direction, devsel, trdy in rows} == measured


@pytest.mark.parametrize("doc, accesses", [("README.md", ACCESSES),
                                           ("docs/instructions.md", ("I/O read", "I/O write"))])
def test_the_first_trdy_the_docs_state_is_the_cards(doc, accesses, measured):
    stated = STATED.findall((ROOT / doc).read_text())
    assert sorted({access for access, _ in stated}) == sorted(accesses)
    assert all(int(clocks) == measured[access][1] for access, clocks in stated), stated
