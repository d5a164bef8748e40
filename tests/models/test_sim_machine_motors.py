"""The simulated machine's motors (models/sim_machine.py's Motor on models/motor_model.py): what a
step turns into on the encoder pins, against facts written down from the definition (docs/machine.md,
"Motors") and the card's own decoder model (models/encoder_model.py)."""
import random

import pytest

from models.encoder_model import EncoderModel
from models.sim_machine import MachineConfig, Motor, SimMachine


def _machine(**motor):
    return SimMachine(MachineConfig(motors={"X": Motor(**motor)}))


def _pins(word, axis=0):
    return word >> 3 * axis & 1, word >> 3 * axis + 1 & 1, word >> 3 * axis + 2 & 1


def _steps(machine, count, forward=True, period=4, drive=True, decoder=None):
    """``count`` X steps, a STEP rise every ``period`` clocks; the encoder pins of every clock."""
    words = []
    for clock in range(count * period):
        machine.clock(clock % period == 0, forward, False, False, drive)
        words.append(machine.encoder_pins)
        if decoder is not None:
            decoder.clock(*_pins(words[-1]), 0)
    return words


def _settle(machine, clocks, decoder=None):
    """``clocks`` clocks without a step."""
    words = []
    for _ in range(clocks):
        machine.clock(False, True, False, False, True)
        words.append(machine.encoder_pins)
        if decoder is not None:
            decoder.clock(*_pins(words[-1]), 0)
    return words


def _decoder(spacing):
    model = EncoderModel()
    model.filter = spacing - 1   # the filter that passes edges this close, no closer
    return model


@pytest.mark.parametrize("ratio,steps,counts", [(4, 10, 40), (1, 7, 7), ((5, 2), 5, 13), ((5, 2), 4, 10),
                                                ((1, 3), 10, 3), ((1, 3), 11, 4)])
def test_encoder_ends_at_the_steps_times_the_ratio_rounded_half_up(ratio, steps, counts):
    # 5 x 2.5 = 12.5 -> 13 (a half rounds up); 10 / 3 -> 3; 11 / 3 = 3.67 -> 4
    machine, decoder = _machine(counts_per_step=ratio, spacing=3), _decoder(3)
    _steps(machine, steps, period=16, decoder=decoder)
    _settle(machine, 64, decoder)
    assert machine.counts(0) == counts and machine.positions == [steps, 0]
    assert decoder.signed_count == counts and not decoder.quad_error, "the card's decoder counts every edge"


def test_backwards_steps_count_down_through_the_decoder():
    machine, decoder = _machine(counts_per_step=4, spacing=2), _decoder(2)
    _steps(machine, 6, forward=True, period=10, decoder=decoder)
    _steps(machine, 9, forward=False, period=10, decoder=decoder)
    _settle(machine, 40, decoder)
    assert machine.counts(0) == decoder.signed_count == -12 and machine.positions[0] == -3


@pytest.mark.parametrize("lag", [0, 1, 5, 40])
def test_first_edge_comes_lag_clocks_after_the_step(lag):
    # the step's rise is taken in clock 1; with no lag its count shows on the pins that clock
    machine = _machine(counts_per_step=1, lag=lag)
    words = _steps(machine, 1, period=lag + 8)
    assert words.index(1) == lag and not any(words[:lag])


@pytest.mark.parametrize("spacing,jitter,seed", [(1, 0, 1), (3, 0, 1), (4, 5, 7), (2, 3, 11)])
def test_edges_keep_the_spacing_the_jitter_adds_to_it_and_the_seed_repeats_it(spacing, jitter, seed):
    def run():
        machine = _machine(counts_per_step=16, spacing=spacing, jitter=jitter, seed=seed)
        words = [machine.encoder_pins] + _steps(machine, 3, period=4) + _settle(machine, 400)
        return [n for n, (a, b) in enumerate(zip(words, words[1:]), 1) if a != b]

    edges = run()
    gaps = [b - a for a, b in zip(edges, edges[1:])]
    assert len(edges) == 48 and min(gaps) >= spacing and max(gaps) <= spacing + jitter
    if jitter:
        assert len(set(gaps)) > 1, "the jitter varies the spacing"
    assert run() == edges


def test_index_is_high_at_every_multiple_of_its_period():
    machine = _machine(counts_per_step=1, spacing=1, index_period=5)
    highs = []
    for _ in range(12):
        _steps(machine, 1, period=2)
        highs.append(_pins(machine.encoder_pins)[2])
    assert [count for count, high in enumerate(highs, 1) if high] == [5, 10]


def test_a_motor_stalled_from_its_clock_stops_turning_while_the_steps_go_on():
    # a step every 4 clocks from clock 1: clocks 1, 5, 9, ...; the stall from clock 21 (the 6th step)
    machine = _machine(counts_per_step=4, spacing=1, stall_at=21)
    _steps(machine, 10, period=4)
    _settle(machine, 20)
    assert machine.positions == [5, 0] and machine.lost == [5, 0] and machine.counts(0) == 20


def test_a_stall_on_request_and_a_disabled_drive_lose_the_steps():
    machine = _machine(counts_per_step=2, spacing=1)
    _steps(machine, 3)
    machine.stall(0)
    _steps(machine, 4)
    machine.stall(0, False)
    _steps(machine, 2)
    _steps(machine, 3, drive=False)
    _settle(machine, 20)
    assert machine.positions == [5, 0] and machine.lost == [7, 0] and machine.counts(0) == 10
    with pytest.raises(ValueError, match="no motor"):
        machine.stall(1)


def test_a_random_walk_ends_where_the_decoder_counts_it():
    rng = random.Random(5)
    machine, decoder = _machine(counts_per_step=(3, 2), lag=9, spacing=3, jitter=2, seed=4), _decoder(3)
    steps = 0
    for _ in range(40):
        forward = rng.random() < 0.6
        steps += 1 if forward else -1
        _steps(machine, 1, forward, period=rng.randrange(2, 12), decoder=decoder)
    _settle(machine, 200, decoder)
    assert machine.positions[0] == steps
    assert decoder.signed_count == machine.counts(0) == (2 * steps * 3 + 2) // 4 and not decoder.quad_error


@pytest.mark.parametrize("bad", [dict(counts_per_step=0), dict(counts_per_step=(1, 0)), dict(counts_per_step=2.5),
                                 dict(counts_per_step=(1, 2, 3)), dict(counts_per_step=1 << 17),
                                 dict(lag=-1), dict(spacing=0), dict(jitter=-2), dict(index_period=-1),
                                 dict(stall_at=-5), dict(stall_at=1.5), dict(lag=True)])
def test_bad_motor_settings_are_refused(bad):
    with pytest.raises(ValueError, match="motor X"):
        MachineConfig(motors={"X": Motor(**bad)})


def test_a_motor_on_no_axis_or_on_an_axis_the_card_lacks_is_refused():
    with pytest.raises(ValueError, match="no motor axis 'W'"):
        MachineConfig(motors={"W": Motor()})
    with pytest.raises(ValueError, match=r"lacks: motor Z; the card has 2 axes \(X, Y\): build it with --axes 3"):
        SimMachine(MachineConfig(motors={"Z": Motor()}), axes=2)


def test_motors_json_round_trip():
    config = MachineConfig(motors={"X": Motor(counts_per_step=(5, 2), lag=30, spacing=4, jitter=2, seed=9,
                                              index_period=400, stall_at=12_000), "Y": Motor()})
    assert MachineConfig.from_json(config.to_json()) == config
    assert MachineConfig.from_json('{"motors": {"Y": {"counts_per_step": [1, 3]}}}').motors["Y"].ratio == (1, 3)
    with pytest.raises(ValueError, match="not a machine configuration"):
        MachineConfig.from_json('{"motors": {"X": {"gear": 3}}}')
    with pytest.raises(ValueError, match="counts_per_step"):
        MachineConfig.from_json('{"motors": {"X": {"counts_per_step": "4"}}}')


def test_a_z_motor_drives_the_third_encoders_pins_and_stalls_alone():
    """On a 3-axis card Z's motor is encoder 2 (bits 6..8 of the word); X and Y have none here."""
    machine, decoder = SimMachine(MachineConfig(motors={"Z": Motor(counts_per_step=3, spacing=3)}), axes=3), _decoder(3)
    for clock in range(100):   # 5 steps, then 5 stalled; the counts follow 3 clocks apart
        if clock == 20:
            machine.stall(2)
        machine.clock(False, True, False, True, clock % 4 == 0 and clock < 40, False, True)   # Z backwards
        assert machine.encoder_pins & 0o77 == 0
        decoder.clock(*_pins(machine.encoder_pins, 2), 0)
    assert machine.positions == [0, 0, -5] and machine.lost == [0, 0, 5]
    assert decoder.signed_count == machine.counts(2) == -15
    with pytest.raises(ValueError, match="axis 1 has no motor"):
        machine.stall(1)
