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
from models.machine_model import REASON
from sim.card.machine_bench import (WIDTH, clear_stop, field, read, run_machine, set_input, snapshot, wait_clocks,
                                    write)

MODES = [False, True]
MODE_IDS = ["myhdl", "icarus"]
WATCHDOG_MAX = (1 << regmap.WATCHDOG_BITS) - 1


@pytest.mark.parametrize("cosim", MODES, ids=MODE_IDS)
def test_watchdog_write_too_large_is_clamped_not_off(cosim):
    """WATCHDOG of 2**24 or more loads the largest timeout and sets CLAMPED, as
    the table's range says, instead of being cut to 24 bits (0: off)."""
    results = {}
    written = (1 << regmap.WATCHDOG_BITS, (1 << regmap.WATCHDOG_BITS) + 5000)
    model = RegisterModel()

    def scenario(driver, pins, pin_log, machine_log):
        for value in written:
            yield from write(driver, "WATCHDOG", value)
            yield from wait_clocks(driver, 10)
            left = yield from read(driver, "WATCHDOG")
            status = yield from read(driver, "INT_STATUS")
            yield from write(driver, "INT_STATUS", status)
            results[value] = (left, field("INT_STATUS", "CLAMPED", status))

    run_machine("watchdog_clamped", scenario, cosim)
    for value in written:
        left, clamped = results[value]
        assert model.write("WATCHDOG", value) and model.honour(regmap.register("WATCHDOG"), value)[0] == WATCHDOG_MAX
        assert WATCHDOG_MAX - 40 < left <= WATCHDOG_MAX, (value, left)
        assert clamped == 1, value


@pytest.mark.parametrize("cosim", MODES, ids=MODE_IDS)
def test_refused_clear_stop_keeps_the_fifo(cosim):
    """CLEAR_STOP while the E-stop input is active changes nothing: the card
    stays stopped and the FIFO keeps its words; once the E-stop is released a
    CLEAR_STOP drops them (they were written before it)."""
    words = command_words(LineCommand(5, 3)) * 2
    results = {}

    def scenario(driver, pins, pin_log, machine_log):
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

    pin_log, _ = run_machine("clear_stop_refused", scenario, cosim)
    before, refused, cleared = results["before"], results["refused"], results["cleared"]
    assert field("STATUS", "FIFO_LEVEL", before["STATUS"]) == len(words)
    assert field("STATUS", "FIFO_LEVEL", refused["STATUS"]) == len(words), "a refused CLEAR_STOP kept the words"
    assert field("STOP_REASON", "REASON", refused["STOP_REASON"]) == REASON["ESTOP"]
    assert field("STATUS", "STOPPED", refused["STATUS"]) == 1
    assert field("STATUS", "FIFO_LEVEL", cleared["STATUS"]) == 0 and cleared["STOP_REASON"] == 0
    assert not pin_log.rises and cleared["position"] == (0, 0)
