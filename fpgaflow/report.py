"""The figures of ``flow.synthesize`` as text, one format for every family."""
from fpgaflow.flow import FAMILIES, PCI_MHZ
from fpgaflow.pin_timing import (PCI33_CLOCK_TO_OUT_NS, PCI33_SETUP_NS, PCI_PREFIX, pin_budget_misses, pin_groups,
                                 worst_pci_pins)
from fpgaflow.wrapper import is_wrapper_register, wrapper_own


def format_figures(figures, freq=PCI_MHZ):
    """Human-readable lines for one unit's figures."""
    family = FAMILIES[figures["family"]]
    lines = [
        f"== {figures['unit']} on {family.name} ({figures['seconds']} s)",
        f"   {family.logic_label} {figures['lcs']} / {figures['lcs_available']}, flip-flops "
        f"{figures['fabric_ffs']} in fabric + {figures['io_ffs']} in I/O cells, {family.ram_label} "
        f"{figures['brams']} / {figures['brams_available']}, I/O {figures['ios']}",
    ]
    if figures["unread_ffs"]:
        lines.append(f"   of the fabric flip-flops, {figures['unread_ffs']} are register bits that nothing "
                     "reads, kept with the register names (docs/synthesis.md)")
    if figures["placed"]:
        lines.append(f"   fmax {figures['fmax_mhz']} MHz ({'meets' if figures['meets'] else 'FAILS'} {freq:g} MHz)")
    else:
        lines.append(f"   packed only: {figures['ios']} port bits exceed the {family.package_ios} I/O of the "
                     "package (no fmax; see the top, or --wrap)")
    if figures["wrapped"]:
        lines.append(f"   wrapped: every port bit between flip-flops (--wrap); the counts above include the "
                     f"wrapper's {figures['wrapper_ffs']} flip-flops")
    lines += format_paths(figures["paths"], figures["wrapped"])
    critical = figures["critical"]
    if critical and critical["lines"]:
        lines.append(f"   critical path {critical['ns']} ns through {critical['logic_cells']} logic cells: "
                     + ", ".join(critical["lines"][:8]))
    lines += format_pins(figures, family)
    return "\n".join(lines)


def format_pins(figures, family):
    """The pin table: worst figure per port, with the estimate at the balls where the family has one."""
    groups = {name: entry for name, entry in pin_groups(figures["pins"]).items()
              if (figures["unit"] == "top" or name.startswith(PCI_PREFIX))
              and any(entry[key] is not None for key in ("in", "out", "oe"))}  # not the clock pad
    if not groups:
        return []
    budgets = f"PCI 33 allows set-up {PCI33_SETUP_NS:g}, clock to output {PCI33_CLOCK_TO_OUT_NS:g}"
    if family.pad_figures:
        lines = [f"   pins: nextpnr path [estimate at the balls with the data sheet pad delays], ns; {budgets}"]
    else:
        lines = [f"   pins: nextpnr path, ns (its model has no pad buffer and no clock tree delay); {budgets}"]
        report = figures.get("io_report", {})
        if report:
            lines.append("     nextpnr's report, worst: pin to register "
                         f"{report.get('in', '-')}, register to pin {report.get('out', '-')}")
    lines.append(f"     {'port':<14}{'pin -> register':>22}{'register -> pin':>22}{'register -> enable':>22}")
    for name, entry in groups.items():
        cells = "".join(f"{_cell(family, key, entry.get(key)):>22}" for key in ("in", "out", "oe"))
        if entry["in_cells"]:
            cells += f"   (up to {entry['in_cells']} logic cells after the pin)"
        lines.append(f"     {name:<14}{cells}")
    return lines


def _cell(family, direction, value):
    if value is None:
        return "-"
    if not family.pad_figures:
        return str(value)
    return f"{value} [{family.at_the_pins(direction, value)}]"


def format_paths(paths, wrapped):
    """Lines listing the worst register-to-register paths (``paths.worst_paths``)."""
    if not paths:
        return []
    lines = ["   worst register-to-register paths (from the SDF; one per end register or bus):",
             f"     {'ns':>6} {'MHz':>6} {'LUTs':>5} {'carry':>5}  start -> end  (generated process)"]
    for path in paths:
        start, end = path["start"], path["end"]
        text = f"{start[0]} ({start[1] or '-'}) -> {end[0]} ({end[1] or '-'})"
        note = ""
        if wrapped and is_wrapper_register(start[0]) and is_wrapper_register(end[0]):
            note = "  [wrapper's own]" if wrapper_own(path) else "  [unit input to unit output, no register]"
        lines.append(f"     {path['ns']:6.2f} {1000 / path['ns']:6.1f} {path['luts']:5d} {path['carries']:5d}  "
                     f"{text}{note}")
    if wrapped and wrapper_own(paths[0]):
        lines.append("   WARNING: the worst path is the wrapper's own: the unit's fmax is higher than shown")
    return lines


def format_pad_figures(family):
    """The data sheet figures used for the estimates at the balls (none for a family without them)."""
    if not family.pad_figures:
        return ""
    return f"   data sheet ({family.name}, typical) figures added at the balls:\n" + "\n".join(
        f"     {key:<8} {value:4.1f} ns  {text}" for key, (value, text) in family.pad_figures.items())


def format_sweep(results, family):
    """One line per seed (fmax, LCs, worst PCI pins at the balls) and the worst over the seeds."""
    lines = [f"   {'seed':>4} {'fmax MHz':>9} {family.logic_label:>12} {'FFs':>6} {'pin->reg':>9} "
             f"{'reg->pin':>9} {'reg->oe':>9}"]
    worst = {}
    for seed, figures in results:
        if isinstance(figures, Exception):
            lines.append(f"   {seed:>4}  failed: {str(figures).splitlines()[0]}")
            continue
        pins = worst_pci_pins(figures, family)
        for key, value in pins.items():
            worst[key] = max(worst.get(key, value), value)
        misses = pin_budget_misses(figures, family)   # named per seed: the last seed's pin table is the only one printed
        lines.append(f"   {seed:>4} {figures['fmax_mhz']:>9} {figures['lcs']:>12} {figures['fabric_ffs']:>6} "
                     + " ".join(f"{pins.get(key, '-'):>9}" for key in ("in", "out", "oe"))
                     + (f"   over budget: {', '.join(misses)}" if misses else ""))
    lines.append("   worst PCI pin over the seeds (ns): " + ", ".join(
        f"{label} {worst[key]}" for key, label in (("in", "pin to register"), ("out", "register to pin"),
                                                   ("oe", "register to enable")) if key in worst))
    return "\n".join(lines)
