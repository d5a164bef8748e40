"""A unit under test on a back end, for the unit benches.

``Unit(factory, module, ports, backend)`` puts the unit (``factory`` a
MyHDL block, ``module`` its name) on ``backend``: "myhdl" (the block),
"icarus" (its Verilog in Icarus), "verilator" (its Verilog in Verilator,
the ports Verilated ports in Signals' clothes) or a Verilog file (a given
Verilog, e.g. with a defect put in, in Icarus); ``run(name, step, cycles)``
clocks it: the reset, one edge, then ``step(index)`` before each of
``cycles`` edges (traced under ``name`` on the MyHDL and Icarus paths).
"""
import copy

from myhdl import block

from sim.backends.clocking import clock_source, reset_then_step
from sim.backends.icarus import convert_and_cosimulate, convert_module, cosimulate
from sim.backends.verilator.build import build_model
from sim.backends.verilator.model import VerilatedModel
from sim.backends.waves import run_traced

HALF_PERIOD = 5


@block
def _bench(factory, module, ports, backend, step, cycles):
    """The unit (``backend``: "myhdl", "icarus", or a Verilog file) with a clock, the reset and ``step``."""
    clock, reset = ports["clock"], ports["reset"]
    if backend == "myhdl":
        dut = factory(**ports)
    elif backend == "icarus":
        dut = convert_and_cosimulate(factory, module, ports)
    else:
        dut = cosimulate(module, ports, [backend])
    return dut, clock_source(clock, 2 * HALF_PERIOD), reset_then_step(clock, reset, cycles, step)


class _VerilatedPort:
    """A port of a Verilated model in a Signal's clothes: ``int()`` reads it, ``.next =`` sets it."""

    def __init__(self, model, name):
        self._model, self._name = model, name

    def __int__(self):
        return self._model[self._name]

    @property
    def next(self):
        raise AttributeError("read a Verilated port with int()")

    @next.setter
    def next(self, value):
        self._model[self._name] = int(value)


class Unit:
    """A unit under test on ``backend``: its ``ports`` (for "verilator",
    copies of the interfaces whose signals are the Verilated model's ports)
    and ``run(name, step, cycles)``: the reset, one edge, then ``step(index)``
    before each of ``cycles`` edges."""

    def __init__(self, factory, module, ports, backend):
        self.factory, self.module, self.backend, self.ports = factory, module, backend, ports
        if backend == "verilator":
            self.model = VerilatedModel(build_model([convert_module(factory, module, ports)], module))
            self.model.bind_clock("clock")
            self.ports = {name: self._proxy(name, value) for name, value in ports.items()}

    def _proxy(self, name, value):
        if hasattr(value, "_val"):   # a Signal
            return self._port(name, value)
        proxy = copy.copy(value)
        for attribute, member in vars(value).items():
            if hasattr(member, "_val"):
                setattr(proxy, attribute, self._port(f"{name}_{attribute}", member))
        return proxy

    def _port(self, name, signal):
        """The model's port ``name``; an input starts at ``signal``'s initial value, as in MyHDL."""
        port = _VerilatedPort(self.model, name)
        if name in self.model.ports and not self.model.ports[name][2]:
            port.next = int(signal.val)
        return port

    def run(self, name, step, cycles):
        if self.backend != "verilator":
            label = self.backend if self.backend in ("myhdl", "icarus") else "mutant"
            run_traced(_bench(self.factory, self.module, self.ports, self.backend, step, cycles), f"{name}_{label}")
            return
        self.model["reset"] = 0
        self.model.tick(2)
        self.model["reset"] = 1
        self.model.tick()   # the edge after the reset's release, as reset_then_step has it
        for index in range(cycles):
            step(index)
            self.model.tick()
        self.model.close()
