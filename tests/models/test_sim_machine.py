"""The simulated machine's golden model (models/sim_machine.py): the switch's
definition from the spec, bounce, drives, the configuration's checks."""
import pytest

from models import registers as regmap
from models.homing_model import BouncingSwitch
from models.sim_machine import INPUTS, MachineConfig, SimMachine, Switch, switch_closed


def _walk(switch, positions):
    closed, seen = False, []
    for position in positions:
        closed = switch_closed(switch, position, closed)
        seen.append(closed)
    return seen


@pytest.mark.parametrize("p,h", [(10, 0), (10, 2), (-7, 3)])
def test_switch_reads_closed_from_p_and_open_past_p_minus_h(p, h):
    """Positive side: closed from p going up, open again at p - h - 1 going down;
    the negative side mirrored."""
    up = list(range(p - 5, p + 4))
    down = list(range(p + 3, p - h - 4, -1))
    seen = _walk(Switch(p, positive=True, hysteresis=h), up + down)
    assert seen[:len(up)] == [x >= p for x in up]
    assert seen[len(up):] == [x >= p - h for x in down]
    mirrored = _walk(Switch(-p, positive=False, hysteresis=h), [-x for x in up + down])
    assert mirrored == seen


def test_switch_agrees_with_the_homing_benchs_switch():
    """BouncingSwitch (models/homing_model.py, written for the homing bench) trips
    and releases at the same positions (no bounce)."""
    trip, hysteresis = 12, 3
    walk = list(range(0, 20)) + list(range(20, -1, -1))
    bench = BouncingSwitch(trip, hysteresis=hysteresis, chatter=0)
    levels = []
    for before, after in zip(walk, walk[1:]):
        levels.append(bench.clock(True, after > before))
    assert _walk(Switch(trip, hysteresis=hysteresis), walk[1:]) == levels


def test_bounce_chatters_then_settles_and_is_seeded():
    config = MachineConfig(switches={"HOME_X": Switch(3, bounce=20, longest_run=3, seed=7)})

    def run():
        machine, words = SimMachine(config), []
        for clock in range(60):
            step = clock % 4 == 1 and clock < 20     # 5 steps forward: the switch closes at 3
            words.append(machine.clock(step, True, False, False, True) >> INPUTS.index("HOME_X") & 1)
        return machine, words

    machine, words = run()
    changes = sum(a != b for a, b in zip(words, words[1:]))
    assert changes >= 5 and words[-25:] == [1] * 25 and machine.positions == [5, 0]
    assert run()[1] == words, "the same seed bounces the same"


def test_a_disabled_drive_loses_the_step_and_says_so():
    machine = SimMachine(MachineConfig(dir_positive=(False, True)))
    machine.clock(True, False, True, True, True)
    machine.clock(False, False, False, True, True)
    machine.clock(True, False, True, True, False)
    assert machine.positions == [1, 1] and machine.lost == [1, 1]


def test_estop_and_active_low_wiring():
    machine = SimMachine(MachineConfig(switches={"LIMIT_NEG_Y": Switch(0, positive=False, active_low=True)},
                                       estop_active_low=True))
    # active low: the E-stop released reads 1, the limit (closed at 0) reads 0
    assert machine.pins == 1 << INPUTS.index("ESTOP")
    machine.press_estop()
    assert machine.pins == 0
    machine.clock(True, True, True, True, True)   # Y leaves the switch: it opens
    assert machine.pins == 1 << INPUTS.index("LIMIT_NEG_Y")


@pytest.mark.parametrize("bad", [dict(switches={"ESTOP": Switch(1)}), dict(switches={"HOME_X": 5}),
                                 dict(switches={"HOME_X": Switch(1, longest_run=0)}), dict(start=(0,)),
                                 dict(switches={"HOME_X": Switch(1.5)})])
def test_bad_configuration_is_refused(bad):
    with pytest.raises(ValueError):
        MachineConfig(**bad)


def test_json_round_trip():
    config = MachineConfig(switches={"HOME_Y": Switch(-4, positive=False, hysteresis=2, bounce=9, seed=3)},
                           start=(10, -2), dir_positive=(True, False))
    assert MachineConfig.from_json(config.to_json()) == config
    with pytest.raises(ValueError, match="not a machine configuration"):
        MachineConfig.from_json('{"switches": {"HOME_Y": {"place": 3}}}')


def test_a_two_axis_configuration_on_a_three_axis_card_leaves_z_bare():
    """The stated rule (docs/machine.md): axes the configuration does not name have no switch and no
    motor, start at 0 and move forward with DIR high."""
    config = MachineConfig.from_json('{"switches": {"HOME_X": {"position": 2}}, "start": [1, -1], '
                                     '"dir_positive": [false, true]}')
    machine = SimMachine(config, axes=3)
    assert machine.inputs == regmap.input_names(3) and machine.positions == [1, -1, 0]
    machine.clock(True, True, False, False, True, True, True)      # X backwards (DIR low forward), Z forward
    machine.clock(False, True, False, False, False, True, True)
    machine.clock(False, True, False, False, True, False, False)   # Z's step with the drives off: lost
    assert machine.positions == [0, -1, 1] and machine.lost == [0, 0, 1] and machine.encoder_pins == 0
    assert SimMachine(config).axes == 2 and config.axes == 2


@pytest.mark.parametrize("positive", [True, False])
def test_a_z_limit_closes_where_z_moves_to_and_sets_its_input_bit(positive):
    name = f"LIMIT_{'POS' if positive else 'NEG'}_Z"
    machine = SimMachine(MachineConfig(switches={name: Switch(2 if positive else -2, positive=positive)},
                                       start=(0, 0, 0)), axes=3)
    words = []
    for clock in range(12):
        machine.clock(False, True, False, True, clock % 4 == 0, positive, True)
        words.append(machine.pins)
    # Z steps at clocks 0, 4, 8: at 2 (or -2) after the second step, the switch closes
    bit = 1 << regmap.input_names(3).index(name)
    assert [w == bit for w in words] == [False] * 4 + [True] * 8 and machine.positions == [0, 0, 3 if positive else -3]


def test_the_configuration_says_which_build_it_needs_and_a_smaller_card_refuses_it():
    config = MachineConfig(switches={"HOME_A": Switch(5)}, start=(0, 0, 4))
    assert config.axes == 4 and MachineConfig(start=(0, 0, 7)).axes == 3
    SimMachine(config, axes=6)
    with pytest.raises(ValueError, match=r"lacks: HOME_A, start \(3 axes\); the card has 2 axes \(X, Y\): "
                                         r"build it with --axes 4"):
        SimMachine(config, axes=2)
    with pytest.raises(ValueError, match="takes STEP and DIR of each axis and DRIVE_ENABLE: 9 pins, not 5"):
        SimMachine(config).clock(True, True, False, False, True)


@pytest.mark.parametrize("bad", [dict(start=(0,) * 7), dict(dir_positive=(True,)), dict(start=(0, 1.5)),
                                 dict(switches={"HOME_W": Switch(1)})])
def test_bad_axes_in_a_configuration_are_refused(bad):
    with pytest.raises(ValueError):
        MachineConfig(**bad)


def test_a_six_axis_json_round_trip():
    config = MachineConfig(switches={"LIMIT_NEG_C": Switch(-9, positive=False)}, start=(1, 2, 3, 4, 5, 6),
                           dir_positive=(True, False, True, False, True, False))
    assert MachineConfig.from_json(config.to_json()) == config and config.axes == 6
