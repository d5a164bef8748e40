"""``python -m formal``: run every proof and print a table.

    python -m formal                    # every group on gen/
    python -m formal --gen DIR          # the same properties on the Verilog in DIR
    python -m formal --group pci_protocol --group pci_covers
    python -m formal --fast             # the groups of the default test suite
    python -m formal --list             # the groups and what they prove

The exit status is 0 only when every proof passed (and every cover was
reached).  Work files (the .sby files, logs, counterexample traces) go to
``build/formal/``; ``python -m formal.trace TRACE.vcd SIGNAL ...`` prints a
trace as a table.
"""
import argparse
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from formal import groups as catalogue
from formal.sby import run, tools_available
from rtl.convert import BUILD_DIR, GEN_DIR

WORK_DIR = BUILD_DIR / "formal"


def depth_text(result):
    task = result.task
    if task.mode == "prove":
        return "unbounded" if result.passed else f"k={task.depth}"
    return f"{task.depth}"


def engine_text(result):
    task = result.task
    kind = {"prove": "k-induction", "bmc": "bmc", "cover": "cover"}[task.mode]
    return f"smtbmc yices {kind}"


def outcome_text(result):
    if result.task.mode == "cover":
        reached = len(result.covered)
        total = reached + len(result.missed)
        return f"{result.status} {reached}/{total} covers" if total else result.status
    if result.failed:
        step = f" at step {result.step}" if result.step is not None else ""
        return f"{result.status}: {', '.join(sorted(set(result.failed)))}{step}"
    return result.status


def print_table(results, out=sys.stdout):
    rows = [("group", "engine", "depth", "result", "seconds")]
    for result in results:
        rows.append((result.task.name, engine_text(result), depth_text(result), outcome_text(result),
                     f"{result.seconds:.0f}"))
    widths = [max(len(row[i]) for row in rows) for i in range(4)]
    for row in rows:
        print("  ".join(cell.ljust(width) for cell, width in zip(row[:4], widths)) + "  " + row[4].rjust(7),
              file=out)
    for result in results:
        if result.trace is not None:
            print(f"{result.task.name}: trace {result.trace}", file=out)
        if result.task.mode == "cover" and result.missed:
            print(f"{result.task.name}: not reached: {', '.join(result.missed)}", file=out)


def run_groups(chosen, gen_dir, work_dir=WORK_DIR, jobs=1):
    tasks = [group.task(gen_dir) for group in chosen]
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        return list(pool.map(lambda task: run(task, work_dir), tasks))


def _parser():
    parser = argparse.ArgumentParser(prog="python -m formal", description=__doc__.split("\n\n")[0])
    parser.add_argument("--gen", type=Path, default=GEN_DIR,
                        help="folder with the generated Verilog to prove (default: gen/)")
    parser.add_argument("--group", action="append", default=[], help="run only this group (repeatable)")
    parser.add_argument("--fast", action="store_true", help="only the groups of the default test suite")
    parser.add_argument("--list", action="store_true", help="list the groups and exit")
    parser.add_argument("--jobs", type=int, default=1, help="proofs run at once (default 1)")
    parser.add_argument("--work", type=Path, default=WORK_DIR, help="work folder (default build/formal)")
    return parser


def main(argv=None):
    args = _parser().parse_args(argv)
    if args.list:
        for group in catalogue.GROUPS:
            depth = "k-induction" if group.mode == "prove" else f"{group.mode} {group.depth}"
            suite = "default" if group.fast else "slow"
            print(f"{group.name:16} {group.unit + '.v':14} {depth:12} {suite:8} {group.text}")
        return 0
    try:
        chosen = [catalogue.group(name) for name in args.group] or list(catalogue.GROUPS)
    except ValueError as error:
        print(f"python -m formal: error: {error}", file=sys.stderr)
        return 2
    if args.fast:
        chosen = [group for group in chosen if group.fast]
    missing = [str(path) for group in chosen for path in group.sources(args.gen)[:1] if not path.exists()]
    if missing:
        print(f"python -m formal: error: missing {', '.join(sorted(set(missing)))}", file=sys.stderr)
        return 2
    problem = tools_available()
    if problem:
        print(f"python -m formal: error: {problem}", file=sys.stderr)
        return 2
    results = run_groups(chosen, args.gen, args.work, args.jobs)
    print_table(results)
    return 0 if all(result.passed for result in results) else 1


if __name__ == "__main__":
    sys.exit(main())
