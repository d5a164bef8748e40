"""The card API end to end on the simulated card: identity from the build
parameters, timing in nanoseconds measured on the pins, moves against the
DDA's golden model, card errors named with their command, stop.

The expectations come from the build's parameter table, the register table,
``models.dda_model`` (the card's step path) and the pins; never from the API."""
import math

import pytest

from host.card import Card, CardError, IdentityError, MachineStopped
from host.homing import HomingError
from host.transports.base import Transport
from host.transports.simulated import SimTransport
from models import instructions as isa
from models import registers as regmap
from models.dda_model import ArcCommand, LineCommand
from models.parameters import PARAMETERS, VARIANT_NAMES, VARIANT_SETS
from sim.card.card_bench import expected_path
from sim.card.card_jobs import check_pin_timing

CLOCK_HZ = PARAMETERS["clock_hz"].default


@pytest.fixture(scope="module")
def transport():
    with SimTransport("verilator") as opened:
        yield opened


@pytest.fixture
def card(transport):
    card = Card(transport)
    card.stop()
    card.clear_stop()
    card.configure()
    card.write("COMMAND", regmap.field_of("COMMAND", CLEAR_POSITION=1))
    card.start(interrupts=("ERROR", "DONE"))
    yield card
    card.stop()


def test_identity_is_the_build(transport):
    identity = Card(transport).identify()
    names = VARIANT_SETS[PARAMETERS["variants"].default_for("card")]
    assert identity.version == (regmap.VERSION >> 8, regmap.VERSION & 0xFF)
    assert identity.clock_hz == CLOCK_HZ
    assert identity.fifo_words == PARAMETERS["fifo_depth"].default
    assert identity.coord_width == PARAMETERS["coord_width"].default
    assert identity.axes == 2
    assert identity.variants == tuple(VARIANT_NAMES.index(name) for name in names)
    assert (identity.vendor_id, identity.device_id) == (PARAMETERS["vendor_id"].default,
                                                         PARAMETERS["device_id"].default)


class FakeRegisters(Transport):
    """Registers in a dict: enough to show what identification refuses."""

    name = "fake card"

    def __init__(self, id_word):
        self.values = {regmap.offset("ID"): id_word}

    def read(self, offset, size=4):
        return self.values.get(offset, 0)

    def config_read(self, register, size=4):
        return 0


MAJOR = regmap.VERSION >> 8


# a card of another major version, newer or older (1.3: before a stop cleared
# MACHINE_CONTROL.DRIVE_ENABLE; 2.4: before AREA), is refused
@pytest.mark.parametrize("id_word, text", [
    (0x12340101, "not a DDA card"),
    (regmap.ID_MAGIC << 16 | (MAJOR + 1) << 8 | 1, f"register map {MAJOR + 1}.1; this host software speaks {MAJOR}.x"),
    (regmap.ID_MAGIC << 16 | 0x0103, f"register map 1.3; this host software speaks {MAJOR}.x"),
    (regmap.ID_MAGIC << 16 | 0x0100, f"register map 1.0; this host software speaks {MAJOR}.x"),
    # 2.4: a helical ARC's ITERATIONS where 3.0 sends AREA_LO, AREA_HI
    (regmap.ID_MAGIC << 16 | 0x0204, f"register map 2.4; this host software speaks {MAJOR}.x"),
])
def test_identification_refuses_other_cards_and_versions(id_word, text):
    with pytest.raises(IdentityError, match=text):
        Card(FakeRegisters(id_word))


def high_times(edges, bit):
    """Clocks each pulse of pin ``bit`` stays high, from the pins' edges."""
    times, rose, state = [], None, 0
    for clock, new in edges:
        if new & bit and not state & bit:
            rose = clock
        elif state & bit and not new & bit:
            times.append(clock - rose)
        state = new
    return times


@pytest.mark.parametrize("width_ns, setup_ns, hold_ns, space_ns", [(2000, 500, 300, None), (30, 1, 7000, 3000)])
def test_pulse_timing_in_nanoseconds_is_met_on_the_pins(card, transport, width_ns, setup_ns, hold_ns, space_ns):
    card.configure(step_width_ns=width_ns, dir_setup_ns=setup_ns, dir_hold_ns=hold_ns, step_space_ns=space_ns)
    # the low time between steps is the high time unless STEP_SPACE is given
    expect = [max(1, math.ceil(ns * 1e-9 * CLOCK_HZ - 1e-9))
              for ns in (width_ns, setup_ns, hold_ns, width_ns if space_ns is None else space_ns)]
    first = len(transport.pins.edges)
    card.line(6, -4)
    card.line(-5, 3)
    card.wait_done()
    edges = transport.pins.edges[first:]
    assert set(high_times(edges, 1)) == {expect[0]}  # STEP X
    assert check_pin_timing(edges, *expect) is None
    assert card.read("STEP_SPACE") == expect[3]
    assert card.position() == (1, -1)


def test_timing_the_card_cannot_make_is_refused_before_anything_is_written(card):
    before = card.read("STEP_WIDTH")
    with pytest.raises(ValueError, match="STEP_WIDTH"):
        card.configure(step_width_ns=256 / CLOCK_HZ * 1e9, dir_setup_ns=500)
    with pytest.raises(ValueError, match="polarity"):
        card.configure(polarity=(0, 2))
    assert card.read("STEP_WIDTH") == before


def test_commands_end_where_the_model_says(card, transport):
    moves = [LineCommand(40, 25), ArcCommand(0, -30, 30, 0, ccw=True, variant=3), LineCommand(-70, 0),
             ArcCommand(-20, 0, -20, 0, ccw=False, variant=3)]
    first = len(transport.pins.rises)
    card.line(40, 25, blend=True)
    card.arc(centre=(0, 30), end=(30, 30), ccw=True)
    card.set("FEED_RATE", 8000)
    tag = card.mark()
    card.line(-70, 0)
    card.dwell(20e-6)
    card.arc(centre=(20, 0), end=(0, 0))
    card.wait_done()
    assert card.last_mark() == tag
    assert card.read("FEED_RATE") == 8000
    ideal = expected_path(moves)
    assert card.position() == ideal[-1]
    pins = transport.pins
    pins_path = [(0, 0)]
    for _, sx, sy, dx, dy in pins.rises[first:]:
        pins_path.append((pins_path[-1][0] + (sx if dx else -sx), pins_path[-1][1] + (sy if dy else -sy)))
    assert pins_path == ideal


def test_direct_pulses(card):
    card.write("PULSE_PERIOD_X", 5)
    card.pulse(7, -3)
    card.wait_done()
    assert card.position() == (7, -3)


def test_queue_space_counts_the_fifo(card):
    card.write("CONTROL", 0)
    depth = card.identity.fifo_words
    assert card.queue_space() == depth
    for _ in range(10):
        card.mark()
    # the instruction register holds the first command (docs/instructions.md)
    assert card.queue_space() == depth - 9
    with pytest.raises(TimeoutError, match="still busy"):
        card.wait_done(timeout=1e-4)


@pytest.mark.parametrize("error, words", [
    ("BAD_OPCODE", [0xF0000000]),
    ("RESERVED_BITS", [isa.encode("LINE", 1, 1)[0] | 1 << 7, 1, 1]),   # bit 7: no field of LINE (AXES is 25:20)
    ("RANGE", isa.encode("SET", 5, INDEX=15)),
    ("RANGE", isa.encode("LINE", 1 << 25, 0)),
    ("DDA_REJECTED", isa.encode("ARC", 5, 0, 0, 7, VARIANT=3)),
])
def test_card_errors_name_the_command(card, transport, error, words):
    card.line(3, 0)
    card.send(words, "the bad one")
    card.line(0, 3)
    card.line(0, 4)
    with pytest.raises(CardError) as raised:
        card.wait_done()
    assert raised.value.name == error
    assert raised.value.code == isa.ERROR_CODE[error]
    assert raised.value.command == "the bad one"
    transport.sleep(20e-6)  # the move before it finishes (its last step may still be in the pulse stage)
    assert card.position() == (3, 0)  # the commands before it ran, nothing after it
    card.clear_error()
    if error != "BAD_OPCODE":  # the card empties the FIFO then
        card.wait_done()
        assert card.position() == (3, 7)


@pytest.mark.parametrize("call, text", [
    (lambda c: c.line(1 << 23, 0), "does not fit"),
    (lambda c: c.line(0, 0), "moves nowhere"),
    (lambda c: c.arc(centre=(5, 0), end=(5, 7)), "ARC centre"),
    (lambda c: c.arc(centre=(5, 0), end=(10, 5), variant=0), "not built"),
    (lambda c: c.set("STEP_WIDTH", 0), "outside 1..255"),
    (lambda c: c.set("CONTROL", 1), "no SET index"),
    (lambda c: c.mark(1 << 16), "outside 0..65535"),
    (lambda c: c.pulse(1 << 23, 0), "24 signed bits"),
    (lambda c: c.dwell(-1), "DWELL"),
    (lambda c: c.write("FEED_RATE", 0), "outside 1..32768"),
])
def test_bad_commands_are_refused_before_a_word_is_queued(card, call, text):
    with pytest.raises(ValueError, match=text):
        call(card)
    assert card.queue_space() == card.identity.fifo_words and card.consumed() == 0


def test_stop_mid_motion_reports_where_the_pins_stopped(card, transport):
    first = len(transport.pins.rises)
    card.set("FEED_RATE", 2000)
    card.line(5000, 1000)
    transport.sleep(1e-3)
    position = card.stop()
    transport.sleep(1e-4)
    assert card.position() == position
    rises = transport.pins.rises[first:]
    assert 0 < position[0] < 5000
    assert position == (sum(r[1] for r in rises), sum(r[2] for r in rises))
    status = card.status()
    assert not regmap.field_value("STATUS", "BUSY", status) and regmap.field_value("STATUS", "FIFO_EMPTY", status)


def test_a_short_job_on_myhdl():
    with SimTransport("myhdl") as transport:
        card = Card(transport)
        card.configure()
        card.start(interrupts=("ERROR", "DONE"))
        card.line(4, -3)
        card.arc(centre=(-4, 3), end=(-4, 8), ccw=True)
        card.wait_done()
        assert card.position() == expected_path([LineCommand(4, -3), ArcCommand(4, -3, 0, 5, ccw=True,
                                                                               variant=3)])[-1]


def test_machine_at_rest_and_drive_enable(card, transport):
    assert not card.estop_state() and card.limits() == () and card.stop_reason() == ("NONE", ())
    card.drive(True)
    transport.sleep(1e-6)
    assert regmap.field_value("MACHINE_STATUS", "DRIVE_ENABLE", card.read("MACHINE_STATUS")) == 1
    card.drive(False)
    transport.sleep(1e-6)
    assert regmap.field_value("MACHINE_STATUS", "DRIVE_ENABLE", card.read("MACHINE_STATUS")) == 0


def test_filter_setting_is_what_the_registers_hold(card):
    honoured = card.inputs(active_low=("HOME_X", "HOME_Y"), filter_ns=2000)
    samples, tick = card.read("INPUT_FILTER"), card.read("INPUT_TICK")
    assert card.read("INPUT_POLARITY") == 1 << 5 | 1 << 6
    assert samples <= 15 and samples * tick >= 2000e-9 * CLOCK_HZ
    assert honoured == pytest.approx(samples * tick * 1e9 / CLOCK_HZ)
    card.inputs()


def test_watchdog_stops_a_move_the_host_forgets(card, transport):
    """The host writes the watchdog once and then only waits: the card stops
    the move about that long after the write and says why."""
    first = len(transport.pins.rises)
    card.set("FEED_RATE", 2000)
    card.drive(True)
    written = transport.clocks
    clocks = card.watchdog(200e-6)
    card.line(5000, 1000)
    with pytest.raises(MachineStopped, match="WATCHDOG") as stopped:
        card.wait_done(timeout=5e-3)
    assert stopped.value.reason == "WATCHDOG"
    rises = transport.pins.rises[first:]
    assert rises and rises[-1][0] <= written + clocks + 50
    position = card.position()
    assert position == (sum(r[1] for r in rises), sum(r[2] for r in rises)) and 0 < position[0] < 5000
    assert regmap.field_value("MACHINE_STATUS", "DRIVE_ENABLE", card.read("MACHINE_STATUS")) == 0
    card.watchdog(0)
    with pytest.raises(MachineStopped, match="WATCHDOG"):
        card.drive(True)   # not kept while stopped: refused before anything is written
    card.clear_stop()
    assert card.stop_reason() == ("NONE", ())
    # CLEAR_STOP does not re-energise: the drives stay off until drive(True)
    transport.sleep(1e-6)
    assert card.field("MACHINE_STATUS", "DRIVE_ENABLE") == 0 and card.field("MACHINE_CONTROL", "DRIVE_ENABLE") == 0
    card.drive(True)
    transport.sleep(1e-6)
    assert card.field("MACHINE_STATUS", "DRIVE_ENABLE") == 1
    card.drive(False)


@pytest.mark.parametrize("ramp_step", [0, 300])
def test_hold_and_resume_keep_the_path(card, transport, ramp_step):
    """hold() returns once the pins are still; nothing moves until resume();
    the pins then finish the path the DDA's model gives, step for step."""
    first = len(transport.pins.rises)
    card.write("RAMP_START", 500)
    card.write("RAMP_STEP", ramp_step)
    card.set("FEED_RATE", 6000)
    card.drive(True)
    try:
        card.line(700, 260)
        card.arc(centre=(-90, 0), end=(-180, 0), ccw=True)
        transport.sleep(60e-6)
        position = card.hold()
        held_rises = len(transport.pins.rises)
        transport.sleep(100e-6)
        assert card.position() == position and len(transport.pins.rises) == held_rises, "a step while held"
        assert card.field("MACHINE_CONTROL", "DRIVE_ENABLE") == 1, "hold keeps the drive bit"
        card.resume()
        card.wait_done(timeout=5e-3)
    finally:
        card.resume()
        card.write("RAMP_STEP", 0)
    rises = transport.pins.rises[first:]
    path = [(0, 0)]
    for _, step_x, step_y, dir_x, dir_y in rises:
        path.append((path[-1][0] + (1 if dir_x else -1) * step_x, path[-1][1] + (1 if dir_y else -1) * step_y))
    assert 0 < held_rises - first < len(rises), "the hold came mid-path"
    expected = expected_path([LineCommand(700, 260), ArcCommand(90, 0, -90, 0, ccw=True, variant=3)])
    assert path == expected and card.position() == expected[-1]


HOME_REGISTERS = ("HOME_SEEK_PERIOD", "HOME_RELEASE_PERIOD", "HOME_BACKOFF", "HOME_SEARCH")


def test_home_without_a_switch_steps_the_search_at_the_seek_rate(card, transport):
    """The harness's home inputs stay open: the seek runs out, NOT_FOUND, nothing zeroed.
    (A period of 100 clocks: longer than a pulse and its low time, 2 x STEP_WIDTH;
    the first two steps leave late by the DIR change, DIR_HOLD and DIR_SETUP.)"""
    first = len(transport.pins.rises)
    with pytest.raises(HomingError, match="NOT_FOUND") as failed:
        card.home("Y", direction="negative", seek_rate=CLOCK_HZ / 100, search=40)
    assert failed.value.reason == "NOT_FOUND" and failed.value.axis == "Y"
    assert [card.read(name) for name in HOME_REGISTERS] == [100, round(CLOCK_HZ / 1000.0), 0, 40]
    rises = transport.pins.rises[first:]
    assert len(rises) == 40 and all(r[2] and not r[1] and not r[4] for r in rises), "40 steps, Y-"
    assert {b[0] - a[0] for a, b in zip(rises[2:], rises[3:])} == {100}
    assert card.position() == (0, -40)


def test_home_while_a_move_runs_is_refused_and_the_move_goes_on(card, transport):
    card.set("FEED_RATE", 2000)
    card.line(3000, 0)
    transport.sleep(1e-4)
    with pytest.raises(HomingError, match="REFUSED"):
        card.home("X")
    card.wait_done()
    assert card.position() == (3000, 0)


@pytest.mark.parametrize("settings", [dict(axis="Z"), dict(axis="X", direction="up"), dict(axis="X", seek_rate=1),
                                      dict(axis="X", release_rate=3 * CLOCK_HZ), dict(axis="X", backoff=-1),
                                      dict(axis="X", search=0), dict(axis="X", search=1 << 23)])
def test_home_values_are_checked_before_anything_is_written(card, settings):
    before = [card.read(name) for name in HOME_REGISTERS + ("HOME", "HOME_STATUS")]
    with pytest.raises(ValueError):
        card.home(**settings)
    assert [card.read(name) for name in HOME_REGISTERS + ("HOME", "HOME_STATUS")] == before
