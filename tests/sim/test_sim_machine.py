"""The simulated machine in the compiled Verilator harness against its golden
model (models/sim_machine.py), clock for clock, driven by the card through the host API.

The harness records every change of the input pins it drives (and of
DRIVE_ENABLE); the card's STEP/DIR edges are in the pin log.  Replaying those
pins through ``SimMachine`` must give the same input pins in every clock, the
same positions and the same lost steps.
"""
import numpy as np

from host.card import Card
from host.machine_io import MachineStopped
from host.transports.simulated import SimTransport
from models import registers as regmap
from models.sim_machine import INPUTS, MachineConfig, SimMachine, Switch
from sim.backends.verilator.model import DRIVE_BIT

import pytest

CONFIG = MachineConfig(switches={
    "HOME_X": Switch(40, hysteresis=3, bounce=30, longest_run=4, seed=5),
    "LIMIT_POS_X": Switch(90, hysteresis=1, bounce=12, seed=11),
    "LIMIT_NEG_X": Switch(-20, positive=False, active_low=True),
    "HOME_Y": Switch(-10, positive=False, hysteresis=2, bounce=16, longest_run=2, seed=3),
}, start=(0, 5), dir_positive=(True, False))

INPUT_BITS = (1 << len(regmap.input_names(2))) - 1   # the two-axis card's inputs


def _replay(edges, changes, presses, last_clock):
    """The golden model on the recorded pins: [(clock, input word)] where it differs from the harness's."""
    machine, differences = SimMachine(CONFIG), []
    edge_at = {clock: state for clock, state in edges}
    recorded = {}
    for clock, word in changes:
        recorded[clock] = word      # the last record of a clock counts (an E-stop press after its edge)
    first = min(recorded)       # the clock the harness started the machine in
    state = next((state for clock, state in reversed(edges) if clock <= first), 0)
    drive, expected = bool(recorded[first] >> DRIVE_BIT & 1), recorded[first] & INPUT_BITS
    assert machine.pins == expected and not state & 5, "no STEP high when the machine starts"
    for clock in range(first + 1, last_clock + 1):
        state = edge_at.get(clock, state)
        if clock in recorded:
            drive = bool(recorded[clock] >> DRIVE_BIT & 1)
        word = machine.clock(state & 1, state & 2, state & 4, state & 8, drive)
        for pressed in presses.get(clock, ()):
            machine.press_estop(pressed)
            word = machine.pins
        if clock in recorded:
            expected = recorded[clock] & INPUT_BITS
        if word != expected:
            differences.append((clock, word, expected))
    return machine, differences


def test_compiled_machine_matches_its_golden_model():
    presses = {}
    with SimTransport("verilator", machine=CONFIG) as transport:
        card = Card(transport)
        card.configure()
        card.start(interrupts=("ERROR", "DONE"))
        card.inputs(active_low=("LIMIT_NEG_X",), filter_ns=0)
        card.set("FEED_RATE", 3000)
        card.drive(True)
        # over HOME_X (40) and, Y reversed, HOME_Y (-10), back off both, on towards the limit
        for dx, dy in ((60, 25), (-30, -14), (45, 0)):
            card.line(dx, dy)
        card.wait_done()
        card.drive(False)
        card.line(-20, 4)           # the drives off: steps on the pins, lost by the machine
        card.wait_done()
        transport.machine.press_estop()
        presses.setdefault(transport.clocks, []).append(True)
        transport.sleep(2e-6)
        with pytest.raises(MachineStopped, match="ESTOP"):
            card.check()
        transport.machine.release_estop()
        presses.setdefault(transport.clocks, []).append(False)
        transport.sleep(2e-6)
        card.clear_stop()
        card.drive(True)
        card.line(30, 0)             # to the positive limit at 90: the card stops on it
        with pytest.raises(MachineStopped, match="LIMIT"):
            card.wait_done()
        state = transport.machine.state()
        changes = list(zip(*(array.tolist() for array in transport.session._runner.card.model.take_machine_changes())))
        edges = list(transport.pins.edges)
        last = transport.clocks
    machine, differences = _replay(edges, changes, presses, last)
    assert differences == []
    assert tuple(machine.positions) == state.positions and tuple(machine.lost) == state.lost
    assert state.lost == (20, 4) and state.positions[0] >= 90 and state.pin("LIMIT_POS_X")
    rises = np.array([r[1:3] for r in transport.pins.rises]).sum(axis=0)
    assert sum(state.lost) + abs(state.positions[0]) + abs(state.positions[1] - 5) <= rises.sum()
    words = [word & INPUT_BITS for _, word in changes]
    bit = 1 << INPUTS.index("HOME_X")
    assert sum((a ^ b) & bit != 0 for a, b in zip(words, words[1:])) >= 6, "HOME_X bounced at each change"
    assert regmap.INPUT_NAMES[:len(INPUTS)] == INPUTS   # the X/Y machine's inputs are the card's first
