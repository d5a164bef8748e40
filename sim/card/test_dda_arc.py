"""``rtl/dda_arc.py`` against the golden model on every clock, in MyHDL and in Icarus.

The same bench (``sim/card/dda_bench.py``) runs on the MyHDL block and on the
generated Verilog through co-simulation, for both builds of the variants
option: the card's default (``gen/dda_arc.v``; ``DDA_VERILOG_DIR`` names
another folder, e.g. a fresh ``python -m rtl.top --convert --out build/x``)
and ``all`` (converted for these tests into a folder under ``build/cosim``).  A command
for a variant its build left out must be rejected.  Each run writes a VCD and
a ``.gtkw`` under ``build/waves``; some checks read the VCD back.
"""
import functools
import math
import os
import random
from pathlib import Path

import pytest

from models.dda_build import ALL_VARIANTS, DEFAULT_VARIANTS, variants_choice
from models.dda_model import (IMPROVED, PAPER_V_ARC, PRECISE, TRADITIONAL, WEIGHTED, ArcCommand, LineCommand,
                              paper_configuration, setup_clocks, v_arc)
from rtl.convert import GEN_DIR, convert_unit
from rtl.dda_arc import dda_arc_ports
from sim.backends.conversions import converted
from sim.backends.waves import Waveform, run_traced
from sim.card.dda_bench import HALF_PERIOD, Record, accepted, dda_bench, end_point, random_arc, write_view

VERILOG_DIR = Path(os.environ.get("DDA_VERILOG_DIR", GEN_DIR))
BUILDS = {"default": DEFAULT_VARIANTS, "all": ALL_VARIANTS}

PAPER_CASES = [ArcCommand(8, 0, 0, 8, variant=v) for v in range(4)] + \
    [paper_configuration(v)[0] for v in (TRADITIONAL, WEIGHTED, IMPROVED)] + \
    [ArcCommand(100, 0, 0, 100)]
LINES = [LineCommand(12, 11), LineCommand(-5, 3), LineCommand(0, -4), LineCommand(7, 0, blend=True),
         LineCommand(0, 0), LineCommand(-9, -9)]
BAD = [ArcCommand(100, 0, 0, 103), ArcCommand(0, 0, 5, 5), ArcCommand(7, 7, 0, 0),
       ArcCommand(-(1 << 23), 0, 0, -(1 << 23)),
       ArcCommand(50, 0, 0, 50, variant=WEIGHTED, acc_bits=25, lambda_shift=5)]


def octant_arcs(seed, radius_limit=60):
    """One arc starting in each octant, in each direction, all variants in turn."""
    rng = random.Random(seed)
    arcs = []
    for octant in range(8):
        for ccw in (True, False):
            radius = rng.uniform(2, radius_limit)
            angle = (octant + rng.random()) * math.pi / 4
            span = rng.uniform(0.2, 1.8)
            arcs.append(_arc_at(rng, radius, angle, span, ccw, variant=(octant + ccw) % 4))
    return arcs


def _arc_at(rng, radius, angle, span, ccw, variant):
    for _ in range(50):
        end = angle + (span if ccw else -span)
        command = ArcCommand(round(radius * math.cos(angle)), round(radius * math.sin(angle)),
                             round(radius * math.cos(end)), round(radius * math.sin(end)), ccw,
                             variant, rng.randrange(4) if variant in (WEIGHTED, IMPROVED) else 0)
        if accepted(command):
            return command
        radius += 0.37
    return random_arc(rng, radius=radius, variant=variant, ccw=ccw)


def wide_arcs(seed, count):
    """Short arcs (a few dozen steps) at radii up to the 24-bit maximum, precise mode."""
    rng = random.Random(seed)
    arcs = []
    for index in range(count):
        radius = 2 ** rng.uniform(0, 23) if index else (1 << 23) - 2
        span = min(2 * math.pi, 40 / max(radius, 1))
        arcs.append(random_arc(rng, radius=radius, span=span, variant=PRECISE))
    return arcs


def full_circles():
    return [ArcCommand(1, 0, 1, 0), ArcCommand(0, -3, 0, -3, ccw=False),
            ArcCommand(6, 8, 6, 8, variant=IMPROVED, lambda_shift=2),
            ArcCommand(-12, 5, -12, 5, ccw=False, variant=PRECISE)]


def quadrant_crossings():
    return [ArcCommand(10, -1, -10, 1), ArcCommand(-3, 20, 3, -20, ccw=False, blend=True),
            ArcCommand(15, 1, 15, -1), ArcCommand(15, -1, 15, 1, ccw=False, variant=TRADITIONAL),
            ArcCommand(0, 30, 30, 0, variant=WEIGHTED, lambda_shift=1)]


def verilog_of(build):
    """The generated ``dda_arc.v`` of ``build``: ``gen/`` for the default, else a kept
    conversion (``sim/backends/conversions.py``)."""
    if BUILDS[build] == DEFAULT_VARIANTS:
        return VERILOG_DIR / "dda_arc.v"
    params = {"coord_width": 24, "variants": variants_choice(BUILDS[build])}
    return converted("dda_arc", repr(params), functools.partial(convert_unit, "dda_arc", params))


def run_bench(name, commands, cosim=False, seed=1, advance_rate=0.7, idle_gap=3, coord_width=24,
              overlap=False, alternate=False, build="default", trace=None):
    """Run the bench; return the record and the VCD path (None if untraced: ``trace`` as
    ``sim.backends.waves.run_traced`` takes it)."""
    ports = dda_arc_ports(coord_width=coord_width, variants=BUILDS[build])
    record = Record()
    verilog = [verilog_of(build)] if cosim else None
    bench = dda_bench(ports, commands, record, verilog=verilog, seed=seed, advance_rate=advance_rate,
                      idle_gap=idle_gap, overlap=overlap, alternate=alternate)
    vcd = run_traced(bench, name, trace=trace)
    if vcd is not None:
        write_view(vcd)
    return record, vcd


def check_moves(record, bad=BAD, variants=ALL_VARIANTS):
    """Independent of the model: accepted moves end on their end point, bad ones (and those
    for a variant the build left out) raise error."""
    for move in record.moves:
        command = move["command"]
        if isinstance(command, LineCommand):
            assert move["done"] and end_point(move) == (command.dx, command.dy)
        elif command in bad or command.variant not in variants:
            assert move["error"] and not move["steps"]
        else:
            assert move["done"] and not move["error"], command
            assert end_point(move) == (command.xe, command.ye), command


def sampled(wave, suffix, clocks):
    """Value of ``suffix`` in each clock (sampled at the falling edges)."""
    first_fall = wave.edges("clock", "0")
    return [wave.at(suffix, t) for t in first_fall[:clocks]]


BENCHES = {
    "paper": lambda: PAPER_CASES,
    "lines_and_bad": lambda: LINES + BAD,
    "octants": lambda: octant_arcs(7),
    "circles_crossings": lambda: full_circles() + quadrant_crossings(),
    "wide": lambda: wide_arcs(5, 8),
}


def _rtl_cases():
    """Every bench on the default build; on the build with all four variants the paper's
    arcs by default, the other benches (the same moves on the wider datapath) in the slow set."""
    wider = pytest.mark.slow(reason="the default build's bench again on the all-variants datapath")
    return [pytest.param(name, build, marks=[wider] if build == "all" and name != "paper" else [])
            for build in sorted(BUILDS) for name in sorted(BENCHES)]


@pytest.mark.parametrize("name,build", _rtl_cases())
def test_rtl_equals_model_on_every_clock(name, build):
    # overlapped commands (each started as soon as the setup stage is free) in two benches;
    # the default build rejects the commands for the paper's traditional and weighted variants
    overlap = name in ("lines_and_bad", "circles_crossings")
    record, _ = run_bench(f"dda_{name}_{build}", BENCHES[name](), overlap=overlap, build=build)
    check_moves(record, variants=BUILDS[build])


@pytest.mark.parametrize("build, name", [("default", "paper"), ("default", "lines_and_bad"),
                                         ("default", "circles_crossings"), ("default", "wide"),
                                         ("all", "paper"), ("all", "octants")])
def test_generated_verilog_equals_model_on_every_clock(name, build):
    record, _ = run_bench(f"dda_{name}_{build}_cosim", BENCHES[name](), cosim=True,
                          overlap=name == "lines_and_bad", build=build)
    check_moves(record, variants=BUILDS[build])


CHAIN = [ArcCommand(100, 0, 0, 100, blend=True), ArcCommand(0, 100, -100, 0), LineCommand(120, -50),
         ArcCommand(-100, 0, 0, -100), ArcCommand(0, -100, 103, 0), LineCommand(5, 5)]
CHAIN_BAD = [ArcCommand(0, -100, 103, 0)]


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
def test_chained_moves_leave_no_gap(cosim):
    """Arc after arc, line after arc, arc after line at the fastest feed rate (advance
    every other clock): each move is set up while the one before runs, and its first
    iteration comes two clocks after the last one of the move before; a rejected arc
    started while an arc runs raises error only after that arc's done."""
    record, _ = run_bench("dda_chain" + ("_cosim" if cosim else ""), CHAIN, cosim=cosim,
                          overlap=True, alternate=True)
    check_moves(record, bad=CHAIN_BAD)
    moves = record.moves
    for before, after in zip(moves[:3], moves[1:4]):
        assert after["start_clock"] < before["done_clock"]
        assert after["ticks"][0] - before["ticks"][-1] == 2
        assert after["ticks"][0] == before["done_clock"] + 2
    # the line's every iteration steps its major axis: its pulses show the ticks
    assert [s[0] for s in moves[2]["steps"]] == moves[2]["ticks"]
    assert moves[4]["error_clock"] == moves[3]["done_clock"] + 1
    assert moves[5]["start_clock"] >= moves[4]["error_clock"]


def device_points(move):
    """Start point and the point after each step pulse of the device."""
    command = move["command"]
    x, y = command.xs, command.ys
    points = [(x, y)]
    for _, step_x, step_y, dir_x, dir_y in move["steps"]:
        x += (1 if dir_x else -1) * step_x
        y += (1 if dir_y else -1) * step_y
        points.append((x, y))
    return points


def test_device_reproduces_the_paper_and_the_accuracy_target():
    """V_arc of the device's own step pulses (the ``all`` build): the paper's figure 6 (eq. 13)
    and the precise target."""
    traditional = paper_configuration(TRADITIONAL)[0]
    record, _ = run_bench("dda_accuracy", [traditional, ArcCommand(100, 0, 0, 100)], advance_rate=0.5,
                          build="all")
    paper_move, precise_move = record.moves
    assert v_arc(device_points(paper_move), 100) == pytest.approx(PAPER_V_ARC[TRADITIONAL], rel=0.01)
    points = device_points(precise_move)
    assert v_arc(points, 100) <= 0.10
    assert max(abs(math.hypot(x, y) - 100) for x, y in points) <= 0.75


NARROW_BAD = [ArcCommand(511, 40, 40, 511), ArcCommand(-512, 0, 0, -512)]


def test_narrow_width_up_to_the_largest_radius():
    """10-bit coordinates: radii 1 .. 511 (the largest), and radii that do not fit."""
    rng = random.Random(11)
    commands = [ArcCommand(511, 0, 511, 0, ccw=False), ArcCommand(1, 0, 0, 1), ArcCommand(0, -1, 0, -1)]
    commands += [random_arc(rng, coord_width=10, radius=rng.uniform(400, 511), span=0.05) for _ in range(3)]
    commands += [LineCommand(-512, 511)] + NARROW_BAD
    record, _ = run_bench("dda_narrow", commands, coord_width=10, advance_rate=0.9)
    check_moves(record, bad=NARROW_BAD)


def test_line_pulses_read_back_from_the_vcd():
    # advance in every clock: an iteration takes two, so the X pulses come every other clock
    record, vcd = run_bench("dda_line_12_11", [LineCommand(12, 11)], advance_rate=1.0, trace=True)
    wave = Waveform(vcd)
    clocks = record.clocks
    for suffix, total in (("steps_step_x", 12), ("steps_step_y", 11)):
        values = sampled(wave, suffix, clocks + 2)
        high = [i for i, v in enumerate(values) if v == "1"]
        assert len(high) == total
        gaps = [b - a for a, b in zip(high, high[1:])]
        assert all(gap % 2 == 0 for gap in gaps)
        assert max(gaps) - min(gaps) <= 2
    done = [i for i, v in enumerate(sampled(wave, "cmd_done", clocks + 2)) if v == "1"]
    assert len(done) == 1


def test_arc_setup_time_and_steps_read_back_from_the_vcd():
    command = ArcCommand(8, 0, 0, 8)
    record, vcd = run_bench("dda_arc_8", [command], advance_rate=1.0, trace=True)
    wave = Waveform(vcd)
    busy = sampled(wave, "cmd_busy", record.clocks + 2)
    step_y = sampled(wave, "steps_step_y", record.clocks + 2)
    first_busy = busy.index("1")
    first_step = min(i for i, v in enumerate(step_y) if v == "1")
    # the first iteration comes one clock after the setup (setup_clocks from the start edge)
    assert first_step - first_busy == setup_clocks(24, line=False) + 1
    assert sum(v == "1" for v in step_y) == 8
    assert wave.at("cmd_quadrant", record.clocks * 2 * HALF_PERIOD) == 0


@pytest.mark.slow(reason="long random arcs: more of what the default benches check on every clock")
@pytest.mark.parametrize("seed", range(4))
def test_rtl_random_arcs_long(seed):
    rng = random.Random(seed)
    commands = octant_arcs(seed + 100, radius_limit=400) + wide_arcs(seed + 200, 20)
    commands += [random_arc(rng, radius=rng.uniform(1, 200), variant=rng.randrange(4)) for _ in range(20)]
    build = sorted(BUILDS)[seed % 2]
    record, _ = run_bench(f"dda_random_{seed}", commands, seed=seed, build=build)
    check_moves(record, variants=BUILDS[build])


@pytest.mark.slow(reason="long random arcs in Icarus: more of what the default co-simulation checks")
@pytest.mark.parametrize("build", sorted(BUILDS))
def test_generated_verilog_random_arcs_long(build):
    seed = sorted(BUILDS).index(build)
    commands = octant_arcs(seed + 300) + wide_arcs(seed + 400, 10) + BENCHES["paper"]()
    record, _ = run_bench(f"dda_random_cosim_{build}", commands, cosim=True, seed=seed, build=build)
    check_moves(record, variants=BUILDS[build])
