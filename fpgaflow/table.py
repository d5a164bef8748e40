"""Where the cells go: logic cells and flip-flops per unit and per register group, largest first.

The generated Verilog is flat (MyHDL writes one module), but every name in
it carries the instance path: ``card1_card_core1_dda_arc2_x_inward`` is
the register ``x_inward`` of ``dda_arc`` inside ``card_core`` inside
``card``.  The blocks are the ``@block`` functions of ``rtl/``; a block
whose function is named after its file is a unit (``dda_arc``), any other
(``_store``, ``pin_lut``) belongs to the unit it sits in.

Counted on the packed netlist nextpnr writes (``flow.run_nextpnr``), so the
logic-cell total is the tool's own:

- a register group is a register of the RTL, its bits together: the name
  ``keep`` preserves on every flip-flop (``tools.PREPARE``), bit indices
  stripped; a flip-flop that synthesis made itself carries a made-up name,
  shown as the RTL name it starts with and ``*``;
- a register's unit is the unit of the process that assigns it (its
  ``begin:`` label, through the flip-flop's source line), else of its name;
- a logic cell that holds a flip-flop belongs to that register; any other
  logic cell (a LUT, a carry) is shared equally among the register groups,
  pads and memories it feeds through other logic cells (its logic cone's
  ends); one that feeds none is counted as such.  A pad's group is named
  after the net into it (``pad <- card1_pci_slave2_ad_out_next``: the
  next value of the AD I/O-cell registers), a memory after its cells, a
  global buffer (nextpnr puts clocks, resets, enables and, with
  ``--promote-logic``, high-fanout logic nets there) after its net.
"""
import ast
import re
import sys
from collections import defaultdict
from pathlib import Path

from fpgaflow.flow import PCI_MHZ, family_named, run_nextpnr, synthesised, work_folder
from fpgaflow.ice40 import ICE40
from fpgaflow.timing_paths import register_names, rtl_net_names
from fpgaflow.tools import TIMEOUT_S, load_module
from rtl.convert import GEN_DIR

_BIT_INDEX = re.compile(r"(\[\d+\])+$")
_MADE_BY_SYNTHESIS = re.compile(r"_(SB_|TRELLIS_|LUT4_|CCU2C_|PFUMX_|L6MUX21_|DP16KD_)|\$")
_MEMORY_INDEX = re.compile(r"(\.\d+)+(_RAM)?$")
TOP_UNIT = "top"
NO_END = "(feeds no register, pad, global or memory)"


def rtl_blocks(rtl_dir=None):
    """``{block function name: True if it is a unit}`` from the ``@block`` functions of ``rtl/``."""
    if rtl_dir is None:
        import rtl

        rtl_dir = Path(rtl.__file__).parent
    blocks = {}
    for path in sorted(Path(rtl_dir).rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.FunctionDef) and any(
                    getattr(d, "id", getattr(d, "attr", None)) == "block" for d in node.decorator_list):
                blocks[node.name] = blocks.get(node.name, False) or node.name == path.stem
    return blocks


class Hierarchy:
    """Splits a generated name into its instance path and leaf."""

    def __init__(self, blocks):
        self.units = {name for name, unit in blocks.items() if unit}
        alternatives = "|".join(re.escape(name) for name in sorted(blocks, key=len, reverse=True))
        self._segment = re.compile(rf"({alternatives})(\d+)_")

    def split(self, name):
        """``([(block, index), ...], leaf)`` of a generated name."""
        segments, position = [], 0
        while True:
            found = self._segment.match(name, position)
            if not found:
                return segments, name[position:]
            segments.append((found[1], int(found[2])))
            position = found.end()

    def unit(self, name):
        """The unit path (``card/card_core/dda_arc``; ``top`` for the top's own) of a name."""
        segments, _ = self.split(name)
        path = [block for block, _ in segments if block in self.units]
        return "/".join(path) or TOP_UNIT

    def instance(self, name):
        """The unit instance path with indices (``card1/card_core1/regs_fifo2/reg_word62``)."""
        segments, _ = self.split(name)
        return "/".join(f"{block}{index}" for block, index in segments if block in self.units) or TOP_UNIT


def register_group(signal):
    """A register's group: its RTL name without bit indices (``*`` after a synthesis-made name's RTL part)."""
    made = _MADE_BY_SYNTHESIS.search(signal)
    if made:
        return signal[:made.start()] + "*"
    return _BIT_INDEX.sub("", signal)


class CellTable:
    """Logic cells, flip-flops and memories of a packed netlist, per register group and per unit.

    ``packed`` is nextpnr's ``--write`` JSON, ``netlist`` yosys's (for the
    RTL names), ``sources`` the Verilog (for the processes), ``blocks``
    those of ``rtl_blocks`` unless given.
    """

    def __init__(self, packed, netlist, top, sources, family, blocks=None):
        self.family = family
        self.hierarchy = Hierarchy(rtl_blocks() if blocks is None else blocks)
        self.module = load_module(packed)
        self.names = register_names(packed, netlist, top, sources, family)
        self.net_names = rtl_net_names(self.module, load_module(netlist, top))
        self.groups = defaultdict(lambda: {"lcs": 0.0, "ffs": 0, "rams": 0, "bits": set(),
                                           "unit": TOP_UNIT, "instance": TOP_UNIT})
        self._count()

    def _group(self, group, owner):
        """The entry of ``group``, placed in the unit that the generated name ``owner`` belongs to."""
        entry = self.groups[group]
        entry["unit"], entry["instance"] = self.hierarchy.unit(owner), self.hierarchy.instance(owner)
        return group

    def _register(self, cell_name):
        signal, process = self.names.get(cell_name, (cell_name, ""))
        return self._group(register_group(signal), process or signal), signal

    def _end(self, cell_name, cell, bit):
        """The group a cone ends in at ``cell`` (a register, pad, global buffer or memory) through
        net ``bit``, else None."""
        family = self.family
        if family.is_placed_register(cell):
            return self._register(cell_name)[0]
        net = self.net_names.get(bit, "")
        if cell["type"] in family.io_types:
            # named after the net into the pad: the RTL's name for what the
            # pin shows (or, with an I/O-cell register, its next value)
            if not net or _MADE_BY_SYNTHESIS.search(net):
                net = family.pad_pin(cell_name, cell, self.net_names)
            return self._group(f"pad <- {_BIT_INDEX.sub('', net)}", net)
        if cell["type"] in family.buffers:
            return self._group(f"global <- {_BIT_INDEX.sub('', net or cell_name)}", net or cell_name)
        if cell["type"] == family.utilisation["ram"]:
            return self._group(f"memory {_MEMORY_INDEX.sub('', cell_name)}", cell_name)
        return None

    def _count(self):
        cells, family = self.module["cells"], self.family
        readers = defaultdict(list)
        for name, cell in cells.items():
            for port, bits in cell["connections"].items():
                if cell["port_directions"].get(port) == "input":
                    for bit in bits:
                        readers[bit].append(name)
        ends = {}
        sys.setrecursionlimit(max(sys.getrecursionlimit(), 20000))  # long carry chains

        def cone(name):
            if name in ends:
                return ends[name]
            ends[name] = frozenset()  # a combinational loop reads as no end
            found, cell = set(), cells[name]
            for port, bits in cell["connections"].items():
                if cell["port_directions"].get(port) != "output":
                    continue
                # (nextpnr ties the unused LUT output of a carry cell to its own input)
                for bit, reader in ((bit, r) for bit in bits for r in readers.get(bit, ()) if r != name):
                    end = self._end(reader, cells[reader], bit)
                    if end is not None:
                        found.add(end)
                    elif family.is_placed_logic(cells[reader]):
                        found |= cone(reader)
            ends[name] = frozenset(found)
            return ends[name]

        for name, cell in cells.items():
            if family.is_placed_register(cell):
                group, signal = self._register(name)
                self.groups[group]["ffs"] += 1
                self.groups[group]["bits"].add(signal)
            elif cell["type"] == family.utilisation["ram"]:
                self.groups[self._end(name, cell, None)]["rams"] += 1
            if not family.is_placed_logic(cell):
                continue
            if family.is_placed_register(cell):
                shares = {self._register(name)[0]}
            else:
                shares = cone(name) or {self._group(f"{NO_END} {self.hierarchy.unit(name)}", name)}
            for group in shares:
                self.groups[group]["lcs"] += 1 / len(shares)

    def totals(self):
        """(logic cells, flip-flops, memories) over every group."""
        return (round(sum(g["lcs"] for g in self.groups.values())),
                sum(g["ffs"] for g in self.groups.values()), sum(g["rams"] for g in self.groups.values()))

    def by_group(self):
        """``[(group, unit, bits, logic cells, flip-flops)]``, most logic cells first."""
        rows = [(group, entry["unit"], len(entry["bits"]), entry["lcs"], entry["ffs"])
                for group, entry in self.groups.items()]
        return sorted(rows, key=lambda row: (-row[3], -row[4], row[0]))

    def by_unit(self):
        """``[(unit, instances, logic cells, flip-flops, memories)]``: each unit's own (its sub-units
        apart), most logic cells first."""
        units = defaultdict(lambda: {"lcs": 0.0, "ffs": 0, "rams": 0, "instances": set()})
        for entry in self.groups.values():
            unit = units[entry["unit"]]
            unit["lcs"] += entry["lcs"]
            unit["ffs"] += entry["ffs"]
            unit["rams"] += entry["rams"]
            unit["instances"].add(entry["instance"])
        rows = [(name, len(u["instances"]), u["lcs"], u["ffs"], u["rams"]) for name, u in units.items()]
        return sorted(rows, key=lambda row: (-row[2], -row[3], row[0]))


def cell_table(unit, *, family=ICE40, gen_dir=GEN_DIR, wrap=False, build=None, timeout=TIMEOUT_S, blocks=None):
    """``CellTable`` of ``unit``: synthesised and packed (no placement: the cell counts are final
    after packing).  Work files go to ``<build>/<unit>/`` (``build`` defaults to ``build/synth/cells/``)."""
    family = family_named(family)
    build = Path(build) if build else work_folder("cells", family)  # apart from placed runs
    stage = synthesised(unit, family=family, gen_dir=gen_dir, wrap=wrap, build=build, timeout=timeout)
    _, _, packed, _ = run_nextpnr(stage["name"], stage["netlist"], stage["constraints"], stage["work"], family,
                                  PCI_MHZ, 1, place=False, timeout=timeout)
    return CellTable(packed, stage["netlist"], stage["name"], stage["sources"], family, blocks)


def format_table(table, title, rows=40):
    """The unit table and the ``rows`` largest register groups, as text."""
    family = table.family
    lcs, ffs, rams = table.totals()
    label = family.logic_label
    lines = [f"== {title}: {lcs} {label}, {ffs} fabric flip-flops, {rams} {family.ram_label} (packed)",
             f"   by unit, its own logic (sub-units apart), most {label} first; "
             "a unit with several instances counts them all:",
             f"     {'unit':<44}{'inst':>5}{label:>12}{'%':>7}{'FFs':>7}{family.ram_label:>11}"]
    for unit, instances, unit_lcs, unit_ffs, unit_rams in table.by_unit():
        lines.append(f"     {unit:<44}{instances:>5}{unit_lcs:>12.1f}{100 * unit_lcs / max(lcs, 1):>7.1f}"
                     f"{unit_ffs:>7}{unit_rams:>11}")
    groups = table.by_group()
    width = max(len(group) for group, *_ in groups[:rows]) + 2
    lines += [f"   by register group (RTL name, bits together), most {label} first"
              f" ({min(rows, len(groups))} of {len(groups)}):",
              f"     {'register group':<{width}}{'bits':>5}{label:>12}{'FFs':>7}  unit"]
    for group, unit, bits, group_lcs, group_ffs in groups[:rows]:
        lines.append(f"     {group:<{width}}{bits:>5}{group_lcs:>12.1f}{group_ffs:>7}  {unit}")
    rest = groups[rows:]
    if rest:
        lines.append(f"     ... {len(rest)} more groups: {sum(row[3] for row in rest):.1f} {label}, "
                     f"{sum(row[4] for row in rest)} FFs")
    return "\n".join(lines)
