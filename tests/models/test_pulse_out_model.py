"""``PulseOutModel`` against what docs/registers.md promises for the pins:
STEP_WIDTH high, STEP_SPACE low between steps, and the three STEP_MODEs
(hostmot2's step_type: step/dir, up/down, quadrature)."""
import pytest

from models.card_model import PulseOutModel


def pins_of(steps, clocks=200, **timing):
    """Feed X steps (+1/-1 each, one per iteration as the queue takes them) and
    return the (STEP_X, DIR_X) pins at every clock."""
    model, waiting, pins = PulseOutModel(), list(steps), []
    for _ in range(clocks):
        step = bool(waiting) and model.ready
        direction = waiting.pop(0) > 0 if step else False
        model.clock((step, False), (direction, False), **timing)
        pins.append((model.step_pins[0], model.dir_pins[0]))
    assert not model.active, "the steps did not all leave within the clocks given"
    return pins


def runs(levels):
    """[(level, clocks)] of a pin, its runs of one level (the first and last cut by the window)."""
    out = []
    for level in levels:
        if out and out[-1][0] == level:
            out[-1][1] += 1
        else:
            out.append([level, 1])
    return [tuple(run) for run in out]


@pytest.mark.parametrize("width, space", [(3, 5), (5, 1), (2, 2)])
def test_step_is_high_for_width_and_low_for_space_between_steps(width, space):
    step = [s for s, _ in pins_of([1, 1, 1, 1], width=width, space=space)]
    pulses = runs(step)[1:-1]   # from the first rise to the last fall
    assert [clocks for level, clocks in pulses if level] == [width] * 4
    # back to back: the queue is full, so each low time is the least allowed
    assert [clocks for level, clocks in pulses if not level] == [space] * 3


def test_without_step_space_the_low_time_is_the_width():
    assert pins_of([1, 1, 1], width=4) == pins_of([1, 1, 1], width=4, space=4)


@pytest.mark.parametrize("polarity", [False, True])
def test_up_down_puts_each_direction_on_its_own_pin(polarity):
    steps = [1, 1, -1, 1]
    pins = pins_of(steps, width=2, space=3, polarity=(polarity, False), mode=1)
    up, down = [s for s, _ in pins], [d for _, d in pins]
    assert not any(u and d for u, d in pins)
    ups = [clocks for level, clocks in runs(up) if level]
    downs = [clocks for level, clocks in runs(down) if level]
    # DIR_POLARITY turns which direction is "up", as it inverts DIR in step/dir mode
    assert (len(ups), len(downs)) == ((1, 3) if polarity else (3, 1))
    assert set(ups + downs) == {2}
    # the pulses keep the step/dir mode's times: the same STEP pulses, split over two pins
    merged = [u or d for u, d in pins]
    assert merged == [s for s, _ in pins_of(steps, width=2, space=3, polarity=(polarity, False))]


def test_quadrature_changes_one_pin_per_step_a_step_period_apart():
    pins = pins_of([1, 1, 1, -1, -1, -1, -1], width=2, space=3, mode=2)
    states = [state for state, _ in runs(pins)]
    # A/B from (0, 0): up 10, 11, 01; down 11, 10, 00, 01
    assert states == [(False, False), (True, False), (True, True), (False, True), (True, True),
                      (True, False), (False, False), (False, True)]
    changes = [index for index in range(1, len(pins)) if pins[index] != pins[index - 1]]
    assert all(sum(a != b for a, b in zip(pins[i], pins[i - 1])) == 1 for i in changes)
    # the least time between changes is one step period, width + space
    assert min(later - earlier for earlier, later in zip(changes, changes[1:])) == 2 + 3


def test_a_mode_outside_the_table_is_refused():
    with pytest.raises(ValueError, match="step mode"):
        PulseOutModel().clock(mode=3)
