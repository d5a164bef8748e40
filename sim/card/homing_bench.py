"""Bench pieces for HOME on the card core: the settings, the write, the wait,
and one whole homing run with a home switch (``sim/card/test_homing.py``,
``bench/homing_figures.py``)."""
from models import registers as regmap
from sim.card.card_bench import read_position, wait_idle
from sim.card.machine_bench import read, run_machine, write

SAMPLES = 4        # INPUT_FILTER: the switch's chatter runs (1..3 clocks) never pass it
SEEK, RELEASE = 9, 60   # HOME_*_PERIOD: the release period outlasts chatter, filter and a step
WIDTH = 2
BACKOFF = 5
AXES = "xy"


def arm(driver, backoff=BACKOFF, search=200, samples=SAMPLES, tick=1):
    """The HOME_* registers, the filter, STEP_WIDTH, the drives on, INT_ENABLE.HOMED."""
    for name, value in (("STEP_WIDTH", WIDTH), ("STEP_SPACE", WIDTH), ("INPUT_FILTER", samples),
                        ("INPUT_TICK", tick), ("HOME_SEEK_PERIOD", SEEK),
                        ("HOME_RELEASE_PERIOD", RELEASE), ("HOME_BACKOFF", backoff), ("HOME_SEARCH", search),
                        ("MACHINE_CONTROL", 1), ("INT_ENABLE", regmap.field_of("INT_ENABLE", HOMED=1))):
        yield from write(driver, name, value)


def home(driver, axis, negative):
    """Write HOME: ``axis`` 0 X, 1 Y; ``negative``: the switch's end."""
    yield from write(driver, "HOME", regmap.field_of("HOME", AXIS=axis, NEGATIVE=int(negative)))


def wait_homed(driver, limit=20000):
    """Read HOME_STATUS until BUSY is 0; that word."""
    for _ in range(limit):
        word = yield from read(driver, "HOME_STATUS")
        if not regmap.field_value("HOME_STATUS", "BUSY", word):
            return word
    raise AssertionError("still homing")


def outcome(word):
    """HOME_STATUS's fields by name."""
    return {name: regmap.field_value("HOME_STATUS", name, word) for name in ("BUSY", "DONE", "NOT_FOUND", "REFUSED", "PHASE")}


def homing_run(name, cosim, axis, negative, switch, backoff=BACKOFF, search=200, during=None, samples=SAMPLES,
               tick=1):
    """HOME with ``switch`` on ``axis``, the filter at ``samples`` x ``tick``;
    (pin log, registers read at the end)."""
    words = {}

    def scenario(driver, pins, pin_log, machine_log):
        yield from arm(driver, backoff, search, samples, tick)
        yield from home(driver, axis, negative)
        if during:
            yield from during(driver, pins, pin_log, machine_log, words)
        words["HOME_STATUS"] = yield from wait_homed(driver)
        yield from wait_idle(driver)
        for register in ("HOME", "INT_STATUS", "STATUS", "STOP_REASON"):
            words[register] = yield from read(driver, register)
        words["position"] = yield from read_position(driver)

    pin_log, _ = run_machine(name, scenario, cosim, switches=[(AXES[axis], switch)])
    return pin_log, words
