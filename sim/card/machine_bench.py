"""Bench pieces for the machine side of the card: input pins, DRIVE_ENABLE capture, pulse checks.

``run_machine`` runs a scenario on ``card_core`` (MyHDL, or its Verilog in
Icarus) like ``sim.card.card_bench.run_core``, and hands the scenario the
machine's pins as well as the bus driver, so that it can press the E-stop
or trip a limit at a chosen clock (``set_input``); ``home_switch`` is a
home switch the axis position moves (``models.homing_model.BouncingSwitch``).
"""
from dataclasses import dataclass, field

from myhdl import block, delay, instance

from models import registers as regmap
from models.commands import command_words
from models.dda_model import LineCommand
from models.machine_model import REASON
from rtl.card_core import card_core_ports
from sim.backends.waves import run_traced
from sim.card.card_bench import PinLog, core_bench, expected_path, read_position

FIFO_DEPTH = 16
WIDTH = 3   # STEP_WIDTH of the machine benches: a pulse cut short would show
SAMPLES = regmap.register("INPUT_FILTER").reset
# From a pin's change after falling edge N: the synchroniser (2 edges) and the
# filter (SAMPLES edges) make the input active after edge N + SAMPLES + 2;
# a STEP taken in the clock before rises on the pin one edge later, and
# DRIVE_ENABLE falls at that edge: clock N + SAMPLES + 3 in the pin log.
REACTION = SAMPLES + 3


@dataclass
class MachineLog:
    """DRIVE_ENABLE per clock (numbered as ``PinLog``) and the clocks inputs were set at."""
    drive: list = field(default_factory=list)
    inputs: list = field(default_factory=list)   # (clock, name, level)


@block
def drive_capture(clock, pins, log):
    @instance
    def capture():
        while True:
            yield clock.negedge
            log.drive.append(bool(pins.drive_enable))

    return capture


def set_input(pins, pin_log, machine_log, name, level):
    """Set input pin ``name`` one time unit after a falling edge; the rising
    edge that follows takes it into the synchroniser.  Returns its clock
    number (``PinLog`` numbering: that of the falling edge before)."""
    yield delay(1)
    getattr(pins, name).next = level
    machine_log.inputs.append((pin_log.clock, name, level))
    return pin_log.clock


@block
def home_switch(clock, pins, switch, axis):
    """Drive the home pin of ``axis`` ("x" or "y") from ``switch``, moved by
    that axis's STEP/DIR pins (sampled at falling edges, as ``PinLog`` does;
    the level is set one time unit later, for the next rising edge)."""
    step, direction, home = (getattr(pins, f"{name}_{axis}") for name in ("step", "dir", "home"))

    @instance
    def follow():
        before = False
        while True:
            yield clock.negedge
            rose = bool(step) and not before
            before = bool(step)
            level = switch.clock(rose, bool(direction))
            yield delay(1)
            home.next = level

    return follow


def run_machine(name, scenario, cosim=False, fifo_depth=FIFO_DEPTH, switches=()):
    """Run ``scenario(driver, pins, pin_log, machine_log)`` with home
    ``switches`` ([(axis, BouncingSwitch)]); (pin log, machine log)."""
    ports = card_core_ports()
    pin_log, machine_log, failures = PinLog(), MachineLog(), []
    pins = ports["pins"]

    def with_pins(driver):
        yield from scenario(driver, pins, pin_log, machine_log)

    run_traced(_machine_bench(ports, with_pins, pin_log, machine_log, failures, cosim, fifo_depth, switches),
               f"machine_{name}_{'icarus' if cosim else 'myhdl'}")
    return pin_log, machine_log


@block
def _machine_bench(ports, scenario, pin_log, machine_log, failures, cosim, fifo_depth, switches):
    """``core_bench`` (its pin-model check off: the guard holds steps back), the
    DRIVE_ENABLE capture and the home switches."""
    clock, pins = ports["clock"], ports["pins"]
    return (core_bench(ports, scenario, pin_log, failures, cosim, False, fifo_depth),
            drive_capture(clock, pins, machine_log), [home_switch(clock, pins, switch, axis) for axis, switch in switches])


def pulse_widths(pin_log, pin="step_x"):
    """High times of a STEP pin in clocks, from the pin log's edges (a pulse
    still high at the end is left out)."""
    bit = {"step_x": 1, "step_y": 4}[pin]
    widths, rose = [], None
    for clock, state in pin_log.edges:
        high = bool(state & bit)
        if high and rose is None:
            rose = clock
        elif not high and rose is not None:
            widths.append(clock - rose)
            rose = None
    return widths


def step_pulses(pin_log):
    """(rise, fall) clocks of every STEP pulse of both pins (``PinLog``
    numbering: high from clock rise, low again in clock fall; a pulse still
    high at the end has fall None)."""
    pulses = []
    for bit in (1, 4):   # step_x, step_y (PIN_BITS)
        rose, before = None, 0
        for clock, state in pin_log.edges:
            high, was = bool(state & bit), bool(before & bit)
            if high and not was:
                rose = clock
            elif was and not high:
                pulses.append((rose, clock))
                rose = None
            before = state
        if rose is not None:
            pulses.append((rose, None))
    return sorted(pulses)


def pulses_outside_drive(pin_log, machine_log):
    """The STEP pulses during which DRIVE_ENABLE was low in some clock from
    the rise to the clock the STEP pin is low again (that one included: the
    drive may count on either edge)."""
    end = len(machine_log.drive)
    return [(rise, fall) for rise, fall in step_pulses(pin_log)
            if not all(drive_at(machine_log, clock) for clock in range(rise, min(fall or end, end) + 1))]


def read(driver, name):
    word = yield from driver.io_read(regmap.offset(name))
    return word


def write(driver, name, value):
    yield from driver.io_write(regmap.offset(name), value)


def field(name, field_name, word):
    return regmap.field_value(name, field_name, word)


def wait_clocks(driver, count):
    for _ in range(count):
        yield driver.clock.negedge


def snapshot(driver):
    """The registers that tell why the card stopped."""
    words = {}
    for name in ("STATUS", "STOP_REASON", "MACHINE_STATUS", "INT_STATUS"):
        words[name] = yield from read(driver, name)
    words["position"] = yield from read_position(driver)
    return words


def clear_stop(driver):
    """COMMAND.CLEAR_STOP, and the clocks it takes to reach the latch (bus write, register, strobe)."""
    yield from write(driver, "COMMAND", regmap.field_of("COMMAND", CLEAR_STOP=1))
    yield from wait_clocks(driver, 3)


def drive_at(machine_log, clock):
    return machine_log.drive[clock - 1]   # the first falling edge is clock 1


def assert_stopped(words, reason):
    assert field("STATUS", "STOPPED", words["STATUS"]) == 1
    assert field("STOP_REASON", "REASON", words["STOP_REASON"]) == REASON[reason]
    assert field("MACHINE_STATUS", "STOPPED", words["MACHINE_STATUS"]) == 1
    assert field("MACHINE_STATUS", "DRIVE_ENABLE", words["MACHINE_STATUS"]) == 0
    assert field("INT_STATUS", "STOPPED", words["INT_STATUS"]) == 1
    assert not field("STATUS", "BUSY", words["STATUS"]), "the queue is held"


def assert_exact(pin_log, position, commands, width=WIDTH):
    """The pins' path is a prefix of the uninterrupted one and ends at POS_X/POS_Y."""
    path = pin_log.path()
    assert path == expected_path(commands)[:len(path)]
    assert path[-1] == position
    assert set(pulse_widths(pin_log, "step_x") + pulse_widths(pin_log, "step_y")) <= {width}, "a partial pulse"


STOP_CAUSES = ("watchdog", "estop", "limit", "decelerated")


def stop_and_clear(driver, pins, pin_log, machine_log, cause, wait, results):
    """A line towards X+, stopped ``wait`` clocks in by ``cause`` (``STOP_CAUSES``;
    "decelerated": the watchdog with RAMP_STEP set), the input released, CLEAR_STOP,
    then MACHINE_CONTROL.DRIVE_ENABLE written again; what the registers said at each
    step goes to ``results`` (a list of dicts)."""
    ramp = cause == "decelerated"
    yield from write(driver, "RAMP_STEP", 512 if ramp else 0)
    yield from driver.push_all(command_words(LineCommand(150, 40)))
    yield from wait_clocks(driver, 60 + wait)
    record = dict(cause=cause, at=pin_log.clock)
    if cause in ("watchdog", "decelerated"):
        yield from write(driver, "WATCHDOG", 1)
    else:
        yield from set_input(pins, pin_log, machine_log, "estop" if cause == "estop" else "limit_pos_x", 1)
    for _ in range(200):
        status = yield from read(driver, "STATUS")
        if field("STATUS", "STOPPED", status):
            break
    record["stopped"] = yield from snapshot(driver)
    record["control_stopped"] = yield from read(driver, "MACHINE_CONTROL")
    if cause in ("estop", "limit"):
        yield from set_input(pins, pin_log, machine_log, "estop" if cause == "estop" else "limit_pos_x", 0)
        yield from wait_clocks(driver, 3 * REACTION)
    yield from write(driver, "MACHINE_CONTROL", 1)    # while stopped: not kept
    yield from clear_stop(driver)
    record["cleared"] = yield from snapshot(driver)
    record["control_cleared"] = yield from read(driver, "MACHINE_CONTROL")
    yield from write(driver, "MACHINE_CONTROL", 1)
    yield from wait_clocks(driver, 3)
    record["enabled"] = yield from read(driver, "MACHINE_STATUS")
    results.append(record)


def stop_cycles(results, waits=range(6)):
    """A scenario: ``stop_and_clear`` for every cause, ``waits`` clocks into the line."""
    def scenario(driver, pins, pin_log, machine_log):
        for name, value in (("FEED_RATE", regmap.RATE_MAX // 2), ("RAMP_START", 1024), ("STEP_WIDTH", WIDTH),
                            ("CONTROL", 1), ("MACHINE_CONTROL", 1)):
            yield from write(driver, name, value)
        for cause in STOP_CAUSES:
            for wait in waits:
                yield from stop_and_clear(driver, pins, pin_log, machine_log, cause, wait, results)
        results.append(dict(position=(yield from read_position(driver))))
    return scenario


def drive_margins(pin_log, machine_log, at, until):
    """(clocks from the last STEP rise to DRIVE_ENABLE low, from that STEP's fall to it)
    for the stop caused at clock ``at`` (the first DRIVE_ENABLE fall after it, before ``until``)."""
    fell = next(clock for clock in range(at + 1, until) if not drive_at(machine_log, clock))
    rise, fall = max((p for p in step_pulses(pin_log) if p[0] < fell), default=(None, None))
    if rise is None:
        return None, None
    return fell - rise, fell - fall


def drive_low_at(pin_log, latch):
    """The clock DRIVE_ENABLE reads low for a stop that would drop it at clock
    ``latch``: a STEP pulse that rose by then keeps it high to the clock after
    its fall (docs/machine.md)."""
    falls = [fall for rise, fall in step_pulses(pin_log) if rise <= latch and fall is not None and fall >= latch]
    return max([latch] + [fall + 1 for fall in falls])
