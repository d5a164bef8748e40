"""The simulated machine's motors in the compiled Verilator harness against their golden model
(models/sim_machine.py), clock for clock, on a card built with encoders driven through the host API;
and the card's ENC_COUNT, read over PCI, against the model's count (on Verilator and on the MyHDL
card, whose machine process runs the model itself).

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
from models.sim_machine import MachineConfig, Motor, SimMachine

pytestmark = pytest.mark.xdist_group("encoder_card")

CONFIG = MachineConfig(motors={
    "X": Motor(counts_per_step=(5, 2), lag=7, spacing=3, jitter=2, seed=5, index_period=24),
    "Y": Motor(counts_per_step=4, lag=0, spacing=3, index_period=10),
}, start=(3, 0), dir_positive=(True, False))


def _record(transport):
    model = transport.session._runner.card.model
    drive = {int(c): int(w) >> 7 & 1 for c, w in zip(*model.take_machine_changes())}
    encoder = {int(c): int(w) for c, w in zip(*model.take_encoder_changes())}
    return drive, encoder


def _replay(edges, drive, encoder, stalls, last_clock):
    """The golden model on the recorded pins: [(clock, model word, harness word)] where they differ."""
    machine, differences = SimMachine(CONFIG), []
    first = min(encoder)     # the clock the harness started the machine in
    pins = next((state for clock, state in reversed(edges) if clock <= first), 0)
    edge_at, enabled, expected = dict(edges), drive[first], encoder[first]
    assert machine.encoder_pins == expected
    for clock in range(first + 1, last_clock + 1):
        pins = edge_at.get(clock, pins)
        for axis in stalls.get(clock - 1, ()):
            machine.stall(axis)
        machine.clock(pins & 1, pins & 2, pins & 4, pins & 8, enabled)
        enabled, expected = drive.get(clock, enabled), encoder.get(clock, expected)
        if machine.encoder_pins != expected:
            differences.append((clock, machine.encoder_pins, expected))
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
