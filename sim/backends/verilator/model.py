"""A Verilated model behind the compiled harness, loaded with ctypes.

``VerilatedModel(library)`` is one instance of a model built by
``sim.backends.verilator.build.build_model``: ports by name (``model["pins_step_x"]``,
``model["reset"] = 1``; an unknown name or a write to an output is a
``VerilatorError``), ``tick(count)``, ``eval()``, ``run(...)`` until an
event, and the STEP/DIR edges the harness recorded, as numpy arrays.
Roles (clock, PCI lines, motor pins) are bound by port name once the model
is loaded (``bind_clock``, ``bind_pins``, ``bind_bus``).
"""
import ctypes
import enum
from pathlib import Path

import numpy as np

from models.axes import AXIS_NAMES
from models.sim_machine import AXIS_OF, INPUTS, MOTOR_AXES
from sim.backends.verilator.build import VerilatorError

LINES = ("ad", "cbe", "par", "frame", "irdy", "trdy", "devsel", "stop", "perr", "serr", "inta")
# bit i of an edge state is PINS[i]: STEP and DIR of X, Y, Z, A, B, C (a card's absent ones unbound)
PINS = tuple(f"{kind}_{name.lower()}" for name in AXIS_NAMES for kind in ("step", "dir"))

_u64, _int, _p = ctypes.c_uint64, ctypes.c_int, ctypes.c_void_p
_u64_array = np.ctypeslib.ndpointer(np.uint64, flags="C_CONTIGUOUS")
_u32_array = np.ctypeslib.ndpointer(np.uint32, flags="C_CONTIGUOUS")
_u16_array = np.ctypeslib.ndpointer(np.uint16, flags="C_CONTIGUOUS")
_int_array = np.ctypeslib.ndpointer(np.intc, flags="C_CONTIGUOUS")
_i64_array = np.ctypeslib.ndpointer(np.int64, flags="C_CONTIGUOUS")
MAX_AXES = len(AXIS_NAMES)   # the harness's room (sim_machine.h's kMaxAxes, kMaxInputs)
DRIVE_BIT = 31               # DRIVE_ENABLE's bit in a recorded input word (sim_machine.h's kDriveBit)
_SIGNATURES = {
    "vc_new": (_p, []),
    "vc_free": (None, [_p]),
    "vc_trace_kind": (_int, []),
    "vc_port_count": (_int, [_p]),
    "vc_port_name": (ctypes.c_char_p, [_p, _int]),
    "vc_port_width": (_int, [_p, _int]),
    "vc_port_direction": (_int, [_p, _int]),
    "vc_get": (_u64, [_p, _int]),
    "vc_set": (None, [_p, _int, _u64]),
    "vc_eval": (None, [_p]),
    "vc_clocks": (_u64, [_p]),
    "vc_step_rises": (_u64, [_p]),
    "vc_bind_clock": (None, [_p, _int]),
    "vc_bind_pins": (None, [_p, _int_array]),
    "vc_bind_bus": (None, [_p, _int_array, _int_array, _int_array, _int, _int]),
    "vc_io": (None, [_p, _int, _p, _p, _int, _int, _p, _p]),
    "vc_step_bus": (_int, [_p, _p, _p, _p, _p, _p]),
    "vc_tick": (None, [_p, _u64]),
    "vc_run": (_int, [_p, _u64, _int, _u64, ctypes.POINTER(_u64)]),
    "vc_edge_count": (_u64, [_p]),
    "vc_take_edges": (None, [_p, _u64_array, _u16_array]),
    "vc_trace_open": (_int, [_p, ctypes.c_char_p, _u64, _u64, _u64]),
    "vc_machine_start": (_int, [_p, _int, _int, _int_array, _int_array, _int, _i64_array, _int, _int]),
    "vc_machine_switch": (None, [_p, _int, ctypes.c_int64, _int, ctypes.c_int64, ctypes.c_int64, ctypes.c_int64,
                                 _int, ctypes.c_uint32]),
    "vc_machine_estop": (None, [_p, _int]),
    "vc_machine_state": (None, [_p, ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(_u64), ctypes.POINTER(_u64)]),
    "vc_machine_take_changes": (None, [_p, _u64_array, _u32_array]),
    "vc_machine_motor": (None, [_p, _int, ctypes.c_int64, ctypes.c_int64, ctypes.c_int64, ctypes.c_int64,
                                ctypes.c_int64, ctypes.c_uint32, ctypes.c_int64, ctypes.c_int64, _int_array]),
    "vc_machine_stall": (None, [_p, _int, _int]),
    "vc_machine_encoders": (None, [_p, ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(_u64)]),
    "vc_machine_take_encoder_changes": (None, [_p, _u64_array, _u32_array]),
    "vc_trace_close": (None, [_p]),
}
_LIBRARIES = {}


class Stop(enum.IntEnum):
    """Why ``run`` returned (the harness's codes)."""

    LIMIT = 0       # the clock limit
    INTERRUPT = 1   # INTA# was asserted in the clock before the last edge
    STEPS = 2       # the STEP rises asked for were recorded before the last edge
    BUS = 3         # the card drove a PCI line other than INTA#


def _library(path):
    path = str(Path(path).resolve())
    if path not in _LIBRARIES:
        try:
            library = ctypes.CDLL(path)
        except OSError as error:
            raise VerilatorError(f"cannot load {path}: {error}") from None
        for name, (restype, argtypes) in _SIGNATURES.items():
            function = getattr(library, name)
            function.restype, function.argtypes = restype, argtypes
        _LIBRARIES[path] = library
    return _LIBRARIES[path]


class VerilatedModel:
    """One instance of a built model (``library``: the ``libmodel.so`` path)."""

    def __init__(self, library):
        self._lib = _library(library)
        self._handle = self._lib.vc_new()
        count = self._lib.vc_port_count(self._handle)
        self.ports = {}
        for index in range(count):
            name = self._lib.vc_port_name(self._handle, index).decode()
            width = self._lib.vc_port_width(self._handle, index)
            output = bool(self._lib.vc_port_direction(self._handle, index))
            self.ports[name] = (index, width, output)
        self.trace_kind = (None, "vcd", "fst")[self._lib.vc_trace_kind()]
        self.machine_axes = 0   # the simulated machine's axes, once started

    # ----- ports --------------------------------------------------------------
    def index(self, name):
        """Port index of ``name``; VerilatorError naming the ports if there is none."""
        try:
            return self.ports[name][0]
        except KeyError:
            raise VerilatorError(f"the model has no port {name!r}; its ports: {', '.join(self.ports)}") from None

    def input_index(self, name):
        index = self.index(name)
        if self.ports[name][2]:
            raise VerilatorError(f"{name} is an output of the model: it cannot be set")
        return index

    def __getitem__(self, name):
        return self._lib.vc_get(self._handle, self.index(name))

    def __setitem__(self, name, value):
        index = self.input_index(name)
        width = self.ports[name][1]
        if not 0 <= int(value) < 1 << width:
            raise VerilatorError(f"{value} does not fit the {width}-bit port {name}")
        self._lib.vc_set(self._handle, index, int(value))

    def eval(self):
        """Settle the logic after inputs changed (no clock edge)."""
        self._lib.vc_eval(self._handle)

    # ----- roles --------------------------------------------------------------
    def bind_clock(self, name):
        self._lib.vc_bind_clock(self._handle, self.input_index(name))
        self._clock_bound = True

    def bind_pins(self, names):
        """The motor pins, in the order of ``PINS`` (a name the model lacks, or past the
        names given: unbound)."""
        indices = [self.index(n) if n in self.ports else -1 for n in names]
        indices += [-1] * (len(PINS) - len(indices))   # the harness reads one index per pin of PINS
        self._lib.vc_bind_pins(self._handle, np.array(indices, dtype=np.intc))

    def bind_bus(self, line_ports, idsel, idsel_bit):
        """``line_ports[line] = (in, out, oe)`` port names (None where absent)."""
        columns = [[], [], []]
        for line in LINES:
            names = line_ports.get(line, (None, None, None))
            for column, name in zip(columns, names):
                column.append(-1 if name is None else self.index(name))
        arrays = [np.array(c, dtype=np.intc) for c in columns]
        self._lib.vc_bind_bus(self._handle, *arrays, self.input_index(idsel), idsel_bit)

    # ----- time ---------------------------------------------------------------
    @property
    def clocks(self):
        """Rising edges so far."""
        return self._lib.vc_clocks(self._handle)

    @property
    def step_rises(self):
        """STEP rises so far, both axes (a diagonal counts two)."""
        return self._lib.vc_step_rises(self._handle)

    def _need_clock(self):
        if not getattr(self, "_clock_bound", False):
            raise VerilatorError("bind_clock first: the harness does not know the clock port")

    def tick(self, count=1):
        """``count`` clocks with the inputs as they are."""
        self._need_clock()
        self._lib.vc_tick(self._handle, int(count))

    def io_exchange(self, inputs, outputs):
        """A prepared exchange of ``inputs`` and ``outputs`` (port names): see ``Exchange``."""
        return Exchange(self, [self.input_index(n) for n in inputs], [self.index(n) for n in outputs])

    def run(self, limit, until_interrupt=False, steps=0):
        """Clocks in compiled code until ``limit`` clocks, INTA# (``until_interrupt``),
        ``steps`` more STEP rises, or bus activity; returns (Stop, clocks run)."""
        self._need_clock()
        if limit < 0 or steps < 0:
            raise VerilatorError("run: limit and steps must not be negative")
        done = _u64()
        reason = self._lib.vc_run(self._handle, int(limit), int(bool(until_interrupt)), int(steps),
                                  ctypes.byref(done))
        return Stop(reason), done.value

    def bus(self):
        """Arrays for ``step_bus``: see ``BusArrays``."""
        self._need_clock()
        return BusArrays()

    def step_bus(self, bus):
        """One bus clock (``harness.cpp``'s ``vc_step_bus``): the host's drive in
        ``bus.host_out`` / ``bus.host_oe``, the sampled segment back in
        ``bus.values`` / ``drivers`` / ``floating``; one foreign call."""
        rounds = self._lib.vc_step_bus(self._handle, *bus.pointers)
        if rounds < 0:
            raise VerilatorError(f"the bus never settled in clock {self.clocks + 1}: a combinational loop "
                                 "through the card's PCI lines")
        return rounds

    def take_edges(self):
        """(clocks, states) of the pin changes recorded since the last call, as
        numpy arrays (uint64, uint16; bit i of a state is ``PINS[i]``)."""
        count = self._lib.vc_edge_count(self._handle)
        clocks, states = np.empty(count, np.uint64), np.empty(count, np.uint16)
        if count:
            self._lib.vc_take_edges(self._handle, clocks, states)
        return clocks, states

    # ----- the simulated machine (models/sim_machine.py) -----------------------
    def start_machine(self, config, axes, inputs, drive, encoders=None):
        """Drive the machine inputs ``inputs`` (port names in ``INPUT_NAMES``
        order: those of a card of ``axes`` axes) from ``config`` (a
        ``MachineConfig``), every clock in the harness, the drives following
        port ``drive`` (DRIVE_ENABLE); each motor of ``config`` drives
        ``encoders[axis]`` (the port names of its axis's A, B and index)."""
        config.check_axes(axes)
        if not 2 <= axes <= MAX_AXES or not 1 <= len(inputs) <= len(INPUTS):
            raise VerilatorError(f"a machine of {axes} axes and {len(inputs)} inputs does not fit the harness")
        self.machine_axes = axes
        for name, motor in config.motors.items():
            axis = MOTOR_AXES.index(name)
            numerator, denominator = motor.ratio
            ports = np.array([self.input_index(port) for port in encoders[axis]], dtype=np.intc)
            self._lib.vc_machine_motor(self._handle, axis, numerator, denominator, motor.lag, motor.spacing,
                                       motor.jitter, motor.seed, motor.index_period,
                                       -1 if motor.stall_at is None else motor.stall_at, ports)
        for name, switch in config.switches.items():
            self._lib.vc_machine_switch(self._handle, INPUTS.index(name), switch.position, int(switch.positive),
                                        switch.hysteresis, switch.bounce, switch.longest_run,
                                        int(switch.active_low), switch.seed)
        ports = np.array([self.input_index(name) for name in inputs], dtype=np.intc)
        input_axis = np.array([AXIS_OF.get(name, -1) for name in INPUTS[:len(inputs)]], dtype=np.intc)
        start = np.array([config.start_of(axis) for axis in range(axes)], dtype=np.int64)
        directions = sum(int(config.forward_level(axis)) << axis for axis in range(axes))
        if self._lib.vc_machine_start(self._handle, axes, len(inputs), ports, input_axis, self.index(drive), start,
                                      directions, int(config.estop_active_low)) < 0:
            raise VerilatorError(f"the harness refused a machine of {axes} axes and {len(inputs)} inputs")

    def press_estop(self, pressed=True):
        self._lib.vc_machine_estop(self._handle, int(bool(pressed)))

    def _machine_state(self):
        position, lost, pins = (ctypes.c_int64 * MAX_AXES)(), (_u64 * MAX_AXES)(), (_u64 * 2)()
        self._lib.vc_machine_state(self._handle, position, lost, pins)
        return position, lost, pins

    def machine_state(self):
        """(positions, lost steps, input word) of the simulated machine, per axis of its card."""
        position, lost, pins = self._machine_state()
        axes = self.machine_axes
        return tuple(position[:axes]), tuple(lost[:axes]), pins[0]

    def stall(self, axis, stalled=True):
        """Stall (or free) the motor of ``axis`` from the next clock on."""
        self._lib.vc_machine_stall(self._handle, int(axis), int(bool(stalled)))

    def _machine_encoders(self):
        counts, state = (ctypes.c_int64 * MAX_AXES)(), (_u64 * 3)()
        self._lib.vc_machine_encoders(self._handle, counts, state)
        return counts, state

    def machine_encoders(self):
        """(the motors' counts per axis of the card, the machine's clocks, the encoder word)."""
        counts, state = self._machine_encoders()
        return tuple(counts[:self.machine_axes]), state[0], state[1]

    def take_encoder_changes(self):
        """(clocks, words) of the encoder word's changes since the last call
        (``SimMachine.encoder_pins``: set after the rising edge ``clocks``
        counts, taken by the next)."""
        _, state = self._machine_encoders()
        clocks, words = np.empty(state[2], np.uint64), np.empty(state[2], np.uint32)
        if state[2]:
            self._lib.vc_machine_take_encoder_changes(self._handle, clocks, words)
        return clocks, words

    def take_machine_changes(self):
        """(clocks, words) of the input word's changes since the last call: the
        word set after the rising edge ``clocks`` counts, taken by the next
        (bit n: ``INPUTS[n]``), with DRIVE_ENABLE as sampled after that edge
        at bit ``DRIVE_BIT``."""
        _, _, pins = self._machine_state()
        clocks, words = np.empty(pins[1], np.uint64), np.empty(pins[1], np.uint32)
        if pins[1]:
            self._lib.vc_machine_take_changes(self._handle, clocks, words)
        return clocks, words

    # ----- waves --------------------------------------------------------------
    def trace(self, path, first=0, last=1 << 62, half_period=15):
        """Write the clocks ``first`` .. ``last`` (rising-edge counts) to ``path``."""
        if self.trace_kind is None:
            raise VerilatorError("this model was built without tracing: build_model(..., trace='vcd' or 'fst')")
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        self._lib.vc_trace_open(self._handle, str(path).encode(), first, last, half_period)

    def close(self):
        """Finish the model (flushes a trace); the instance is unusable afterwards."""
        if self._handle:
            self._lib.vc_free(self._handle)
            self._handle = None

    def __del__(self):
        try:
            self.close()
        except Exception:  # interpreter shutdown: ctypes may be gone
            pass


class BusArrays:
    """Per PCI line (``LINES`` order), uint64: ``host_out``, ``host_oe`` (what the
    host drives), ``values``, ``drivers`` (bit 0 host, bit 1 card),
    ``floating`` (as sampled); their addresses are taken once."""

    def __init__(self):
        self.host_out, self.host_oe, self.values, self.drivers, self.floating = (
            np.zeros(len(LINES), np.uint64) for _ in range(5))
        self.pointers = [a.ctypes.data for a in (self.host_out, self.host_oe, self.values, self.drivers,
                                                 self.floating)]


class Exchange:
    """``values`` (uint64, one per input port) go in, ``out`` (one per output
    port) comes back, with a tick or a settle in between: one foreign call."""

    def __init__(self, model, inputs, outputs):
        self._model = model
        self._inputs, self._outputs = np.array(inputs, np.intc), np.array(outputs, np.intc)
        self.values, self.out = np.zeros(len(inputs), np.uint64), np.zeros(len(outputs), np.uint64)
        self._call = model._lib.vc_io
        self._args = (len(inputs), self._inputs.ctypes.data, self.values.ctypes.data)
        self._out_args = (len(outputs), self._outputs.ctypes.data, self.out.ctypes.data)

    def __call__(self, tick):
        if tick:
            self._model._need_clock()
        self._call(self._model._handle, *self._args, int(tick), *self._out_args)
