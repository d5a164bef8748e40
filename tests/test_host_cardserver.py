"""The card server the LinuxCNC driver's tests use: its protocol on the Verilator card."""
import json
import socket
import struct
import subprocess
import sys

import pytest

from host.cardserver import ADVANCE, ANSWER, FIFO, READ, REQUEST, WRITE, main
from rtl import registers as regmap

CLOCK_HZ = 1_000_000
LINE_5_M3 = [1 << 28, 5, (-3) & 0xFFFFFFFF]  # LINE (5, -3) (docs/instructions.md)


class Client:
    def __init__(self, tmp_path):
        self.path, self.log = tmp_path / "card.sock", tmp_path / "card.json"
        self.process = subprocess.Popen(
            [sys.executable, "-m", "host.cardserver", "--socket", str(self.path), "--log", str(self.log),
             "--clock-hz", str(CLOCK_HZ)], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
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
    x = sum((1 if r[3] else -1) * r[1] for r in record["rises"])
    y = sum((1 if r[4] else -1) * r[2] for r in record["rises"])
    assert (x, y) == (5, -3)
    assert all(0 < r[0] < 1000 for r in record["rises"])


def test_bad_requests_are_answered_with_the_reason(client):
    value, error = client.ask(READ, 0x200)
    assert value is None and "0x200" in error
    value, error = client.ask(9)
    assert value is None and "unknown request 9" in error
    assert client.ask(READ, regmap.offset("ID")) == (regmap.register("ID").reset, None)  # still serving
    client.finish()


@pytest.mark.parametrize("argv", [["--clock-hz", "0"], ["--clock-hz", str(1 << 32)]])
def test_bad_options_are_refused_before_anything_is_written(tmp_path, capsys, argv):
    with pytest.raises(SystemExit):
        main(["--socket", str(tmp_path / "s"), "--log", str(tmp_path / "l"), *argv])
    assert "--clock-hz must be" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []
