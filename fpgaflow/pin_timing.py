"""Pin timing from nextpnr's SDF, and PCI 33's budgets.

"pin to register" is the longest path from a pin's pad cell to a
register's set-up, "register to pin" the longest clock-to-output path into
a pin's pad cell (its data and its output enable).  A pin whose register
sits in the pad cell (iCE40 ``SB_IO`` PIN_TYPE) has no fabric path: it is
shown as ``io-reg``.  What nextpnr's model leaves out (pad buffers, the
clock ball's path to the global network) the family adds from its data
sheet where it has the figures (``Family.at_the_pins``).
"""
import sys
from collections import defaultdict
from pathlib import Path

from fpgaflow.sdf import TimingGraph, ns

PCI33_SETUP_NS = 7.0
PCI33_CLOCK_TO_OUT_NS = 11.0
BUDGETS = {"in": PCI33_SETUP_NS, "out": PCI33_CLOCK_TO_OUT_NS, "oe": PCI33_CLOCK_TO_OUT_NS}
PCI_PREFIX = "pci_"
NEXTPNR_PAD_SUFFIXES = ("$sb_io", "$tr_io")  # pads nextpnr makes for plain top-level ports


def pin_timing(sdf, io_cells, family):
    """``{pin: {"in": ns | "io-reg" | None, "in_cells", "out": ..., "oe": ...}}`` per pin with a pad cell.

    ``in_cells`` counts the logic cells (LUTs, carries) on the worst input
    path.  ``io_cells`` maps the pad instances of the netlist to (pin,
    registers in use), see ``Family.io_cells``; the pads nextpnr makes itself
    for plain ports (``<pin>$sb_io``, ``<pin>$tr_io``) have no registers.
    """
    graph = TimingGraph(Path(sdf).read_text())
    sys.setrecursionlimit(max(sys.getrecursionlimit(), 20000))  # long carry chains
    cells = dict(io_cells)
    for instance, kind in graph.cell_type.items():
        if kind in family.io_types and instance.endswith(NEXTPNR_PAD_SUFFIXES) and instance not in cells:
            cells[instance] = (instance.rsplit("$", 1)[0], (False, False, False))
    in_port, out_port, oe_port = family.io_ports
    unregistered_inputs = {(name, in_port) for name, (_, registers) in cells.items() if not registers[0]}
    figures = {}
    for instance, (pin, (in_reg, out_reg, oe_reg)) in cells.items():
        if pin is None:
            continue
        worst_in = None if in_reg else graph.worst_to_register((instance, in_port))
        entry = {"in": "io-reg" if in_reg else ns(worst_in and worst_in[0]),
                 "in_cells": worst_in[1] if worst_in else 0}
        for key, port, registered in (("out", out_port, out_reg), ("oe", oe_port, oe_reg)):
            entry[key] = "io-reg" if registered and bool(graph.fanin.get((instance, port))) else \
                ns(graph.worst_from_register((instance, port), unregistered_inputs))
        figures[pin] = entry
    return figures


def pin_budget_misses(figures, family):
    """The PCI pins of ``figures`` that miss PCI 33's budgets at the balls, as text."""
    return [f"{pin} {key} {family.at_the_pins(key, entry[key])} ns"
            for pin, entry in figures["pins"].items() if pin.startswith(PCI_PREFIX)
            for key, budget in BUDGETS.items()
            if entry[key] is not None and _over(family.at_the_pins(key, entry[key]), budget)]


def _over(figure, budget):
    return isinstance(figure, float) and figure > budget


def worst_pci_pins(figures, family):
    """Worst PCI figure per direction at the balls (``at_the_pins``), ``io-reg`` ones included."""
    worst = {}
    for pin, entry in figures["pins"].items():
        if pin.startswith(PCI_PREFIX):
            for key in BUDGETS:
                value = family.at_the_pins(key, entry[key])
                if value is not None and value != "io-reg":
                    worst[key] = max(worst.get(key, value), value)
    return worst


def pin_groups(pins):
    """Worst figure per port name (``ad[0..31]`` -> ``ad``), per direction."""
    groups = defaultdict(dict)
    for pin, entry in pins.items():
        group = groups[pin.split("[")[0]]
        for key in ("in", "out", "oe"):
            group[key] = _worse(group.get(key), entry[key])
        group["in_cells"] = max(group.get("in_cells", 0), entry["in_cells"])
    return dict(sorted(groups.items()))


def _worse(a, b):
    if a is None or a == "io-reg" and isinstance(b, float):
        return b
    if isinstance(a, float) and isinstance(b, float):
        return max(a, b)
    return a
