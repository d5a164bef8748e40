"""Entry point: ``python -m rtl.top --convert`` writes the card's Verilog into ``gen/``.

Every convertible unit is listed in ``UNITS``: its module name, the function
that builds its ports, and the command-line parameters it takes.  The files
written are byte-stable (MyHDL's date line is dropped) so that a test can tell
when ``gen/`` is stale.
"""
import argparse
import importlib
import sys
import tempfile
from pathlib import Path

GEN_DIR = Path(__file__).resolve().parent.parent / "gen"

# Parameter name -> (type, default, help).  Each unit takes a subset.
PARAMETERS = {
    "coord_width": (int, 24, "signed coordinate width of the DDA (bits)"),
}

# Unit (module in rtl/ and block name) -> the parameters it takes.
UNITS = {
    "dda_arc": ("coord_width",),
}


def unit_block(unit, params):
    """The block instance of ``unit`` with fresh ports, ready to convert."""
    module = importlib.import_module(f"rtl.{unit}")
    ports = getattr(module, f"{unit}_ports")(**params)
    return getattr(module, unit)(**ports, **params)


def _strip_date(text):
    return "".join(line for line in text.splitlines(keepends=True) if not line.startswith("// Date:"))


def convert_unit(unit, params, out_dir):
    """Convert one unit into ``out_dir``; return the path written."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        unit_block(unit, params).convert(hdl="Verilog", path=work, name=unit, testbench=False)
        text = (Path(work) / f"{unit}.v").read_text()
    target = out_dir / f"{unit}.v"
    target.write_text(_strip_date(text))
    return target


def convert_all(out_dir=GEN_DIR, **values):
    """Convert every unit with ``values`` (defaults for the rest); list the paths."""
    unknown = set(values) - set(PARAMETERS)
    if unknown:
        raise ValueError(f"unknown parameters: {sorted(unknown)}")
    settings = {name: values.get(name, spec[1]) for name, spec in PARAMETERS.items()}
    written = []
    for unit, names in UNITS.items():
        written.append(convert_unit(unit, {n: settings[n] for n in names}, out_dir))
    return written


def _parser():
    parser = argparse.ArgumentParser(
        prog="python -m rtl.top",
        description="Convert the PCI DDA motion-control card to Verilog.",
    )
    parser.add_argument("--convert", action="store_true", help="write the Verilog of every unit")
    parser.add_argument("--out", type=Path, default=GEN_DIR, help="output folder (default: gen/)")
    for name, (kind, default, text) in PARAMETERS.items():
        parser.add_argument(f"--{name.replace('_', '-')}", type=kind, default=default,
                            help=f"{text} (default: {default})")
    return parser


def main(argv=None):
    parser = _parser()
    args = parser.parse_args(argv)
    if not args.convert:
        parser.error("nothing to do: pass --convert")
    values = {name: getattr(args, name) for name in PARAMETERS}
    try:
        written = convert_all(args.out, **values)
    except ValueError as error:
        parser.exit(2, f"{parser.prog}: error: {error}\n")
    for path in written:
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
