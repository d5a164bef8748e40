"""The machine side's golden models agree with each other and with docs/machine.md's formulas."""
import pytest

from models.machine_model import INPUT, InputFilterModel, MachineGuardModel, reaction_clocks


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
