"""A Verilog PCI target on the bench's bus, in Icarus: floating lines and an X/Z detector.

``VerilogTarget`` describes any target by its files, top module, pin map,
defines and include folders.  ``pci_target_cosimulation`` wraps it in a
generated Verilog module that

* feeds every line the target reads from the MyHDL bus model.  In float
  mode (``floating=True``, the default for Verilog runs) an AD, C/BE# or PAR
  line nobody drives reaches the target as ``z``, as on a real bus (MyHDL
  has no Z on plain Signals: the bus model says per line whether it is
  driven, the wrapper makes the ``z``); IDSEL is AD[``idsel_bit``] and
  floats with it;
* hands back the target's drive per line as ``<line>_out`` / ``<line>_oe``
  (an agent of the bus model), from split out/oe ports or read off a
  tri-state port's net;
* watches every line while the target drives it: an output enable that is
  X or Z, an X or Z on an enabled line, or a multi-bit line driven in part
  sets that line's bit of ``unknown``; the bus model hands it to the monitor
  in each sample, which reports rule 19 with the clock (rule 20 for X/Z
  that the host takes as read data);
* hands the target's further outputs named in ``outputs`` to MyHDL as they are.

Pin map: ``{line: port}`` for a tri-state (``inout``) port, or ``{line:
(in, out, oe)}`` for split ports (any of them None: the target neither reads
nor drives that way).  An enable is one bit for the whole line or one bit
per bit of the line (32 on AD, 4 on C/BE#); any other width, or a port whose
width is not the line's, is refused.  A name starting with ``~`` is active
low (an enable ``~ad_oe_n``), also for ``reset`` (RST# itself is active low:
``reset="rst_n"``; an active-high reset input is ``"~rst"``).  Lines:
``sim.pci.lines.LINE_WIDTHS``.  The ports are read as Icarus elaborates the
target (``sim.backends.icarus.elaborated_ports``).
"""
from dataclasses import dataclass, field
from pathlib import Path

from myhdl import Signal, intbv

from sim.backends.icarus import (CosimError, elaborated_ports, icarus_cosimulation, port_directions, port_width,
                                 read_verilog)
from sim.pci.lines import FLOATING, LINE_WIDTHS, PULLED_UP

HOST_ONLY = ("cbe", "frame", "irdy")   # a target reads these, never drives them


@dataclass
class VerilogTarget:
    """A PCI target written in Verilog: ``files``, ``top`` module, ``pins``
    (the pin map above), ``clock`` and ``reset`` port names, ``idsel`` port
    (None: the target has none), ``defines`` (names or a dict),
    ``include_dirs``, ``libraries`` (files compiled only where instantiated),
    ``ties`` (``{port: value}`` for other inputs), ``outputs`` (names of
    other outputs the bench offers as Signals, ``PciBench.outputs``; the
    rest are left open)."""

    files: list
    top: str
    pins: dict
    clock: str = "clk"
    reset: str = "rst_n"
    idsel: str = "idsel"
    defines: object = ()
    include_dirs: list = field(default_factory=list)
    libraries: list = field(default_factory=list)
    ties: dict = field(default_factory=dict)
    outputs: list = field(default_factory=list)

    def __post_init__(self):
        unknown = set(self.pins) - set(LINE_WIDTHS)
        if unknown:
            raise ValueError(f"pin map names lines PCI has not: {sorted(unknown)}")
        for line, pin in self.pins.items():
            if not isinstance(pin, str) and (not isinstance(pin, tuple) or len(pin) != 3):
                raise ValueError(f"pin of {line} must be a port name or (in, out, oe), not {pin!r}")

    def split(self, line):
        pin = self.pins.get(line)
        return pin if isinstance(pin, tuple) else None

    def drives(self, line):
        """Whether the target may drive ``line`` (a target only reads C/BE#,
        FRAME#, IRDY#)."""
        pin = self.pins.get(line)
        if isinstance(pin, str):
            return line not in HOST_ONLY
        return pin is not None and pin[1] is not None

    def ports(self):
        """``[(direction, range, name)]`` of the top module, as Icarus
        elaborates it with these defines, include folders and libraries."""
        if not hasattr(self, "_ports"):
            self._ports = elaborated_ports(self.files, self.top, self.libraries, self.defines,
                                           self.include_dirs)
        return self._ports

    def output_widths(self):
        """``{name: bits}`` of the ``outputs`` the bench watches."""
        declared = {name: (direction, port_width(rng)) for direction, rng, name in self.ports()}
        widths = {}
        for name in self.outputs:
            if name not in declared or declared[name][0] != "output":
                raise CosimError(f"{self.top} has no output {name}")
            widths[name] = declared[name][1]
        return widths


class TargetAgent:
    """The MyHDL side of a wrapped target, an agent of the bus model:
    ``<line>_out`` / ``<line>_oe`` for every line it drives, ``<line>_in``
    and ``idsel_in`` (fed by the bus model, unused: the wrapper reads the
    resolved lines)."""

    def __init__(self, driven):
        for line, width in LINE_WIDTHS.items():
            idle = 1 if line in PULLED_UP else 0
            setattr(self, f"{line}_in", _signal(width, idle))
            if line in driven:
                setattr(self, f"{line}_out", _signal(width, idle))
                setattr(self, f"{line}_oe", Signal(bool(0)))
        self.idsel_in = Signal(bool(0))


def _signal(width, value):
    return Signal(bool(value)) if width == 1 else Signal(intbv(value)[width:])


def _port(name):
    """(port, Verilog expression of its active-high value)."""
    return (name[1:], f"!{name[1:]}") if name.startswith("~") else (name, name)


def _range(width):
    return f"[{width - 1}:0] " if width > 1 else ""


def _bits(net, width):
    return [f"{net}[{bit}]" if width > 1 else net for bit in range(width)]


WRAPPER = "pci_target_wrapper"


def wrapper_verilog(target, declared, idsel_bit, floating, others=()):
    """Text of the wrapper module; ``others``: names of further ports of the
    target that go to MyHDL as they are (a back-end bus, outputs to watch)."""
    widths = {name: port_width(rng) for _, rng, name in declared}
    directions = {name: (direction, rng) for direction, rng, name in declared}
    decls = {"clock": "input clock;", "reset": "input reset;"}  # MyHDL-side port -> declaration
    body, connect, unknown = [], {}, []
    reset_port, reset_value = _port(target.reset)
    for name in (target.clock, reset_port, *others, *target.ties):
        if name not in directions:
            raise CosimError(f"{target.top} has no port {name}")
    for name in (target.clock, reset_port, target.idsel):
        _check_width(target, name, None, 1, widths)
    connect[target.clock] = "clock"
    connect[reset_port] = "!reset" if reset_value.startswith("!") else "reset"
    for line, width in LINE_WIDTHS.items():
        pin = target.pins.get(line)
        if pin is None:
            continue
        if isinstance(pin, str):
            _check_width(target, pin, line, width, widths)
            source = _tristate(line, width, pin, decls, body, connect, unknown)
        else:
            source = _split(target, line, width, pin, floating, widths, decls, body, connect, unknown)
        if line == "ad" and target.idsel is not None:
            connect[target.idsel] = f"{source}[{idsel_bit}]"
    for name in others:
        direction, rng = directions[name]
        decls[name] = f"{direction} {rng}{name};"
        connect[name] = name
    decls["unknown"] = f"output {_range(max(1, len(unknown)))}unknown;"
    body.append("assign unknown = {" + ", ".join(f"({u})" for u in reversed(unknown)) + "};"
                if unknown else "assign unknown = 1'b0;")
    for name, value in target.ties.items():
        connect[name] = str(value)
    for direction, _, name in declared:
        if name not in connect and direction == "input":
            raise CosimError(f"input {name} of {target.top} is neither in the pin map nor tied")
    inputs = [p for p, d in decls.items() if d.startswith("input")]
    outputs = [p for p, d in decls.items() if d.startswith("output")]
    connections = ",\n    ".join(f".{name}({connect[name]})" for _, _, name in declared if name in connect)
    text = "\n".join(["`timescale 1ns/1ps", f"module {WRAPPER};",
                      *[("reg " if d.startswith("input") else "wire ") + d.split(None, 1)[1]
                        for d in decls.values()],
                      *body, "initial begin", f"    $from_myhdl({', '.join(inputs)});",
                      f"    $to_myhdl({', '.join(outputs)});", "end",
                      f"{target.top} dut(\n    {connections}\n);", "endmodule", ""])
    return text, list(decls)


def _check_width(target, port, line, width, widths, enable=False):
    """Refuse a port of ``line`` (None: clock, reset, IDSEL) whose width
    does not fit: ``width`` bits, or for an output enable 1 or ``width``."""
    if port is None:
        return
    name = _port(port)[0]
    if name not in widths:
        raise CosimError(f"{target.top} has no port {name}")
    bits = widths[name]
    allowed = (1, width) if enable else (width,)
    if bits in allowed:
        return
    what = f"PCI's {line.upper()}" if line else "a one-bit signal"
    if enable:
        raise CosimError(f"{target.top}: output enable {name} of {line.upper()} is {bits} bits; "
                         f"give one enable (1 bit) or one per bit ({width} bits)")
    raise CosimError(f"{target.top}: port {name} is {bits} bits, {what} has {width}")


def _tristate(line, width, pin, decls, body, connect, unknown):
    """A tri-state port on a net the host drives too; returns the net."""
    rng = _range(width)
    net = f"net_{line}"
    decls[f"host_{line}_out"] = f"input {rng}host_{line}_out;"
    decls[f"host_{line}_oe"] = f"input host_{line}_oe;"
    # A pulled-up line the target only reads gets its pull-up; a line it may
    # drive is a plain net, so that released reads z and its drive shows.
    body.append(f"{'tri1' if line in PULLED_UP and line in HOST_ONLY else 'tri'} {rng}{net};")
    body.append(f"assign {net} = host_{line}_oe ? host_{line}_out : {{{width}{{1'bz}}}};")
    connect[pin] = net
    if line in HOST_ONLY:
        return net
    bits = _bits(net, width)
    seen = " || ".join(f"{b} !== 1'bz" for b in bits)
    decls[f"{line}_out"] = f"output {rng}{line}_out;"
    decls[f"{line}_oe"] = f"output {line}_oe;"
    body.append(f"assign {line}_oe = !host_{line}_oe && ({seen});")
    body.append(f"assign {line}_out = {{{', '.join(f'{b} === 1' for b in reversed(bits))}}};")
    # X, Z in part of a driven line, or contention with the host
    unknown.append(f"({line}_oe || host_{line}_oe) && ^{net} === 1'bx")
    return net


def _split(target, line, width, pin, floating, widths, decls, body, connect, unknown):
    """Split in / out / oe ports; returns the net the target reads (or None)."""
    in_port, out_port, oe_port = pin
    rng = _range(width)
    source = None
    if in_port is not None or line == "ad":
        source = f"in_{line}"
        decls[f"bus_{line}"] = f"input {rng}bus_{line};"
        if line in FLOATING and floating:
            decls[f"driven_{line}"] = f"input driven_{line};"
            body.append(f"wire {rng}{source} = driven_{line} ? bus_{line} : {{{width}{{1'bz}}}};")
        else:
            body.append(f"wire {rng}{source} = bus_{line};")
        if in_port is not None:
            _check_width(target, in_port, line, width, widths)
            connect[in_port] = source
    if out_port is None:
        return source
    _check_width(target, out_port, line, width, widths)
    _check_width(target, oe_port, line, width, widths, enable=True)
    decls[f"{line}_out"] = f"output {rng}{line}_out;"
    decls[f"{line}_oe"] = f"output {line}_oe;"
    body.append(f"wire {rng}drive_{line};")
    connect[out_port] = f"drive_{line}"
    per_bit = oe_port is not None and width > 1 and widths[_port(oe_port)[0]] == width
    if oe_port is None:
        enable = "1'b1"
    else:
        oe_name, value = _port(oe_port)
        if oe_name not in connect:   # one net per enable port: lines may share one
            body.append(f"wire {rng if per_bit else ''}enable_{oe_name};")
            connect[oe_name] = f"enable_{oe_name}"
        enable = f"~{connect[oe_name]}" if value.startswith("!") else connect[oe_name]
    if per_bit:
        _per_bit_drive(line, rng, enable, body, unknown)
        return source
    body.append(f"assign {line}_out = drive_{line};")
    body.append(f"assign {line}_oe = {enable} === 1'b1;")
    unknown.append(f"(({enable}) !== 1'b0 && ({enable}) !== 1'b1) || "
                   f"(({enable}) === 1'b1 && ^drive_{line} === 1'bx)")
    return source


def _per_bit_drive(line, rng, enable, body, unknown):
    """A line with one enable per bit: driven while any bit is enabled, each
    bit's value only where it is; reported when an enable is X or Z, when
    only some bits are enabled, or when an enabled bit is X or Z."""
    body.append(f"wire {rng}bit_oe_{line} = {enable};")
    body.append(f"assign {line}_oe = |bit_oe_{line} === 1'b1;")
    body.append(f"assign {line}_out = drive_{line} & bit_oe_{line};")
    unknown.append(f"(^bit_oe_{line} === 1'bx) || (|bit_oe_{line} === 1'b1 && &bit_oe_{line} !== 1'b1) || "
                   f"(^(drive_{line} & bit_oe_{line}) === 1'bx)")


def watched_lines(target):
    """The lines the wrapper's ``unknown`` reports, bit 0 first."""
    return [line for line in LINE_WIDTHS if target.drives(line)]


def pci_target_cosimulation(target, clock, reset, agent, segment, host_agent, idsel_bit, floating=True,
                            others=None):
    """The ``Cosimulation`` of ``target`` (a ``VerilogTarget``) whose drive
    appears on ``agent`` (``<line>_out`` / ``<line>_oe`` Signals):
    ``segment`` is the bus model (its lines and ``<line>_driven`` feed the
    target), ``host_agent`` the other agent's out/oe (for tri-state ports);
    ``others``: ``{port: Signal}`` of further ports, passed to MyHDL as they
    are.  The X/Z report (one bit per line of ``watched_lines``) goes to the
    segment (``watch_unknown``), so that every sample carries it."""
    others = dict(others or {})
    watched = watched_lines(target)
    unknown = Signal(intbv(0)[max(1, len(watched)):])
    files = [Path(f) for f in target.files]
    declared = target.ports()
    wrapper, names = wrapper_verilog(target, declared, idsel_bit, floating, others)
    bus = segment.lines
    signals = {"clock": clock, "reset": reset, "unknown": unknown, **others}
    for name in names:
        if name in signals:
            continue
        kind, line = name.split("_", 1)[0], name.split("_", 1)[-1]
        if kind == "bus":
            signals[name] = getattr(bus, line)
        elif kind == "driven":
            signals[name] = getattr(bus, f"{line}_driven")
        elif kind == "host":
            signals[name] = getattr(host_agent, line)
        else:
            signals[name] = getattr(agent, name)
    segment.watch_unknown(unknown, watched)
    return icarus_cosimulation(target.top, WRAPPER, wrapper, signals, files, target.libraries,
                               target.defines, target.include_dirs)


def split_pins(verilog_files, top, prefix="pci_"):
    """Pin map of a module with split ports named ``<prefix><line>_in`` /
    ``_out`` / ``_oe`` (the converter's names for a ``PciBus`` argument)."""
    text = "\n".join(read_verilog(f) for f in verilog_files)
    names = {name for _, _, name in port_directions(text, top)}
    pins = {}
    for line in LINE_WIDTHS:
        ends = [f"{prefix}{line}_{end}" for end in ("in", "out", "oe")]
        found = tuple(name if name in names else None for name in ends)
        if any(found):
            pins[line] = found
    return pins
