"""Unloading the driver while the servo thread is inside it.

``halcmd stop`` only keeps a thread from starting its next pass; a pass
already inside the driver's read or write goes on while ``unload`` runs the
driver's exit.  On the simulated card a pass waits for the card server's
answers, which on a loaded machine take long, so the window is wide.  Here a
relay between the driver and the card server answers every READ of the
servo thread ``READ_DELAY`` late (a pass then takes seconds, so halrun's
own stop and unload always come while the thread is inside the driver) and
records every request in the order the card server got them.
"""
import queue
import shutil
import socket
import struct
import threading
import time

import pytest

from models import card_socket
from models import registers as regmap
from sim.card.card_socket_server import receive
from tests.linuxcnc.halrun import listening_socket, run_halrun
from tests.linuxcnc.session import missing, run_folder

pytestmark = [pytest.mark.linuxcnc, pytest.mark.xdist_group("linuxcnc"),
              pytest.mark.skipif(missing() is not None, reason=str(missing()))]

READ_DELAY = 0.25  # s: each READ answer once the thread runs (after the first ADVANCE)
WORD = struct.Struct("<I")

SCRIPT = """loadrt threads name1=servo-thread period1=1000000
loadrt dda_card sim={socket}
addf dda-card.0.read servo-thread
addf dda-card.0.write servo-thread
start
loadusr -w sleep 1
"""


class SlowRelay:
    """The driver's one connection at ``listen_path`` relayed to the card server at
    ``card_path``; ``requests``: every (op, a, b) in the order relayed."""

    def __init__(self, listen_path, card_path):
        self.listener = listening_socket(listen_path)
        self.card_path = card_path
        self.requests = []
        self.ops = queue.Queue()   # the op of each request whose answer is still to come
        self.thread = threading.Thread(target=self.serve, daemon=True)
        self.thread.start()

    def serve(self):
        try:
            driver, _ = self.listener.accept()
        finally:
            self.listener.close()
        card = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        card.connect(str(self.card_path))
        answers = threading.Thread(target=self.answer, args=(card, driver), daemon=True)
        answers.start()
        try:
            while (header := receive(driver, card_socket.REQUEST_WORDS * WORD.size)) is not None:
                op, a, b = struct.unpack("<3I", header)
                data = receive(driver, a * WORD.size) if op == card_socket.FIFO else b""
                self.requests.append((op, a, b))
                self.ops.put(op)
                card.sendall(header + (data or b""))
        except OSError:
            pass
        finally:
            # the card server sees the driver go (close alone would wait for the answers thread's receive)
            card.shutdown(socket.SHUT_RDWR)
        answers.join(60)
        card.close()
        driver.close()

    def answer(self, card, driver):
        running = False
        try:
            while (answer := receive(card, card_socket.ANSWER_WORDS * WORD.size)) is not None:
                status, value = struct.unpack("<2I", answer)
                message = (receive(card, value) or b"") if status else b""
                op = self.ops.get()
                running = running or op == card_socket.ADVANCE
                if running and op == card_socket.READ:
                    time.sleep(READ_DELAY)
                driver.sendall(answer + message)
        except OSError:
            pass


def test_unload_waits_for_the_thread_to_leave_the_driver(linuxcnc_alone):
    """halrun's stop and unload come while a pass is inside the driver: halrun ends cleanly
    (rtapi_app does not crash), and from the exit's first request on the card server gets
    the exit's requests only, whole and in order (the queue halted, the watchdog off, the
    drives off): the thread's pass had left the driver before the exit used the card."""
    run = run_folder()
    relay = SlowRelay(run / "slow.sock", run / "card.sock")
    run_halrun(run, SCRIPT.format(socket=run / "slow.sock"), {"card": ()})
    relay.thread.join(60)
    write = card_socket.WRITE
    exit_requests = [(write, regmap.offset("CONTROL"), 0),
                     (write, regmap.offset("COMMAND"), regmap.field_of("COMMAND", SOFT_RESET=1)),
                     (write, regmap.offset("WATCHDOG"), 0), (write, regmap.offset("MACHINE_CONTROL"), 0)]
    # the driver's open halts the card with the same four writes: the exit's are the last four
    assert relay.requests[-4:] == exit_requests and relay.requests.count(exit_requests[0]) == 2
    shutil.rmtree(run, ignore_errors=True)
