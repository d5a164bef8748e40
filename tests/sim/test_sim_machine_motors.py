"""The simulated machine's motors in the compiled Verilator harness against their golden model
(models/sim_machine.py), clock for clock, on a card built with encoders driven through the host API
(two axes; three, with Z's motor, switch, stall and limit stop); and the card's ENC_COUNT, read over
PCI, against the model's count (on Verilator and on the MyHDL card, whose machine process runs the
model itself).

The harness records every change of the encoder pins it drives; the card's STEP/DIR edges are in the
pin log, DRIVE_ENABLE's changes in the machine's input record.  Replaying them through ``SimMachine``
(with the stall asked at the same clock) must give the same encoder pins in every clock, the same
counts, positions and lost steps.
"""
import pytest

from host import encoders
from host.card import Card
from host.machine_io import MachineStopped
from host.transports.simulated import SimTransport
from models import registers as regmap
from models.commands import command_words
from models.dda_plan import AxesLineCommand
from models.sim_machine import MachineConfig, Motor, SimMachine, Switch
from sim.backends.verilator.model import DRIVE_BIT

pytestmark = pytest.mark.xdist_group("encoder_card")

CONFIG = MachineConfig(motors={
    "X": Motor(counts_per_step=(5, 2), lag=7, spacing=3, jitter=2, seed=5, index_period=24),
    "Y": Motor(counts_per_step=4, lag=0, spacing=3, index_period=10),
}, start=(3, 0), dir_positive=(True, False))


def _record(transport, with_inputs=False):
    """The harness's records: {clock: DRIVE_ENABLE}, {clock: encoder word} (and {clock: input word})."""
    model = transport.session._runner.card.model
    changes = list(zip(*(array.tolist() for array in model.take_machine_changes())))
    drive = {c: w >> DRIVE_BIT & 1 for c, w in changes}
    encoder = {int(c): int(w) for c, w in zip(*model.take_encoder_changes())}
    inputs = {c: w & ~(1 << DRIVE_BIT) for c, w in changes}
    return (drive, encoder, inputs) if with_inputs else (drive, encoder)


def _replay(edges, drive, encoder, stalls, last_clock, config=CONFIG, axes=2, inputs=None):
    """The golden model of a card of ``axes`` axes on the recorded pins: [(clock, model word, harness
    word)] where the encoder words differ (and, given the harness's ``inputs`` record, the input words)."""
    machine, differences = SimMachine(config, axes), []
    first = min(encoder)     # the clock the harness started the machine in
    pins = next((state for clock, state in reversed(edges) if clock <= first), 0)
    edge_at, enabled, expected = dict(edges), drive[first], encoder[first]
    assert machine.encoder_pins == expected
    for clock in range(first + 1, last_clock + 1):
        pins = edge_at.get(clock, pins)
        for axis in stalls.get(clock - 1, ()):
            machine.stall(axis)
        word = machine.clock(*(pins >> bit & 1 for bit in range(2 * axes)), enabled)
        enabled, expected = drive.get(clock, enabled), encoder.get(clock, expected)
        if machine.encoder_pins != expected:
            differences.append((clock, machine.encoder_pins, expected))
        if inputs is not None and clock in inputs and word != inputs[clock]:
            differences.append((clock, word, inputs[clock]))
    return machine, differences


@pytest.mark.slow(reason="the Verilator card with encoders (a build of its own, about a minute of CPU); the MyHDL "
                         "card below runs the motors in the default set, tests/models their definition")
def test_compiled_motors_match_their_golden_model_and_the_card_counts_them():
    stalls = {}
    with SimTransport("verilator", machine=CONFIG, encoders=1) as transport:
        card = Card(transport)
        card.configure()
        card.start(interrupts=("ERROR", "DONE"))
        card.set("FEED_RATE", 4000)
        card.drive(True)
        for dx, dy in ((40, 25), (-17, -31), (12, 0)):
            card.line(dx, dy)
        card.wait_done()
        card.drive(False)
        card.line(-6, 5)             # the drives off: steps on the pins, lost by the machine
        card.wait_done()
        card.drive(True)
        transport.machine.stall(0)   # X stalls: its steps go on, its encoder stops
        stalls.setdefault(transport.clocks, []).append(0)
        card.line(9, 4)
        card.wait_done()
        transport.sleep(5e-6)         # the last counts through the lag, the spacing and the filter
        state = transport.machine.state()
        read = [encoders.read_encoder(card, axis).count for axis in (0, 1)]
        drive, encoder = _record(transport)
        edges, last = list(transport.pins.edges), transport.clocks
    machine, differences = _replay(edges, drive, encoder, stalls, last)
    assert differences == []
    assert (tuple(machine.positions), tuple(machine.lost)) == (state.positions, state.lost)
    # X: 35 steps taken (from 3), 6 lost to the drive off, 9 to the stall; Y reversed (DIR low forward)
    assert state.positions == (38, 2) and state.lost == (15, 5)
    assert state.counts == (88, 8) == (machine.counts(0), machine.counts(1))   # 35 x 2.5 = 87.5 -> 88; 2 x 4
    assert tuple(read) == state.counts, "the card's decoder counted every edge the motors made"


def test_the_myhdl_card_counts_its_motors_and_a_stall_trips_its_following_error():
    # the MyHDL machine process is the golden model itself: what is checked is the wiring to the card
    config = MachineConfig(motors={"X": Motor(counts_per_step=3, spacing=3), "Y": Motor(counts_per_step=(1, 2))})
    with SimTransport("myhdl", machine=config, encoders=1) as transport:
        card = Card(transport)
        card.configure()
        encoders.set_following_error(card, 0, 3, 4)   # ENC_SCALE 3.0, FERROR_LIMIT 4 counts
        card.start(interrupts=("ERROR", "DONE"))
        card.set("FEED_RATE", 30000)
        card.drive(True)
        card.line(5, -7)
        card.wait_done()
        transport.sleep(1e-6)
        state = transport.machine.state()
        read = tuple(encoders.read_encoder(card, axis).count for axis in (0, 1))
        transport.machine.stall(0)
        card.line(6, 0)              # the second step lost passes the limit: 6 counts behind
        with pytest.raises(MachineStopped, match="FOLLOWING_ERROR"):
            card.wait_done()
        reason, drive = card.read("STOP_REASON"), transport.session.pin("drive_enable")
        stalled = transport.machine.state()
    assert state.counts == read == (15, -3)   # -7 / 2 = -3.5 rounds up to -3
    assert regmap.field_value("STOP_REASON", "AXIS", reason) == 0 and not drive
    assert stalled.counts[0] == 15 and 2 <= stalled.lost[0] < 6


# Z: a lagging, jittering motor at 3/2 counts a step and a bouncing home switch (input bit 9: beyond
# the two-axis card's seven); X a motor with its DIR reversed, Y none (its steps move it all the same)
CONFIG_3 = MachineConfig(motors={
    "X": Motor(counts_per_step=4, spacing=3, index_period=16),
    "Z": Motor(counts_per_step=(3, 2), lag=9, spacing=3, jitter=2, seed=7, index_period=30),
}, switches={"HOME_Z": Switch(-12, positive=False, hysteresis=2, bounce=20, longest_run=3, seed=4)},
    start=(0, 2, 0), dir_positive=(False, True, True))
Z_SCALE, Z_LIMIT = 1.5, 6   # ENC_SCALE = Z's counts per step; FERROR_LIMIT in counts


def _line(card, *steps):
    card.send(command_words(AxesLineCommand(steps)), f"LINE {steps}")


def _z_following_card(transport, feed_rate):
    """A three-axis card started on ``transport`` with Z's following-error stop set and its drives on."""
    card = Card(transport)
    card.configure(steps_per_mm=(200.0,) * 3)
    encoders.set_following_error(card, 2, Z_SCALE, Z_LIMIT)
    card.start(interrupts=("ERROR", "DONE"))
    card.set("FEED_RATE", feed_rate)
    card.drive(True)
    return card


def test_a_three_axis_machine_matches_its_model_and_a_z_stall_stops_the_card_on_z():
    stalls = {}
    with SimTransport("verilator", machine=CONFIG_3, encoders=1, axes=3) as transport:
        card = _z_following_card(transport, feed_rate=4000)
        for steps in ((20, -9, -30), (-7, 4, 25), (0, 0, -19)):   # Z over its home switch, off it, on again
            _line(card, *steps)
        card.wait_done()
        card.drive(False)
        _line(card, 3, 0, -4)        # the drives off: steps on the pins, lost by the machine
        card.wait_done()
        card.drive(True)
        transport.sleep(2e-6)        # the last counts through Z's lag, the spacing and the filter
        encoders.set_following_error(card, 2, Z_SCALE, Z_LIMIT)   # re-aligned after the steps lost
        state = transport.machine.state()
        read = tuple(encoders.read_encoder(card, axis).count for axis in range(3))
        transport.machine.stall(2)   # Z stalls: its steps go on, its encoder stops, the error grows
        stalls.setdefault(transport.clocks, []).append(2)
        _line(card, 2, 0, -12)
        with pytest.raises(MachineStopped, match="FOLLOWING_ERROR"):
            card.wait_done()
        reason, drive = card.stop_reason(), transport.session.pin("drive_enable")
        stalled = transport.machine.state()
        drive_record, encoder, inputs = _record(transport, with_inputs=True)
        edges, last = list(transport.pins.edges), transport.clocks
    machine, differences = _replay(edges, drive_record, encoder, stalls, last, CONFIG_3, 3, inputs)
    assert differences == []
    assert (tuple(machine.positions), tuple(machine.lost)) == (stalled.positions, stalled.lost)
    # X: 13 steps of DIR-reversed pins, 3 lost to the drives off; Y without a motor moves as told; Z -24
    # steps taken, 4 lost; -24 x 3/2 = -36 counts; Y's encoder inputs stay low: ENC_COUNT 0
    assert state.positions == (-13, -3, -24) and state.lost == (3, 0, 4)
    assert state.counts == (-52, None, -36) and read == (-52, 0, -36)
    # the fifth step lost is 7.5 counts behind, past the limit of 6: the stop, on Z
    assert reason == ("FOLLOWING_ERROR", ("Z",)) and not drive
    assert stalled.counts[2] == -36 and 4 + 5 <= stalled.lost[2] < 4 + 12
    assert inputs and any(word >> regmap.INPUT_NAMES.index("HOME_Z") & 1 for word in inputs.values())


def test_a_z_limit_switch_of_the_machine_stops_the_card_naming_it():
    config = MachineConfig(switches={"LIMIT_POS_Z": Switch(15, bounce=6, seed=2)})   # start, DIR: the defaults
    with SimTransport("verilator", machine=config, encoders=1, axes=3) as transport:
        card = Card(transport)
        card.configure(steps_per_mm=(200.0,) * 3)
        card.start(interrupts=("ERROR", "DONE"))
        card.set("FEED_RATE", 4000)
        card.drive(True)
        _line(card, 4, 4, 40)
        with pytest.raises(MachineStopped, match="LIMIT"):
            card.wait_done()
        state = transport.machine.state()
        reason, drive = card.stop_reason(), transport.session.pin("drive_enable")
    assert reason == ("LIMIT", ("LIMIT_POS_Z",)) and not drive
    assert 15 <= state.positions[2] < 40 and state.pin("LIMIT_POS_Z")


@pytest.mark.slow(reason="the three-axis MyHDL card with encoders, 8 s of CPU; its machine process is the golden "
                         "model itself: the two-axis MyHDL card above checks its wiring by default, the three-axis "
                         "Verilator card the compiled machine clock for clock")
def test_the_myhdl_three_axis_card_counts_its_z_motor_and_a_z_stall_stops_it_on_z():
    config = MachineConfig(motors={"Z": Motor(counts_per_step=(3, 2), spacing=3)})
    with SimTransport("myhdl", machine=config, encoders=1, axes=3) as transport:
        card = _z_following_card(transport, feed_rate=30000)
        _line(card, 3, -2, -7)
        card.wait_done()
        transport.sleep(1e-6)
        state = transport.machine.state()
        read = tuple(encoders.read_encoder(card, axis).count for axis in range(3))
        transport.machine.stall(2)
        _line(card, 0, 1, 8)             # the fifth step lost is 7.5 counts behind: past the limit of 6
        with pytest.raises(MachineStopped, match="FOLLOWING_ERROR"):
            card.wait_done()
        reason, drive = card.stop_reason(), transport.session.pin("drive_enable")
    assert state.positions == (3, -2, -7) and state.counts == (None, None, -10)   # -10.5 rounds up to -10
    assert read == (0, 0, -10)
    assert reason == ("FOLLOWING_ERROR", ("Z",)) and not drive
