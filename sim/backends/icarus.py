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
import warnings
from pathlib import Path

from myhdl import Cosimulation
from myhdl._Signal import _Signal

from rtl.convert import build_dir
from sim.backends.conversions import converted, port_key

_DIRECTION = re.compile(r"\b(input|output|inout)\b")
_DECLARATION = re.compile(
    r"\b(input|output|inout)\s+((?:(?:wire|reg|tri|logic|signed|unsigned)\s+)*)(\[[^\]]+\]\s*)?"
    r"([\w\s,]+?)\s*(?=;|\)\s*;|,\s*(?:input|output|inout)\b|$)", re.S)
_PARAMETER = re.compile(r"\b(?:parameter|localparam)\s+(?:integer\s+)?(\w+)\s*=\s*([^,;)]+)")
_COMMENTS = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
_ATTRIBUTES = re.compile(r"\(\*(?!\)).*?\*\)", re.S)   # (* keep *), not @(*)
_SUBROUTINES = re.compile(r"\bfunction\b.*?\bendfunction\b|\btask\b.*?\bendtask\b", re.S)
_PORT_INFO = re.compile(r'\s*\.port_info\s+\d+\s+/(INPUT|OUTPUT|INOUT)\s+(\d+)\s+"([^"]+)"')
_PORT_WIDTH_WARNING = re.compile(r"warning: Port .* expects \d+ bits?, got \d+")


class CosimError(RuntimeError):
    """Icarus or the VPI module could not be built or run."""


class CosimWarning(UserWarning):
    """Icarus warned while compiling a design for co-simulation."""


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


def read_verilog(path):
    """Text of a Verilog file in whatever encoding it was written: the
    bytes as Latin-1, which never fails and keeps ASCII (all that Verilog
    syntax uses) as it is."""
    return Path(path).read_bytes().decode("latin-1")


def port_directions(verilog_text, module):
    """``[(direction, range, name)]`` of a module's ports, in port order;
    both port styles (ANSI ``module m(input [7:0] a, ...)`` and the names in
    the header with their declarations in the body, where the inputs of a
    ``function`` or ``task`` are not ports).  Comments and attributes are
    skipped; ranges over parameters with plain integer values are evaluated
    (``[WIDTH-1:0]`` becomes ``[31:0]``).  No preprocessor: a design with
    macros or `` `ifdef`` in its ports is read by ``elaborated_ports``."""
    text = _ATTRIBUTES.sub(" ", _COMMENTS.sub(" ", verilog_text))
    match = re.search(rf"\bmodule\s+{module}\b(.*?)\bendmodule\b", text, re.S)
    if not match:
        raise CosimError(f"module {module} not found")
    body = match.group(1)
    parameters = {name: value.strip() for name, value in _PARAMETER.findall(body)}
    header, rest = _port_list(body)
    ansi = bool(_DIRECTION.search(header))
    declared = {}
    for direction, kinds, width, names in _DECLARATION.findall(header if ansi else _SUBROUTINES.sub(" ", rest)):
        signed = "signed " if "signed" in kinds.split() else ""
        for name in re.split(r"[\s,]+", names.strip()):
            if name:
                declared[name] = (direction, signed + _evaluate_range(width, parameters, module), name)
    if ansi:
        return list(declared.values())
    order = [name.strip() for name in header.split(",") if name.strip()]
    missing = [name for name in order if name not in declared]
    if missing:
        raise CosimError(f"cannot read the port declarations of {module}: no direction for {missing}")
    return [declared[name] for name in order]


def elaborated_ports(verilog_files, module, libraries=(), defines=(), include_dirs=()):
    """``[(direction, range, name)]`` of ``module``'s ports as Icarus
    elaborates it, in port order: the simulator's own reading, with the
    design's defines, include folders and libraries (macros, `` `ifdef``,
    functions, any constant expression in a range).  Ranges come back as
    ``[width-1:0]``."""
    with tempfile.TemporaryDirectory(prefix=f"{module}_ports_", dir=build_dir("cosim")) as work:
        image = Path(work) / "ports.vvp"
        result = subprocess.run(["iverilog", *_options(libraries, defines, include_dirs), "-s", module,
                                 "-o", str(image), *map(str, verilog_files)], capture_output=True, text=True)
        if result.returncode:
            raise CosimError(f"Icarus cannot elaborate {module}:\n{result.stdout}{result.stderr}")
        lines = image.read_text(errors="replace").splitlines()
    root = re.compile(rf'^\S+ \.scope module, "{re.escape(module)}" "{re.escape(module)}" \d+ \d+;$')
    start = next((index for index, line in enumerate(lines) if root.match(line)), None)
    if start is None:
        raise CosimError(f"Icarus elaborated no module {module}")
    ports = []
    for line in lines[start + 1:]:
        if line.startswith("S_"):
            break
        found = _PORT_INFO.match(line)
        if found:
            direction, width, name = found.groups()
            ports.append((direction.lower(), _range(int(width)), name))
    return ports


def _range(width):
    return f"[{width - 1}:0] " if width > 1 else ""


def port_width(declared_range):
    """Bits of a port from its ``(direction, range, name)`` range text."""
    bounds = re.search(r"\[\s*(-?\d+)\s*:\s*(-?\d+)\s*\]", declared_range)
    return abs(int(bounds.group(1)) - int(bounds.group(2))) + 1 if bounds else 1


def _port_list(body):
    """(port list, the rest) of a module's text after its name."""
    position = 0
    if body.lstrip().startswith("#"):
        position = _after_parentheses(body, body.index("("))
    start = body.find("(", position)
    semicolon = body.find(";", position)
    if start < 0 or 0 <= semicolon < start:
        return "", body[semicolon + 1:]
    end = _after_parentheses(body, start)
    return body[start + 1:end - 1], body[end:]


def _after_parentheses(text, start):
    depth = 0
    for index in range(start, len(text)):
        depth += {"(": 1, ")": -1}.get(text[index], 0)
        if depth == 0:
            return index + 1
    raise CosimError("unbalanced parentheses in a module header")


def _evaluate_range(width, parameters, module):
    if not width:
        return ""
    expression = width.strip()[1:-1]
    for _ in range(8):  # parameters defined by other parameters
        replaced = re.sub(r"\b[A-Za-z_]\w*\b", lambda m: f"({parameters[m.group(0)]})"
                          if m.group(0) in parameters else m.group(0), expression)
        if replaced == expression:
            break
        expression = replaced
    bounds = []
    for part in expression.split(":"):
        if not re.fullmatch(r"[\d\s()+\-*/]+", part):
            raise CosimError(f"{module}: cannot evaluate the port range [{width.strip()[1:-1]}]")
        bounds.append(int(eval(part.replace("/", "//"))))  # digits and arithmetic only
    return "[" + ":".join(str(b) for b in bounds) + "] "


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


def cosimulate(module, ports, verilog_files, libraries=(), defines=(), include_dirs=()):
    """A ``Cosimulation`` of ``module`` (defined in ``verilog_files``).

    ``ports`` maps each argument of the MyHDL block to the Signal or interface
    the bench uses; every port of the Verilog module must be covered.
    ``libraries``: Verilog files whose modules are compiled only where
    instantiated (a vendor's cell models); ``defines``: ``NAME`` or
    ``NAME=value`` macros for the compiler (or a dict); ``include_dirs``:
    folders for `` `include``.  Files may be in any encoding.
    """
    verilog_files = [Path(f) for f in verilog_files]
    text = "\n".join(read_verilog(f) for f in verilog_files)
    declared = port_directions(text, module)
    signals = flatten_ports(ports)
    missing = [n for _, _, n in declared if n not in signals]
    if missing:
        raise CosimError(f"bench gives no signal for ports {missing} of {module}")
    used = {n: signals[n] for _, _, n in declared}
    return icarus_cosimulation(module, f"tb_{module}", _wrapper(module, declared), used, verilog_files,
                               libraries, defines, include_dirs)


def icarus_cosimulation(name, wrapper_module, wrapper_text, signals, verilog_files, libraries=(),
                        defines=(), include_dirs=()):
    """Compile ``wrapper_text`` (module ``wrapper_module``, which calls
    ``$from_myhdl`` / ``$to_myhdl`` on the names of ``signals``) with the
    design files in Icarus; the ``Cosimulation`` that runs it."""
    work = Path(tempfile.mkdtemp(prefix=f"{name}_", dir=build_dir("cosim")))
    wrapper = work / f"{wrapper_module}.v"
    wrapper.write_text(wrapper_text)
    image = work / f"{name}.vvp"
    result = _run(["iverilog", *_options(libraries, defines, include_dirs), "-s", wrapper_module,
                   "-o", str(image), str(wrapper), *map(str, verilog_files)])
    _report_warnings(name, wrapper, result.stdout + result.stderr)
    cosim = Cosimulation(f"vvp -m {vpi_module()} {image}", **signals)
    cosim.name = name  # lets MyHDL's tracer list it among a bench's instances
    return cosim


def _options(libraries, defines, include_dirs):
    """iverilog's language, ``-D``, ``-I`` and ``-l`` options."""
    if isinstance(defines, dict):
        defines = [name if value is None else f"{name}={value}" for name, value in defines.items()]
    options = ["-g2005", *(f"-D{define}" for define in defines)]
    options += [f"-I{Path(folder)}" for folder in include_dirs]
    for library in libraries:
        options += ["-l", str(library)]
    return options


def _report_warnings(name, wrapper, output):
    """Icarus's warnings on a compile that succeeded: a port width mismatch
    in the generated wrapper is a wiring error (``CosimError``); any other
    warning is passed on (``CosimWarning``), never dropped."""
    text = output.strip()
    if not text:
        return
    if any(_PORT_WIDTH_WARNING.search(line) and line.startswith(str(wrapper)) for line in text.splitlines()):
        raise CosimError(f"{name}: the wrapper's port widths do not match the design:\n{text}")
    warnings.warn(f"Icarus on {name}:\n{text}", CosimWarning, stacklevel=3)


def convert_module(block_factory, module, ports, **params):
    """The Verilog of ``block_factory(**ports, **params)`` as module ``module``: converted
    once for these sources, ports and parameters (``sim/backends/conversions.py``)."""
    key = f"{block_factory.__module__}.{block_factory.__qualname__} {sorted(params.items())!r} {port_key(ports)}"

    def convert(folder):
        block_factory(**ports, **params).convert(hdl="Verilog", path=str(folder), name=module)
        return folder / f"{module}.v"

    return converted(module, key, convert)


def convert_and_cosimulate(block_factory, module, ports, **params):
    """Convert ``block_factory(**ports, **params)`` (``convert_module``) and co-simulate it.

    For configurations other than the defaults committed in ``gen/``.
    """
    return cosimulate(module, ports, [convert_module(block_factory, module, ports, **params)])
