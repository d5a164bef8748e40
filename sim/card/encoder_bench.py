"""Benches of the encoder units (``rtl/encoder/``) against ``models/encoder_model.py``, every clock.

``run_encoder``, ``run_following_error`` and ``run_probe`` drive a
unit (the MyHDL block, its Verilog in Icarus or in Verilator, or a given
Verilog file in Icarus) and compare every output with the model after
every edge: the pins, writes and strobes are driven at the falling edge,
the model takes the coming rising edge at once (a strobe acts at the edge
that ends its clock: the model's method, then its ``clock``), and the
unit's outputs are compared at the next falling edge.

The waveforms are ``sim/card/encoder_waves.py``'s, the unit on its back end
``sim/card/backend_unit.py``'s ``Unit``, the defects the benches must
reject ``sim/card/encoder_defects.py``'s.
"""
import random

from models.encoder_model import MASK32, SCALE_FRACTION_BITS, EncoderModel, ProbeModel
from rtl.encoder.encoder import encoder, encoder_ports
from rtl.encoder.following_error import following_error, following_error_ports
from rtl.encoder.probe import probe, probe_ports
from sim.card.encoder_waves import FILTERS, Sample, encoder_waves
from sim.card.backend_unit import Unit

ONE = 1 << SCALE_FRACTION_BITS
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
