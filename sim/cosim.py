"""Co-simulation of generated Verilog against MyHDL benches through Icarus.

``cosimulate(name, ports, verilog_files)`` returns a ``Cosimulation`` that
stands in for a block instance: the bench drives and samples the very same
Signals (and interface objects) it would hand to the MyHDL block.  Interface
arguments are flattened the way MyHDL's converter names top-level ports
(``<argument>_<attribute>``).  The ``myhdl.vpi`` module is built once from the
sources the ``myhdl`` wheel ships, into ``build/vpi``.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from myhdl import Cosimulation
from myhdl._Signal import _Signal

from sim.paths import build_dir

_PORT_DECL = re.compile(
    r"^\s*(input|output)\s+(?:wire\s+|reg\s+)?(signed\s+)?(\[[^\]]+\]\s*)?(\w+)\s*;",
    re.MULTILINE,
)


class CosimError(RuntimeError):
    """Icarus or the VPI module could not be built or run."""


def vpi_module():
    """Path of ``myhdl.vpi``, compiled on first use from the wheel's sources."""
    target = build_dir("vpi") / "myhdl.vpi"
    if target.exists():
        return target
    if shutil.which("iverilog-vpi") is None:
        raise CosimError("iverilog-vpi not found: install Icarus Verilog")
    sources = Path(sys.prefix) / "share" / "myhdl" / "cosimulation" / "icarus"
    if not (sources / "myhdl.c").exists():
        raise CosimError(f"MyHDL's VPI sources are missing under {sources}")
    with tempfile.TemporaryDirectory() as work:
        for name in ("myhdl.c", "myhdl_table.c"):
            shutil.copy(sources / name, work)
        _run(["iverilog-vpi", "myhdl.c", "myhdl_table.c"], cwd=work)
        staged = target.with_name(f"myhdl.vpi.{os.getpid()}")
        shutil.move(str(Path(work) / "myhdl.vpi"), str(staged))
    os.replace(staged, target)  # atomic: parallel test workers may race here
    return target


def flatten_ports(ports):
    """``{name: Signal}`` from ``{argument: Signal or interface}``."""
    flat = {}
    for name, value in ports.items():
        if isinstance(value, _Signal):
            flat[name] = value
            continue
        for attr, member in vars(value).items():
            if isinstance(member, _Signal):
                flat[f"{name}_{attr}"] = member
    return flat


def port_directions(verilog_text, module):
    """``[(direction, range, name)]`` of a module's ports, in declaration order."""
    match = re.search(rf"\bmodule\s+{module}\b(.*?)\bendmodule\b", verilog_text, re.S)
    if not match:
        raise CosimError(f"module {module} not found")
    return [(d, (s or "") + (r or ""), n) for d, s, r, n in _PORT_DECL.findall(match.group(1))]


def _wrapper(module, ports):
    inputs = [n for d, _, n in ports if d == "input"]
    outputs = [n for d, _, n in ports if d == "output"]
    lines = [f"module tb_{module};"]
    lines += [f"reg {r} {n};" for d, r, n in ports if d == "input"]
    lines += [f"wire {r} {n};" for d, r, n in ports if d == "output"]
    lines.append("initial begin")
    lines.append(f"    $from_myhdl({', '.join(inputs)});")
    if outputs:
        lines.append(f"    $to_myhdl({', '.join(outputs)});")
    lines.append("end")
    connections = ", ".join(f".{n}({n})" for _, _, n in ports)
    lines.append(f"{module} dut({connections});")
    lines.append("endmodule")
    return "\n".join(lines) + "\n"


def _run(cmd, cwd=None):
    result = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    if result.returncode:
        raise CosimError(f"{' '.join(map(str, cmd))} failed:\n{result.stdout}{result.stderr}")
    return result


def cosimulate(module, ports, verilog_files, libraries=(), defines=()):
    """A ``Cosimulation`` of ``module`` (defined in ``verilog_files``).

    ``ports`` maps each argument of the MyHDL block to the Signal or interface
    the bench uses; every port of the Verilog module must be covered.
    ``libraries``: Verilog files whose modules are compiled only where
    instantiated (a vendor's cell models); ``defines``: ``NAME`` or
    ``NAME=value`` macros for the compiler.
    """
    verilog_files = [Path(f) for f in verilog_files]
    text = "\n".join(f.read_text() for f in verilog_files)
    declared = port_directions(text, module)
    signals = flatten_ports(ports)
    missing = [n for _, _, n in declared if n not in signals]
    if missing:
        raise CosimError(f"bench gives no signal for ports {missing} of {module}")
    work = Path(tempfile.mkdtemp(prefix=f"{module}_", dir=build_dir("cosim")))
    wrapper = work / f"tb_{module}.v"
    wrapper.write_text(_wrapper(module, declared))
    image = work / f"{module}.vvp"
    options = [f"-D{name}" for name in defines]
    for library in libraries:
        options += ["-l", str(library)]
    _run(["iverilog", "-g2005", *options, "-s", f"tb_{module}", "-o", str(image), str(wrapper),
          *map(str, verilog_files)])
    used = {n: signals[n] for _, _, n in declared}
    cosim = Cosimulation(f"vvp -m {vpi_module()} {image}", **used)
    cosim.name = module  # lets MyHDL's tracer list it among a bench's instances
    return cosim


def convert_and_cosimulate(block_factory, module, ports, **params):
    """Convert ``block_factory(**ports, **params)`` afresh and co-simulate it.

    For configurations other than the defaults committed in ``gen/``.
    """
    work = Path(tempfile.mkdtemp(prefix=f"{module}_conv_", dir=build_dir("cosim")))
    block_factory(**ports, **params).convert(hdl="Verilog", path=str(work), name=module)
    return cosimulate(module, ports, [work / f"{module}.v"])
