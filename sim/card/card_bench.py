"""Bench pieces shared by the card benches: clock, pin capture, path rebuild, pin model check."""
from dataclasses import dataclass, field

from myhdl import StopSimulation, block, delay, instance, now

from models import instructions as isa
from models.axes import AXIS_NAMES
from models import registers as regmap
from models.card_model import PulseOutModel
from models.dda_model import ArcCommand, iterate
from models.dda_axes import iterate_axes, move_start
from models.parameters import COORD_WIDTH, Build
from rtl.card_core import card_core, card_core_ports
from sim.backends.clocking import clock_source
from sim.backends.icarus import convert_and_cosimulate
from sim.backends.waves import Waveform, find, run_traced, write_gtkw
from sim.card.local_bus_driver import LocalBusDriver

HALF_PERIOD = 5
FIFO_DEPTH = 16
TIMING = dict(width=1, setup=1, hold=1)  # the reset values of STEP_WIDTH, DIR_SETUP, DIR_HOLD
BUS_GROUPS = {"bus": ["local_we", "local_re", "local_space", "local_addr", "local_be", "local_ready",
                      "local_retry", "local_wdata", "local_rdata", "irq"]}
STEP_PINS = ["pin_capture.pins_step_x", "pin_capture.pins_step_y"]
PINS = [f"pin_capture.pins_{line}" for line in ("step_x", "dir_x", "step_y", "dir_y")]
OPERANDS = [f"sequencer.operand_{index}" for index in range(isa.MAX_OPERANDS)]
POSITIONS = ["pulse_out.axis_x.position", "pulse_out.axis_y.position"]
MOTION_GROUPS = {
    "STEP/DIR pins": PINS,
    "position (steps)": POSITIONS,
    "sequencer: command": ["sequencer.state", "sequencer.opcode", "sequencer.header"] + OPERANDS
    + ["sequencer.error_code", "regs_fifo.fifo_level"],
    "feed rate": ["feed_rate.rate", "feed_rate.tick"],
}
MOTION_DISPLAY = dict(signed=POSITIONS + OPERANDS,
                      names={"sequencer.opcode": {op.code: op.name for op in isa.OPCODES}})


# the pins' state as one number: axis i's STEP at bit 2i, its DIR at bit 2i + 1 (X: 1, 2; Y: 4, 8)
PIN_BITS = {f"{kind}_{name.lower()}": 1 << (2 * axis + bit) for axis, name in enumerate(AXIS_NAMES)
            for bit, kind in enumerate(("step", "dir"))}


@dataclass
class PinLog:
    """Rises of the STEP pins: (clock, x stepped, y stepped, x dir pin, y dir pin);
    ``edges``: every change of the STEP/DIR pins of every axis, (clock, state by ``PIN_BITS``).
    A clock is numbered by the rising edges before it: pins that change after
    edge n are recorded with clock n."""
    rises: list = field(default_factory=list)
    edges: list = field(default_factory=list)
    clock: int = 0

    def path(self, start=(0, 0), polarity=(0, 0)):
        """Points visited, one per clock with a rise (a diagonal is one point)."""
        x, y = start
        points = [(x, y)]
        for _, sx, sy, dx, dy in self.rises:
            x += (1 if dx != polarity[0] else -1) * sx
            y += (1 if dy != polarity[1] else -1) * sy
            points.append((x, y))
        return points

    def axis_rises(self, axes, polarity=0):
        """[(clock, point)] of every clock in which a STEP pin of ``axes`` axes rose (a clock's
        rises together one point), from the edges; ``polarity``: bit i, axis i's DIR_POLARITY."""
        here, before, result = [0] * axes, 0, []
        for clock, state in self.edges:
            rose = state & ~before
            if any(rose >> (2 * axis) & 1 for axis in range(axes)):
                for axis in range(axes):
                    if rose >> (2 * axis) & 1:
                        positive = bool(state >> (2 * axis + 1) & 1) != bool(polarity >> axis & 1)
                        here[axis] += 1 if positive else -1
                result.append((clock, tuple(here)))
            before = state
        return result

    def axis_points(self, axes, polarity=0):
        """The origin and the points of ``axis_rises``."""
        return [(0,) * axes] + [point for _, point in self.axis_rises(axes, polarity)]

    def gaps(self):
        """Clocks between consecutive rises."""
        return [b[0] - a[0] for a, b in zip(self.rises, self.rises[1:])]


@block
def clock_and_pins(clock, pins, log):
    """The bench clock and the STEP/DIR capture."""

    clock_gen = clock_source(clock, 2 * HALF_PERIOD)

    return clock_gen, pin_capture(clock, pins, log)


@block
def pin_capture(clock, pins, log):
    """Record every STEP rise into ``log`` (pins sampled at each falling edge)."""

    @instance
    def capture():
        before, state_before = (False, False), 0
        while True:
            yield clock.negedge
            log.clock += 1
            now = (bool(pins.step_x), bool(pins.step_y))
            sx, sy = now[0] and not before[0], now[1] and not before[1]
            if sx or sy:
                log.rises.append((log.clock, sx, sy, bool(pins.dir_x), bool(pins.dir_y)))
            before = now
            state = sum(bit for name, bit in PIN_BITS.items() if getattr(pins, name, False))
            if state != state_before:
                log.edges.append((log.clock, state))
            state_before = state

    return capture


@block
def pin_model_check(clock, reset, pins, regs_block, timing, failures):
    """Compare the pins every clock with ``PulseOutModel`` fed with the DDA's own
    step outputs and the core's clear (MyHDL runs only: reads internal signals).
    Stops at the first direct pulse (the model is fed from the DDA only)."""
    sig = regs_block.sigdict
    steps = [sig[f"steps_{name}"] for name in ("step_x", "step_y", "dir_x", "dir_y")]
    clear, ready, direct_busy = sig["core_clear"], sig["out_ready"], sig["pulse_busy"]
    model = PulseOutModel()

    def differences():
        seen = {"STEP": ((bool(pins.step_x), bool(pins.step_y)), model.step_pins),
                "DIR": ((bool(pins.dir_x), bool(pins.dir_y)), model.dir_pins),
                "ready": (bool(ready), model.ready)}
        return [f"{name} {rtl} != model {golden} at {now()}" for name, (rtl, golden) in seen.items()
                if rtl != golden]

    @instance
    def check():
        yield reset.posedge  # released at a falling edge: the next rising edge is the first
        while not bool(direct_busy):
            model.clock((bool(steps[0]), bool(steps[1])), (bool(steps[2]), bool(steps[3])),
                        clear=bool(clear), **timing)
            yield clock.negedge
            if not failures:
                failures.extend(differences())

    return check


@block
def core_bench(ports, scenario, log, failures, cosim, check_pins, fifo_depth):
    """``card_core`` (MyHDL or Icarus) on the back-end bus driver, pins captured."""
    clock, reset = ports["clock"], ports["reset"]
    if cosim:
        core = convert_and_cosimulate(card_core, "card_core", ports, build=Build(fifo_depth=fifo_depth))
        parts = [core, clock_and_pins(clock, ports["pins"], log)]
    else:
        core = card_core(**ports, build=Build(fifo_depth=fifo_depth))
        parts = [core, clock_and_pins(clock, ports["pins"], log)]
        if check_pins:
            parts.append(pin_model_check(clock, reset, ports["pins"], core.subs[1], TIMING, failures))
    driver = LocalBusDriver(clock, ports["local"])
    return parts, scenario_runner(clock, reset, driver, scenario)


@block
def scenario_runner(clock, reset, driver, scenario):
    """Hold reset for two clocks, then run ``scenario(driver)`` and stop."""

    @instance
    def run():
        reset.next = 0
        yield delay(1)  # a delay in the body: MyHDL then allows every kind of wait in the scenario
        yield clock.negedge
        yield clock.negedge
        reset.next = 1
        yield from scenario(driver)
        raise StopSimulation

    return run


def wait_idle(driver, limit=50000):
    """Read STATUS until BUSY is 0; returns that STATUS word."""
    for _ in range(limit):
        status = yield from driver.io_read(regmap.offset("STATUS"))
        if not regmap.field_value("STATUS", "BUSY", status):
            return status
    raise AssertionError("card still busy")


def wait_error(driver, limit, settle=50):
    """Read STATUS until ERROR is set (at most ``limit`` reads), then let
    ``settle`` clocks pass (the stopped card must stay stopped); returns
    STATUS.ERROR, 0 if no error came."""
    for _ in range(limit):
        status = yield from driver.io_read(regmap.offset("STATUS"))
        if regmap.field_value("STATUS", "ERROR", status):
            break
    for _ in range(settle):
        yield driver.clock.negedge
    return regmap.field_value("STATUS", "ERROR", status)


def read_position(driver):
    """(POS_X, POS_Y) in steps."""
    x = yield from driver.io_read(regmap.offset("POS_X"))
    y = yield from driver.io_read(regmap.offset("POS_Y"))
    return regmap.field_value("POS_X", "STEPS", x), regmap.field_value("POS_Y", "STEPS", y)


def run_core(name, scenario, cosim=False, check_pins=True, fifo_depth=FIFO_DEPTH, trace=None):
    """Run ``scenario(driver)`` (a generator) on the core; (pin log, waveform or None if
    untraced: ``trace`` as ``sim.backends.waves.run_traced`` takes it)."""
    ports = card_core_ports()
    log, failures = PinLog(), []
    vcd = run_traced(core_bench(ports, scenario, log, failures, cosim, check_pins, fifo_depth), name, trace=trace)
    wave = None if vcd is None else Waveform(vcd)
    if wave is not None:
        write_motion_view(vcd, BUS_GROUPS, wave)
    assert not failures, failures[0]
    return log, wave


def write_motion_view(vcd, groups=None, wave=None):
    """The save file of a card or motion bench: ``groups`` (e.g. the bus), then
    STEP/DIR, positions, the sequencer's command and the feed rate, as far as
    the VCD has them (a co-simulated core shows only its pins); the whole run,
    the marker on the first STEP pulse."""
    wave = wave or Waveform(vcd)
    steps = [find(wave.changes, pin) for pin in STEP_PINS]
    rises = [wave.edges(full, "1")[:1] for full in steps if full]
    marker = min((times[0] for times in rises if times), default=None)
    return write_gtkw(vcd, {**(groups or {}), **MOTION_GROUPS}, optional=True, marker=marker,
                      **MOTION_DISPLAY)


def expected_path(commands, coord_width=24):
    """Points of the model's paths of ``commands`` (ArcCommand / LineCommand), chained."""
    points = [(0, 0)]
    for command in commands:
        path = iterate(command, coord_width)
        x0, y0 = points[-1]
        if isinstance(command, ArcCommand):
            sx, sy = command.xs, command.ys
            points += [(x0 + x - sx, y0 + y - sy) for x, y in path.points()[1:]]
        else:
            points += [(x0 + x, y0 + y) for x, y in path.points()[1:]]
    return points


def axes_path(commands, axes, coord_width=COORD_WIDTH.default):
    """Points the golden model's moves of ``axes`` axes visit (``models.dda_axes.iterate_axes``),
    chained from the origin (a diagonal is one point)."""
    points = [(0,) * axes]
    for command in commands:
        path = iterate_axes(command, axes, coord_width=coord_width)
        start = move_start(command, axes)
        here = points[-1]
        points += [tuple(h + p - s for h, p, s in zip(here, point, start)) for point in path.points()[1:]]
    return points
