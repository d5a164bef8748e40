"""Register-to-register paths: named after the RTL's registers and processes.

``worst_paths`` lists the worst path into each register (bus) from a
static timing pass over nextpnr's SDF (``TimingGraph.register_paths``):
the same delays as nextpnr, clock insertion left out as in nextpnr; its
worst path equals nextpnr's figure to the picosecond.  ``critical_path``
is nextpnr's own worst path with its lines in the generated Verilog.
"""
import re
from pathlib import Path

from fpgaflow.sdf import TimingGraph, ns
from fpgaflow.tools import bit_names, load_module

_SOURCE_LINE = re.compile(r"([\w.]+\.v):(\d+)\.")
_PROCESS_LABEL = re.compile(r"\bbegin\s*:\s*(\w+)")


def process_labels(sources):
    """``{file name: [process label of each line]}``: the ``begin: label`` a line sits in, or ""."""
    labels = {}
    for path in sources:
        label, labels[Path(path).name] = "", []
        for line in Path(path).read_text().splitlines():
            found = _PROCESS_LABEL.search(line)
            label = found[1] if found else ("" if line.startswith(("assign", "endmodule")) else label)
            labels[Path(path).name].append(label)
    return labels


def source_line(cell):
    """(file name, line) of a netlist cell's ``src`` attribute, or None."""
    match = _SOURCE_LINE.search(cell.get("attributes", {}).get("src", ""))
    return (match[1], int(match[2])) if match else None


def rtl_net_names(placed, synthesised):
    """``{bit of nextpnr's netlist: the plainest name of that net in yosys's}``.

    nextpnr keeps one name per net; yosys's netlist has every alias, among
    them the RTL's (``keep`` on register outputs, see ``tools.PREPARE``).
    """
    synthesised_names = bit_names(synthesised)
    bit_of = {}
    for name, net in synthesised["netnames"].items():
        for index, bit in enumerate(net["bits"]):
            bit_of[f"{name}[{index}]" if len(net["bits"]) > 1 else name] = bit
    # nextpnr renames a net it connects to a pad it made (``total[3]$SB_IO_OUT``)
    return {bit: synthesised_names.get(bit_of.get(name, bit_of.get(name.split("$")[0])), name)
            for bit, name in bit_names(placed).items()}


def register_names(routed, netlist, top, sources, family):
    """Name each placed cell's register: ``{cell: (signal driven, process)}``.

    ``routed`` is nextpnr's ``--write`` JSON (cells as placed), ``netlist``
    yosys's; the process is the ``begin: label`` of the generated Verilog
    that assigns the flip-flop (MyHDL names it after the generator), found
    through the flip-flop's ``src`` line in ``sources``.
    """
    placed = load_module(routed)  # nextpnr calls it "top"
    synthesised = load_module(netlist, top)
    synthesised_names = bit_names(synthesised)
    net_names = rtl_net_names(placed, synthesised)
    assigned_at = {}
    for cell in synthesised["cells"].values():
        if family.is_ff(cell["type"]) and cell["connections"].get("Q") and source_line(cell):
            assigned_at[synthesised_names.get(cell["connections"]["Q"][0])] = source_line(cell)
    labels = process_labels(sources)
    names = {}
    for name, cell in placed["cells"].items():
        output = next((cell["connections"][port] for port in family.placed_outputs
                       if cell["connections"].get(port)), None)
        if not output or not isinstance(output[0], int):
            continue
        signal = net_names.get(output[0], name)
        file, line = assigned_at.get(signal, ("", 0))
        process = labels.get(file, [])[line - 1] if 0 < line <= len(labels.get(file, [])) else ""
        names[name] = (signal, process)
    return names


def worst_paths(sdf, names, family, count=10, skip=None):
    """The ``count`` worst register-to-register paths, one per end register (bus).

    Each: ``ns``, ``start``/``end`` (signal and process, see
    ``register_names``), ``luts`` (LUT levels, on iCE40 the end register's
    own input LUT included) and ``carries`` (carry-chain steps).  Paths that
    end in the bits of one bus count once, with their worst bit.  ``skip`` (a
    regular expression) leaves out the paths whose start or end register or
    process it finds, e.g. a unit already known to be slow.
    """
    paths = TimingGraph(Path(sdf).read_text()).register_paths()
    skipped = re.compile(skip) if skip else None
    seen, found = set(), []
    for (end, port), (ps, steps) in sorted(paths.items(), key=lambda item: -item[1][0]):
        start = steps[0][0][0]
        end_name = names.get(end, (f"{end}/{port}", ""))
        start_name = names.get(start, (start, ""))
        if skipped and any(skipped.search(text) for text in (*start_name, *end_name)):
            continue
        if end_name[0].split("[")[0] in seen:
            continue
        seen.add(end_name[0].split("[")[0])
        cells = [node for node, kind in steps if kind == "cell"]
        found.append({"ns": ns(ps), "start": start_name, "end": end_name,
                      "luts": sum(1 for _, pin in cells if pin in family.lut_outputs)
                      + (port in family.lut_inputs),
                      "carries": sum(1 for _, pin in cells if pin in family.carry_outputs)})
        if len(found) == count:
            break
    return found


def critical_path(report, gen_dir):
    """The worst register-to-register path: its delay, its logic cells and its lines in ``gen/``."""
    paths = [p for p in report.get("critical_paths", [])
             if p["from"].startswith("posedge") and p["to"].startswith("posedge")]
    if not paths:
        return None
    worst = max(paths, key=lambda p: sum(step["delay"] for step in p["path"]))
    gen_files = {path.name for path in Path(gen_dir).glob("*.v")}
    lines = []
    for step in worst["path"]:
        for source in step.get("sources", []):
            name, _, position = Path(source).name.partition(":")
            line = f"{name}:{position.split('.')[0]}"
            if name in gen_files and line not in lines:
                lines.append(line)
    return {"ns": round(sum(step["delay"] for step in worst["path"]), 2),
            "logic_cells": sum(1 for step in worst["path"] if step["type"] == "logic"),
            "lines": lines}


def io_report(report):
    """nextpnr's own worst pin figures (ns): ``in`` (pin to register) and ``out`` (register to pin).

    Those are the report's paths from and to ``<async>`` (the top's ports);
    the per-pin figures of ``pins.pin_timing`` come from the same model and
    their worst equals these.
    """
    worst = {}
    for path in report.get("critical_paths", []):
        key = "in" if path["from"] == "<async>" else "out" if path["to"] == "<async>" else None
        if key:
            delay = round(sum(step["delay"] for step in path["path"]), 2)
            worst[key] = max(worst.get(key, delay), delay)
    return worst
