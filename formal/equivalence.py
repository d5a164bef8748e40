"""Equivalence of two versions of a unit's Verilog: a miter proved with SymbiYosys.

    python -m formal.equivalence --unit dda_arc OLD.v NEW.v
    git show BASE:gen/dda_arc.v > old.v && python -m formal.equivalence --unit dda_arc old.v gen/dda_arc.v
    python -m formal.equivalence --unit regs_fifo old.v new.v --pair pulse_out0_level_x=pulse_out0_axis_x_level

Both files define the module ``--unit``; the new one is renamed
``<unit>_new`` as it is read.  The miter instantiates both with the same
inputs, holds the reset in the first clock and asserts, at every clock
after it, that each output of the two is the same (``same_<output>``).

Register correspondence (the default): memories are made registers, one
a word (yosys ``memory_map``), and the registers both versions have under
the same name and width are made ports (``expose -dff -shared``); they
are assumed equal in the first clock (both copies power up in the same
state, whatever it is, registers without a reset included) and asserted
equal, with the outputs, in every clock after the reset.  For a
refactoring that keeps its registers a k-induction then closes: at k = 1
when every register is paired, at k = 2 when some register of one
version is reloaded in every clock.  A register the change renamed is
paired with ``--pair OLD=NEW`` (the new version's ``NEW`` is read as ``OLD``).  Proved, the claim is: from any
common power-up state and for every input sequence, the two versions
give the same outputs clock for clock after a reset.  ``--outputs-only``
drops the correspondence: the copies power up independently and only the
outputs are compared (a bounded check is then what usually finishes).
The checks are combinational in each clock after the first (the reset's).

Verdicts: ``equivalent`` (a k-induction closed: unbounded; or a bounded
check passed: to its depth), ``different`` (an output differs: the
counterexample's step and outputs), ``registers differ`` (outputs agree so
far but a shared register does not: the correspondence does not hold),
``not proved`` (the induction step failed: from a common state the
versions part within k clocks, a real difference or one no run from the
reset reaches; or time ran out).
Work files go to ``build/formal/equivalence/<unit>/``.
"""
import argparse
import json
import re
import shutil
import sys
from dataclasses import dataclass, field
from pathlib import Path

from formal.mutation import yosys
from formal.sby import Task, run, short_name, tools_available
from rtl.convert import BUILD_DIR

WORK_DIR = BUILD_DIR / "formal" / "equivalence"
IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
OUTPUT_PREFIX = "same_"
MARKER = "EQUIVALENCE"     # names a work folder this module may replace
INDUCTION_FAILED = re.compile(r"induction: .*Assert failed in \S+: (\S+)")


@dataclass
class Port:
    name: str
    direction: str
    width: int
    local: str = ""     # the miter's name for it (a register's name may hold brackets: a memory word)

    def __post_init__(self):
        self.local = self.local or re.sub(r"\W", "_", self.name)

    @property
    def reference(self):
        """The port as Verilog names it (an escaped identifier where needed)."""
        return self.name if IDENTIFIER.match(self.name) else f"\\{self.name} "


@dataclass
class Verdict:
    status: str                  # sby's: PASS, FAIL, UNKNOWN, TIMEOUT, ERROR
    mode: str
    depth: int
    seconds: float
    outputs: list = field(default_factory=list)      # outputs that differ
    registers: list = field(default_factory=list)    # shared registers that differ
    step: int = None
    matched: list = field(default_factory=list)       # the shared registers compared
    trace: Path = None
    induction: bool = False                           # the names come from a failed induction step

    @property
    def equivalent(self):
        return self.status == "PASS"

    def text(self):
        if self.status == "PASS":
            reach = "unbounded (k-induction)" if self.mode == "prove" else f"bounded to {self.depth} clocks"
            return f"equivalent, {reach}"
        if self.induction:
            return (f"not proved: from a common state {', '.join((self.outputs + self.registers)[:6])} "
                    f"part within k = {self.depth} clocks (a difference, or one the reset never "
                    "reaches: a deeper --depth, or a bounded check, tells)")
        if self.outputs:
            return f"different: {', '.join(self.outputs)} at step {self.step} from the reset"
        if self.registers:
            return (f"registers differ: {', '.join(self.registers[:6])} at step {self.step} from the reset "
                    "(outputs agree so far; try --outputs-only)")
        if self.status == "UNKNOWN":
            return f"not proved: the induction did not close at k = {self.depth}"
        if self.status == "TIMEOUT":
            return "not proved: time ran out"
        return f"not proved: sby ended {self.status}"


def read_script(unit, old_name, new_name, match_registers, pairs=()):
    """yosys commands reading both versions (the new one renamed, its
    registers of ``pairs``, (old, new) names, given the old names), and the
    shared registers made ports when ``match_registers``."""
    script = [f"read_verilog -formal {new_name}", f"rename {unit} {unit}_new"]
    if pairs:
        script += [f"cd {unit}_new"] + [f"rename {new} {old}" for old, new in pairs] + ["cd"]
    script += [f"read_verilog -formal {old_name}", "prep"]
    if match_registers:
        # memories become registers, one a word, so that their words are paired too; each
        # paired register R becomes an output R (its value) and an input R.i (what its
        # readers read)
        script += ["memory_map", f"expose -cut -dff -shared {unit} {unit}_new"]
    return script


def module_ports(json_file, module):
    ports = json.loads(Path(json_file).read_text())["modules"][module]["ports"]
    return [Port(name, port["direction"], len(port["bits"])) for name, port in ports.items()]


def plan_ports(work, unit, old_name, new_name, match_registers, pairs=()):
    """(inputs, outputs, registers, paired) of the miter: the two versions'
    ports must agree; ``registers`` are the registers made ports that both
    have (same width, ``pairs`` renamed), ``paired`` every register whose
    readers were cut from it in both (those and the output ports that are registers)."""
    script = read_script(unit, old_name, new_name, False, pairs)
    script.append("write_json before.json")
    if match_registers:
        script += read_script(unit, old_name, new_name, True, pairs)[-2:] + ["write_json after.json"]
    yosys("; ".join(script), work)
    old, new = module_ports(work / "before.json", unit), module_ports(work / "before.json", f"{unit}_new")
    if {(p.name, p.direction, p.width) for p in old} != {(p.name, p.direction, p.width) for p in new}:
        only_old = sorted(p.name for p in old if p not in new)
        only_new = sorted(p.name for p in new if p not in old)
        raise ValueError(f"the two versions of {unit} have different ports: old only {only_old}, "
                         f"new only {only_new}")
    bad = [p.name for p in old if not IDENTIFIER.match(p.name)]
    if bad:
        raise ValueError(f"ports the miter cannot name: {bad}")
    inputs = [p for p in old if p.direction == "input"]
    outputs = [p for p in old if p.direction != "input"]
    if any(p.direction == "inout" for p in old):
        raise ValueError(f"{unit} has inout ports: compare its core, not its pads")
    registers, paired = [], []
    if match_registers:
        known = {p.name for p in old}
        cut_old, cut_new = (module_ports(work / "after.json", name) for name in (unit, f"{unit}_new"))
        registers = [p for p in cut_old if p.name not in known and p.direction == "output"
                     and (p.name, p.direction, p.width) in {(q.name, q.direction, q.width) for q in cut_new}]
        taken = {p.local for p in old} | {"clock", "started"}
        for port in registers:
            while port.local in taken:
                port.local += "_"
            taken.add(port.local)
        readers_old = {(p.name, p.width) for p in cut_old if p.direction == "input" and p.name not in known}
        readers_new = {(p.name, p.width) for p in cut_new if p.direction == "input" and p.name not in known}
        if readers_old != readers_new:
            raise ValueError(f"registers paired by name but not by width: {sorted(readers_old ^ readers_new)[:6]}")
        paired = [p for p in outputs + registers if (f"{p.name}.i", p.width) in readers_old]
    return inputs, outputs, registers, paired


def vector(width):
    return f"[{width - 1}:0] " if width > 1 else ""


def miter_text(unit, inputs, outputs, registers, paired=(), reset="reset", reset_active=0):
    """The harness ``equivalence_miter``: ``unit`` (``before``) and
    ``<unit>_new`` (``after``) on the same inputs, reset in the first clock,
    outputs and ``registers`` asserted equal after it.  The readers of each
    ``paired`` register read the old version's register in both copies."""
    if reset not in {p.name for p in inputs}:
        raise ValueError(f"{unit} has no input {reset!r} (name the reset with --reset)")
    compared = outputs + registers
    lines = ["module equivalence_miter ("]
    lines.append(",\n".join(f"    input wire {vector(p.width)}{p.name}" for p in inputs))
    lines.append(");")
    for port in compared:
        lines.append(f"    wire {vector(port.width)}before_{port.local}, after_{port.local};")
    for instance, module in (("before", unit), ("after", f"{unit}_new")):
        connections = [f".{p.name}({p.name})" for p in inputs]
        connections += [f".{p.reference}({instance}_{p.local})" for p in compared]
        connections += [f".{Port(p.name + '.i', 'input', p.width).reference}(before_{p.local})" for p in paired]
        lines.append(f"    {module} {instance} (\n        " + ",\n        ".join(connections) + ");")
    lines += ["    reg started = 0;", "    always @(posedge clock) started <= 1;",
              "    always @(*) if (!started) begin",
              f"        assume({reset} == 1'b{reset_active});", "    end",
              "    always @(*) if (started) begin"]
    lines += [f"        {OUTPUT_PREFIX}{p.local}: assert(before_{p.local} == after_{p.local});" for p in compared]
    lines += ["    end", "endmodule", ""]
    return "\n".join(lines)


def check(unit, old_file, new_file, mode="prove", depth=4, work=None, match_registers=True,
          reset="reset", reset_active=0, timeout=3600, pairs=()):
    """Prove ``new_file`` equivalent to ``old_file`` (module ``unit`` in both); a ``Verdict``.
    ``pairs``: (old, new) names of registers the change renamed, paired as one."""
    for name in (name for pair in pairs for name in pair):
        if not IDENTIFIER.match(name):
            raise ValueError(f"--pair: {name!r} is not a Verilog name")
    texts = [Path(source).read_text() for source in (old_file, new_file)]
    for source, text in zip((old_file, new_file), texts):
        if not re.search(rf"^\s*module\s+{re.escape(unit)}\b", text, re.MULTILINE):
            raise ValueError(f"{source} defines no module {unit}")
    work = Path(work or WORK_DIR / unit)
    if work.exists() and any(work.iterdir()) and not (work / MARKER).exists():
        raise ValueError(f"{work} holds files of something else: name a new folder")
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    (work / MARKER).write_text("work folder of python -m formal.equivalence, replaced by each run\n")
    old_name, new_name = f"{unit}_old.v", f"{unit}_new.v"
    for name, text in zip((old_name, new_name), texts):
        (work / name).write_text(text)
    inputs, outputs, registers, paired = plan_ports(work, unit, old_name, new_name, match_registers, pairs)
    miter = work / "equivalence_miter.sv"
    miter.write_text(miter_text(unit, inputs, outputs, registers, paired, reset, reset_active))
    task = Task(name=f"{unit}_{mode}", mode=mode, depth=depth, top="equivalence_miter", sources=[],
                script=read_script(unit, old_name, new_name, match_registers, pairs)
                + [f"read_verilog -formal -sv {miter.name}", "prep -top equivalence_miter",
                   # one netlist: what the two versions compute alike from the same registers merges
                   "flatten", "opt -fast -keepdc"],
                files=[work / old_name, work / new_name, miter], timeout=timeout)
    result = run(task, work)
    failed, induction = result.failed, False
    if result.status == "UNKNOWN":
        failed, induction = [short_name(name) for name in INDUCTION_FAILED.findall(result.log)], True
        result.trace = work / task.name / "engine_0" / "trace_induct.vcd"
    failed = {name[len(OUTPUT_PREFIX):] for name in failed}
    return Verdict(result.status, mode, depth, result.seconds, step=result.step, matched=[p.name for p in registers],
                   outputs=[p.name for p in outputs if p.local in failed],
                   registers=[p.name for p in registers if p.local in failed],
                   trace=result.trace if result.trace and result.trace.exists() else None, induction=induction)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m formal.equivalence", description=__doc__.split("\n\n")[0])
    parser.add_argument("old", type=Path, help="the Verilog before the change")
    parser.add_argument("new", type=Path, help="the Verilog after the change")
    parser.add_argument("--unit", required=True, help="the module both files define (e.g. dda_arc)")
    parser.add_argument("--mode", choices=("prove", "bmc"), default="prove",
                        help="prove: k-induction (unbounded when it closes, default); bmc: bounded")
    parser.add_argument("--depth", type=int, default=4,
                        help="k of the induction, or the clocks of the bounded check (default 4)")
    parser.add_argument("--outputs-only", action="store_true",
                        help="compare the outputs only, from independent states (no register correspondence)")
    parser.add_argument("--pair", action="append", default=[], metavar="OLD=NEW",
                        help="the new version's register NEW is the old one's OLD (renamed by the change); "
                             "repeat for each")
    parser.add_argument("--reset", default="reset", help="the reset input, held in the first clock (default reset)")
    parser.add_argument("--reset-active", type=int, choices=(0, 1), default=0,
                        help="the reset's active level (default 0: the card's RST#)")
    parser.add_argument("--timeout", type=int, default=3600, help="seconds sby may take (default 3600)")
    parser.add_argument("--work", type=Path, default=None, help="work folder (default build/formal/equivalence/UNIT)")
    args = parser.parse_args(argv)
    if args.depth < 1:
        parser.error("argument --depth: must be at least 1")
    pairs = [tuple(pair.split("=")) for pair in args.pair]
    if any(len(pair) != 2 for pair in pairs):
        parser.error("argument --pair: OLD=NEW, two register names")
    for path in (args.old, args.new):
        if not path.is_file():
            parser.error(f"{path}: no such file")
    missing = tools_available()
    if missing:
        parser.error(missing)
    try:
        verdict = check(args.unit, args.old, args.new, mode=args.mode, depth=args.depth, work=args.work,
                        match_registers=not args.outputs_only, reset=args.reset,
                        reset_active=args.reset_active, timeout=args.timeout, pairs=pairs)
    except (ValueError, RuntimeError) as error:
        parser.exit(2, f"{parser.prog}: error: {error}\n")
    engine = "smtbmc yices " + ("k-induction" if args.mode == "prove" else "bmc")
    print(f"{args.unit}: {verdict.text()} ({engine}, depth {args.depth}, "
          f"{len(verdict.matched)} shared registers compared, {verdict.seconds:.0f} s)")
    if verdict.trace is not None:
        print(f"counterexample: {verdict.trace}")
    return 0 if verdict.equivalent else 1


if __name__ == "__main__":
    sys.exit(main())
