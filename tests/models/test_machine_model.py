"""The machine side's golden models agree with each other and with docs/machine.md's formulas."""
import pytest

from models import registers as regmap
from models.machine_model import INPUT, REASON, InputFilterModel, MachineGuardModel, reaction_clocks


def _estop_reaction(samples, tick, press_at):
    """Clocks from the clock the E-stop pin rises in (``press_at``, clocks since
    reset) to the first clock with DRIVE_ENABLE low, by the models edge by edge."""
    inputs, guard = InputFilterModel(), MachineGuardModel()
    for edge in range(1, press_at + samples * tick + 20):
        pins = 1 << INPUT["ESTOP"] if edge > press_at else 0   # the edge after the clock it changed in takes it
        active = inputs.active   # the guard sees ACTIVE as it was before this edge
        inputs.clock(pins, 0, samples, tick)
        guard.clock(active=active, drive_request=True)
        if edge > press_at and not guard.drive_enable:
            return edge - press_at
    raise AssertionError("DRIVE_ENABLE never fell")


@pytest.mark.parametrize("samples,tick", [(3, 1), (3, 8), (1, 5), (15, 2)])
def test_reaction_formula_matches_the_models(samples, tick):
    """Every phase of the filter's prescaler gives a reaction inside
    ``reaction_clocks``, and the fewest and the most both occur."""
    seen = {_estop_reaction(samples, tick, press_at) for press_at in range(40, 40 + tick)}
    first, last = reaction_clocks(samples, tick)
    assert seen == set(range(first, last + 1))


# docs/machine.md's input order, written out: today's seven, then Z, A, B, C's limit and home inputs
DOCUMENTED_INPUTS = ("ESTOP", "LIMIT_POS_X", "LIMIT_NEG_X", "LIMIT_POS_Y", "LIMIT_NEG_Y", "HOME_X", "HOME_Y",
                     "LIMIT_POS_Z", "LIMIT_NEG_Z", "HOME_Z", "LIMIT_POS_A", "LIMIT_NEG_A", "HOME_A",
                     "LIMIT_POS_B", "LIMIT_NEG_B", "HOME_B", "LIMIT_POS_C", "LIMIT_NEG_C", "HOME_C")


@pytest.mark.parametrize("axes,count", [(2, 7), (3, 10), (4, 13), (6, 19)])
def test_a_card_has_the_inputs_of_its_axes_in_the_documented_order(axes, count):
    """Bit n of INPUT_POLARITY / INPUT_RAW / INPUT_ACTIVE is input n of the documented order, and a card
    of N axes builds the first 7 + 3 (N - 2) of them: a two-axis card keeps today's seven bits."""
    assert regmap.INPUT_NAMES == DOCUMENTED_INPUTS
    assert regmap.input_names(axes) == DOCUMENTED_INPUTS[:count]
    for name in ("INPUT_POLARITY", "INPUT_RAW", "INPUT_ACTIVE"):
        built = regmap.built_register(regmap.register(name), axes)
        assert [(f.name, f.lsb, f.width) for f in built.fields] == [(n, bit, 1) for bit, n in
                                                                      enumerate(DOCUMENTED_INPUTS[:count])]
    assert regmap.register("MACHINE_STATUS").field("RAW").width == 7   # X and Y's, as before


def test_stop_reason_limits_keep_x_and_y_bits_and_add_every_axis():
    """LIMITS is bits 15:4, bit n the n-th of POS_X NEG_X POS_Y NEG_Y POS_Z ...: bits 7:4 mean what they
    meant, and bits 16 on are left free."""
    limits = regmap.register("STOP_REASON").field("LIMITS")
    assert (limits.lsb, limits.lsb + limits.width - 1) == (4, 15)
    expected = [f"LIMIT_{end}_{axis}" for axis in "XYZABC" for end in ("POS", "NEG")]
    assert list(regmap.LIMIT_NAMES) == expected


# (axes, axis, positive, the STOP_REASON.LIMITS value docs/machine.md gives: bit 2 axis, + 1 for the negative end)
LIMIT_CASES = [(2, 0, True, 0b1), (2, 1, False, 0b1000), (3, 2, True, 0b1_0000), (3, 2, False, 0b10_0000),
               (4, 3, False, 0b1000_0000), (6, 5, True, 0b100_0000_0000), (6, 5, False, 0b1000_0000_0000)]


@pytest.mark.parametrize("axes,axis,positive,limits", LIMIT_CASES)
def test_a_step_towards_any_axis_limit_stops_with_its_bit(axes, axis, positive, limits):
    """A step of ``axis`` towards its active limit is dropped with every other axis's request of that
    clock and latches LIMIT with that limit's bit; a step away from it passes."""
    active = 1 << DOCUMENTED_INPUTS.index(f"LIMIT_{'POS' if positive else 'NEG'}_{'XYZABC'[axis]}")
    steps = tuple(True for _ in range(axes))
    towards = tuple(positive if a == axis else True for a in range(axes))
    away = tuple((not positive) if a == axis else True for a in range(axes))
    guard = MachineGuardModel()
    assert guard.granted(active, steps, away) == steps
    guard.clock(active=active, steps=steps, dirs=away)
    assert not guard.stopped
    assert guard.granted(active, steps, towards) == (False,) * axes
    guard.clock(active=active, steps=steps, dirs=towards)
    assert guard.stopped and guard.reason == REASON["LIMIT"] and guard.limits == limits
