"""The card's small units against their golden models (``models/card_model.py``), every clock.

Each bench drives seeded random inputs at the falling edge, advances the model
by the coming rising edge, and at the next falling edge compares every output.
The same bench runs on the MyHDL block and on its Verilog in Icarus.
"""
import random

import pytest
from myhdl import block

from models.card_model import DirectPulseModel, FeedRateModel, FifoModel, PulseOutModel
from models.registers import RATE_MAX, RATE_ONE
from rtl.interfaces import LocalBus, axis_suffixes
from rtl.regs.direct_pulse import direct_pulse, direct_pulse_ports
from rtl.regs.feed_rate import feed_rate, feed_rate_ports
from rtl.regs.pulse_out import pulse_out, pulse_out_ports
from rtl.regs.sync_fifo import sync_fifo, sync_fifo_ports
from sim.backends.clocking import clock_source, reset_then_step
from sim.backends.icarus import convert_and_cosimulate
from sim.backends.waves import Waveform, run_traced, write_gtkw

HALF_PERIOD = 5
ROOM_PLACES = LocalBus.ROOM_PLACES


def _dut(factory, module, ports, cosim, **params):
    """What the bench needs to make the device under test (MyHDL or Icarus)."""
    return factory, module, params, cosim


@block
def _bench(dut_spec, ports, step, cycles):
    """Clock, reset, then ``step(clock_index)`` at every falling edge."""
    clock, reset = ports["clock"], ports["reset"]
    factory, module, params, cosim = dut_spec
    if cosim:
        dut = convert_and_cosimulate(factory, module, ports, **params)
    else:
        dut = factory(**ports, **params)

    clock_gen = clock_source(clock, 2 * HALF_PERIOD)

    stimulus = reset_then_step(clock, reset, cycles, step)

    return dut, clock_gen, stimulus


def _run(name, dut, ports, step, cycles, groups):
    """Run traced; the MyHDL run also gets a GTKWave save file (a co-simulated
    block has no MyHDL hierarchy for the trace to show)."""
    vcd = run_traced(_bench(dut, ports, step, cycles), name, trace=True)
    cosim = dut[3]
    if not cosim:
        write_gtkw(vcd, groups)
    return Waveform(vcd), cosim


# the chance an axis steps in a clock that wants steps, and that its direction is positive
STEP_CHANCES, DIR_CHANCES = (0.7, 0.5, 0.6, 0.4, 0.3, 0.5), (0.7, 0.4, 0.5, 0.6, 0.5, 0.3)


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
@pytest.mark.parametrize("seed, axes", [(1, 2), (2, 2), (3, 3)])
def test_pulse_out_timing(seed, axes, cosim):
    """Random steps and settings (STEP_WIDTH, STEP_SPACE, DIR_SETUP, DIR_HOLD,
    DIR_POLARITY, and STEP_MODE: step/dir, up/down, quadrature, changed with
    the queue empty as docs/registers.md asks) against the model every clock,
    on the pulse outputs of two axes and of three (every axis's pins and
    position: the queue and the timing are shared, the pins per axis)."""
    rng = random.Random(seed)
    ports = pulse_out_ports(axes=axes)
    request, control, pins, position = ports["request"], ports["control"], ports["pins"], ports["position"]
    model = PulseOutModel(axes=axes)
    timing = {}
    rises, pulses = [], []   # rises of the STEP_X pin; X pulses, by the mode they left in
    every = range(axes)

    def step(index):
        if index == 0:
            model.clock()  # the first edge after reset, inputs idle
        assert tuple(bool(pins.step(a)) for a in every) == model.step_pins, f"STEP at clock {index}"
        assert tuple(bool(pins.dir(a)) for a in every) == model.dir_pins, f"DIR at clock {index}"
        assert [int(position.of(a)) for a in every] == model.positions, f"clock {index}"
        assert bool(control.ready) == model.ready and bool(control.active) == model.active
        if index % 300 == 0:
            timing.update(width=rng.randint(1, 4), space=rng.randint(1, 6), setup=rng.randint(1, 4),
                          hold=rng.randint(1, 4))
            timing["polarity"] = tuple(rng.random() < 0.5 for _ in every)
        if index % 300 == 20:   # the queue has run empty (no requests since 280)
            timing["mode"] = (index // 300 + seed) % 3
        wanted = model.ready and rng.random() < 0.6 and index % 300 < 280
        steps = tuple(wanted and rng.random() < chance for chance in STEP_CHANCES[:axes])
        dirs = tuple(rng.random() < chance for chance in DIR_CHANCES[:axes])
        flags = dict(clear=rng.random() < 0.005, clear_position=rng.random() < 0.003)
        for axis in every:
            request.step(axis).next, request.dir(axis).next = steps[axis], dirs[axis]
        for key, value in dict(flags, **timing).items():
            if key == "polarity":
                for axis in every:
                    control.polarity(axis).next = value[axis]
            else:
                getattr(control, key).next = value
        was_high, pulse_before = model.step_pins[0], model.pulses[0]
        model.clock(steps, dirs, **flags, **timing)
        if model.step_pins[0] and not was_high:
            rises.append(index)
        if model.pulses[0] and not pulse_before:
            pulses.append(timing.get("mode", 0))

    # the MyHDL trace names each axis's pins in its instance axis_x, axis_y, ... (rtl/regs/pulse_out.py)
    axis_pins = [f"axis_{suffix}.{name}" for suffix in axis_suffixes(axes) for name in ("pin_step", "pin_dir")]
    wave, cosim = _run(f"pulse_out_{seed}_{axes}_{'icarus' if cosim else 'myhdl'}",
                       _dut(pulse_out, "pulse_out", ports, cosim), ports, step, 1200,
                       {"request": ["request_steps", "request_dirs", "control_ready"],
                        "pins": [*axis_pins, "axis_x.position"]})
    assert all(pulses.count(mode) > 20 for mode in range(3)), "every STEP_MODE carried steps"
    if not cosim:
        assert len(wave.edges("axis_x.pin_step", "1")) == len(rises)


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
def test_feed_rate_ramp(cosim):
    """Random settings, holds, feed holds and moves; ``stop_left`` counts the
    ticks down like a DDA (sometimes a clock late, sometimes blending: all ones)."""
    rng = random.Random(7)
    ports = feed_rate_ports()
    ramp, feed = ports["settings"], ports["feed"]
    model = FeedRateModel()
    ticks, paused, left = [], [], {"count": None, "late": False, "pause": False}
    all_ones = (1 << len(feed.stop_left)) - 1

    def step(index):
        assert bool(feed.tick) == model.tick, f"tick at clock {index}"
        assert bool(feed.held) == model.held, f"held at clock {index}"
        ticks.append(model.tick)
        paused.append(model.held)
        if rng.random() < 0.01:
            left["pause"] = not left["pause"]
        if index % 400 == 0:
            settings = dict(target=rng.choice([1, 3000, 20000, RATE_MAX]), ramp_start=rng.randint(1, RATE_MAX),
                            ramp_step=rng.choice([0, 1, 500, 9000]))
            if index % 1200 == 800:  # a SET during the move
                settings["target"] = rng.randint(1, RATE_MAX)
            step.settings = settings
            left.update(count=rng.choice([None, rng.randint(20, 300)]), late=rng.random() < 0.5)
        if index % 400 == 200:
            ramp.target.next = step.settings["target"]
        if index % 400 < 2:
            for key, value in step.settings.items():
                getattr(ramp, key).next = value
        inputs = dict(run=index % 400 > 5, hold=rng.random() < 0.1,
                      target=int(ramp.target.next), ramp_start=int(ramp.ramp_start.next),
                      ramp_step=int(ramp.ramp_step.next),
                      stop_left=all_ones if left["count"] is None else left["count"], pause=left["pause"])
        feed.run.next = inputs["run"]
        feed.pause.next = inputs["pause"]
        feed.hold.next = inputs["hold"]
        feed.stop_left.next = inputs["stop_left"]
        model.clock(**inputs)
        if left["count"] and model.tick and not left["late"]:
            left["count"] -= 1
        elif left["count"] and ticks[-1] and left["late"]:
            left["count"] -= 1

    _run(f"feed_rate_{'icarus' if cosim else 'myhdl'}", _dut(feed_rate, "feed_rate", ports, cosim),
         ports, step, 4800, {"feed": ["feed_run", "feed_hold", "feed_pause", "settings_target", "feed_stop_left",
                                      "feed_tick", "feed_held"]})
    assert sum(ticks) > 400
    assert 0.1 < sum(paused) / len(paused) < 0.6, "the feed holds and resumes often"


def _model_intervals(iterations, target, ramp_start, ramp_step, late):
    """Clocks between the ticks of a move of ``iterations`` on ``FeedRateModel``,
    ``stop_left`` counted down on each tick (``late``: one clock after it)."""
    model, left, times, clock = FeedRateModel(), iterations, [], 0
    settings = dict(target=target, ramp_start=ramp_start, ramp_step=ramp_step)
    model.clock(run=False, hold=False, **settings)
    model.clock(run=False, hold=False, **settings)
    pending = False
    while left:
        clock += 1
        model.clock(run=True, hold=False, stop_left=left, **settings)
        if pending:
            left, pending = left - 1, False
        if model.tick:
            times.append(clock)
            if late:
                pending = True
            else:
                left -= 1
    return [b - a for a, b in zip([0] + times, times)]


@pytest.mark.parametrize("late", [False, True], ids=["fresh", "late"])
@pytest.mark.parametrize("iterations, target, ramp_start, ramp_step", [
    (400, RATE_MAX, 2048, 700), (400, 20000, 1000, 3000), (60, RATE_MAX, 1000, 500), (9, 30000, 5000, 9000)])
def test_feed_rate_model_is_a_trapezoid(iterations, target, ramp_start, ramp_step, late):
    """The spec of the ramp, on the model: intervals shrink, stay, grow back,
    the first and the last are those of RAMP_START, and the deceleration
    mirrors the acceleration (within the margin of two iterations)."""
    gaps = _model_intervals(iterations, target, ramp_start, ramp_step, late)
    assert len(gaps) == iterations
    start_gap = RATE_ONE / ramp_start
    # the phase left by the faster tick before it can shorten the last interval by up to step/start
    assert abs(gaps[0] - start_gap) <= 1 and abs(gaps[-1] - start_gap) <= 1 + ramp_step / ramp_start, \
        (gaps[:3], gaps[-3:])
    fastest = min(gaps)
    low = gaps.index(fastest)
    high = len(gaps) - 1 - gaps[::-1].index(fastest)
    # dithering of the phase accumulator: one clock either way
    assert all(b <= a + 1 for a, b in zip(gaps[:low], gaps[1:low + 1])), "not shrinking"
    assert all(b >= a - 1 for a, b in zip(gaps[high:], gaps[high + 1:])), "not growing back"
    if fastest <= RATE_ONE / target + 1 and iterations > 100:
        assert all(abs(g - fastest) <= 1 for g in gaps[low:high + 1]), "not steady at FEED_RATE"
    up = sum(1 for g in gaps[:len(gaps) // 2] if g > fastest + 1)
    down = sum(1 for g in gaps[len(gaps) // 2:] if g > fastest + 1)
    assert abs(up - down) <= 3, (up, down)


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
def test_direct_pulse_counts(cosim):
    rng = random.Random(3)
    ports = direct_pulse_ports()
    command, out = ports["command"], ports["out"]
    model = DirectPulseModel()

    def step(index):
        assert bool(out.step) == model.request, f"request at clock {index}"
        assert int(command.remaining) == model.remaining
        if model.request:
            assert bool(out.dir) == model.direction
        # retarget: homing's back-off, the count changed under way, its timing kept
        inputs = dict(load=model.remaining == 0 and rng.random() < 0.1,
                      count=rng.randint(-20, 20), period=rng.randint(1, 5),
                      ready=rng.random() < 0.8, clear=rng.random() < 0.003)
        inputs["retarget"] = not inputs["load"] and rng.random() < 0.03
        assert bool(command.busy) == model.busy(bool(command.load))
        for key, value in inputs.items():
            getattr(out if key == "ready" else command, key).next = value
        model.clock(**inputs)

    _run(f"direct_pulse_{'icarus' if cosim else 'myhdl'}", _dut(direct_pulse, "direct_pulse", ports, cosim),
         ports, step, 1500, {"direct": ["command_load", "command_retarget", "command_count", "command_period",
                                        "out_step", "command_remaining"]})


# output_register: the ECP5 build's FIFO, dout a fabric flip-flop loaded from the RAM's head word
# or, for a word written where the head is read, from din registered: the same words at the same clocks
@pytest.mark.parametrize("output_register", [False, True], ids=["ram_dout", "fabric_dout"])
@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
def test_sync_fifo_against_queue(cosim, output_register):
    rng = random.Random(5)
    depth = 16
    ports = sync_fifo_ports(depth=depth)
    model = FifoModel(depth)

    def step(index):
        assert int(ports["level"]) == model.level, f"level at clock {index}"
        assert bool(ports["full"]) == model.full and bool(ports["empty"]) == (model.level == 0)
        assert bool(ports["room"]) == model.room(ROOM_PLACES), f"room at clock {index}"
        assert int(ports["dout"]) == model.dout, f"dout at clock {index}"
        burst = (index // 100) % 2
        inputs = dict(push=rng.random() < (0.8 if burst else 0.3), din=rng.getrandbits(32),
                      pop=rng.random() < (0.3 if burst else 0.8), flush=rng.random() < 0.005)
        for key, value in inputs.items():
            ports[key].next = value
        model.clock(**inputs)

    _run(f"sync_fifo_{'fabric_' if output_register else ''}{'icarus' if cosim else 'myhdl'}",
         _dut(sync_fifo, "sync_fifo", ports, cosim, depth=depth, output_register=output_register), ports, step, 1000,
         {"fifo": ["push", "din", "pop", "dout", "level", "full", "empty", "room"]})
