"""Rules of the machine side that an outside bench found broken or unsaid (issue 28),
on the whole card core, judged from its pins and registers.

``card_core`` runs as MyHDL and as its Verilog in Icarus.  Golden values:
the register table's ranges (``models.card_model.RegisterModel``), the
FIFO's words, the drive-enable rule of docs/machine.md (every counted STEP
rises and ends its high time while DRIVE_ENABLE is high), the reaction time
from the input filter's model (``models.machine_model.reaction_clocks``).
"""
import pytest

from models import registers as regmap
from models.card_model import RegisterModel
from models.commands import command_words
from models.dda_model import LineCommand
from models.machine_model import REASON, reaction_clocks
from sim.card.machine_bench import (STOP_CAUSES, clear_stop, drive_at, field, pulses_outside_drive, read, run_machine,
                                    set_input, snapshot, stop_cycles, wait_clocks, write)

MODES = [False, True]
MODE_IDS = ["myhdl", "icarus"]
WATCHDOG_MAX = (1 << regmap.WATCHDOG_BITS) - 1


@pytest.mark.parametrize("cosim", MODES, ids=MODE_IDS)
def test_watchdog_clamps_and_a_refused_clear_stop_changes_nothing(cosim):
    """WATCHDOG of 2**24 or more loads the largest timeout and sets CLAMPED, as
    the table's range says, instead of being cut to 24 bits (0: off).  Then
    CLEAR_STOP while the E-stop input is active changes nothing: the card stays
    stopped and the FIFO keeps its words; once the E-stop is released a
    CLEAR_STOP drops them (they were written before it)."""
    written = (1 << regmap.WATCHDOG_BITS, (1 << regmap.WATCHDOG_BITS) + 5000)
    words = command_words(LineCommand(5, 3)) * 2
    model, results = RegisterModel(), {}

    def scenario(driver, pins, pin_log, machine_log):
        for value in written:
            yield from write(driver, "WATCHDOG", value)
            yield from wait_clocks(driver, 10)
            left = yield from read(driver, "WATCHDOG")
            status = yield from read(driver, "INT_STATUS")
            yield from write(driver, "INT_STATUS", status)
            results[value] = (left, field("INT_STATUS", "CLAMPED", status))
        yield from write(driver, "WATCHDOG", 0)
        yield from write(driver, "CONTROL", 1)
        yield from set_input(pins, pin_log, machine_log, "estop", 1)
        yield from wait_clocks(driver, 20)
        yield from driver.push_all(words)
        results["before"] = yield from snapshot(driver)
        yield from clear_stop(driver)
        results["refused"] = yield from snapshot(driver)
        yield from set_input(pins, pin_log, machine_log, "estop", 0)
        yield from wait_clocks(driver, 20)
        yield from clear_stop(driver)
        results["cleared"] = yield from snapshot(driver)

    pin_log, _ = run_machine("watchdog_and_clear_stop", scenario, cosim)
    for value in written:
        left, clamped = results[value]
        assert model.write("WATCHDOG", value) and model.honour(regmap.register("WATCHDOG"), value)[0] == WATCHDOG_MAX
        assert WATCHDOG_MAX - 40 < left <= WATCHDOG_MAX, (value, left)
        assert clamped == 1, value
    before, refused, cleared = results["before"], results["refused"], results["cleared"]
    assert field("STATUS", "FIFO_LEVEL", before["STATUS"]) == len(words)
    assert field("STATUS", "FIFO_LEVEL", refused["STATUS"]) == len(words), "a refused CLEAR_STOP kept the words"
    assert field("STOP_REASON", "REASON", refused["STOP_REASON"]) == REASON["ESTOP"]
    assert field("STATUS", "STOPPED", refused["STATUS"]) == 1
    assert field("STATUS", "FIFO_LEVEL", cleared["STATUS"]) == 0 and cleared["STOP_REASON"] == 0
    assert not pin_log.rises and cleared["position"] == (0, 0)


# the Verilog run is slow: machine_drive proves the rule on the generated Verilog (docs/formal.md)
@pytest.mark.parametrize("cosim,waits", [(False, range(6)), pytest.param(True, range(6), marks=pytest.mark.slow)],
                         ids=["myhdl", "icarus"])
def test_every_counted_step_inside_drive_enable(cosim, waits):
    """For every stop cause, each a few clocks apart so that a pulse starts in
    the cause's clock once: every STEP pulse rises and falls while
    DRIVE_ENABLE is high, POS counts exactly the pins' rises, and CLEAR_STOP
    does not re-energise: DRIVE_ENABLE (pin and register) stays low, a write
    of 1 while stopped included, until the host writes it again."""
    results = []
    pin_log, machine_log = run_machine("drive_rule", stop_cycles(results, waits), cosim)
    *cycles, end = results
    assert len(cycles) == len(STOP_CAUSES) * len(waits)
    assert pulses_outside_drive(pin_log, machine_log) == []
    assert end["position"] == pin_log.path()[-1]
    for cycle in cycles:
        reason = "WATCHDOG" if cycle["cause"] == "decelerated" else cycle["cause"].upper()
        assert field("STOP_REASON", "REASON", cycle["stopped"]["STOP_REASON"]) == REASON[reason]
        assert field("MACHINE_CONTROL", "DRIVE_ENABLE", cycle["control_stopped"]) == 0, "a stop clears it"
        cleared = cycle["cleared"]
        assert field("STATUS", "STOPPED", cleared["STATUS"]) == 0, cycle["cause"]
        assert field("MACHINE_STATUS", "DRIVE_ENABLE", cleared["MACHINE_STATUS"]) == 0, "not re-energised"
        assert field("MACHINE_CONTROL", "DRIVE_ENABLE", cycle["control_cleared"]) == 0
        assert field("MACHINE_STATUS", "DRIVE_ENABLE", cycle["enabled"]) == 1, "the new write enables"
    assert len(pin_log.rises) > 4 * len(cycles), "each stop came with the line under way"


@pytest.mark.parametrize("cosim", [False, pytest.param(True, marks=pytest.mark.slow)], ids=MODE_IDS)
def test_estop_reaction_with_a_slow_filter(cosim):
    """INPUT_TICK 8, INPUT_FILTER 3 (the outside bench's 26 clocks): pressed at
    every phase of the filter's prescaler, DRIVE_ENABLE falls within
    ``reaction_clocks`` and takes each value of it.  (The Verilog run is slow:
    the same filter's Verilog is checked every clock by test_machine_units.)"""
    samples, tick = 3, 8
    presses = []

    def scenario(driver, pins, pin_log, machine_log):
        for name, value in (("INPUT_FILTER", samples), ("INPUT_TICK", tick), ("MACHINE_CONTROL", 1)):
            yield from write(driver, name, value)
        for wait in range(2 * tick):
            yield from wait_clocks(driver, 4 + wait)   # DRIVE_ENABLE high again first
            presses.append((yield from set_input(pins, pin_log, machine_log, "estop", 1)))
            yield from wait_clocks(driver, 2 * samples * tick)
            yield from set_input(pins, pin_log, machine_log, "estop", 0)
            yield from wait_clocks(driver, 2 * samples * tick)
            yield from clear_stop(driver)
            yield from write(driver, "MACHINE_CONTROL", 1)
            yield from wait_clocks(driver, 3)

    _, machine_log = run_machine("estop_reaction_tick", scenario, cosim)
    reactions = [next(c for c in range(at, at + 100) if not drive_at(machine_log, c)) - at for at in presses]
    first, last = reaction_clocks(samples, tick)
    assert set(reactions) == set(range(first, last + 1)), reactions
    assert 26 in reactions
