"""The machine-side units against their golden models (``models/machine_model.py``), every clock.

Seeded random inputs are driven at the falling edge, the model advances by
the coming rising edge, and every output is compared at the next falling
edge; the same bench runs on the MyHDL block and on its Verilog in Icarus.
"""
import random

import pytest
from myhdl import block

from models import registers as regmap
from models.machine_model import INPUT, REASON, InputFilterModel, MachineGuardModel
from rtl.machine.input_filter import input_filter, input_filter_ports
from rtl.machine.machine_guard import machine_guard, machine_guard_ports
from sim.backends.clocking import clock_source, reset_then_step
from sim.backends.icarus import convert_and_cosimulate
from sim.backends.waves import run_traced

HALF_PERIOD = 5
# (axes, seed): the two-axis card and a three-axis one, whose Z inputs and limits the units take too
BUILDS = [(2, 1), (3, 2)]


@block
def _bench(factory, module, ports, cosim, step, cycles, after):
    """Clock, reset, then ``step(clock_index)`` at every falling edge and
    ``after(clock_index)`` one time unit later (combinational outputs of
    the inputs ``step`` gave, before the rising edge)."""
    clock, reset = ports["clock"], ports["reset"]
    dut = convert_and_cosimulate(factory, module, ports) if cosim else factory(**ports)
    clock_gen = clock_source(clock, 2 * HALF_PERIOD)

    stimulus = reset_then_step(clock, reset, cycles, step, after)

    return dut, clock_gen, stimulus


def _run(name, factory, module, ports, cosim, step, cycles, after=None):
    run_traced(_bench(factory, module, ports, cosim, step, cycles, after), f"{name}_{'icarus' if cosim else 'myhdl'}")


def _bouncing(rng, level, bounce, inputs):
    """A pin level that flips now and then, with bursts of bounce."""
    if rng.random() < bounce:
        return level ^ (1 << rng.randrange(inputs))
    return level


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
@pytest.mark.parametrize("axes,seed", BUILDS)
def test_input_filter_against_model(axes, seed, cosim):
    rng = random.Random(seed)
    ports = input_filter_ports(axes)
    inputs = ports["inputs"]
    count = len(regmap.input_names(axes))
    model = InputFilterModel(count)
    changes = []
    state = dict(pins=0, polarity=0, samples=int(inputs.samples), tick=int(inputs.tick))

    def step(index):
        if index == 0:
            model.clock(0, 0, state["samples"], state["tick"])
        assert int(inputs.raw) == model.raw, f"raw at clock {index}"
        assert int(inputs.active) == model.active, f"active at clock {index}"
        assert bool(inputs.changed) == model.changed, f"changed at clock {index}"
        if model.changed:
            changes.append(index)
        if index % 500 == 0:
            state.update(samples=rng.choice([1, 2, 5, 15]), tick=rng.choice([1, 1, 2, 7]),
                         polarity=rng.randrange(1 << count))
        if rng.random() < 0.02:
            state["pins"] ^= 1 << rng.randrange(count)   # a real change, bouncing for a while
        pins = _bouncing(rng, state["pins"], 0.15, count)
        inputs.pins.next, inputs.polarity.next = pins, state["polarity"]
        inputs.samples.next, inputs.tick.next = state["samples"], state["tick"]
        model.clock(pins, state["polarity"], state["samples"], state["tick"])

    _run(f"input_filter_{axes}_{seed}", input_filter, "input_filter", ports, cosim, step, 3000)
    assert len(changes) > 30


@pytest.mark.parametrize("samples", [1, 3, 15])
def test_input_filter_reaction_and_glitch(samples):
    """From the spec: a clean edge is active max(1, samples) + 1 clocks after
    the edge that takes it into the synchroniser; a pulse one clock shorter
    than the filter never shows."""
    ports = input_filter_ports()
    inputs = ports["inputs"]
    seen = []
    length = max(samples, 1)
    glitch_at, edge_at = 10, 60

    def step(index):
        inputs.samples.next = samples
        seen.append(int(inputs.active) & 1)
        # the pin changes after falling edge ``index``: the synchroniser takes it at rising edge index + 1
        if glitch_at <= index < glitch_at + length - 1:
            inputs.pins.next = 1
        elif index >= edge_at:
            inputs.pins.next = 1
        else:
            inputs.pins.next = 0

    _run(f"input_filter_reaction_{samples}", input_filter, "input_filter", ports, False, step, 120)
    first = seen.index(1)
    # ``seen[i]`` is the state after rising edge i; the pin is taken at edge edge_at + 1
    assert first == edge_at + 1 + length + 1, (first, samples)
    assert all(seen[first:])


def _guard_inputs(rng, model, index, state, axes):
    if index % 200 == 0:
        limits = [regmap.limit_input(axis, positive) for axis in range(axes) for positive in (True, False)]
        state["active"] = rng.choice([0, 0, 1 << INPUT["ESTOP"],
                                      rng.randrange(1 << len(regmap.input_names(axes))) & ~1,
                                      1 << rng.choice(limits)])
    steps = tuple(rng.random() < 0.3 for _ in range(axes))
    dirs = tuple(rng.random() < 0.5 for _ in range(axes))
    load = rng.random() < 0.01
    if index % 300 == 0:
        state["ramp"] = rng.random() < 0.5
    return dict(active=state["active"], steps=steps, dirs=dirs, drive_request=rng.random() < 0.9,
                clear_stop=model.stopped and rng.random() < 0.05, watchdog_load=load,
                watchdog_timeout=rng.choice([0, 3, 40, 150]) if load else state.get("timeout", 0),
                ramp=state["ramp"], held=model.stopping and rng.random() < 0.1,
                pulsing=rng.random() < 0.4)


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
@pytest.mark.parametrize("axes,seed", BUILDS)
def test_machine_guard_against_model(axes, seed, cosim):
    """Every output every clock; on three axes a Z step towards Z's active limit stops with
    STOP_REASON.LIMITS's Z bit (the model's, from the docs' bit order)."""
    rng = random.Random(seed)
    ports = machine_guard_ports(axes)
    guard, request, granted = ports["guard"], ports["request"], ports["granted"]
    model = MachineGuardModel()
    reasons, decelerated, limits_seen = set(), set(), set()
    state = {"active": 0}

    def step(index):
        if index == 0:
            model.clock()
        for name in ("stopped", "stopping", "stop_event", "drive_enable"):
            assert bool(getattr(guard, name)) == getattr(model, name), f"{name} at clock {index}"
        for name in ("reason", "limits", "watchdog_left"):
            assert int(getattr(guard, name)) == getattr(model, name), f"{name} at clock {index}"
        reasons.add(model.reason)
        limits_seen.add(model.limits)
        given = _guard_inputs(rng, model, index, state, axes)
        state["timeout"] = given["watchdog_timeout"]
        guard.active.next = given["active"]
        for axis in range(axes):
            request.step(axis).next, request.dir(axis).next = given["steps"][axis], given["dirs"][axis]
        for name in ("drive_request", "clear_stop", "watchdog_load", "watchdog_timeout", "ramp", "held", "pulsing"):
            getattr(guard, name).next = given[name]
        pending[:] = [model.granted(given["active"], given["steps"], given["dirs"], given["ramp"]),
                      model.halt(given["active"])]
        was_stopping = model.stopping
        model.clock(**given)
        if was_stopping and model.stop_event:
            decelerated.add(model.reason)

    def check(index):
        wanted, halt = pending
        assert tuple(bool(granted.step(axis)) for axis in range(axes)) == wanted, f"granted at clock {index}"
        assert bool(guard.halt) == halt, f"halt at clock {index}"

    pending = []
    _run(f"machine_guard_{axes}_{seed}", machine_guard, "machine_guard", ports, cosim, step, 6000, check)
    assert reasons >= {REASON["NONE"], REASON["ESTOP"], REASON["WATCHDOG"], REASON["LIMIT"]}
    assert decelerated >= {REASON["WATCHDOG"], REASON["LIMIT"]}, "decelerated stops of both kinds"
    axis_limits = {1 << regmap.limit_bit(axis, positive) for axis in range(axes) for positive in (True, False)}
    assert axis_limits <= limits_seen, "a stop at each limit of every axis"
