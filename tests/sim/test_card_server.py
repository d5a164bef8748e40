"""The card server the LinuxCNC driver's tests use: its protocol on the Verilator card."""
import json
import socket
import struct
import subprocess
import sys

import pytest

from models import registers as regmap
from models.card_socket import ADVANCE, FIFO, READ, WRITE
from models.sim_machine import MachineConfig, Motor, Switch
from sim.card.card_server import main
from sim.card.card_socket_server import ANSWER, REQUEST

CLOCK_HZ = 1_000_000
LINE_5_M3 = [1 << 28, 5, (-3) & 0xFFFFFFFF]  # LINE (5, -3) (docs/instructions.md)
LONG_LINE = 2000  # X steps: at the reset FEED_RATE (one iteration every 16 clocks) 32,000 clocks
WATCHDOG_CLOCKS = 3000
WATCHDOG_SLACK = 3  # docs/machine.md: the stop comes TIMEOUT clocks after the write, within 3
FREE_RUN = 20_000


class Client:
    def __init__(self, tmp_path, *options):
        self.path, self.log = tmp_path / "card.sock", tmp_path / "card.json"
        self.process = subprocess.Popen(
            [sys.executable, "-m", "sim.card.card_server", "--socket", str(self.path), "--log", str(self.log),
             "--clock-hz", str(CLOCK_HZ), *options], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        assert "listening" in self.process.stdout.readline()
        self.connection = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.connection.connect(str(self.path))

    def ask(self, op, a=0, b=0, words=()):
        """(value, None) or (None, the server's message)."""
        self.connection.sendall(REQUEST.pack(op, a, b) + struct.pack(f"<{len(words)}I", *words))
        status, value = ANSWER.unpack(self.connection.recv(ANSWER.size, socket.MSG_WAITALL))
        if status:
            return None, self.connection.recv(value, socket.MSG_WAITALL).decode()
        return value, None

    def finish(self):
        """Go away; the server's log."""
        self.connection.close()
        assert self.process.wait(timeout=60) == 0
        assert not self.path.exists()
        return json.loads(self.log.read_text())


@pytest.fixture
def client(tmp_path):
    client = Client(tmp_path)
    yield client
    client.connection.close()
    client.process.kill()


def test_registers_fifo_and_lock_step_time(client):
    assert client.ask(READ, regmap.offset("ID")) == (regmap.register("ID").reset, None)
    assert client.ask(READ, regmap.offset("CLOCK_HZ")) == (CLOCK_HZ, None)
    assert client.ask(WRITE, regmap.offset("CONTROL"), 1) == (0, None)
    assert client.ask(FIFO, len(LINE_5_M3), words=LINE_5_M3) == (0, None)
    # card time is the sum of the ADVANCEs, the bus accesses before them included
    assert client.ask(ADVANCE, 1000) == (1000, None)
    assert client.ask(ADVANCE, 500) == (1500, None)
    record = client.finish()
    assert record["clock_hz"] == CLOCK_HZ
    assert [after for _, after in record["advances"]] == [1000, 1500]
    assert record["requests"] == [5, 1]  # the requests of each period, its ADVANCE included
    x = sum((1 if r[3] else -1) * r[1] for r in record["rises"])
    y = sum((1 if r[4] else -1) * r[2] for r in record["rises"])
    assert (x, y) == (5, -3)
    assert all(0 < r[0] < 1000 for r in record["rises"])


def test_bad_requests_are_answered_with_the_reason(client):
    value, error = client.ask(READ, 0x1000)   # beyond BAR2's 4 KiB
    assert value is None and "0x1000" in error
    value, error = client.ask(9)
    assert value is None and "unknown request 9" in error
    assert client.ask(READ, regmap.offset("ID")) == (regmap.register("ID").reset, None)  # still serving
    client.finish()


@pytest.mark.parametrize("ppm, ends", [(1500, [1001, 2003, 3004]), (-1500, [998, 1997, 2995])])
def test_a_card_clock_ppm_fast_or_slow_runs_more_or_fewer_clocks_per_advance(tmp_path, ppm, ends):
    """--ppm: each ADVANCE of 1000 clocks runs 1000 (1 + ppm / 1e6) card clocks, the fractions carried."""
    client = Client(tmp_path, "--ppm", str(ppm))
    assert [client.ask(ADVANCE, 1000)[0] for _ in ends] == ends
    client.finish()


def field(name, register, value):
    item = next(f for f in regmap.register(register).fields if f.name == name)
    return (value & item.mask) >> item.lsb


@pytest.mark.parametrize("gone", ["closed", "killed"])
def test_a_card_left_alone_is_stopped_by_its_watchdog(tmp_path, gone):
    """The client goes mid-move; the server runs the card on its own (--free-run),
    as a real card goes on without its PC: the watchdog the client wrote last
    stops the steps and drops DRIVE_ENABLE WATCHDOG clocks after that write
    (docs/machine.md), the card says why, and the pins went no further than
    the queue and agree with the step counter."""
    client = Client(tmp_path, "--free-run", str(FREE_RUN))
    drive = regmap.field_of("MACHINE_CONTROL", DRIVE_ENABLE=1)
    assert client.ask(WRITE, regmap.offset("MACHINE_CONTROL"), drive) == (0, None)
    assert client.ask(FIFO, 3, words=[1 << 28, LONG_LINE, 0]) == (0, None)
    assert client.ask(WRITE, regmap.offset("CONTROL"), 1) == (0, None)
    started, _ = client.ask(ADVANCE, 1000)
    assert client.ask(WRITE, regmap.offset("WATCHDOG"), WATCHDOG_CLOCKS) == (0, None)
    if gone == "killed":  # a client that dies with a request half sent
        client.connection.sendall(REQUEST.pack(ADVANCE, 1000, 0)[:5])
    record = client.finish()
    written = record["free_run"]["start"]  # the watchdog write was the last request
    assert started <= written < started + 100
    assert record["writes"][-1] == [written, regmap.offset("WATCHDOG"), WATCHDOG_CLOCKS]
    assert record["free_run"]["end"] >= written + FREE_RUN
    assert record["drive"][0][1] == 0 and record["drive"][1][1] == 1 and record["drive"][1][0] < started
    assert len(record["drive"]) == 3, f"DRIVE_ENABLE changed more than once after it rose: {record['drive']}"
    fell, level = record["drive"][2]
    assert level == 0 and written + WATCHDOG_CLOCKS - WATCHDOG_SLACK <= fell <= written + WATCHDOG_CLOCKS + WATCHDOG_SLACK
    rises = [r[0] for r in record["rises"]]
    assert rises and rises[-1] <= fell, "a step after the watchdog's stop"
    assert rises[-1] > fell - 100, "the card was not moving when its watchdog ran out"
    final = record["final"]
    assert field("REASON", "STOP_REASON", final["STOP_REASON"]) == regmap.STOP_REASONS.index("WATCHDOG")
    assert field("STOPPED", "STATUS", final["STATUS"]) == 1
    assert field("DRIVE_ENABLE", "MACHINE_STATUS", final["MACHINE_STATUS"]) == 0
    assert final["POS_X"] == len(rises) < LONG_LINE and final["POS_Y"] == 0
    print(f"\nwatchdog {WATCHDOG_CLOCKS} clocks: DRIVE_ENABLE low {fell - written} clocks after the last "
          f"write, last step {fell - rises[-1]} clocks before, {len(rises)} of {LONG_LINE} steps made")


def test_without_free_run_the_card_stays_where_the_client_left_it(client):
    assert client.ask(FIFO, 3, words=[1 << 28, LONG_LINE, 0]) == (0, None)
    assert client.ask(WRITE, regmap.offset("CONTROL"), 1) == (0, None)
    assert client.ask(ADVANCE, 1000) == (1000, None)
    record = client.finish()
    assert record["free_run"] == dict(start=1000, clocks=0, end=1000)
    assert record["fifo"] == [[record["fifo"][0][0], [1 << 28, LONG_LINE, 0]]]
    # only the final reads' few bus clocks ran after the last ADVANCE (16 clocks a step)
    assert 1000 // 16 - 1 <= len(record["rises"]) <= (1000 + 100) // 16
    assert 0 <= len(record["rises"]) - record["final"]["POS_X"] <= 1


@pytest.mark.parametrize("argv, message", [
    (["--clock-hz", "0"], "--clock-hz must be"), (["--clock-hz", str(1 << 32)], "--clock-hz must be"),
    (["--free-run", "-1"], "--free-run must be"), (["--free-run", str((1 << 30) + 1)], "--free-run must be"),
    (["--ppm", "100001"], "--ppm must be"), (["--ppm", "-100001"], "--ppm must be"),
    (["--axes", "7"], "--axes must be"), (["--axes", "1"], "--axes must be")])
def test_bad_options_are_refused_before_anything_is_written(tmp_path, capsys, argv, message):
    with pytest.raises(SystemExit):
        main(["--socket", str(tmp_path / "s"), "--log", str(tmp_path / "l"), *argv])
    assert message in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_an_unplugged_card_reads_all_ones_and_loses_writes(tmp_path):
    client = Client(tmp_path, "--fail", "unplug@1")
    assert client.ask(READ, regmap.offset("ID")) == (regmap.register("ID").reset, None)
    client.ask(ADVANCE, 100)
    assert client.ask(READ, regmap.offset("ID")) == (0xFFFFFFFF, None)
    assert client.ask(WRITE, regmap.offset("CONTROL"), 1) == (0, None)
    assert client.ask(FIFO, 3, words=LINE_5_M3) == (0, None)
    record = client.finish()
    assert [op for _, op in record["lost"]] == [WRITE, FIFO] and record["fifo"] == [] and record["writes"] == []


def test_a_frozen_card_does_not_run(tmp_path):
    client = Client(tmp_path, "--fail", "freeze@1")
    assert client.ask(ADVANCE, 1000) == (1000, None)
    assert client.ask(FIFO, 3, words=LINE_5_M3) == (0, None)
    assert client.ask(WRITE, regmap.offset("CONTROL"), 1) == (0, None)
    stopped, _ = client.ask(ADVANCE, 1000)
    assert stopped < 1100, "the card ran on"  # only the accesses' own bus clocks
    assert len(client.finish()["rises"]) < 5, "the card made its LINE though frozen"


def test_a_stalled_server_keeps_the_socket_but_answers_no_more(tmp_path):
    """(--fail hang-up closes the socket instead: tests/linuxcnc/test_halrun.py.)"""
    client = Client(tmp_path, "--fail", "stall@1")
    client.ask(ADVANCE, 100)
    client.connection.settimeout(0.5)
    client.connection.sendall(REQUEST.pack(READ, regmap.offset("ID"), 0))
    with pytest.raises(socket.timeout):
        client.connection.recv(ANSWER.size)
    client.finish()


@pytest.mark.parametrize("value", ["melt@3", "unplug", "unplug@x"])
def test_bad_failures_are_refused(tmp_path, capsys, value):
    with pytest.raises(SystemExit):
        main(["--socket", str(tmp_path / "s"), "--log", str(tmp_path / "l"), "--fail", value])
    assert "--fail must be KIND@N" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_simulated_machine_and_estop_schedule(tmp_path):
    """--machine: a home switch at X 3 the line crosses (MACHINE_STATUS shows it while
    the machine is on it); --estop: pressed at clock 30,000 (the card stops, ESTOP),
    released at 40,000; the log has the machine's positions and lost steps."""
    config = MachineConfig(switches={"HOME_X": Switch(3, hysteresis=1, bounce=4, seed=2)})
    (tmp_path / "machine.json").write_text(config.to_json())
    client = Client(tmp_path, "--machine", str(tmp_path / "machine.json"), "--estop", "30000", "--estop", "40000")
    try:
        assert client.ask(WRITE, regmap.offset("MACHINE_CONTROL"), 1) == (0, None)
        assert client.ask(WRITE, regmap.offset("CONTROL"), 1) == (0, None)
        assert client.ask(FIFO, 3, words=[1 << 28, 5, 0]) == (0, None)
        client.ask(ADVANCE, 2000)
        status, _ = client.ask(READ, regmap.offset("MACHINE_STATUS"))
        assert regmap.field_value("MACHINE_STATUS", "ACTIVE", status) == 1 << regmap.INPUT_NAMES.index("HOME_X")
        client.ask(ADVANCE, 33000)
        reason, _ = client.ask(READ, regmap.offset("STOP_REASON"))
        client.ask(ADVANCE, 10000)
        record = client.finish()
    finally:
        client.connection.close()
        client.process.kill()
    assert regmap.field_value("STOP_REASON", "REASON", reason) == regmap.STOP_REASONS.index("ESTOP")
    assert record["machine"] == dict(positions=[5, 0], lost=[0, 0], inputs=1 << regmap.INPUT_NAMES.index("HOME_X"),
                                     estop=False, counts=[None, None])
    assert [level for _, level in record["drive"]] == [0, 1, 0], "on, then the E-stop's stop"
    assert record["drive"][-1][0] == record["advances"][1][1], "sampled at the end of the ADVANCE spanning 30,000"


def test_machine_options_are_checked(tmp_path, capsys):
    with pytest.raises(SystemExit):
        main(["--socket", str(tmp_path / "s"), "--log", str(tmp_path / "l"), "--estop", "5"])
    assert "--estop needs --machine" in capsys.readouterr().err
    (tmp_path / "bad.json").write_text('{"switches": {"ESTOP": {"position": 1}}}')
    with pytest.raises(SystemExit):
        main(["--socket", str(tmp_path / "s"), "--log", str(tmp_path / "l"), "--machine", str(tmp_path / "bad.json")])
    assert "no switch input 'ESTOP'" in capsys.readouterr().err
    # a machine of three axes on the default two-axis card, refused before anything is built
    (tmp_path / "z.json").write_text('{"switches": {"LIMIT_POS_Z": {"position": 9}}}')
    with pytest.raises(SystemExit):
        main(["--socket", str(tmp_path / "s"), "--log", str(tmp_path / "l"), "--machine", str(tmp_path / "z.json")])
    assert "the machine names axes the card lacks: LIMIT_POS_Z; the card has 2 axes" in capsys.readouterr().err
    assert sorted(path.name for path in tmp_path.iterdir()) == ["bad.json", "z.json"]


@pytest.mark.parametrize("argv, message", [
    (["--encoders", "--stall", "X@100"], "--machine has no motor on X"),
    (["--encoders", "--stall", "Z@100"], "--machine has no motor on Z"),
    (["--encoders", "--stall", "W@100"], "--stall must be AXIS@CLOCK"),
    (["--encoders", "--stall", "Y@-1"], "--stall must be AXIS@CLOCK"),
    (["--encoders", "--stall", "Y"], "--stall must be AXIS@CLOCK"), ([], "add --encoders")])
def test_motor_options_are_checked_before_anything_is_written(tmp_path, capsys, argv, message):
    (tmp_path / "machine.json").write_text(MachineConfig(motors={"Y": Motor()}).to_json())
    with pytest.raises(SystemExit):
        main(["--socket", str(tmp_path / "s"), "--log", str(tmp_path / "l"), "--machine",
              str(tmp_path / "machine.json"), *argv])
    assert message in capsys.readouterr().err
    assert sorted(path.name for path in tmp_path.iterdir()) == ["machine.json"]


@pytest.mark.slow(reason="builds a three-axis Verilator card at the tests' clock (about a minute); "
                         "sim/card/test_axis_block.py covers the session's BAR2 routing by default")
def test_bar2_block_offsets_reach_every_axis_and_bar0_offsets_serve_as_before(tmp_path):
    """READ and WRITE take BAR2's per-axis block offsets beyond BAR0's (axis i at
    0x100 + 0x40 * i: POS +0, PULSE_COUNT +8; docs/registers.md), so a client of
    a three-axis card drives Z; BAR0's offsets answer as they always did."""
    client = Client(tmp_path, "--axes", "3")
    try:
        build, _ = client.ask(READ, regmap.offset("BUILD"))
        assert regmap.field_value("BUILD", "AXES", build) == 3
        assert client.ask(WRITE, regmap.offset("CONTROL"), regmap.field_of("CONTROL", MODE=1)) == (0, None)
        assert client.ask(WRITE, 0x188, 4) == (0, None)          # PULSE_COUNT of Z: four pulses
        client.ask(ADVANCE, 200)
        assert client.ask(READ, 0x188) == (0, None)              # none left
        assert client.ask(READ, regmap.offset("POS_X")) == (0, None)   # captures the other axes
        assert client.ask(READ, 0x180) == (4, None)              # POS of Z
        assert client.ask(READ, 0x1C0) == (0, None)              # A's block: a three-axis card has none
        record = client.finish()
        assert record["rises"] == []                             # X and Y stood still
    finally:
        client.connection.close()
        client.process.kill()


@pytest.mark.slow(reason="builds the Verilator card with encoders at the tests' clock (about a minute); the "
                         "motors and their stall are checked in tests/sim/test_sim_machine_motors.py")
def test_motors_follow_and_a_scheduled_stall_trips_the_following_error(tmp_path):
    """--encoders --machine with a motor on X (4 counts a step), --stall X@12000: the card, its
    following error set (ENC_SCALE 4.0, FERROR_LIMIT 6), runs a long line; the motor stops turning
    at 12,000 and the card stops with FOLLOWING_ERROR on X; the log has the motor's count."""
    (tmp_path / "machine.json").write_text(MachineConfig(motors={"X": Motor(counts_per_step=4)}).to_json())
    client = Client(tmp_path, "--encoders", "--machine", str(tmp_path / "machine.json"), "--stall", "X@12000")
    try:
        client.ask(WRITE, regmap.axis_register("ENC_SCALE", 0).offset, 4 << 16)
        client.ask(WRITE, regmap.axis_register("FERROR_LIMIT", 0).offset, 6)
        client.ask(WRITE, regmap.offset("MACHINE_CONTROL"), 1)
        client.ask(WRITE, regmap.offset("CONTROL"), 1)
        client.ask(FIFO, 3, words=[1 << 28, LONG_LINE, 0])
        client.ask(ADVANCE, 20000)
        reason, _ = client.ask(READ, regmap.offset("STOP_REASON"))
        record = client.finish()
    finally:
        client.connection.close()
        client.process.kill()
    assert (regmap.field_value("STOP_REASON", "REASON", reason), regmap.field_value("STOP_REASON", "AXIS", reason)) \
        == (regmap.STOP_REASONS.index("FOLLOWING_ERROR"), 0)
    machine = record["machine"]
    # 12,000 clocks at one step every 16: about 750 steps turned; two lost steps (8 counts) pass the limit of 6
    assert 600 < machine["positions"][0] < 800 and machine["counts"] == [4 * machine["positions"][0], None]
    assert machine["lost"][0] >= 2 and record["final"]["POS_X"] == machine["positions"][0] + machine["lost"][0]
    assert [level for _, level in record["drive"]] == [0, 1, 0]
