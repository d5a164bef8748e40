"""The converter: ``python -m rtl.top --convert`` writes the card's Verilog into ``gen/``.

This module owns the project's output folders: ``gen/`` (``GEN_DIR``: the
default build, written only here) and ``build/`` (``BUILD_DIR``: scratch for
other builds, simulations and flows, ignored by git; ``build_dir``).

Every convertible unit is listed in ``UNITS`` with the build parameters it
takes from the command line (``models/parameters.py``, the one table of
defaults and ranges); it is converted from one ``Build`` record, those
values and the unit's defaults for the rest.  The command line checks every
value before anything is converted, converts into a temporary folder beside
the output and moves it into place whole, so a failed run leaves the
previous output as it was.  The files written are
byte-stable (MyHDL's date line is dropped) so that a test can tell when
``gen/`` is stale.

``gen/`` holds the default build: the units and the card as generic
Verilog, the top for iCE40 (``device``'s default for the top); other builds
go to ``--out``.
"""
import argparse
import importlib
import os
import shutil
import subprocess
import sys
import tempfile
import warnings
from collections import namedtuple
from pathlib import Path

from myhdl import ToVerilogWarning

from models import card_socket, instruction_c, parameters, register_docs
from models.dda_build import DDA_MIN_WIDTH, DEFAULT_VARIANTS
from models.parameters import DEVICE, PARAMETERS, PCI_IDS, Build, ParameterError
from models.registers import STOP_REASONS
from rtl.card import slave_build
from rtl.pci.pci_slave_build import alias_bar_bits

ROOT = Path(__file__).resolve().parent.parent
GEN_DIR = ROOT / "gen"
BUILD_DIR = ROOT / "build"
C_HEADER = "dda_card.h"
PROG = "python -m rtl.top"

# The one place that says which build parameters each unit converted alone
# takes from the command line (``names``; the others keep the unit's defaults:
# the card sizes its BARs from its register map, so --io-bar-bits and
# --mem-bar-bits shape the stand-alone pci_slave only), and which of them its
# ports factory takes as plain keywords (``port_names``: they shape its
# ports).  The block takes the whole ``Build`` as ``build=``, but for a unit
# whose every parameter shapes its ports (dda_arc reads its build from its
# DdaPort).
Unit = namedtuple("Unit", "names port_names")
_CARD = ("fifo_depth", "coord_width", "clock_hz", "variants", "device", "axes", "encoders", *PCI_IDS)
UNITS = {
    "dda_arc": Unit(("coord_width", "variants"), ("coord_width", "variants")),
    "pci_slave": Unit((*PCI_IDS, "io_bar_bits", "mem_bar_bits", "reg_bar_bits", "device"),
                      ("io_bar_bits", "mem_bar_bits", "reg_bar_bits")),
    "regs_fifo": Unit(("fifo_depth", "clock_hz", "device", "coord_width", "variants", "axes", "encoders"),
                      ("coord_width", "variants", "axes", "encoders")),
    "card": Unit(_CARD, ("axes", "encoders")),
    "top": Unit(_CARD, ("axes", "encoders")),
}
# Sub-packages of rtl/ that hold units below the tops (``unit_block`` finds a unit there too).
SUB_PACKAGES = ("pci", "dda", "regs", "machine", "encoder")


def build_dir(*parts):
    """A folder under ``build/`` (ignored by git), created on demand."""
    path = BUILD_DIR.joinpath(*parts)
    path.mkdir(parents=True, exist_ok=True)
    return path


def unit_build(values, unit):
    """The ``Build`` of ``unit``: ``values`` of the parameters it takes where
    given, the unit's defaults for the rest; ParameterError on a bad value
    (device limits too)."""
    parameters.check(values)
    device = DEVICE.default_for(unit)
    try:
        return Build.for_unit(unit, **{name: values[name] for name in UNITS[unit].names if name in values})
    except ParameterError as error:
        if "device" in values or device == DEVICE.default:
            raise
        raise ParameterError(f"{error.problem}; without --device the {unit} is built for {device}",
                             error.parameter) from None


def unit_builds(values):
    """``{unit: Build}`` of every unit for the command line's ``values``."""
    return {unit: unit_build(values, unit) for unit in UNITS}


def write_c_header(out_dir=GEN_DIR, **values):
    """Write the C header of the top built with ``values`` (build parameters,
    the top's defaults for the rest): PCI identity and BAR sizes of the card,
    stop reasons, the simulated card's socket protocol, register map (reset
    values of this build), command set and command builders; return its path."""
    build = unit_build(values, "top")
    bars = slave_build(build)
    identity = [f"#define DDA_PCI_{name.upper()} {PARAMETERS[name].shown(value)}u"
                for name, value in build.view(PCI_IDS).items()]
    identity += [f"#define DDA_BAR0_SIZE {1 << bars.io_bar_bits}u /* I/O: function registers */",
                 f"#define DDA_BAR1_SIZE {1 << bars.mem_bar_bits}u /* memory: the command FIFO window */",
                 f"#define DDA_BAR2_SIZE {1 << alias_bar_bits(bars.io_bar_bits, bars.reg_bar_bits)}u"
                 " /* memory: the function registers at BAR0's offsets, then the per-axis blocks */",
                 f"#define DDA_FIFO_DEPTH {build.fifo_depth}u /* words */", ""]
    identity += [f"#define DDA_STOP_{name} {code}u /* STOP_REASON.REASON */"
                 for code, name in enumerate(STOP_REASONS) if code] + [""]
    identity += ["/* The simulated card's socket protocol (sim/card/card_server.py) */", card_socket.c_defines()]
    target = Path(out_dir) / C_HEADER
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(register_docs.c_header(extra="\n".join(identity) + instruction_c.c_defines() + "\n"
                                         + instruction_c.c_builders(), values=build.as_dict()))
    return target


def _unit_module(unit):
    """The module of ``unit``: ``rtl/<unit>.py`` or ``rtl/<sub-package>/<unit>.py``."""
    for package in ("rtl", *(f"rtl.{sub}" for sub in SUB_PACKAGES)):
        try:
            module = importlib.import_module(f"{package}.{unit}")
        except ModuleNotFoundError as error:
            if error.name != f"{package}.{unit}":
                raise
            continue
        if not hasattr(module, "__path__"):   # not a sub-package of the unit's name (rtl/encoder/ holds encoder.py)
            return module
    raise ValueError(f"no unit named {unit} in rtl/")


def unit_block(unit, values):
    """The block instance of ``unit`` with fresh ports, ready to convert: a
    unit of ``UNITS`` from its ``Build`` (``values``, its defaults for the
    rest), another unit with ``values`` as its keyword parameters."""
    if unit in UNITS:
        return unit_instance(unit, unit_build(values, unit))
    module = _unit_module(unit)
    return getattr(module, unit)(**getattr(module, f"{unit}_ports")(**values), **values)


def unit_instance(unit, build):
    """The block instance of ``unit`` (of ``UNITS``) for ``build``, with fresh ports."""
    module, (names, port_names) = _unit_module(unit), UNITS[unit]
    block_of, ports = getattr(module, unit), getattr(module, f"{unit}_ports")(**build.view(port_names))
    return block_of(**ports) if names == port_names else block_of(**ports, build=build)


def _strip_run_details(text):
    """Drop MyHDL's date and temporary-path lines, which differ on every run."""
    return "".join(line for line in text.splitlines(keepends=True)
                   if not line.startswith(("// Date:", "// File:")))


def convert_block(unit, instance, out_dir):
    """Convert an elaborated unit into ``out_dir``; return the path written."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        instance.convert(hdl="Verilog", path=work, name=unit, testbench=False)
        text = (Path(work) / f"{unit}.v").read_text()
    target = out_dir / f"{unit}.v"
    write_whole(target, _strip_run_details(text))
    return target


def write_whole(path, text):
    """Write ``text`` to ``path`` through a temporary file renamed into place, so a
    reader (another test worker) finds the old file or the new one, never half of one."""
    path = Path(path)
    with tempfile.NamedTemporaryFile("w", dir=path.parent, prefix=f".{path.name}.", delete=False) as staged:
        staged.write(text)
    os.replace(staged.name, path)


def convert_unit(unit, params, out_dir):
    """Elaborate and convert one unit into ``out_dir``; return the path written."""
    return convert_block(unit, unit_block(unit, params), out_dir)


def convert_narrow_dda(out_dir, coord_width=DDA_MIN_WIDTH, variants=DEFAULT_VARIANTS):
    """Write ``dda_arc.v`` of a ``coord_width`` build into ``out_dir`` (not gen/;
    the interpolator alone runs narrower than the card's range); its path."""
    from rtl.dda_arc import dda_arc, dda_arc_ports

    ports = dda_arc_ports(coord_width=coord_width, variants=variants)
    return convert_block("dda_arc", dda_arc(**ports), out_dir)


class OutputError(ValueError):
    """``--out`` names something the converter must not replace."""


def check_output(out_dir):
    """``out_dir`` as a Path if the converter may replace it whole: a folder
    that does not exist yet, or one of Verilog files and C headers only."""
    out_dir = Path(out_dir)
    if out_dir.exists() and not out_dir.is_dir():
        raise OutputError(f"{out_dir} is a file, not a folder")
    if out_dir.is_dir():
        foreign = sorted(path.name for path in out_dir.iterdir()
                         if not (path.is_file() and path.suffix in (".v", ".h")))
        if foreign:
            shown = ", ".join(foreign[:3]) + (", ..." if len(foreign) > 3 else "")
            raise OutputError(f"{out_dir} holds more than Verilog and C headers ({shown}); the whole "
                              "folder is replaced: name a new one")
    for parent in out_dir.resolve().parents:
        if parent.exists():
            if not parent.is_dir():
                raise OutputError(f"{out_dir}: {parent} is a file, not a folder")
            break
    return out_dir


def _set_folder_mode(staged, target):
    """Give ``staged`` (made private by ``mkdtemp``) the mode ``target`` has,
    or the one a new folder gets."""
    if target.is_dir():
        shutil.copymode(target, staged)
        return
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(staged, 0o777 & ~umask)


def _move_into_place(staged, target):
    """Replace the folder ``target`` by ``staged`` (same file system)."""
    if not target.exists():
        os.rename(staged, target)
        return
    old = Path(tempfile.mkdtemp(prefix=f".{target.name}.old.", dir=target.parent))
    os.rename(target, old / target.name)
    try:
        os.rename(staged, target)
    except OSError:
        os.rename(old / target.name, target)
        old.rmdir()
        raise
    shutil.rmtree(old)


def convert_all(out_dir=GEN_DIR, **values):
    """Convert every unit for the build ``values`` (each unit's defaults for
    the rest) into ``out_dir``, replacing it whole; list the paths written.

    Every value is checked and every unit elaborated before anything is
    written; the files go to a temporary folder beside ``out_dir``, which
    replaces ``out_dir`` only once all are written (and is removed if not).
    """
    builds = unit_builds(values)
    out_dir = check_output(out_dir)
    blocks = {unit: unit_instance(unit, builds[unit]) for unit in UNITS}
    out_dir.parent.mkdir(parents=True, exist_ok=True)
    staged = Path(tempfile.mkdtemp(prefix=f".{out_dir.name}.new.", dir=out_dir.parent))
    _set_folder_mode(staged, out_dir)
    try:
        names = [convert_block(unit, instance, staged).name for unit, instance in blocks.items()]
        names.append(write_c_header(staged, **values).name)
        _move_into_place(staged, out_dir)
    finally:
        shutil.rmtree(staged, ignore_errors=True)
    return [out_dir / name for name in names]


class _Parser(argparse.ArgumentParser):
    """Reports a bad command line in one line (no usage block) and exits 2."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message}\n")


def _argument_type(parameter):
    def parse(text):
        try:
            return parameter.parse(text)
        except ParameterError as error:
            raise argparse.ArgumentTypeError(error.problem) from None

    return parse


def _parser():
    parser = _Parser(
        prog=PROG, allow_abbrev=False,
        description="Convert the PCI DDA motion-control card to Verilog (and its C header). "
                    "Every value is checked before anything is written; the output folder is "
                    "replaced whole, or left as it was if the conversion fails.  Integers are decimal or "
                    "0x-, 0o-, 0b-prefixed.",
    )
    parser.add_argument("--convert", action="store_true", help="write the Verilog of every unit")
    parser.add_argument("--out", type=Path, default=GEN_DIR,
                        help="output folder, replaced whole: a new one, or one with only Verilog and "
                             "C headers in it (default: gen/)")
    for parameter in PARAMETERS.values():
        text = parameter.describe()
        if parameter.flag:
            parser.add_argument(parameter.option, action="store_const", const=1, default=None,
                                help=text.replace("%", "%%"))
            continue
        parser.add_argument(parameter.option, type=_argument_type(parameter), default=None,
                            metavar="VALUE" if parameter.choices is None else "{" + ",".join(parameter.choices) + "}",
                            help=text.replace("%", "%%"))
    return parser


def _rerun_with_fixed_hash_seed(argv):
    """Run the converter again with PYTHONHASHSEED=0; return its exit code.

    MyHDL writes sensitivity lists and reset blocks in set order, which follows
    Python's string hashing: a fixed seed makes ``gen/`` byte-stable.
    """
    env = dict(os.environ, PYTHONHASHSEED="0")
    return subprocess.run([sys.executable, "-m", "rtl.top", *argv], env=env).returncode


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = _parser()
    args = parser.parse_args(argv)
    if not args.convert:
        parser.error("nothing to do: pass --convert")
    values = {name: getattr(args, name) for name in PARAMETERS if getattr(args, name) is not None}
    try:
        unit_builds(values)
        check_output(args.out)
    except ParameterError as error:
        parser.error(f"argument {error.parameter.option}: {error.problem}" if error.parameter else str(error))
    except OutputError as error:
        parser.error(f"argument --out: {error}")
    if os.environ.get("PYTHONHASHSEED") != "0":
        return _rerun_with_fixed_hash_seed(argv)
    # MyHDL's notes on unread trace-only signals would bury the result;
    # tests/rtl/test_lint.py runs verilator -Wall on the output, which is the check that counts.
    warnings.simplefilter("ignore", ToVerilogWarning)
    try:
        written = convert_all(args.out, **values)
    except (ValueError, OSError) as error:
        parser.exit(2, f"{parser.prog}: error: {error}\n")
    for path in written:
        print(f"wrote {path}")
    return 0

