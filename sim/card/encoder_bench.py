"""Benches of the encoder units (``rtl/encoder/``) against ``models/encoder_model.py``, every clock.

``encoder_waves(rng, clocks)`` makes a seeded random encoder waveform, one
``Sample`` a clock: quadrature walks with reversals at every spacing the
filter passes (down to ENC_FILTER + 1 clocks), glitches of 1 .. ENC_FILTER
clocks inside the holds (which the filter must remove), illegal samples (A
and B together), pure noise, step/dir stretches, index pulses, and the
host's writes (filter, polarity, mode, INDEX_ZERO, INDEX_ARM, QUAD_ERROR's
clear).  ``run_encoder``, ``run_following_error`` and ``run_probe`` drive a
unit (the MyHDL block, its Verilog in Icarus or in Verilator, or a given
Verilog file in Icarus) and compare every output with the model after
every edge: the pins, writes and strobes are driven at the falling edge,
the model takes the coming rising edge at once (a strobe acts at the edge
that ends its clock: the model's method, then its ``clock``), and the
unit's outputs are compared at the next falling edge.
"""
import copy
import random
import re
from dataclasses import dataclass, field
from pathlib import Path

from myhdl import block

from models.encoder_model import (FILTER_MAX, GRAY, MASK32, MODE_QUADRATURE, MODE_STEP_DIR, SCALE_FRACTION_BITS,
                                  EncoderModel, ProbeModel)
from rtl.encoder.encoder import encoder, encoder_ports
from rtl.encoder.following_error import following_error, following_error_ports
from rtl.encoder.probe import probe, probe_ports
from sim.backends.clocking import clock_source, reset_then_step
from sim.backends.icarus import convert_and_cosimulate, convert_module, cosimulate
from sim.backends.verilator.build import build_model
from sim.backends.verilator.model import VerilatedModel
from sim.backends.waves import run_traced

HALF_PERIOD = 5
FILTERS = (0, 0, 1, 2, 3, 7, FILTER_MAX)   # the smallest filter most often: the closest spacing
ONE = 1 << SCALE_FRACTION_BITS


@dataclass
class Sample:
    """One clock of stimulus: the pins and the host's writes in it (``settings``:
    register values from this clock on; ``strobes``: names of one-clock writes)."""
    a: int
    b: int
    index: int
    settings: dict = field(default_factory=dict)
    strobes: tuple = ()


class Walk:
    """The waveform's state: the encoder's phase, the walk's position (legal
    edges only) and the settings in force."""

    def __init__(self, rng):
        self.rng = rng
        self.phase, self.position, self.index = 0, 0, 0
        self.a, self.b = 0, 0
        self.filter, self.mode, self.legal_only = 2, MODE_QUADRATURE, True
        self.pending = {}

    def sample(self, a=None, b=None):
        """The next clock: the pins (A, B as given, else as they are), the index
        toggling now and then, the strobes at random, the settings pending."""
        if a is not None:
            self.a, self.b = a, b
        if self.rng.random() < 0.01:
            self.index ^= 1
        chosen = []
        if self.rng.random() < 0.01:
            chosen.append("arm")
        if self.rng.random() < 0.005:
            chosen.append("clear_error")
        settings, self.pending = self.pending, {}
        return Sample(self.a, self.b, self.index, settings, tuple(chosen))

    def hold(self, clocks, glitch=True):
        """Hold the pins ``clocks`` clocks; with room, a glitch the filter removes in the middle."""
        width = self.rng.randint(1, self.filter) if self.filter else 0
        if glitch and width and clocks >= 2 * (self.filter + 1) + width and self.rng.random() < 0.5:
            before = self.filter + 1
            for _ in range(before):
                yield self.sample()
            pin = self.rng.choice("ab")
            steady = (self.a, self.b)
            for _ in range(width):
                yield self.sample(self.a ^ (pin == "a"), self.b ^ (pin == "b"))
                self.a, self.b = steady
            for _ in range(clocks - before - width):
                yield self.sample()
            return
        for _ in range(clocks):
            yield self.sample()


def _spacing(walk):
    """Clocks between edges: the closest the filter passes, often."""
    closest = walk.filter + 1
    return closest if walk.rng.random() < 0.5 else closest + walk.rng.randrange(1, 3 * closest + 4)


def _quadrature(walk, edges):
    for _ in range(edges):
        move = walk.rng.choice((1, 1, -1))
        walk.phase, walk.position = (walk.phase + move) % 4, walk.position + move
        walk.a, walk.b = GRAY[walk.phase]
        yield from walk.hold(_spacing(walk))


def _illegal(walk, count):
    walk.legal_only = False
    for _ in range(count):
        walk.phase = (walk.phase + 2) % 4
        walk.a, walk.b = GRAY[walk.phase]
        yield from walk.hold(_spacing(walk), glitch=False)


def _noise(walk, clocks):
    walk.legal_only = False
    for _ in range(clocks):
        yield walk.sample(walk.rng.randrange(2), walk.rng.randrange(2))
    walk.phase = GRAY.index((walk.a, walk.b))


def _step_dir(walk, pulses):
    walk.legal_only = False
    for _ in range(pulses):
        direction = walk.b if walk.rng.random() < 0.7 else 1 - walk.b
        walk.a, walk.b = 0, direction
        yield from walk.hold(_spacing(walk))
        walk.a = 1
        yield from walk.hold(_spacing(walk))
    walk.phase = GRAY.index((walk.a, walk.b))


def encoder_waves(rng, clocks, kinds=("walk", "walk", "walk", "illegal", "noise", "step_dir"), host=True):
    """About ``clocks`` Samples of a random encoder waveform (module
    docstring), in segments of the ``kinds`` named, each with its
    ``Walk``; ``Walk.legal_only`` stays True while only legal quadrature
    walks were made.  Without ``host`` the polarity stays 0 and INDEX_ZERO
    off (the count then is the walk's position)."""
    walk = Walk(rng)
    made = 0
    while made < clocks:
        kind = rng.choice(kinds)
        # the last edge through the filter first: an edge in flight while the
        # setting changes may be taken out of order with the next (docs/encoders.md)
        for sample in walk.hold(walk.filter + 4, glitch=False):
            made += 1
            yield sample, walk
        walk.filter = rng.choice(FILTERS)
        mode = MODE_STEP_DIR if kind == "step_dir" else MODE_QUADRATURE
        walk.pending = dict(filter=walk.filter, mode=mode, index_zero=host and rng.random() < 0.3)
        if host and rng.random() < 0.1:
            walk.pending["polarity"] = rng.randrange(8)
            walk.legal_only = False
        if mode != walk.mode:
            walk.legal_only = False
            walk.mode = mode
        segment = {"walk": lambda: _quadrature(walk, rng.randrange(5, 40)),
                   "illegal": lambda: _illegal(walk, rng.randrange(1, 4)),
                   "noise": lambda: _noise(walk, rng.randrange(5, 30)),
                   "step_dir": lambda: _step_dir(walk, rng.randrange(3, 12))}[kind]()
        for sample in segment:
            made += 1
            yield sample, walk
    # the pipeline emptied: the last edge counted
    for _ in range(FILTER_MAX + 6):
        yield walk.sample(), walk


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


ENCODER_OUTPUTS = ("count", "direction", "quad_error", "error_count", "time", "armed", "latch", "fired")


def _model_outputs(model):
    return dict(count=model.count, direction=model.direction, quad_error=int(model.quad_error),
                error_count=model.error_count, time=model.time, armed=int(model.index_armed),
                latch=model.index_latch, fired=int(model.index_fired))


def _apply_settings(model, port, settings):
    for name, value in settings.items():
        setattr(model, name, value)
        getattr(port, name).next = value


def run_encoder(seed, clocks, backend="myhdl", waveform=None, **waves):
    """The encoder unit against ``EncoderModel`` on ``encoder_waves(rng,
    clocks, **waves)`` (or on ``waveform``, a list of ``Sample``s); the model
    at the end and what happened (the walk, index fires, the most quadrature
    errors, count edges, and ``unit``: the unit's (count, quad_error) after
    every edge)."""
    rng = random.Random(seed)
    unit = Unit(encoder, "encoder", encoder_ports(), backend)
    pins, port = unit.ports["pins"], unit.ports["port"]
    if waveform is None:
        waveform = list(encoder_waves(rng, clocks, **waves))
    else:
        waveform = [(sample, None) for sample in waveform]
    model, seen = EncoderModel(), dict(fires=0, errors=0, counts=0, walk=waveform[-1][1], unit=[])
    samples = iter(waveform)

    def step(index):
        if index == 0:
            model.clock(0, 0, 0)   # the edge after the reset's release, before the first step
        observed = {name: int(getattr(port, name)) for name in ENCODER_OUTPUTS}
        assert observed == _model_outputs(model), f"clock {index}: unit {observed} != model {_model_outputs(model)}"
        seen["unit"].append((observed["count"], observed["quad_error"]))
        sample = next(samples, (Sample(int(pins.a), int(pins.b), int(pins.index)),))[0]
        _apply_settings(model, port, sample.settings)
        port.arm.next, port.clear_error.next = "arm" in sample.strobes, "clear_error" in sample.strobes
        if "arm" in sample.strobes:
            model.arm_index()
        if "clear_error" in sample.strobes:
            model.clear_quad_error()
        port.coming.next = (model.timestamp + 1) & MASK32
        pins.a.next, pins.b.next, pins.index.next = sample.a, sample.b, sample.index
        before = model.count
        model.clock(sample.a, sample.b, sample.index)
        seen["fires"] += model.index_fired
        seen["counts"] += model.count != before
        seen["errors"] = max(seen["errors"], model.error_count)

    unit.run(f"encoder_{seed}", step, len(waveform) + 1)
    return model, seen


def run_following_error(seed, clocks, backend="myhdl"):
    """The following-error unit against ``EncoderModel``'s error and stop:
    the model's count (legal walks, index zeroing) and a step position that
    wanders by one step at a time drive the unit; scales, limits, aligns and
    stop clears at random.  Returns how often the stop rose and the aligns."""
    rng = random.Random(seed)
    unit = Unit(following_error, "following_error", following_error_ports(), backend)
    check = unit.ports["check"]
    model = EncoderModel()
    samples = encoder_waves(rng, clocks, kinds=("walk",))
    state = dict(pos=0, stops=0, aligns=0, stopped=False)

    def step(index):
        if index == 0:
            model.clock(0, 0, 0)
        observed = (int(check.error), int(check.stop))
        expected = (model.ferror & MASK32, int(model.stop))
        assert observed == expected, f"clock {index}: unit (error, stop) {observed} != model {expected}"
        state["stops"] += model.stop and not state["stopped"]
        state["stopped"] = model.stop
        sample = next(samples, (Sample(0, 0, 0),))[0]
        for name, value in sample.settings.items():
            setattr(model, name, value)
        if "arm" in sample.strobes:
            model.arm_index()
        if rng.random() < 0.3:
            state["pos"] = (state["pos"] + rng.choice((1, -1, 1))) & MASK32
        pos = state["pos"]
        align = rng.random() < 0.004
        if rng.random() < 0.003:
            scale = rng.choice((ONE, 4 * ONE, ONE * 5 // 2, ONE // 4, 3 * ONE + 1, MASK32, 0))
            model.set_scale(scale, pos)
            check.scale.next, align = scale, True
        elif align:
            model.align(pos)
        state["aligns"] += align
        if rng.random() < 0.01:
            model.limit = rng.choice((0, 1, 2, 3, 5, 8, 20))
        clear = rng.random() < 0.02
        if clear:
            model.clear_stop()
        before = model.count
        model.clock(sample.a, sample.b, sample.index, pos)
        check.count.next, check.zeroing.next = before, bool(model.index_fired and model.index_zero)
        check.pos_low.next, check.limit.next = pos & 3, model.limit
        check.align.next, check.clear_stop.next = align, clear

    unit.run(f"following_error_{seed}", step, clocks)
    return state


def run_probe(seed, clocks, axes=3, backend="myhdl"):
    """The probe unit against ``ProbeModel``: a pin with pulses and glitches,
    counts and positions changing at random, arms, filter and polarity
    changes.  Returns how often it fired."""
    rng = random.Random(seed)
    unit = Unit(probe, "probe", probe_ports(axes), backend)
    port = unit.ports["port"]
    model = ProbeModel()
    encoders = [EncoderModel() for _ in range(axes)]
    state = dict(pin=0, level=0, fires=0, positions=[0] * axes)

    def step(index):
        if index == 0:
            model.clock(0, encoders, state["positions"])
        counts = model.counts or (0,) * axes
        positions = model.positions or (0,) * axes
        observed = (int(port.armed), int(port.fired), tuple(int(port.signals("latched_count", axis))
                                                            for axis in range(axes)),
                    tuple(int(port.signals("latched_pos", axis)) for axis in range(axes)))
        expected = (int(model.armed), int(model.fired), tuple(counts), tuple(positions))
        assert observed == expected, f"clock {index}: unit {observed} != model {expected}"
        state["fires"] += model.fired
        if rng.random() < 0.01:
            model.filter, model.invert = rng.choice(FILTERS), rng.random() < 0.3
            port.filter.next, port.invert.next = model.filter, model.invert
        if rng.random() < 0.03:
            state["level"] ^= 1
        pin = state["level"] ^ (rng.random() < 0.05)   # a glitch now and then
        arm = rng.random() < 0.02
        if arm:
            model.arm()
        for axis, encoder_model in enumerate(encoders):
            if rng.random() < 0.3:
                encoder_model.count = rng.randrange(MASK32 + 1)
                state["positions"][axis] = rng.randrange(MASK32 + 1)
            port.signals("count", axis).next = encoder_model.count
            port.signals("pos", axis).next = state["positions"][axis]
        model.clock(pin, encoders, state["positions"])
        port.pin.next, port.arm.next = pin, arm

    unit.run(f"probe_{seed}_{axes}", step, clocks)
    return state


# Defects put by hand into the units' converted Verilog, for the benches and
# the proofs to reject: name -> (unit, [(pattern, replacement), ...]).
DEFECTS = {
    "a_double_change_counted": ("encoder", [(r"\(decoder_changed_a && \(!decoder_changed_b\) && "
                                             r"\(conditioner_a_level != conditioner_b_level\)\)",
                                             "(decoder_changed_a && (conditioner_a_level != conditioner_b_level))")]),
    "the_filter_one_clock_short": ("encoder", [(r"\((conditioner_\w+)_run >= port_filter\)",
                                                r"((\1_run + 1) >= port_filter)")]),
    "the_index_not_disarmed": ("encoder", [(r"port_armed <= \(index_latch_armed_now && \(!index_latch_fire\)\);",
                                            "port_armed <= index_latch_armed_now;")]),
    "step_dir_counting_both_edges_of_a": ("encoder", [(r"\(conditioner_a_level && \(!decoder_seen_a\) && "
                                                       r"conditioner_b_level\)",
                                                       "(decoder_changed_a && conditioner_b_level)")]),
    "the_stop_at_the_limit": ("following_error", [(r"\(folded > check_limit\)", "(folded >= check_limit)")]),
    "the_steps_scaled_one_late": ("following_error", [(r"rounded = scaled_now\[", "rounded = scaled[")]),
    "the_probe_on_its_level": ("probe", [(r"\(armed_now && level && \(!seen\)\)", "(armed_now && level)")]),
}


def with_defect(defect, source, folder):
    """A copy of ``source`` (the unit's Verilog) in ``folder`` with ``defect`` put in; its path."""
    text = Path(source).read_text()
    for pattern, replacement in DEFECTS[defect][1]:
        text, count = re.subn(pattern, replacement, text)
        assert count, f"{Path(source).name} no longer has {pattern!r}: pick the defect {defect} anew"
    mutant = Path(folder) / Path(source).name
    mutant.parent.mkdir(parents=True, exist_ok=True)
    mutant.write_text(text)
    return mutant
