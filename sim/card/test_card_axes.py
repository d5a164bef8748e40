"""The card of N axes (``rtl/card_core.py`` of ``--axes N``) reading the N-axis
command forms (docs/axes.md) over its back-end bus.

Golden values: the paths of ``models.dda_axes.iterate_axes`` (chained, per
axis), the framing of ``models.instructions.split_words`` (a refused
command's operands are skipped, the next command runs), the RANGE rules of
docs/axes.md.  The pins of every axis are captured, so an axis stepping
when it should not shows.
"""
from dataclasses import replace

import pytest
from myhdl import block, instance

from models import instructions as isa
from models import registers as regmap
from models.axes import PLANES
from models.commands import PulseCommand, command_words, decode_words
from models.dda_axes import check_move, check_pulse, with_area
from models.dda_plan import ArcCommand, AxesLineCommand
from models.parameters import Build
from rtl.card_core import card_core, card_core_ports
from sim.backends.clocking import clock_source
from sim.backends.icarus import convert_and_cosimulate
from sim.backends.waves import run_traced
from sim.card.card_bench import FIFO_DEPTH, HALF_PERIOD, axes_path, scenario_runner, wait_error, wait_idle
from sim.card.local_bus_driver import LocalBusDriver

G17, G18, G19 = PLANES[17], PLANES[18], PLANES[19]


@block
def axis_capture(clock, pins, axes, points):
    """Append the position after every clock in which a STEP pin rises (DIR high: positive)."""

    @instance
    def capture():
        before = [False] * axes
        while True:
            yield clock.negedge
            now = [bool(pins.step(a)) for a in range(axes)]
            rises = [n and not b for n, b in zip(now, before)]
            if any(rises):
                here = list(points[-1])
                for axis, rise in enumerate(rises):
                    if rise:
                        here[axis] += 1 if pins.dir(axis) else -1
                points.append(tuple(here))
            before = now

    return capture


@block
def _bench(ports, build, scenario, points, cosim):
    clock = ports["clock"]
    core = (convert_and_cosimulate(card_core, "card_core", ports, build=build) if cosim
            else card_core(**ports, build=build))
    return (core, clock_source(clock, 2 * HALF_PERIOD), axis_capture(clock, ports["pins"], build.axes, points),
            scenario_runner(clock, ports["reset"], LocalBusDriver(clock, ports["local"]), scenario))


def run_axes(name, axes, scenario, cosim=False):
    """Run ``scenario(driver)`` on the core of ``axes`` axes; the points its pins visited."""
    build = Build(fifo_depth=FIFO_DEPTH, axes=axes)
    points = [(0,) * axes]
    run_traced(_bench(card_core_ports(axes), build, scenario, points, cosim), name)
    return points


def start(driver):
    yield from driver.io_write(regmap.offset("FEED_RATE"), regmap.RATE_MAX)
    yield from driver.io_write(regmap.offset("CONTROL"), 1)


def motion(words, results):
    def scenario(driver):
        yield from start(driver)
        yield from driver.push_all(words)
        results["status"] = yield from wait_idle(driver)

    return scenario


def line(*deltas, blend=False):
    return AxesLineCommand(tuple(deltas), blend=blend)


def test_two_axis_card_takes_one_axis_lines_and_refuses_the_reversed_plane():
    # LINE.AXES of X alone, Y alone, X and Y; an arc with U_AXIS, V_AXIS = X, Y; an arc in the
    # plane (Y, X): RANGE on two axes (docs/axes.md), the arc after it runs once the error is cleared
    moves = [line(5, 0), line(0, -3), line(4, 2, blend=True), ArcCommand(10, 0, 0, 10), ArcCommand(0, 10, 10, 0)]
    words = (isa.encode("LINE", 5, AXES=0b01) + isa.encode("LINE", -3, AXES=0b10)
             + isa.encode("LINE", 4, 2, AXES=0b11, BLEND=1) + isa.encode("ARC", 10, 0, 0, 10, CCW=1, VARIANT=3,
                                                                         U_AXIS=0, V_AXIS=1))
    reversed_plane = isa.encode("ARC", 10, 0, 0, 10, CCW=1, VARIANT=3, U_AXIS=1, V_AXIS=0)
    results = {}

    def scenario(driver):
        yield from start(driver)
        yield from driver.push_all(words + reversed_plane + command_words(moves[4]))
        results["error"] = yield from wait_error(driver, 400)
        yield from driver.io_write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", CLEAR_ERROR=1))
        results["status"] = yield from wait_idle(driver)

    points = run_axes("card_axes_two", 2, scenario)
    assert results["error"] == isa.ERROR_CODE["RANGE"]
    assert points == axes_path(moves, 2)
    assert regmap.field_value("STATUS", "ERROR", results["status"]) == 0


# a command the card of three axes refuses (RANGE), as words; each is framed by the N-axis form
REFUSED = {
    "line_axis_beyond": isa.encode("LINE", 1, 2, 3, 4, AXES=0b1111),
    "line_too_wide": isa.encode("LINE", 1, 1 << 23, AXES=0b101),
    "plane_axis_beyond": isa.encode("ARC", 10, 0, 0, 10, U_AXIS=3, V_AXIS=0),
    "plane_one_axis": isa.encode("ARC", 10, 0, 0, 10, U_AXIS=2, V_AXIS=2),
    "helix_on_plane": isa.encode("ARC", 10, 0, 0, 10, 160, 0, 5, HELIX=0b010),
    "helix_axis_beyond": isa.encode("ARC", 10, 0, 0, 10, 160, 0, 5, HELIX=0b1000),
    "helix_area_zero": isa.encode("ARC", 10, 0, 0, 10, 0, 0, 5, HELIX=0b100),
    # AREA_HI's bit 17: AREA's bit 49, beyond its 49 bits on 24-bit coordinates
    "helix_area_too_wide": isa.encode("ARC", 0, 10, 10, 0, 160, 1 << 17, -17, U_AXIS=2, V_AXIS=0, HELIX=0b010),
    "pulse_axis_beyond": isa.encode("PULSE", 3, 4, AXES=0b1001),
}


@pytest.mark.parametrize("cases", [["line_axis_beyond", "plane_one_axis", "helix_on_plane", "helix_area_too_wide"],
                                   ["line_too_wide", "plane_axis_beyond", "pulse_axis_beyond", "helix_area_zero",
                                    "helix_axis_beyond"]])
def test_three_axis_card_refuses_what_it_cannot_run_and_frames_the_rest(cases):
    # the golden model refuses each of them too (models.dda_axes.check_move)
    for case in cases:
        if not case.startswith("pulse"):
            with pytest.raises(ValueError):
                check_move(decode_words(REFUSED[case])[0], axes=3)
    good = line(2, 1, -3)
    results = {}

    def scenario(driver):
        yield from start(driver)
        for case in cases:
            yield from driver.push_all(command_words(good) + REFUSED[case] + command_words(good))
            results[case] = yield from wait_error(driver, 400)
            yield from driver.io_write(regmap.offset("COMMAND"), regmap.field_of("COMMAND", CLEAR_ERROR=1))
            yield from wait_idle(driver)

    points = run_axes("card_axes_refused", 3, scenario)
    assert results == {case: isa.ERROR_CODE["RANGE"] for case in cases}
    # each refused command stopped the stream after the good one before it; the one after it ran
    assert points == axes_path([good] * 2 * len(cases), 3)


MOVES_3D = [line(30, -12, 20, blend=True), ArcCommand(20, 0, 0, 20, plane=G18, blend=True),
            line(-7, 25, -40), ArcCommand(0, -15, 15, 0, ccw=False, plane=G19), line(0, 0, 9),
            ArcCommand(12, 0, 12, 0, plane=(2, 1))]


@pytest.mark.parametrize("cosim", [False, True], ids=["myhdl", "icarus"])
def test_three_axis_card_runs_3d_lines_and_arcs_in_every_plane(cosim):
    results = {}
    words = [word for move in MOVES_3D for word in command_words(move)]
    points = run_axes(f"card_axes_3d_{'icarus' if cosim else 'myhdl'}", 3, motion(words, results), cosim)
    assert points == axes_path(MOVES_3D, 3)
    assert regmap.field_value("STATUS", "ERROR", results["status"]) == 0


# helices: G17 rising on Z, G18 on Y, G19 falling on X, chained (BLEND) and not; the last one's
# AREA a third too large, so that its Z goes on after the arc
HELICES = [with_area(ArcCommand(20, 0, 0, 20, plane=G17, helix=(0, 0, 9), blend=True)),
           with_area(ArcCommand(0, 15, 15, 0, ccw=False, plane=G18, helix=(0, -12, 0), blend=True)),
           line(3, -4, 5),
           with_area(ArcCommand(12, 0, -12, 0, plane=G19, helix=(-20, 0, 0))),
           replace(with_area(ArcCommand(10, 0, 0, 10, helix=(0, 0, 7))), area=210)]


@pytest.mark.slow(reason="the whole core with helices in three planes: the end-to-end short scenario runs two "
                         "helices on the card by default (MyHDL, Icarus, Verilator), the chain bench wrong AREA")
def test_three_axis_card_runs_helices_in_every_plane():
    results = {}
    words = [word for move in HELICES for word in command_words(move)]
    points = run_axes("card_axes_helices", 3, motion(words, results))
    assert points == axes_path(HELICES, 3)
    assert regmap.field_value("STATUS", "ERROR", results["status"]) == 0


# PULSE on any of the card's axes: Z alone, X and Z, the two-axis form (X, Y), Y alone
PULSES = [PulseCommand((0, 0, 5)), PulseCommand((-3, 0, 4)), PulseCommand((2, -2)), PulseCommand((0, 3, 0))]


def test_three_axis_card_pulses_any_axis_mask():
    results = {}
    words = [word for pulse in PULSES for word in command_words(pulse)]
    points = run_axes("card_axes_pulses", 3, motion(words, results))
    # golden: the counts as the decoder reads the stream (models.commands), axis by axis, one step a point
    commands = decode_words(words)
    assert [c.counts for c in commands] == [(0, 0, 5), (-3, 0, 4), (2, -2), (0, 3)]
    for axis in range(3):
        moves = [b[axis] - a[axis] for a, b in zip(points, points[1:]) if b[axis] != a[axis]]
        wanted = [step for c in commands for count in [c.counts[axis] if axis < len(c.counts) else 0]
                  for step in [1 if count > 0 else -1] * abs(count)]
        assert moves == wanted, f"axis {axis}"
    assert regmap.field_value("STATUS", "ERROR", results["status"]) == 0


# PULSE with a one-axis mask on the card of two axes: X alone, Y alone, then both in the N-axis form
TWO_AXIS_PULSES = (isa.encode("PULSE", 4, AXES=0b01) + isa.encode("PULSE", -3, AXES=0b10)
                   + isa.encode("PULSE", -2, 5, AXES=0b11))


@pytest.mark.parametrize("cosim", [
    pytest.param(False, id="myhdl"),
    pytest.param(True, id="icarus", marks=pytest.mark.slow(reason="the generated Verilog of the same scenario (10 s): "
                                                                  "the default suite is at its ten minutes"))])
def test_two_axis_card_pulses_any_mask_of_its_axes(cosim):
    # golden: the counts as the decoder reads the stream (models.commands), which the model of
    # the card's RANGE rules takes on two axes (models.dda_axes.check_pulse)
    commands = decode_words(TWO_AXIS_PULSES)
    assert [check_pulse(c.counts, axes=2) for c in commands] == [(4, 0), (0, -3), (-2, 5)]
    results = {}
    points = run_axes(f"card_axes_two_pulses_{'icarus' if cosim else 'myhdl'}", 2,
                      motion(TWO_AXIS_PULSES, results), cosim)
    assert regmap.field_value("STATUS", "ERROR", results["status"]) == 0
    for axis in range(2):
        moves = [b[axis] - a[axis] for a, b in zip(points, points[1:]) if b[axis] != a[axis]]
        wanted = [step for c in commands for step in [1 if c.counts[axis] > 0 else -1] * abs(c.counts[axis])]
        assert moves == wanted, f"axis {axis}"
