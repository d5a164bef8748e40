"""Several cards under one dda_card driver, and a card's axis count, under halrun.

Each simulated card is a card server of its own (``run/cardK.sock``, its record
``run/cardK.json``); ``sim=`` lists their sockets, dda-card.K the K-th.  The
end positions are read from each card's own STEP/DIR pins and step counters
(the server's record), not from the driver.
"""
import re
import shutil
import socket
import struct
import threading

import pytest

from models import registers as regmap
from models.card_socket import ANSWER_WORDS, READ, REQUEST_WORDS
from tests.linuxcnc.compare import pin_positions
from tests.linuxcnc.halrun import listening_socket, note, run_halrun, until
from tests.linuxcnc.session import as_user, card_server, missing, run_folder

pytestmark = [pytest.mark.linuxcnc, pytest.mark.xdist_group("linuxcnc"),
              pytest.mark.skipif(missing() is not None, reason=str(missing()))]

CARDS = ("card0", "card1")
TWO_CARDS = """loadrt threads name1=servo-thread period1=1000000
loadrt dda_card sim={run}/card0.sock,{run}/card1.sock {options}
addf dda-card.0.read servo-thread
addf dda-card.1.read servo-thread
addf dda-card.0.write servo-thread
addf dda-card.1.write servo-thread
start
"""
# (card, axis): the first targets (steps, position-scale 1), reached before the fault; then card `moving`'s next ones
FIRST = {(0, 0): 120, (0, 1): -80, (1, 0): -60, (1, 1): 150}
NEXT = {0: 250, 1: 40}
FAULT_AFTER = 300  # ADVANCEs of the failing card's server before it fails


def stepgen(card, axis):
    return f"dda-card.{card}.stepgen.{axis:02d}"


def two_card_script(failing):
    """Every joint of both cards to FIRST; the failing card faults; the other card's joints to NEXT."""
    moving = 1 - failing
    body = "".join(f"setp {stepgen(k, i)}.enable 1\n" for k, i in FIRST)
    body += "".join(until(f"dda-card.{k}.fifo-level", "not:0") for k in (0, 1))
    body += "".join(f"setp {stepgen(k, i)}.position-cmd {target}\n" for (k, i), target in FIRST.items())
    body += "".join(until(f"{stepgen(k, i)}.counts", str(target)) for (k, i), target in FIRST.items())
    body += until(f"dda-card.{failing}.error", "TRUE")
    body += note(f"dda-card.{failing}.error-code", f"dda-card.{moving}.error")
    body += "".join(f"setp {stepgen(moving, i)}.position-cmd {target}\n" for i, target in NEXT.items())
    body += "".join(until(f"{stepgen(moving, i)}.counts", str(target)) for i, target in NEXT.items())
    return body + note("dda-card.0.error", "dda-card.1.error", f"dda-card.{failing}.error-code")


def run_two_cards(failing, fault, options=""):
    run = run_folder()
    servers = {name: ("--fail", f"{fault}@{FAULT_AFTER}") if k == failing else () for k, name in enumerate(CARDS)}
    output, notes, records = run_halrun(run, TWO_CARDS.format(run=run, options=options) + two_card_script(failing),
                                        servers)
    ends = {}
    for k, name in enumerate(CARDS):
        _, xs, ys = pin_positions(run / f"{name}.json")
        ends[k] = (xs[-1], ys[-1])
    shutil.rmtree(run, ignore_errors=True)
    return output, notes, records, ends


def counters(record):
    """The card's own step counters at the end (POS_X, POS_Y, signed)."""
    return tuple(regmap.field_value(name, "STEPS", record["final"][name]) for name in ("POS_X", "POS_Y"))


def check_isolated(failing, code, output, notes, records, ends):
    """The failing card holds its fault and its joints where FIRST put them; the other card
    went on to NEXT, no fault; each card's pins and counters say so."""
    moving = 1 - failing
    assert notes[f"dda-card.{failing}.error-code"] == [code, code]
    assert notes[f"dda-card.{moving}.error"] == ["FALSE", "FALSE"]
    assert notes[f"dda-card.{failing}.error"] == ["TRUE"]
    assert ends[failing] == (FIRST[failing, 0], FIRST[failing, 1])
    assert ends[moving] == (NEXT[0], NEXT[1])
    assert counters(records[CARDS[moving]]) == (NEXT[0], NEXT[1])
    said = [line for line in output.splitlines() if ", simulated card at" in line and " Hz, registers " not in line]
    assert said and all(f"dda-card.{failing}, " in line for line in said), said  # the failing card's only


def test_two_cards_each_move_their_joints_and_a_fault_of_card_1_stops_card_1_only(linuxcnc_alone):
    """Two simulated cards in one halrun: each card's two joints reach their commands
    exactly (its STEP/DIR pins and its own counters); card 1 then leaves the bus
    (reads all-ones): its error with -5, said naming it, its joints held; card 0 goes on
    and reaches its next commands with no fault."""
    output, notes, records, ends = run_two_cards(1, "unplug")
    check_isolated(1, "-5", output, notes, records, ends)
    assert counters(records["card1"]) == (FIRST[1, 0], FIRST[1, 1])
    assert output.count("reads all-ones: it has left the bus") == 1
    assert not [op for _, op in records["card1"]["lost"] if op == 3], "FIFO bursts went to a card gone from the bus"


@pytest.mark.slow(reason="the isolation the default two-card test shows, with the other card failing, another way")
def test_a_stall_of_card_0s_server_stops_card_0_only(linuxcnc_alone):
    output, notes, records, ends = run_two_cards(0, "stall", "sim_timeout_ms=300")
    check_isolated(0, "-4", output, notes, records, ends)
    assert output.count("no answer within 300 ms: the card server stalled") == 1


def refuse(run, line, flags=("-k",)):
    """halrun (kept going, -k) of ``line`` then a listing of every pin and function: the output."""
    (run / "load.hal").write_text(f"{line}\nshow pin\nshow funct\n")
    (run / "load.hal").chmod(0o666)
    result = as_user(["halrun", *flags, "-f", str(run / "load.hal")], run, 120)
    return result.stdout + result.stderr


LISTS = {  # sim= (sockets in run/), what the driver says
    "empty item": ("card0.sock,,card1.sock", "socket 1 of the list is empty"),
    "trailing comma": ("card0.sock,", "socket 1 of the list is empty"),
    "five cards": (",".join(f"card{k}.sock" for k in range(5)), "more than 4 cards; this driver serves at most 4"),
    "one socket twice": ("card0.sock,card0.sock", "is given for dda-card.0 and dda-card.1"),
}


@pytest.mark.parametrize("kind", [pytest.param(kind, marks=[] if kind == "empty item" else [pytest.mark.slow(
    reason="the list's other refusals, the same path as an empty item")]) for kind in LISTS])
def test_a_card_list_it_cannot_take_is_refused_at_load_with_nothing_made(linuxcnc_alone, kind):
    """Refused before any card is opened (no server runs: none is reached); no pin, no function."""
    run = run_folder()
    sockets, message = LISTS[kind]
    listing = ",".join(str(run / name) if name else "" for name in sockets.split(","))
    output = refuse(run, f"loadrt dda_card sim={listing}")
    assert f"dda_card: sim={listing}: " in output and message in output, output
    assert "dda-card." not in output.replace(f"sim={listing}", "").replace("dda-card.0 and dda-card.1", "")
    shutil.rmtree(run, ignore_errors=True)


def test_a_card_that_fails_to_open_closes_the_cards_before_it(linuxcnc_alone):
    """sim= card 0 (a server) and card 1 (no server): refused naming card 1; card 0's
    socket closed again (its server sees the driver go), no pin, no function."""
    run = run_folder()
    server = card_server(run, name="card0")
    try:
        output = refuse(run, f"loadrt dda_card sim={run}/card0.sock,{run}/missing.sock")
        assert server.wait(timeout=60) == 0, "card 0's socket stayed open"
    finally:
        server.kill()
    assert f"dda_card: dda-card.1: sim {run}/missing.sock: no card server" in output
    assert "stepgen" not in output and "dda-card.0.read" not in output
    shutil.rmtree(run, ignore_errors=True)


REQUEST = struct.Struct("<" + "I" * REQUEST_WORDS)
ANSWER = struct.Struct("<" + "I" * ANSWER_WORDS)


def card_of_axes(path, axes, stop, positions, reads):
    """A card that answers the socket protocol (models/card_socket.py) with the register
    table's reset values, BUILD.AXES = ``axes`` and the step counters ``positions``
    ({offset: value}); writes are taken and dropped; every offset read is added to ``reads``."""
    build = regmap.register("BUILD")
    field = build.field("AXES")
    registers = {reg.offset: reg.reset for reg in regmap.REGISTERS}
    registers[build.offset] = (build.reset & ~field.mask) | axes << field.lsb
    registers.update(positions)
    listener = listening_socket(path)
    try:
        connection, _ = listener.accept()
        connection.settimeout(30)
        while not stop.is_set():
            request = connection.recv(REQUEST.size, socket.MSG_WAITALL)
            if len(request) < REQUEST.size:
                break
            op, a, _ = REQUEST.unpack(request)
            if op == READ:
                reads.append(a)
            connection.sendall(ANSWER.pack(0, registers.get(a, 0) if op == READ else 0))
        connection.close()
    except OSError:
        pass
    finally:
        listener.close()


def serve_card_of_axes(run, axes, script, positions=None):
    """halrun ``script`` against ``card_of_axes``: (output, offsets read)."""
    stop, reads = threading.Event(), []
    card = threading.Thread(target=card_of_axes, args=(run / "card.sock", axes, stop, positions or {}, reads))
    card.start()
    try:
        output = refuse(run, script)
    finally:
        stop.set()
        socket.socket(socket.AF_UNIX).connect_ex(str(run / "card.sock"))  # release a listener still waiting
        card.join()
    return output, reads


# every axis's step counter where docs/registers.md puts it: POS_X, POS_Y in BAR0,
# axis i >= 2 at 0x100 + 0x40 * i in BAR2; the values the fake card holds there
POS_OFFSETS = {0: 0x20, 1: 0x24, 2: 0x180, 3: 0x1C0, 4: 0x200, 5: 0x240}
COUNTS = {0: 5, 1: -7, 2: 200, 3: -300, 4: 400, 5: 500}


@pytest.mark.parametrize("axes", [3, 6])
def test_a_card_of_more_axes_gets_a_stepgen_per_axis_read_from_its_block(linuxcnc_alone, axes):
    """BUILD.AXES is read at load: a card of N axes gets stepgen.00 .. stepgen.(N-1), whose
    counts come from each axis's step counter, X's read first in a period (it captures
    the others)."""
    run = run_folder()
    positions = {POS_OFFSETS[i]: COUNTS[i] & 0xFFFFFFFF for i in range(axes)}
    script = ("loadrt threads name1=servo-thread period1=1000000\n"
              f"loadrt dda_card sim={run / 'card.sock'}\naddf dda-card.0.read servo-thread\nstart\n"
              "loadusr -w sleep 0.2\n" + "".join(f"show pin {stepgen(0, i)}.counts\n" for i in range(axes)))
    output, reads = serve_card_of_axes(run, axes, script, positions)
    for i in range(axes):
        assert re.search(rf"\s{COUNTS[i]}\s+{re.escape(stepgen(0, i))}\.counts", output), output[-2000:]
    assert f"{stepgen(0, axes)}" not in output
    period = reads[reads.index(POS_OFFSETS[0]):][:axes]
    assert period == [POS_OFFSETS[i] for i in range(axes)]
    shutil.rmtree(run, ignore_errors=True)


def test_a_card_reporting_more_axes_than_the_design_has_is_refused(linuxcnc_alone):
    run = run_folder()
    output, _ = serve_card_of_axes(run, 7, f"loadrt dda_card sim={run / 'card.sock'}")
    assert "reports 7 axes" in output and "no card of this design" in output
    assert "stepgen" not in output
    shutil.rmtree(run, ignore_errors=True)
