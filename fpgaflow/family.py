"""What the flow needs to know about an FPGA family: one ``Family`` per device it targets."""
from dataclasses import dataclass, field
from pathlib import Path

from fpgaflow.tools import SynthError
from rtl.convert import ROOT

CONSTRAINTS = ROOT / "constraints"


@dataclass(frozen=True)
class Family:
    """A device and how yosys and nextpnr treat it.

    ``synth`` is the yosys command (``{top}``, ``{json}`` filled in);
    ``nextpnr`` the place-and-route program and ``device`` its device
    arguments; ``constraints`` the pin file of the whole top and
    ``constraint_flag`` / ``unconstrained_flag`` how nextpnr takes it.
    ``utilisation`` names nextpnr's resource keys for logic, block RAM and
    I/O (flip-flops are counted in the netlist).  ``ff_types`` and
    ``io_types`` are the netlist's flip-flop and pad cell types, ``io_ports``
    a pad's (from the pin, to the pin, output enable) ports, ``lut_outputs``
    and ``carry_outputs`` the SDF arc ends that count as a LUT level and a
    carry step, ``placed_outputs`` the outputs of a placed cell that carry a
    register's name, ``pad_figures`` data sheet delays that nextpnr's model
    leaves out (``at_the_pins``), ``bitstream`` nextpnr's option and file
    suffix for the configuration it writes as text.  In nextpnr's packed
    netlist, ``placed_logic`` is the logic cell type, ``buffers`` the global
    buffers, ``pad_pin_port`` a pad's pin.
    """

    key: str
    name: str
    synth: str
    nextpnr: str
    device: tuple
    constraints: Path
    constraint_flag: str
    unconstrained_flag: str
    package_ios: int
    utilisation: dict
    ff_types: tuple
    io_types: tuple
    io_ports: tuple
    lut_outputs: frozenset
    carry_outputs: frozenset
    placed_outputs: tuple
    lut_inputs: frozenset
    logic_label: str = "logic cells"
    ram_label: str = "block RAMs"
    pad_figures: dict = field(default_factory=dict)
    extra_nextpnr: tuple = field(default_factory=tuple)
    bitstream: tuple = ("--asc", "asc")
    placed_logic: str = "ICESTORM_LC"
    buffers: tuple = ("SB_GB",)
    pad_pin_port: str = "PACKAGE_PIN"

    def at_the_pins(self, direction, figure):
        """A pin figure of nextpnr's (ns or "io-reg") as it compares with a budget at the ball.

        Without data sheet figures for the pads (``pad_figures``) that is
        nextpnr's own figure; see the family's override.
        """
        return figure

    def is_ff(self, cell_type):
        """True for the netlist's flip-flop cells."""
        return cell_type.startswith(self.ff_types)

    def is_placed_logic(self, cell):
        """True for a logic cell of nextpnr's packed netlist."""
        return cell["type"] == self.placed_logic

    def is_placed_register(self, cell):
        """True for a cell of nextpnr's packed netlist that holds a fabric flip-flop."""
        return self.is_placed_logic(cell) and _set(cell["parameters"].get("DFF_ENABLE", "0"))

    def pad_pin(self, name, cell, net_names):
        """The pin (port bit) of a pad cell of nextpnr's packed netlist."""
        if "$" in name and cell["type"] in self.io_types:
            return name.rsplit("$", 1)[0]
        bits = cell["connections"].get(self.pad_pin_port) or [None]
        return net_names.get(bits[0], name)

    def pins(self, path=None):
        """``{port bit name: ball}`` of a constraint file (the family's own by default)."""
        return self._parse_pins(Path(path or self.constraints).read_text())

    def _parse_pins(self, text):
        raise NotImplementedError(self.key)

    def top_constraints(self, ports, work):
        """The pin file of a top with ``ports`` (port bit names): the family's own, with each
        supplementary file ``<name>_<part><suffix>`` beside it whose ports the top has added
        (``_encoders``: a build with encoders; ``_axis_z`` .. ``_axis_c``: a build with that axis)."""
        parts = [extra for extra in sorted(self.constraints.parent.glob(
                     f"{self.constraints.stem}_*{self.constraints.suffix}"))
                 if set(self._parse_pins(extra.read_text())) <= ports]
        if not parts:
            return self.constraints
        stems = "_".join(extra.stem[len(self.constraints.stem) + 1:] for extra in parts)
        path = work / f"top_{stems}{self.constraints.suffix}"
        path.write_text(self.constraints.read_text() + "".join(extra.read_text() for extra in parts))
        return path

    def unit_constraints(self, clock_port, work, unit):
        """A constraint file with only ``clock_port`` on the whole top's clock ball."""
        ball = self.pins().get(clock_port)
        if ball is None:
            raise SynthError(f"{self.constraints} has no pin for '{clock_port}'")
        path = work / f"{unit}{self.constraints.suffix}"
        path.write_text(self.pin_line(clock_port, ball))
        return path

    def pin_line(self, port, ball):
        """The constraint file's line that puts ``port`` on ``ball``."""
        raise NotImplementedError(self.key)

    def prepare_netlist(self, netlist, unit, clock_port):
        """Changes to yosys's netlist before nextpnr reads it (none by default)."""

    def check_sources(self, sources):
        """SynthError if the Verilog cannot go to this family (nothing to check by default)."""

    def io_cells(self, module, names):
        """``{pad instance: (pin, (input registered, output registered, enable registered))}``
        for the pads yosys instantiated; nextpnr's own pads are plain."""
        return {}


def _set(value):
    """A nextpnr JSON parameter (an integer or a string of binary digits) as a truth value."""
    text = str(value)
    return int(text, 2) != 0 if text and set(text) <= {"0", "1"} else bool(value)
