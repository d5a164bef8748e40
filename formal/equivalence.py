"""Are two Verilog versions of a unit the same circuit at their ports?

    python -m formal.equivalence OLD.v NEW.v --top UNIT [--depth N] [--registers]

A miter (formal/mutation.py's) drives both versions with the same inputs,
resets both in the first clock (the ``--reset`` port, active low) and
asserts at every later clock that every output is the same.  With
``--registers`` it also asserts that the registers both versions have under
the same name and width hold the same value: a stronger claim, for a change
that keeps the registers (splitting processes, renaming logic), and one that
lets the k-induction close at a small depth.

It first tries a k-induction of ``--depth`` steps (SymbiYosys ``prove``):
PASS is equivalence for every run from reset.  If the induction does not
close, a bounded check of ``--bmc-depth`` clocks says how far the two agree
at least; a counterexample (the two differ) ends the run with its trace.
Exit status 0 only for an unbounded proof, 2 for a bounded one, 1 when the
versions differ or a run failed.
"""
import argparse
import json
import shutil
import sys
from dataclasses import dataclass
from pathlib import Path

from formal.mutation import miter_text, ports, yosys
from formal.sby import Result, Task, run, tools_available
from rtl.convert import BUILD_DIR

# yosys cell types whose output is a register after `prep`
REGISTER_CELLS = ("$dff", "$adff", "$sdff", "$dffe", "$adffe", "$sdffe", "$sdffce", "$dffsr", "$dffsre",
                  "$aldff", "$aldffe")
NEW_SUFFIX = "_new"


@dataclass
class Verdict:
    status: str          # "equivalent", "bounded", "different", "error"
    proof: Result        # the k-induction
    bounded: Result = None
    compared: tuple = ()  # what the miter compares: outputs, then registers

    @property
    def result(self):
        return self.bounded or self.proof

    def text(self):
        outputs = sum(1 for kind, _ in self.compared if kind == "output")
        registers = len(self.compared) - outputs
        what = f"{outputs} outputs" + (f" and {registers} registers" if registers else "")
        if self.status == "equivalent":
            return (f"equivalent: {what} equal at every clock after reset "
                    f"(k-induction, depth {self.proof.task.depth}, unbounded; {self.proof.seconds:.0f} s)")
        if self.status == "bounded":
            return (f"equal for {self.bounded.task.depth} clocks after reset ({what}; bounded check, "
                    f"{self.bounded.seconds:.0f} s); the k-induction of depth {self.proof.task.depth} "
                    f"did not close ({self.proof.status}, {self.proof.seconds:.0f} s)")
        if self.status == "different":
            result = self.result
            return (f"different: {', '.join(sorted(set(result.failed)))} at step {result.step}; "
                    f"trace {result.trace}")
        return f"error: {self.result.status}\n{self.result.log[-3000:]}"


def register_widths(work, unit_file, top):
    """{name: width} of the registers of ``top`` in ``unit_file`` (a copy in ``work``)."""
    yosys(f"read_verilog -formal {Path(unit_file).name}; prep -top {top}; write_json registers.json", work)
    module = json.loads((work / "registers.json").read_text())["modules"][top]
    names = {}
    for netname, net in module["netnames"].items():
        if not net.get("hide_name"):
            names.setdefault(tuple(net["bits"]), netname)
    found = {}
    for cell in module["cells"].values():
        if cell["type"] in REGISTER_CELLS:
            bits = tuple(cell["connections"]["Q"])
            if bits in names:
                found[names[bits]] = len(bits)
    return found


def prepare(old, new, top, work):
    """Copies of both versions in ``work``: ``<top>.v`` (module ``top``) and
    ``<top>_new.v`` (module ``<top>_new``); their ports, the same for both."""
    for folder in ("old", "new"):
        (work / folder).mkdir(parents=True, exist_ok=True)
    shutil.copyfile(old, work / "old" / f"{top}.v")
    shutil.copyfile(new, work / "new" / f"{top}.v")
    yosys(f"read_verilog -formal {top}.v; prep -flatten -top {top}; rename {top} {top}{NEW_SUFFIX}; "
          f"write_verilog -noattr ../{top}{NEW_SUFFIX}.v", work / "new")
    shutil.copyfile(old, work / f"{top}.v")
    old_ports, new_ports = ports(work / "old", work / "old" / f"{top}.v"), ports(work / "new", work / "new" / f"{top}.v")
    if sorted(old_ports) != sorted(new_ports):
        raise ValueError(f"the two versions of {top} have different ports: "
                         f"{sorted(set(old_ports) ^ set(new_ports))}")
    return old_ports


def build_miter(old, new, top, work, reset="reset", registers=False):
    """The miter's files and yosys script in ``work``; (sources, script, compared)."""
    port_list = prepare(old, new, top, work)
    if reset not in {name for name, direction, _ in port_list if direction == "input"}:
        raise ValueError(f"{top} has no input {reset!r} (--reset names the active-low reset)")
    compared = [("output", name) for name, direction, _ in port_list if direction == "output"]
    script = []
    if registers:
        old_regs = register_widths(work / "old", work / "old" / f"{top}.v", top)
        new_regs = register_widths(work / "new", work / "new" / f"{top}.v", top)
        shared = sorted(name for name, width in old_regs.items()
                        if new_regs.get(name) == width and name not in {p[0] for p in port_list})
        if shared:
            script.append("expose " + " ".join(f"{module}/w:{name}" for module in (top, top + NEW_SUFFIX)
                                               for name in shared))
            port_list = port_list + [(name, "output", old_regs[name]) for name in shared]
            compared += [("register", name) for name in shared]
    (work / "miter.sv").write_text(miter_text(top, port_list, reset=reset, other=top + NEW_SUFFIX))
    script.append("prep -top miter")
    return [work / f"{top}.v", work / f"{top}{NEW_SUFFIX}.v", work / "miter.sv"], script, tuple(compared)


def check(old, new, top, depth=4, bmc_depth=30, reset="reset", registers=False, work=None,
          timeout=3600):
    """The ``Verdict`` on ``old`` and ``new`` (Verilog files of unit ``top``)."""
    work = Path(work or BUILD_DIR / "formal" / "equivalence" / top)
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    sources, script, compared = build_miter(Path(old), Path(new), top, work, reset, registers)

    def task(mode, steps):
        made = Task(name=f"{top}_{mode}", mode=mode, depth=steps, top="miter", sources=sources, script=script)
        made.timeout = timeout
        return made

    proof = run(task("prove", depth), work)
    if proof.passed:
        return Verdict("equivalent", proof, compared=compared)
    if proof.status == "FAIL" and proof.failed:
        return Verdict("different", proof, compared=compared)
    bounded = run(task("bmc", bmc_depth), work)
    if bounded.passed:
        return Verdict("bounded", proof, bounded, compared)
    return Verdict("different" if bounded.failed else "error", proof, bounded, compared)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m formal.equivalence", description=__doc__.split("\n\n")[0])
    parser.add_argument("old", type=Path, help="the unit's Verilog before the change")
    parser.add_argument("new", type=Path, help="the unit's Verilog after it")
    parser.add_argument("--top", required=True, help="the unit's module name (the same in both files)")
    parser.add_argument("--depth", type=int, default=4, help="k of the k-induction (default 4)")
    parser.add_argument("--bmc-depth", type=int, default=30,
                        help="clocks of the bounded check when the induction does not close (default 30)")
    parser.add_argument("--reset", default="reset", help="the active-low reset input (default reset)")
    parser.add_argument("--registers", action="store_true",
                        help="also compare the registers both versions have under one name and width")
    parser.add_argument("--timeout", type=int, default=3600, help="seconds each run may take (default 3600)")
    args = parser.parse_args(argv)
    for path in (args.old, args.new):
        if not path.is_file():
            parser.error(f"no file {path}")
    if args.depth < 1 or args.bmc_depth < 1:
        parser.error("--depth and --bmc-depth must be at least 1")
    missing = tools_available()
    if missing:
        parser.error(missing)
    try:
        verdict = check(args.old, args.new, args.top, args.depth, args.bmc_depth, args.reset, args.registers,
                        timeout=args.timeout)
    except (ValueError, RuntimeError) as error:
        print(f"python -m formal.equivalence: {error}", file=sys.stderr)
        return 1
    print(f"{args.top}: {verdict.text()}")
    return {"equivalent": 0, "bounded": 2}.get(verdict.status, 1)


if __name__ == "__main__":
    sys.exit(main())
