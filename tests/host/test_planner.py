"""Planner: rounding, arcs onto the lattice, feed and ramps, BLEND, the stream.

The planner's words are decoded here and run through the DDA's golden model
(``models.dda_model``); the path is measured against the ideal geometry
(``host.geometry``) and the rounding against ``floor(x * k + 0.5)``.
"""
import math
import random

import pytest

from host.errors import ProgramError
from host.gcode import parse
from host.geometry import Arc, Dwell, Line
from host.machine import Machine
from host.planner import plan
from models.card_model import FeedRateModel
from models.dda_model import ArcCommand, LineCommand, LineIterator, iterate, plan_arc
from models.instructions import BY_CODE, OPCODE_LSB
from models.registers import RATE_ONE, SET_TARGETS

ROUNDING = math.sqrt(2) / 2  # a point rounded to the nearest lattice point moves this far at most


def signed(word):
    return word - (1 << 32) if word >> 31 else word


def decode(words):
    """[(name, header word, operands)] of a word stream, read from the encoding table."""
    commands, i = [], 0
    while i < len(words):
        op = BY_CODE[words[i] >> OPCODE_LSB]
        operands = [signed(w) for w in words[i + 1:i + 1 + len(op.operands)]]
        commands.append((op.name, words[i], operands))
        i += 1 + len(op.operands)
    return commands


def model_command(name, header, operands):
    blend = bool(header >> 16 & 1)
    if name == "LINE":
        return LineCommand(*operands, blend=blend)
    return ArcCommand(*operands, ccw=bool(header & 1), variant=header >> 1 & 3, blend=blend)


def model_moves(planned):
    """[(entry, absolute step points)] of every LINE/ARC, from the words through the model."""
    decoded = decode(planned.words())
    assert len(decoded) == len(planned.entries)
    position, result = (0, 0), []
    for entry, (name, header, operands) in zip(planned.entries, decoded):
        if name not in ("LINE", "ARC"):
            continue
        command = model_command(name, header, operands)
        if name == "ARC":
            plan_arc(command)  # the card's acceptance rule: raises if refused
            origin = (position[0] - command.xs, position[1] - command.ys)
        else:
            origin = position
        points = [(origin[0] + x, origin[1] + y) for x, y in iterate(command).points()]
        assert points[0] == position
        position = points[-1]
        result.append((entry, points))
    return result


def nearest(value):
    return math.floor(value + 0.5)


def deviation_steps(planned, moves):
    """Largest distance (steps) of a model path point from its primitive."""
    machine = planned.machine
    k = machine.steps_per_mm[0]
    return max(planned.drawing[entry.primitive].distance((x / k, y / k)) * k
               for entry, points in moves for x, y in points)


def ends_per_primitive(planned, moves):
    """{primitive index: step position after its last command}."""
    return {entry.primitive: points[-1] for entry, points in moves}


@pytest.mark.parametrize("segments", [10_000, 100_000])
def test_rounding_is_carried_forward_over_many_segments(segments):
    rng = random.Random(2024)
    machine = Machine(steps_per_mm=(80.0, 123.4567))
    drawing, here = [], (0.0, 0.0)
    for number in range(segments):
        there = (here[0] + rng.uniform(-0.3, 0.3), here[1] + rng.uniform(-0.05, 0.05))
        drawing.append(Line(here, there, 600.0, f"seg{number}"))
        here = there
    planned = plan(drawing, machine)
    x = y = 0
    position_after = {}
    for entry, (name, _, operands) in zip(planned.entries, decode(planned.words())):
        if name == "LINE":
            x, y = x + operands[0], y + operands[1]
            position_after[entry.primitive] = (x, y)
    expected = [(nearest(p.end[0] * 80.0), nearest(p.end[1] * 123.4567)) for p in drawing]
    assert (x, y) == expected[-1]
    last = (0, 0)
    for index, end in enumerate(expected):
        last = position_after.get(index, last)
        assert last == end, f"segment {index} ends at {last}, not on its rounded end {end}"


def random_arc(rng, number):
    """A LinuxCNC-accepted arc: circle, near-limit spiral, full circle, any sweep."""
    radius = rng.choice([rng.uniform(0.1, 2), rng.uniform(2, 20), rng.uniform(20, 60)])
    centre = (rng.uniform(-40, 40), rng.uniform(-40, 40))
    a0 = rng.uniform(0, math.tau)
    kind = rng.choice(["circle", "spiral", "full"])
    sweep = math.tau if kind == "full" else rng.uniform(0.05, math.tau - 0.01)
    ccw = rng.random() < 0.5
    end_radius = radius
    if kind == "spiral":
        limit = min(0.5, max(0.005, 0.001 * radius))
        end_radius = radius + rng.choice([-1, 1]) * limit * rng.choice([0.999, rng.random()])
    a1 = a0 + (sweep if ccw else -sweep)
    start = (centre[0] + radius * math.cos(a0), centre[1] + radius * math.sin(a0))
    end = start if kind == "full" else (centre[0] + end_radius * math.cos(a1),
                                        centre[1] + end_radius * math.sin(a1))
    return Arc(start, end, centre, ccw, 600.0, f"arc{number}"), kind


@pytest.mark.parametrize("seed", range(4))
def test_linuxcnc_accepted_arcs_run_on_the_card_and_end_on_the_rounded_end(seed):
    rng = random.Random(seed)
    machine = Machine(steps_per_mm=(20.0, 20.0))
    drawing, kinds = [], {}
    for number in range(50):
        arc, kinds[number] = random_arc(rng, number)
        drawing += [Line(drawing[-1].end if drawing else (0.0, 0.0), arc.start, None, "to"), arc]
    planned = plan(drawing, machine)
    moves = model_moves(planned)
    ends = ends_per_primitive(planned, moves)
    for index, item in enumerate(drawing):
        if index in ends:
            assert ends[index] == (nearest(item.end[0] * 20), nearest(item.end[1] * 20)), item.where
    # the card's half step and the rounding of the drawing's points onto the lattice
    bound = 0.5 + ROUNDING
    for entry, points in moves:
        item = planned.drawing[entry.primitive]
        worst = max(item.distance((x / 20, y / 20)) * 20 for x, y in points)
        assert worst <= bound, f"{item.where} ({kinds.get(entry.primitive // 2)}): {worst:.3f} steps"
    assert {k for k in kinds.values()} == {"circle", "spiral", "full"}


def test_a_spiral_at_the_half_millimetre_limit_is_split_and_stays_close():
    machine = Machine(steps_per_mm=(20.0, 20.0))
    arc = Arc((60.0, 0.0), (-60.5, 0.0), (0.0, 0.0), True, 600.0, "spiral")
    planned = plan([Line((0.0, 0.0), (60.0, 0.0), None), arc], machine)
    moves = model_moves(planned)
    arcs = [e for e, _ in moves if isinstance(e.command, ArcCommand)]
    assert len(arcs) >= 10 / 0.25  # 0.5 mm = 10 steps of radius, a quarter step a piece
    assert moves[-1][1][-1] == (-1210, 0)
    assert deviation_steps(planned, moves[1:]) <= 0.5 + ROUNDING


@pytest.mark.parametrize("words, end", [
    ("G3 X0 Y10 R-10", (0, 200)),     # 270 degrees
    ("G2 X0 Y10 R-10", (0, 200)),
    ("G2 X10 Y0 I-10 J0", (200, 0)),  # full circle
    ("G3 X-10 Y0 I-10 J0", (-200, 0)),
])
def test_gcode_arcs_negative_r_and_full_circles_on_the_card(words, end):
    planned = plan(parse(f"G0 X10 Y0\n{words} F300\n", "t.ngc"), Machine(steps_per_mm=(20.0, 20.0)))
    moves = model_moves(planned)
    assert moves[-1][1][-1] == end
    assert deviation_steps(planned, moves) <= 0.5 + ROUNDING
    sweep = planned.drawing[1].sweep
    steps = sum(len(points) - 1 for entry, points in moves if entry.primitive == 1)
    assert steps >= sweep * 200 * 0.7  # it went the long way round when asked (200 steps radius)


def test_lines_stay_within_half_a_step_plus_the_end_rounding():
    rng = random.Random(7)
    machine = Machine(steps_per_mm=(37.0, 37.0))
    drawing, here = [], (0.0, 0.0)
    for number in range(200):
        there = (rng.uniform(-20, 20), rng.uniform(-20, 20))
        drawing.append(Line(here, there, 900.0, f"l{number}"))
        here = there
    planned = plan(drawing, machine)
    assert deviation_steps(planned, model_moves(planned)) <= 0.5 + ROUNDING


def test_an_arc_beyond_the_coordinate_width_is_refused_with_its_line():
    with pytest.raises(ProgramError, match=r"^t\.ngc:2: arc radius .* beyond the card's 12-bit"):
        plan(parse("G0 X20\nG3 X0 Y20 I-20 J0 F100\n", "t.ngc"),
             Machine(steps_per_mm=(200.0, 200.0), coord_width=12))


def test_a_line_beyond_the_coordinate_width_is_cut_into_parts_that_fit():
    machine = Machine(steps_per_mm=(200.0, 200.0), coord_width=12)
    planned = plan([Line((0.0, 0.0), (100.0, -33.3), 600.0)], machine)
    lines = [operands for name, _, operands in decode(planned.words()) if name == "LINE"]
    assert len(lines) == math.ceil(20000 / 2047)
    assert all(abs(v) <= 2047 for dx, dy in lines for v in (dx, dy))
    assert (sum(dx for dx, _ in lines), sum(dy for _, dy in lines)) == (20000, -6660)


def test_unequal_axis_scales_turn_arcs_into_chords_within_the_tolerance():
    machine = Machine(steps_per_mm=(100.0, 50.0), chord_tolerance=0.01)
    arc = Arc((10.0, 0.0), (10.0, 0.0), (0.0, 0.0), True, 600.0, "circle")
    planned = plan([Line((0.0, 0.0), (10.0, 0.0), None), arc], machine)
    moves = model_moves(planned)
    assert all(isinstance(e.command, LineCommand) for e, _ in moves)
    worst = max(arc.distance((x / 100, y / 50)) for e, points in moves[1:] for x, y in points)
    # chord sagitta, plus the model's half step and the point rounding on the coarser axis
    assert worst <= 0.01 + (0.5 + ROUNDING) / 50


def settings_before(planned, index):
    """Register values in force at entry ``index`` (from the SETs before it)."""
    names = {r.set_index: r.name for r in SET_TARGETS.values()}
    values = {}
    for name, header, operands in decode(planned.words())[:index]:
        if name == "SET":
            values[names[header & 0xF]] = operands[0]
    return values


def test_feed_rate_is_iterations_per_clock_times_65536():
    # 1 MHz card, 200 steps/mm, 600 mm/min along X: 2000 iterations/s = 131.07 units
    machine = Machine(steps_per_mm=(200.0, 200.0), clock_hz=1e6)
    planned = plan([Line((0.0, 0.0), (10.0, 0.0), 600.0)], machine)
    assert settings_before(planned, len(planned.entries))["FEED_RATE"] == round(2000 / 1e6 * 65536)


def test_diagonal_runs_set_the_rate_so_the_path_is_not_faster_than_the_feed():
    machine = Machine(steps_per_mm=(200.0, 200.0), clock_hz=1e6)
    planned = plan([Line((0.0, 0.0), (10.0, 10.0), 600.0)], machine)
    rate = settings_before(planned, len(planned.entries))["FEED_RATE"]
    # one iteration moves sqrt(2) steps; 2000 / sqrt(2) iterations/s
    assert rate == round(2000 / math.sqrt(2) / 1e6 * 65536)


def test_ramp_keeps_the_acceleration_and_stops_at_the_start_rate():
    """The run's settings through the card's feed-rate model over a real line."""
    clock_hz = 1e5  # a slow clock keeps the clock-by-clock model short
    machine = Machine(steps_per_mm=(200.0, 200.0), clock_hz=clock_hz, acceleration=200.0, start_feed=60.0)
    planned = plan([Line((0.0, 0.0), (20.0, 0.0), 1800.0)], machine)
    settings = settings_before(planned, len(planned.entries))
    target, start, step = settings["FEED_RATE"], settings["RAMP_START"], settings["RAMP_STEP"]
    assert start == round(200 / clock_hz * 65536) and step > 0
    line = LineIterator(LineCommand(4000, 0))
    feed = FeedRateModel()
    for _ in range(2):  # settings reach the ramp a clock late; idle loads the start rate
        feed.clock(False, False, target, start, step)
    ticks, clock = [], 0
    while not line.finished:
        feed.clock(True, False, target, start, step, max(line.steps_left()) - 1)
        clock += 1
        if feed.tick:
            line.step()
            ticks.append(clock)
    window = 12  # iterations: whole-clock tick intervals average out
    speeds = [window * clock_hz / (ticks[i + window] - ticks[i]) / 200 for i in range(len(ticks) - window)]
    top = max(speeds)
    assert top == pytest.approx(30.0, rel=0.01)  # 1800 mm/min
    # the ramp is linear in distance, so the acceleration peaks at the top: measure it
    # over the last fifth of the speed rise
    late = next(i for i, v in enumerate(speeds) if v >= top * 0.8)
    rise = next(i for i, v in enumerate(speeds) if v >= top * 0.99)
    acceleration = (speeds[rise] - speeds[late]) / ((ticks[rise] - ticks[late]) / clock_hz)
    assert 0.5 * 200.0 <= acceleration <= 200.0 * 1.05
    assert speeds[-1] <= 2 * start / 65536 * clock_hz / 200


@pytest.mark.parametrize("degrees, blends", [(0, True), (5, True), (30, False), (90, False)])
def test_blend_follows_the_velocity_jump_rule(degrees, blends):
    # 600 mm/min = 10 mm/s, start feed 60 mm/min = 1 mm/s: blend while 2 * 10 * sin(a / 2) <= 1,
    # a <= 5.73 degrees
    angle = math.radians(degrees)
    corner = (10.0, 0.0)
    drawing = [Line((0.0, 0.0), corner, 600.0),
               Line(corner, (10 + 10 * math.cos(angle), 10 * math.sin(angle)), 600.0)]
    planned = plan(drawing, Machine(start_feed=60.0))
    first_line = next(h for n, h, _ in decode(planned.words()) if n == "LINE")
    assert bool(first_line >> 16 & 1) == blends


def test_feed_change_rapid_and_dwell_stop_the_path():
    drawing = [Line((0.0, 0.0), (10.0, 0.0), 600.0), Line((10.0, 0.0), (20.0, 0.0), 900.0),
               Line((20.0, 0.0), (30.0, 0.0), None), Line((30.0, 0.0), (40.0, 0.0), None),
               Dwell(1.0), Line((40.0, 0.0), (50.0, 0.0), None)]
    planned = plan(drawing)
    blends = [bool(h >> 16 & 1) for n, h, _ in decode(planned.words()) if n == "LINE"]
    assert blends == [False, False, True, False, False]


def test_nothing_but_moves_follows_a_blended_move_and_marks_sit_at_stops():
    rng = random.Random(3)
    drawing, here = [], (0.0, 0.0)
    for number in range(300):
        there = (here[0] + rng.uniform(0.5, 2), here[1] + rng.uniform(-0.05, 0.05))
        drawing.append(Line(here, there, rng.choice([600.0, 600.0, 1200.0, None]), f"l{number}"))
        here = there
    planned = plan(drawing, Machine(mark_interval=20))
    decoded = decode(planned.words())
    for (name, header, _), (after, _, _) in zip(decoded, decoded[1:]):
        if name in ("LINE", "ARC") and header >> 16 & 1:
            assert after in ("LINE", "ARC")
    marks = [i for i, (name, _, _) in enumerate(decoded) if name == "MARK"]
    assert len(marks) > 10 and decoded[-1][0] == "MARK"
    tags = [decoded[i][1] & 0xFFFF for i in marks]
    assert tags == list(range(len(tags)))


@pytest.mark.parametrize("seconds, clock_hz, expected", [
    (0.5, 33e6, [16_500_000]),
    (200.0, 33e6, [(1 << 32) - 1, 6_600_000_000 - ((1 << 32) - 1)]),
])
def test_dwell_in_card_clocks(seconds, clock_hz, expected):
    planned = plan([Dwell(seconds, "t.ngc:1")], Machine(clock_hz=clock_hz))
    dwells = [operands[0] & 0xFFFFFFFF for name, _, operands in decode(planned.words()) if name == "DWELL"]
    assert dwells == expected


def test_every_set_index_is_the_register_table_one():
    planned = plan([Line((0.0, 0.0), (1.0, 0.0), 600.0)])
    names = [SET_TARGETS[h & 0xF].name for n, h, _ in decode(planned.words()) if n == "SET"]
    assert sorted(names) == ["FEED_RATE", "RAMP_START", "RAMP_STEP"]


def test_rate_unit_matches_the_register_description():
    # FEED_RATE is iterations per clock times 65536 (docs/registers.md)
    assert Machine(clock_hz=65536).rate_register(1) == 1 and RATE_ONE == 65536
