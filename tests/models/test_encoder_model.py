"""The encoder's golden model (models/encoder_model.py) and the motor helper
(models/motor_model.py) against facts written down from the definitions in
docs/encoders.md: the quadrature Gray code, the filter's rule, the index's
and the following error's rules; none of the expected values comes from
running the model."""
import random

import pytest

from models.encoder_model import (ERROR_COUNT_MAX, FERROR_CLOCKS, MODE_STEP_DIR, POLARITY_INDEX,
                                  EncoderModel, InputConditioner, ProbeModel, pin_to_count, quadrature_delta,
                                  scaled_steps, signed32)
from models.motor_model import MotorModel

ONE = 1 << 16   # 1.0 count per step in ENC_SCALE's 16.16

# Quadrature, from its definition: moving forward, A leads B by a quarter
# cycle, so (A, B) runs 00 -> 10 -> 11 -> 01 -> 00; backwards the reverse;
# a sample where both changed skipped a phase and its direction is unknown.
TRANSITIONS = {
    ((0, 0), (0, 0)): 0, ((0, 0), (1, 0)): 1, ((0, 0), (0, 1)): -1, ((0, 0), (1, 1)): None,
    ((1, 0), (1, 0)): 0, ((1, 0), (1, 1)): 1, ((1, 0), (0, 0)): -1, ((1, 0), (0, 1)): None,
    ((1, 1), (1, 1)): 0, ((1, 1), (0, 1)): 1, ((1, 1), (1, 0)): -1, ((1, 1), (0, 0)): None,
    ((0, 1), (0, 1)): 0, ((0, 1), (0, 0)): 1, ((0, 1), (1, 1)): -1, ((0, 1), (1, 0)): None,
}
PHASES = [(0, 0), (1, 0), (1, 1), (0, 1)]   # the forward order above
# How to reach each state from reset's 00 along legal transitions, and the count there.
PATH_TO = {(0, 0): ([], 0), (1, 0): ([(1, 0)], 1), (1, 1): ([(1, 0), (1, 1)], 2), (0, 1): ([(0, 1)], -1)}

# The filter's rule in words: a level is taken once seen ENC_FILTER + 1 clocks
# in a row, so a glitch of w clocks is rejected when w <= ENC_FILTER.
REJECTED_WIDTHS = {0: (), 1: (1,), 2: (1, 2), 5: (1, 2, 3, 4, 5)}


def _hold(model, a, b, index=0, clocks=1, pos=0):
    for _ in range(clocks):
        model.clock(a, b, index, pos)


def _walk(model, states, spacing, settle=True, index=0):
    """Each (A, B) held ``spacing`` clocks, then the pipeline emptied."""
    for a, b in states:
        _hold(model, a, b, index, clocks=spacing)
    if settle:
        _hold(model, *states[-1], index, clocks=pin_to_count(model.filter) + 1)


def _encoder(filter_setting=0, **registers):
    model = EncoderModel()
    model.filter = filter_setting
    for name, value in registers.items():
        setattr(model, name, value)
    return model


@pytest.mark.parametrize("filter_setting", [0, 2])
def test_full_forward_then_backward_cycle_counts_up_four_then_down_four(filter_setting):
    model = _encoder(filter_setting)
    counts = []
    for state in [(1, 0), (1, 1), (0, 1), (0, 0), (0, 1), (1, 1), (1, 0), (0, 0)]:
        _walk(model, [state], spacing=filter_setting + 1)
        counts.append((model.signed_count, model.direction))
    assert counts == [(1, 1), (2, 1), (3, 1), (4, 1), (3, 0), (2, 0), (1, 0), (0, 0)]
    assert not model.quad_error


@pytest.mark.parametrize("before,after", sorted(TRANSITIONS))
def test_every_transition_of_the_gray_code_as_the_table_says(before, after):
    expected = TRANSITIONS[before, after]
    assert quadrature_delta(before, after) == expected
    path, start = PATH_TO[before]
    model = _encoder(0)
    _walk(model, path or [(0, 0)], spacing=2)
    assert model.signed_count == start and not model.quad_error
    _walk(model, [after], spacing=2)
    assert model.signed_count == start + (expected or 0)
    assert model.quad_error == (expected is None)
    assert model.error_count == (1 if expected is None else 0)


def test_error_counter_saturates_and_the_flag_is_sticky_until_cleared():
    model = _encoder(0)
    for toggle in range(ERROR_COUNT_MAX + 20):
        _hold(model, ~toggle & 1, ~toggle & 1, clocks=2)   # 00 <-> 11: both change every time
    _hold(model, 0, 0, clocks=4)
    assert (model.signed_count, model.quad_error, model.error_count) == (0, True, 255)
    _walk(model, [(1, 0), (1, 1)], spacing=2)   # legal counts do not clear the flag
    assert (model.signed_count, model.quad_error) == (2, True)
    model.clear_quad_error()
    _walk(model, [(0, 1)], spacing=2)
    assert (model.signed_count, model.quad_error, model.error_count) == (3, False, 0)


@pytest.mark.parametrize("setting", sorted(REJECTED_WIDTHS))
@pytest.mark.parametrize("idle", [0, 1])
def test_filter_rejects_exactly_the_glitch_widths_of_its_table(setting, idle):
    """A pulse of w clocks away from ``idle`` on one input, w = 1 .. 8."""
    for width in range(1, 9):
        conditioner = InputConditioner()
        for _ in range(setting + 4):
            conditioner.clock(idle, 0, setting)
        assert conditioner.level == idle
        levels = []
        for pin in [1 - idle] * width + [idle] * (setting + 4):
            conditioner.clock(pin, 0, setting)
            levels.append(conditioner.level)
        assert (1 - idle not in levels) == (width in REJECTED_WIDTHS[setting]), width


@pytest.mark.parametrize("setting", sorted(REJECTED_WIDTHS))
def test_glitch_on_a_reaches_the_count_only_when_the_filter_passes_it(setting):
    for width in range(1, 9):
        model = _encoder(setting)
        _hold(model, 0, 0, clocks=setting + 4)
        seen = []
        for a in [1] * width + [0] * (setting + 6):
            model.clock(a, 0, 0)
            seen.append(model.signed_count)
        passed = width not in REJECTED_WIDTHS[setting]
        assert (1 in seen) == passed and model.signed_count == 0, width


@pytest.mark.parametrize("setting", [0, 2, 15])
def test_a_pin_change_is_counted_at_the_filter_plus_fourth_edge(setting):
    """Synchroniser (2 edges), filter (setting + 1), decoder (1): pin_to_count."""
    model = _encoder(setting)
    _hold(model, 0, 0, clocks=20)
    edges = 0
    while model.count == 0:
        model.clock(1, 0, 0)
        edges += 1
    assert edges == pin_to_count(setting) == setting + 4
    assert model.time == model.timestamp == 20 + setting + 4   # edges since reset at the count


@pytest.mark.parametrize("setting,seed", [(0, 1), (2, 2), (3, 3), (7, 4)])
def test_random_walk_at_the_closest_spacing_the_filter_passes_is_counted_exactly(setting, seed):
    """Edges setting + 1 clocks apart, reversals included: every one counted."""
    rng = random.Random(seed)
    model, phase, position = _encoder(setting), 0, 0
    for _ in range(300):
        move = rng.choice((1, -1, 1))
        phase, position = (phase + move) % 4, position + move
        _hold(model, *PHASES[phase], clocks=setting + 1)
        if rng.random() < 0.1:
            _hold(model, *PHASES[phase], clocks=rng.randrange(1, 20))
    _hold(model, *PHASES[phase], clocks=pin_to_count(setting))
    assert model.signed_count == position and not model.quad_error


def test_count_wraps_at_2_to_the_31_in_its_signed_view():
    model = _encoder(0)
    model.count = 2 ** 31 - 2
    _walk(model, [(1, 0), (1, 1)], spacing=2)
    assert (model.count, model.signed_count) == (2 ** 31, -2 ** 31)
    _walk(model, [(1, 0)], spacing=2)
    assert (model.count, model.signed_count) == (2 ** 31 - 1, 2 ** 31 - 1)
    model.count = 1
    _walk(model, [(0, 0), (0, 1)], spacing=2)   # from (1, 0): down two
    assert (model.count, model.signed_count) == (2 ** 32 - 1, -1)


def test_timestamp_runs_free_and_wraps_and_time_keeps_the_last_count_edge():
    model = _encoder(0)
    model.timestamp = 2 ** 32 - 4
    _hold(model, 1, 0, clocks=3)          # counted at the fourth edge: the timestamp wraps to 0 there
    assert (model.signed_count, model.timestamp) == (0, 2 ** 32 - 1)
    _hold(model, 1, 0, clocks=1)
    assert (model.signed_count, model.time, model.timestamp) == (1, 0, 0)
    _hold(model, 1, 0, clocks=50)
    assert (model.time, model.timestamp) == (0, 50)


@pytest.mark.parametrize("inverted", [False, True])
def test_index_latches_once_per_arm(inverted):
    model = _encoder(1, polarity=POLARITY_INDEX if inverted else 0)
    idle, active = int(inverted), int(not inverted)
    _hold(model, 0, 0, idle, clocks=8)
    _walk(model, [(1, 0), (1, 1), (0, 1)], spacing=2, index=idle)   # count 3
    _hold(model, 0, 1, active, clocks=6)                # an edge while not armed: nothing
    _hold(model, 0, 1, idle, clocks=6)
    assert (model.index_latch, model.index_armed) == (0, False)
    model.arm_index()
    _walk(model, [(0, 0), (1, 0)], spacing=2, index=idle)           # count 5
    _hold(model, 1, 0, active, clocks=6)                # fires: latches 5
    _hold(model, 1, 0, idle, clocks=6)
    _walk(model, [(1, 1)], spacing=2, index=idle)                   # count 6
    _hold(model, 1, 1, active, clocks=6)                # disarmed: nothing
    _hold(model, 1, 1, idle, clocks=6)
    _walk(model, [(0, 1)], spacing=2, index=idle)                   # count 7
    _hold(model, 0, 1, active, clocks=6)
    assert (model.index_latch, model.index_armed, model.signed_count) == (5, False, 7)
    model.arm_index()
    _hold(model, 0, 1, idle, clocks=6)
    _hold(model, 0, 1, active, clocks=6)                # armed again: latches 7
    assert (model.index_latch, model.index_armed) == (7, False)


def test_index_zero_zeroes_the_count_at_the_edge_and_keeps_counting_from_there():
    model = _encoder(0, index_zero=True)
    _walk(model, [(1, 0), (1, 1), (0, 1), (0, 0), (1, 0)], spacing=2)   # count 5
    model.arm_index()
    _hold(model, 1, 0, 1, clocks=4)
    assert (model.index_latch, model.signed_count, model.index_armed) == (5, 0, False)
    _walk(model, [(1, 1), (0, 1)], spacing=2)
    _hold(model, 0, 1, 0, clocks=4)
    _walk(model, [(1, 1), (1, 0), (0, 0)], spacing=2)
    assert model.signed_count == -1


@pytest.mark.parametrize("inverted", [False, True])
def test_probe_latches_every_axis_once_per_arm(inverted):
    axes, probe = [_encoder(0), _encoder(0)], ProbeModel()
    probe.invert, idle = inverted, int(inverted)
    moves = ([(1, 0), (1, 1), (0, 1)], [(0, 1), (1, 1)])   # X to 3, Y to -2
    positions = (30, -20)

    def edge(pin, states=((0, 0), (0, 0))):
        probe.clock(pin, axes, positions)
        for axis, (a, b) in zip(axes, states):
            axis.clock(a, b, 0)

    for _ in range(8):
        edge(idle)
    for step in range(3):
        states = tuple(move[min(step, len(move) - 1)] for move in moves)
        for _ in range(8):
            edge(idle, states)
    assert [axis.signed_count for axis in axes] == [3, -2]
    probe.arm()
    for pin in [1 - idle] * 6 + [idle] * 6:
        edge(pin, states)
    assert (probe.counts, probe.positions, probe.armed) == ((3, 2 ** 32 - 2), (30, -20), False)
    moved = ((0, 0), states[1])                               # X to 4
    for pin in [idle] * 6 + [1 - idle] * 6 + [idle] * 6:      # a second edge, not armed
        edge(pin, moved)
    assert axes[0].signed_count == 4 and probe.counts == (3, 2 ** 32 - 2)
    probe.arm()
    for pin in [1 - idle] * 6:
        edge(pin, moved)
    assert probe.counts == (4, 2 ** 32 - 2) and not probe.armed


@pytest.mark.parametrize("pulses,direction,expected", [(5, 1, 5), (5, 0, -5), (1, 1, 1)])
def test_step_dir_mode_counts_a_rising_edges_in_bs_direction(pulses, direction, expected):
    model = _encoder(0, mode=MODE_STEP_DIR)
    _hold(model, 0, direction, clocks=4)
    for _ in range(pulses):
        _hold(model, 1, direction, clocks=2)
        _hold(model, 0, direction, clocks=2)
    _hold(model, 1, 1 - direction, clocks=2)    # B and A change together: one count, B's new direction
    _hold(model, 0, 1 - direction, clocks=4)
    assert model.signed_count == expected + (1 if direction == 0 else -1)
    assert not model.quad_error


@pytest.mark.parametrize("steps,scale,counts", [
    (1, ONE + ONE // 2, 2), (-1, ONE + ONE // 2, -1),   # 1.5 -> 2, -1.5 -> -1: halves round up
    (2, ONE // 4, 1), (-2, ONE // 4, 0), (3, ONE // 4, 1), (-3, ONE // 4, -1),
    (1000, 4 * ONE, 4000), (-7, 3 * ONE + 1, -21), (7, 3 * ONE + 1, 21),
])
def test_scaled_steps_rounds_half_up(steps, scale, counts):
    assert signed32(scaled_steps(steps, scale)) == counts


@pytest.mark.parametrize("limit,forward", [(3, True), (3, False), (1, True), (40, False)])
def test_following_error_stops_one_count_beyond_the_limit_never_at_it(limit, forward):
    """pos stays 0 while the encoder moves: e equals the count."""
    model = _encoder(0, limit=limit)
    model.set_scale(ONE, pos=0)
    sign = 1 if forward else -1
    for moved in range(1, limit + 1):
        _walk(model, [PHASES[sign * moved % 4]], spacing=4, settle=False)
    _hold(model, *PHASES[sign * limit % 4], clocks=20)
    assert model.ferror == (limit if forward else -limit) and not model.stop
    beyond = PHASES[sign * (limit + 1) % 4]
    while model.signed_count != (limit + 1 if forward else -limit - 1):
        model.clock(*beyond, 0)
    for _ in range(FERROR_CLOCKS - 1):             # the count crossed: the flag FERROR_CLOCKS edges later
        model.clock(*beyond, 0)
        assert not model.stop
    model.clock(*beyond, 0)
    assert model.stop and model.ferror == (limit + 1 if forward else -limit - 1)
    model.clear_stop()
    model.limit = 0                                 # 0: off
    _hold(model, *beyond, clocks=5)
    assert not model.stop


def test_following_error_follows_the_step_position_and_realigns():
    model = _encoder(0, limit=2)
    model.set_scale(2 * ONE, pos=10)          # aligned at step 10, count 0
    _walk(model, [(1, 0), (1, 1)], spacing=2)
    _hold(model, 1, 1, pos=11, clocks=3)
    assert model.ferror == 0                  # 2 counts = 1 step at 2 counts per step
    _hold(model, 1, 1, pos=13, clocks=3)
    assert model.ferror == -4 and model.stop  # 4 counts short, beyond 2
    model.align(pos=13)
    model.clear_stop()
    _hold(model, 1, 1, pos=13, clocks=3)
    assert model.ferror == 0 and not model.stop
    with pytest.raises(ValueError):
        model.set_scale(-1, pos=0)


@pytest.mark.parametrize("filter_setting", [-1, 16])
def test_a_filter_setting_outside_0_to_15_is_refused(filter_setting):
    model = _encoder(filter_setting)
    with pytest.raises(ValueError, match="ENC_FILTER"):
        model.clock(0, 0, 0)


@pytest.mark.parametrize("arguments", [dict(lag=-1), dict(spacing=0), dict(index_period=-4),
                                       dict(counts_per_step=-1)])
def test_motor_refuses_impossible_settings(arguments):
    with pytest.raises(ValueError):
        MotorModel(**arguments)


def test_motor_index_is_high_at_multiples_of_its_period():
    motor = MotorModel(ONE, spacing=1, index_period=8)
    highs = []
    for _ in range(20):
        motor.clock(1, 1)
        highs.append(motor.pins[2])
        motor.clock(0, 1)
    assert [count for count, high in enumerate(highs, 1) if high] == [8, 16]


@pytest.mark.parametrize("counts_per_step,spacing,lag,seed", [
    (4 * ONE, 3, 0, 1), (ONE, 3, 7, 2), (ONE * 5 // 2, 4, 30, 3), (ONE, 1, 0, 4)])
def test_motor_ab_through_the_decoder_gives_back_its_steps(counts_per_step, spacing, lag, seed):
    rng = random.Random(seed)
    motor, model = MotorModel(counts_per_step, lag=lag, spacing=spacing), _encoder(spacing - 1)
    model.set_scale(counts_per_step, pos=0)
    steps, direction, pins = 0, 1, motor.pins
    for _ in range(60):
        direction = direction if rng.random() < 0.8 else 1 - direction
        steps += 1 if direction else -1
        for level in (1, 1, 0) + (0,) * rng.randrange(0, 12 * spacing):
            model.clock(*pins, steps)
            pins = motor.clock(level, direction)
    for _ in range(lag + 4 * spacing * 8 + 10):
        model.clock(*pins, steps)
        pins = motor.clock(0, direction)
    assert motor.steps == steps and motor.lost == 0
    assert model.signed_count == signed32(scaled_steps(steps, counts_per_step))
    assert model.ferror == 0 and not model.quad_error


def test_a_stalled_motor_loses_its_steps_and_trips_the_following_error():
    motor, model = MotorModel(4 * ONE, lag=5, spacing=3), _encoder(2, limit=6)
    model.set_scale(4 * ONE, pos=0)
    pins, pos = motor.pins, 0
    for _ in range(4):
        for level in (1, 1, 0, 0, 0, 0):
            model.clock(*pins, pos)
            pins = motor.clock(level, 1)
        pos += 1
    motor.stalled = True
    for _ in range(3):
        for level in (1, 1, 0, 0, 0, 0):
            model.clock(*pins, pos)
            pins = motor.clock(level, 1)
        pos += 1
    for _ in range(60):
        model.clock(*pins, pos)
        pins = motor.clock(0, 1)
    assert (motor.steps, motor.lost, model.signed_count) == (4, 3, 16)
    assert model.ferror == -12 and model.stop
