"""The whole flow for one unit: yosys, nextpnr, and the figures read back from both.

``synthesize`` runs one placement seed; ``synthesize_closing`` tries seeds
in turn until the clock and the PCI pin budgets are met (a seed sweep, as
vendor flows do).
"""
import json
import re
import time
from pathlib import Path

from fpgaflow.ecp5 import ECP5
from fpgaflow.ice40 import ICE40
from fpgaflow.pin_timing import pin_budget_misses, pin_timing
from fpgaflow.timing_paths import critical_path, io_report, register_names, worst_paths
from fpgaflow.tools import (CLOCK_PORT, TIMEOUT_S, SynthError, bit_names, load_module, port_bits, relative, run,
                            run_yosys, unit_sources)
from fpgaflow.wrapper import WRAPPER_SUFFIX, is_wrapper_register, unit_ports, wrapper_verilog
from rtl.convert import BUILD_DIR as BUILD_ROOT
from rtl.convert import GEN_DIR

BUILD = BUILD_ROOT / "synth"
FAMILIES = {family.key: family for family in (ICE40, ECP5)}
PCI_MHZ = 33.0
SWEEP_SEEDS = 3  # placement seeds tried by default until timing closes (``synthesize_closing``)


def family_named(family):
    """A ``Family`` from itself or its key ("ice40", "ecp5")."""
    if isinstance(family, str):
        if family not in FAMILIES:
            raise SynthError(f"unknown family {family!r}: one of {', '.join(FAMILIES)}")
        return FAMILIES[family]
    return family


def available_units(gen_dir=GEN_DIR):
    """Units that have Verilog in ``gen_dir``: ``top`` alone if present."""
    from rtl.convert import UNITS

    if (Path(gen_dir) / "top.v").exists():
        return ["top"]
    return [unit for unit in UNITS if (Path(gen_dir) / f"{unit}.v").exists()]


def netlist_figures(netlist, unit, family=ICE40):
    """Flip-flop counts of yosys's netlist and its pad cells (``Family.io_cells``).

    ``fabric_ffs``; ``unread_ffs`` of them drive nothing (kept with their
    names, see ``tools.PREPARE``); ``wrapper_ffs`` belong to the ``--wrap``
    wrapper; ``io_ffs`` are pad-cell registers in use.
    """
    module = load_module(netlist, unit)
    port_names = {}
    for name, port in module["ports"].items():
        for index, bit in enumerate(port["bits"]):
            port_names[bit] = f"{name}[{index}]" if len(port["bits"]) > 1 else name
    io_cells = family.io_cells(module, port_names)
    names = bit_names(module)
    flip_flops = [cell for cell in module["cells"].values() if family.is_ff(cell["type"])]
    read = {bit for cell in module["cells"].values() for port, bits in cell["connections"].items()
            if cell["port_directions"].get(port) == "input" for bit in bits}
    read |= {bit for port in module["ports"].values() for bit in port["bits"]}
    return {"fabric_ffs": len(flip_flops),
            "unread_ffs": sum(1 for cell in flip_flops if cell["connections"]["Q"][0] not in read),
            "wrapper_ffs": sum(1 for cell in flip_flops
                               if is_wrapper_register(names.get(cell["connections"]["Q"][0], ""))),
            "io_ffs": sum(sum(registers) for _, registers in io_cells.values()),
            "io_cells": io_cells}


def check_constraints(netlist, unit, family, path):
    """The constraint file pins every port of ``unit`` and nothing else (only for the full top)."""
    ports, pinned = set(port_bits(load_module(netlist, unit))), set(family.pins(path))
    if ports != pinned:
        raise SynthError(f"{path} does not match the ports of {unit}: no pin for "
                         f"{sorted(ports - pinned)}, no port for {sorted(pinned - ports)}")


def run_nextpnr(unit, netlist, constraints, work, family, freq, seed, *, place=True, timeout=TIMEOUT_S):
    """Pack, place and route (or only pack); the report, SDF, placed netlist and log paths."""
    report, sdf, routed, log = (work / "report.json", work / f"{unit}.sdf", work / f"{unit}_routed.json",
                                work / "nextpnr.log")
    for stale in (report, sdf, routed):
        stale.unlink(missing_ok=True)
    command = [family.nextpnr, *family.device, "--json", relative(netlist, work),
               family.constraint_flag, relative(constraints, work), "--freq", str(freq), "--seed", str(seed),
               "--timing-allow-fail", *family.extra_nextpnr, "-q", "--log", relative(log, work),
               "--report", relative(report, work), "--write", relative(routed, work)]
    flag, suffix = family.bitstream
    command += ["--sdf", relative(sdf, work), flag, relative(work / f"{unit}.{suffix}", work)] if place \
        else ["--pack-only"]
    if constraints != family.constraints:
        command.append(family.unconstrained_flag)
    try:
        run(command, log, work, timeout)
    except SynthError as error:
        usage = re.search(rf"{family.utilisation['logic']}:\s*(\d+)/\s*(\d+)",
                          log.read_text() if log.exists() else "")
        if usage and int(usage[1]) > int(usage[2]):
            raise SynthError(f"{unit} does not fit: {usage[1]} / {usage[2]} {family.logic_label}, "
                             f"see {log}") from None
        raise error
    return report, sdf, routed, log


def clock_fmax(report):
    """Achieved fmax (MHz) of the domain clocked by the ``clock`` port, or the slowest one."""
    domains = report.get("fmax", {})
    ours = [v["achieved"] for k, v in domains.items() if re.search(rf"(^|\$){CLOCK_PORT}(_global)?(\$|$)", k)]
    values = ours or [v["achieved"] for v in domains.values()]
    return round(min(values), 1) if values else None


def work_folder(unit, family, wrap=False, build=None):
    """``<build>/<unit>/`` (``<unit>_timed/`` when wrapped), created; ``build`` defaults to
    ``build/synth/`` for iCE40 and ``build/synth/<family>/`` for the others."""
    name = f"{unit}{WRAPPER_SUFFIX}" if wrap else unit
    base = Path(build) if build else BUILD if family is ICE40 else BUILD / family.key
    work = base / name
    work.mkdir(parents=True, exist_ok=True)
    return work


def synthesised(unit, *, family=ICE40, gen_dir=GEN_DIR, wrap=False, build=None, timeout=TIMEOUT_S):
    """yosys's netlist of ``unit`` ready for nextpnr, and what the later steps need.

    Keys: ``name`` (the top synthesised: ``unit`` or its wrapper), ``work``,
    ``netlist``, ``sources``, ``cells`` (``netlist_figures``) and
    ``constraints`` (the family's pin file for the top, else one that only
    pins the clock).
    """
    family = family_named(family)
    work = work_folder(unit, family, wrap, build)
    name = work.name
    extra = ()
    if wrap:
        wrapper = work / f"{name}.v"
        wrapper.write_text(wrapper_verilog(unit, unit_ports(unit, gen_dir, work, timeout)))
        extra = (wrapper,)
    sources = unit_sources(name, gen_dir, extra)
    family.check_sources(sources)
    netlist = run_yosys(name, sources, work, family.synth, timeout)
    cells = netlist_figures(netlist, name, family)
    family.prepare_netlist(netlist, name, CLOCK_PORT)
    if unit == "top" and not wrap:
        constraints = family.top_constraints(set(port_bits(load_module(netlist, name))), work)
        check_constraints(netlist, name, family, constraints)
    else:
        constraints = family.unit_constraints(CLOCK_PORT, work, name)
    return {"name": name, "work": work, "netlist": netlist, "sources": sources, "cells": cells,
            "constraints": constraints}


def synthesize(unit, *, family=ICE40, gen_dir=GEN_DIR, freq=PCI_MHZ, seed=1, timeout=TIMEOUT_S, wrap=False,
               paths=1, skip=None, build=None, stage=None):
    """Synthesise, place and route ``unit`` on ``family`` (a ``Family`` or its key); return its figures.

    Keys: ``unit``, ``family`` (its key), ``placed`` (False for a unit with
    more port bits than the package has I/O: it is only packed, so no fmax
    and no pin timing), ``lcs`` (logic cells; LUT4s on ECP5) and
    ``lcs_available``, ``fabric_ffs`` (``unread_ffs`` of them drive
    nothing), ``io_ffs``, ``brams`` and ``brams_available``, ``ios``,
    ``fmax_mhz`` (of the ``clock`` domain), ``meets`` (fmax >= ``freq``),
    ``critical`` (see ``critical_path``), ``paths`` (the ``paths`` worst
    register-to-register paths but those ``skip`` matches, see
    ``worst_paths``), ``pins`` (see ``pin_timing``; none when wrapped),
    ``io_report`` (nextpnr's own worst pin figures, see ``io_report``),
    ``wrapped``, ``wrapper_ffs`` (the wrapper's flip-flops, counted in
    ``fabric_ffs`` and ``lcs``), ``seconds``, ``logs``, ``work``.  ``wrap``
    places the unit inside ``wrapper_verilog``'s registers, so any unit
    places, whatever its port count.  Work files go to
    ``<build>/<unit>/`` (``<unit>_timed/`` when wrapped; ``build`` defaults
    to ``build/synth/`` for iCE40, ``build/synth/ecp5/`` for ECP5).  Each
    tool gets ``timeout`` seconds.  ``stage``, from ``synthesised`` with the
    same options, skips yosys (a seed sweep synthesises once).
    """
    family = family_named(family)
    started = time.monotonic()
    stage = stage or synthesised(unit, family=family, gen_dir=gen_dir, wrap=wrap, build=build, timeout=timeout)
    name, work, netlist, sources, cells = (stage[key] for key in ("name", "work", "netlist", "sources", "cells"))
    place = len(port_bits(load_module(netlist, name))) <= family.package_ios
    report_path, sdf, routed, log = run_nextpnr(name, netlist, stage["constraints"], work, family, freq, seed,
                                                place=place, timeout=timeout)
    report = json.loads(report_path.read_text())
    usage = report["utilization"]
    keys = family.utilisation
    fmax = clock_fmax(report) if place else None
    names = register_names(routed, netlist, name, sources, family) if place else {}
    return {
        "unit": unit,
        "family": family.key,
        "placed": place,
        "wrapped": wrap,
        "lcs": usage[keys["logic"]]["used"],
        "lcs_available": usage[keys["logic"]]["available"],
        "fabric_ffs": cells["fabric_ffs"],
        "unread_ffs": cells["unread_ffs"],
        "wrapper_ffs": cells["wrapper_ffs"] if wrap else 0,
        "io_ffs": cells["io_ffs"],
        "brams": usage[keys["ram"]]["used"],
        "brams_available": usage[keys["ram"]]["available"],
        "ios": usage[keys["io"]]["used"],
        "fmax_mhz": fmax,
        "meets": fmax is not None and fmax >= freq,
        "critical": critical_path(report, gen_dir) if place else None,
        "paths": worst_paths(sdf, names, family, paths, skip) if place else [],
        "pins": pin_timing(sdf, cells["io_cells"], family) if place and not wrap else {},
        "io_report": io_report(report) if place else {},
        "seconds": round(time.monotonic() - started, 1),
        "logs": {"yosys": str(work / "yosys.log"), "nextpnr": str(log)},
        "work": str(work),
    }


def closes_timing(figures):
    """Placed, meets the clock, and (for the top) every PCI pin meets its budget."""
    return figures["placed"] and figures["meets"] and not pin_budget_misses(figures, FAMILIES[figures["family"]])


def synthesize_closing(unit, seeds, **options):
    """``synthesize`` with each placement seed in turn until timing closes (a
    seed sweep, as vendor flows do); the figures of that seed, else of the last,
    with the seed under ``seed``.  yosys runs once for all seeds."""
    stage = synthesised(unit, **{key: options[key] for key in ("family", "gen_dir", "wrap", "build", "timeout")
                                 if key in options})
    figures, failure = None, None
    for seed in seeds:
        try:
            figures = dict(synthesize(unit, seed=seed, stage=stage, **options), seed=seed)
        except SynthError as error:  # e.g. a router that does not converge on this placement
            failure = error
            continue
        if closes_timing(figures) or not figures["placed"]:
            break
    if figures is None:
        raise failure
    return figures
