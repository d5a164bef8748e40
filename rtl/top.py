"""Entry point: ``python -m rtl.top --convert`` writes the card's Verilog into ``gen/``.

Every convertible unit is listed in ``UNITS``: its module name, the function
that builds its ports, and the command-line parameters it takes.  The files
written are byte-stable (MyHDL's date line is dropped) so that a test can tell
when ``gen/`` is stale.
"""
import argparse
import importlib
import inspect
import os
import subprocess
import sys
import tempfile
import warnings
from pathlib import Path

from myhdl import Signal, ToVerilogWarning, block

from rtl import instructions, registers
from rtl.card import card, slave_params
from rtl.dda_build import COORD_WIDTH, DEFAULT_VARIANTS, parse_variants, variants_text
from rtl.interfaces import MotorPins, PciBus, PciPins, card_reset
from rtl.pci_pads import pci_pads

GEN_DIR = Path(__file__).resolve().parent.parent / "gen"

def integer(text):
    """A command-line integer, decimal or with a 0x / 0o / 0b prefix."""
    return int(text, 0)


# Parameter name -> (type, default, help).  Each unit takes a subset.
PARAMETERS = {
    "coord_width": (int, COORD_WIDTH, "signed coordinate width of the DDA (bits)"),
    "variants": (parse_variants, DEFAULT_VARIANTS,
                 "DDA step rules built in: names joined by '+' (traditional, weighted, improved, precise), "
                 "or 'all'; lines are always there"),
    "vendor_id": (integer, 0x1234, "PCI Vendor ID (placeholder: use your own)"),
    "device_id": (integer, 0xDDA0, "PCI Device ID"),
    "revision_id": (integer, 0x01, "PCI Revision ID"),
    "class_code": (integer, 0x088000, "PCI class code (24 bits)"),
    "subsystem_vendor_id": (integer, 0x1234, "PCI Subsystem Vendor ID"),
    "subsystem_id": (integer, 0x0001, "PCI Subsystem ID"),
    "io_bar_bits": (int, 6, "BAR0 (I/O) size of the stand-alone pci_slave unit is 2**bits bytes (2..8); the card sizes it from its register map"),
    "mem_bar_bits": (int, 12, "BAR1 (memory) size of the stand-alone pci_slave unit is 2**bits bytes (4..24)"),
    "fifo_depth": (int, 512, "data FIFO depth in 32-bit words (a power of two)"),
}

# Unit (module in rtl/ and block name) -> the parameters it takes.
UNITS = {
    "dda_arc": ("coord_width", "variants"),
    "pci_slave": ("vendor_id", "device_id", "revision_id", "class_code", "subsystem_vendor_id",
                  "subsystem_id", "io_bar_bits", "mem_bar_bits"),
    "regs_fifo": ("fifo_depth", "coord_width"),
    "card": ("vendor_id", "device_id", "revision_id", "class_code", "subsystem_vendor_id",
             "subsystem_id", "fifo_depth", "coord_width", "variants"),
    "top": ("vendor_id", "device_id", "revision_id", "class_code", "subsystem_vendor_id",
            "subsystem_id", "fifo_depth", "coord_width", "variants"),
}


C_HEADER = "dda_card.h"


@block
def top(clock, reset, pci_pins, motor, *, fifo_depth=512, coord_width=COORD_WIDTH, variants=DEFAULT_VARIANTS,
        io_registers=True, **ids):
    """The card as synthesised: PCI pads (the only tri-states) around the card.

    Ports: ``clock`` PCI CLK, ``reset`` RST# (``card_reset()``), ``pci_pins``
    (``PciPins``: AD, C/BE#, PAR, FRAME#, IRDY#, TRDY#, DEVSEL#, STOP#, IDSEL,
    PERR#, SERR#, INTA# as on the bus), ``motor`` (``MotorPins``: STEP/DIR).
    Parameters: ``fifo_depth``, ``coord_width``, ``variants`` (the DDA's), the PCI IDs, and
    ``io_registers`` (True: the PCI boundary flip-flops are the iCE40 I/O
    cells' registers, ``rtl/pci_pads.py``; the target is told so).
    ``rtl/card.py`` is the same card with split ports, for benches.

        pins <-> pci_pads <-> card (pci_slave, regs_fifo, dda_arc) --> STEP/DIR
    """
    pci = PciBus()
    pads = pci_pads(clock, pci_pins, pci, io_registers=io_registers)
    core = card(clock, reset, pci, motor, fifo_depth=fifo_depth, coord_width=coord_width, variants=variants,
                io_registers=io_registers, **ids)
    return pads, core


def top_ports(fifo_depth=512, coord_width=COORD_WIDTH, variants=DEFAULT_VARIANTS, io_registers=True, **ids):
    """Fresh ports of ``top`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), pci_pins=PciPins(), motor=MotorPins())


def write_c_header(out_dir=GEN_DIR, **values):
    """Write the C header of the build ``values`` (converter parameters, defaults
    for the rest) describe: PCI identity and BAR sizes of the card, register
    map, command set and command builders; return its path."""
    settings = {name: values.get(name, spec[1]) for name, spec in PARAMETERS.items()}
    bars = slave_params()
    digits = {"revision_id": 2, "class_code": 6}
    identity = [f"#define DDA_PCI_{name.upper()} 0x{settings[name]:0{digits.get(name, 4)}X}u"
                for name in UNITS["card"] if name.endswith("_id") or name == "class_code"]
    identity += [f"#define DDA_BAR0_SIZE {1 << bars['io_bar_bits']}u /* I/O: function registers */",
                 f"#define DDA_BAR1_SIZE {1 << bars['mem_bar_bits']}u /* memory: the command FIFO window */",
                 f"#define DDA_FIFO_DEPTH {settings['fifo_depth']}u /* words */", ""]
    target = Path(out_dir) / C_HEADER
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(registers.c_header(extra="\n".join(identity) + instructions.c_defines() + "\n"
                                         + instructions.c_builders()))
    return target


def unit_block(unit, params):
    """The block instance of ``unit`` with fresh ports, ready to convert.

    The ports are built from every parameter of the unit; the block gets those
    its signature names (the DDA reads its own from the port it receives).
    """
    module = importlib.import_module(f"rtl.{unit}")
    ports = getattr(module, f"{unit}_ports")(**params)
    block_function = getattr(module, unit)
    accepted = inspect.signature(block_function.func).parameters
    return block_function(**ports, **{name: value for name, value in params.items() if name in accepted})


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
    target.write_text(_strip_run_details(text))
    return target


def convert_unit(unit, params, out_dir):
    """Elaborate and convert one unit into ``out_dir``; return the path written."""
    return convert_block(unit, unit_block(unit, params), out_dir)


def convert_all(out_dir=GEN_DIR, **values):
    """Convert every unit with ``values`` (defaults for the rest); list the paths."""
    unknown = set(values) - set(PARAMETERS)
    if unknown:
        raise ValueError(f"unknown parameters: {sorted(unknown)}")
    settings = {name: values.get(name, spec[1]) for name, spec in PARAMETERS.items()}
    # Elaborate every unit first: a bad value fails before anything is written.
    blocks = {unit: unit_block(unit, {n: settings[n] for n in names}) for unit, names in UNITS.items()}
    return [convert_block(unit, instance, out_dir) for unit, instance in blocks.items()]


class _Parser(argparse.ArgumentParser):
    """Reports a bad command line in one line (no usage block) and exits 2."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message}\n")


def _parser():
    parser = _Parser(
        prog="python -m rtl.top",
        description="Convert the PCI DDA motion-control card to Verilog.",
    )
    parser.add_argument("--convert", action="store_true", help="write the Verilog of every unit")
    parser.add_argument("--out", type=Path, default=GEN_DIR, help="output folder (default: gen/)")
    for name, (kind, default, text) in PARAMETERS.items():
        shown = variants_text(default) if name == "variants" else default
        parser.add_argument(f"--{name.replace('_', '-')}", type=kind, default=default,
                            help=f"{text} (default: {shown})")
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
    if os.environ.get("PYTHONHASHSEED") != "0":
        return _rerun_with_fixed_hash_seed(argv)
    # MyHDL's notes on unread trace-only signals would bury the result;
    # tests/test_lint.py runs verilator -Wall on the output, which is the check that counts.
    warnings.simplefilter("ignore", ToVerilogWarning)
    parser = _parser()
    args = parser.parse_args(argv)
    if not args.convert:
        parser.error("nothing to do: pass --convert")
    values = {name: getattr(args, name) for name in PARAMETERS}
    try:
        written = convert_all(args.out, **values)
    except ValueError as error:
        parser.exit(2, f"{parser.prog}: error: {error}\n")
    written.append(write_c_header(args.out, **values))
    for path in written:
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
