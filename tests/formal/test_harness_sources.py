"""The harnesses' files, read without a solver: every group hands SymbiYosys
each file its harness includes (the shared includes and the tables generated
from models/), and no harness retypes a constant those tables define."""
import re

import pytest

from formal import groups as catalogue
from formal.proof_group import PROPS

DIRECTIVE = re.compile(r'^`(ifdef|ifndef|else|endif|include)\b\s*"?([\w.]*)', re.MULTILINE)
# a LocalBus address compared with a literal (a register offset) or a PCI
# command or opcode compared with one: models/registers.py, models/pci.py and
# models/instructions.py define them (formal/*_props.py generate the names)
RETYPED = (re.compile(r"\b\w*addr\s*[!=]=\s*16'h"),
           re.compile(r"\b(command|txn_command|opcode|arriving_opcode|picked_opcode)\s*[!=]=\s*4'[hd]"))


def _includes(text, defines):
    """The files ``text`` includes with ``defines`` set (`ifdef/`ifndef/`else followed)."""
    active, names = [True], []
    for directive, word in DIRECTIVE.findall(text):
        if directive in ("ifdef", "ifndef"):
            active.append(active[-1] and (word in defines) == (directive == "ifdef"))
        elif directive == "else":
            active[-1] = not active[-1] and active[-2]
        elif directive == "endif":
            active.pop()
        elif active[-1]:
            names.append(word)
    return names


def _included(path, available, defines):
    """The files ``path`` includes, followed through the includes (those in
    ``available``, the others returned as they are named)."""
    seen, todo = set(), [path.name]
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        if name in available:
            todo += _includes(available[name](), defines)
    return seen - {path.name}


@pytest.mark.parametrize("name", [group.name for group in catalogue.GROUPS])
def test_group_passes_every_included_file(name):
    group = catalogue.group(name)
    passed = {path.name: path.read_text for path in (PROPS / f for f in (*group.harness, *group.includes))}
    passed.update({file: make for file, make in group.generated.items()})
    top = PROPS / group.harness[-1]
    missing = _included(top, passed, group.defines) - set(passed)
    assert not missing, f"{top.name} includes {sorted(missing)}, which group {name} does not pass"


@pytest.mark.parametrize("path", sorted(PROPS.glob("*_harness.sv")) + sorted(PROPS.glob("*.vh")),
                         ids=lambda path: path.name)
def test_harness_names_table_constants(path):
    text = re.sub(r"//.*", "", path.read_text())
    for pattern in RETYPED:
        assert not pattern.search(text), f"{path.name} types {pattern.search(text).group(0)!r}: use the generated name"
