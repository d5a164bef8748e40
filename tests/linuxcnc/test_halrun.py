"""The dda_card driver under halrun (no motion controller) on the simulated card.

Each run is one halrun script as LinuxCNC's user: a 1 ms ``threads`` thread
with the driver's read and write, pins set by ``setp`` and waited for by
``until.sh`` (halcmd polled), values noted by ``note.sh``.  The card server
(lock-step, 1 MHz card) records every FIFO burst, STEP rise and request;
``--fail`` makes it fail on cue.  Cheaper than a LinuxCNC run: most of the
driver's checks are here, several in one script.
"""
import shutil
import socket
import threading
from collections import Counter

import pytest

from models.commands import SetCommand, decode_words
from models.dda_plan import LineCommand
from models import registers as regmap
from tests.linuxcnc.halrun import listening_socket, note, run_halrun, until
from tests.linuxcnc.session import PERIOD_CLOCKS, as_user, missing, run_folder

# one LinuxCNC (or halrun) per host: every such test runs on one xdist worker, in turn
pytestmark = [pytest.mark.linuxcnc, pytest.mark.xdist_group("linuxcnc"),
              pytest.mark.skipif(missing() is not None, reason=str(missing()))]

THREAD = """loadrt threads name1=servo-thread period1=1000000
loadrt dda_card sim={socket} {options}
addf dda-card.0.read servo-thread
addf dda-card.0.write servo-thread
start
"""
S = "dda-card.0.stepgen"


def run_script(run, body, *server_options, driver_options=""):
    """halrun THREAD + body on one card server; (output, notes {pin: [values]}, record)."""
    script = THREAD.format(socket=run / "card.sock", options=driver_options) + body
    output, notes, records = run_halrun(run, script, {"card": server_options})
    return output, notes, records["card"]


def feed_rates(record):
    """FEED_RATE values the driver SET (docs/instructions.md)."""
    return [command.value for _, words in record["fifo"] for command in decode_words(words)
            if isinstance(command, SetCommand) and command.register == "FEED_RATE"]


STEPS_PER_PERIOD = 50  # maxvel 50000 steps/s at position-scale 1
WRAP_SCALE = 1_000_000  # steps per unit: the wrap test's commands near 2^31 steps
SETTINGS = (
    # axis 01's steplen is beyond the card's 255 clocks (1 us each at 1 MHz): refused at enable
    f"setp {S}.00.steplen 5000\nsetp {S}.00.stepspace 1000\nsetp {S}.01.steplen 300000\n"
    f"setp {S}.00.maxvel {STEPS_PER_PERIOD * 1000}\nsetp {S}.01.position-scale 0\n"
    f"setp {S}.00.enable 1\n" + until("dda-card.0.error", "TRUE") + note("dda-card.0.error-code", f"{S}.01.position-scale")
    # 5 us high, 1 us low asked: STEP_WIDTH 5 and STEP_SPACE 1 clocks, 6 a step, so p = 8
    + f"setp {S}.00.enable 0\n" + until("dda-card.0.error", "FALSE") + f"setp {S}.01.steplen 1000\n"
    # (the queue runs, the axis taken up at 0, before the command moves)
    f"setp {S}.00.enable 1\n" + until("dda-card.0.fifo-level", "not:0")
    + f"setp {S}.00.position-cmd 2000\n" + until(f"{S}.00.counts", "2000")
    # near 2^31 steps: taken up where it stands, then across the wrap of 32 bits
    # (a queue stopped by enable falling is empty at the next read: fifo-level 0)
    + f"setp {S}.00.enable 0\n" + until("dda-card.0.fifo-level", "0")
    + f"setp {S}.00.position-scale {WRAP_SCALE}\nsetp {S}.00.maxvel 0.05\n"
    f"setp {S}.00.position-cmd 2147.483\nsetp {S}.00.enable 1\n" + until(f"{S}.00.counts", "2147483000")
    + f"setp {S}.00.position-cmd 2147.4845\n" + until(f"{S}.00.counts", str(2147484500 - 2**32))
    + note(f"{S}.00.position-fb")
    # a position-cmd that is no number: error -6, that axis holds, the other goes on
    + f"setp {S}.01.enable 1\nsetp {S}.01.position-cmd 5\n" + until(f"{S}.01.counts", "5")
    + f"setp {S}.01.position-cmd nan\n" + until("dda-card.0.error", "TRUE") + note("dda-card.0.error-code")
    + f"setp {S}.00.position-cmd 2147.485\n" + until(f"{S}.00.counts", str(2147485000 - 2**32))
    + note(f"{S}.01.counts", f"{S}.01.position-fb")
)


def test_settings_step_timing_wrap_and_bad_commands(linuxcnc_alone):
    """One script: a step timing the card cannot hold refused at enable naming the parameter;
    position-scale 0 forced to 1; the step cycle planned from the card's rule (p = 16 for
    5 us / 1 us at 1 MHz: p = 8) and met on the pins; maxvel limiting a jump of 2000 steps to 50 a
    period; position-fb across 2^31 steps; a NaN position-cmd holding its axis with error -6."""
    run = run_folder()
    output, notes, record = run_script(run, SETTINGS)
    assert notes["dda-card.0.error-code"] == ["-8", "-6"]
    assert "stepgen.01.steplen 300000 ns is 300 clocks at 1000000 Hz" in output
    assert "hold 1..255 clocks (at most 255000 ns)" in output
    assert notes[f"{S}.01.position-scale"] == ["1"] and "stepgen.01.position-scale 0 is no scale" in output
    # the plan: FEED_RATE 65536 / 8 at both starts; on the pins: 8 clocks a step in a period's run
    assert feed_rates(record) == [65536 // 8] * 2
    x_rises = [r[0] for r in record["rises"] if r[1]]
    gaps = Counter(b - a for a, b in zip(x_rises, x_rises[1:]) if b - a < PERIOD_CLOCKS // 2)
    assert gaps.most_common(1)[0][0] == 8 and min(gaps) >= 6, gaps
    ends = [after for _, after in record["advances"]]
    per_period = Counter(next(k for k, end in enumerate(ends) if end >= clock) for clock in x_rises[:2000])
    assert max(per_period.values()) <= STEPS_PER_PERIOD, "maxvel did not limit the steps of a period"
    # halcmd prints 7 digits: enough to tell 2147.4845 from the wrapped -2147.48
    assert float(notes[f"{S}.00.position-fb"][0]) == pytest.approx(2147.4845, abs=1e-3)
    assert notes[f"{S}.01.counts"] == ["5"] and float(notes[f"{S}.01.position-fb"][0]) == 5.0
    assert output.count("is no position in steps") == 1
    # the card's own counter: the first move and the two across the wrap (the take-up moves nothing)
    assert record["final"]["POS_X"] == 2000 + 2147485000 - 2147483000
    shutil.rmtree(run, ignore_errors=True)


STEP_TYPES = (
    # the axes ask for different step types: the card's STEP_MODE is one for both, refused at enable
    f"setp {S}.00.step_type 1\nsetp {S}.00.enable 1\n" + until("dda-card.0.error", "TRUE")
    + note("dda-card.0.error-code") + f"setp {S}.00.enable 0\n" + until("dda-card.0.error", "FALSE")
    # a type beyond quadrature (2), then up/down on both axes: STEP_MODE 1 written at enable
    + f"setp {S}.00.step_type 3\nsetp {S}.01.step_type 3\nsetp {S}.00.enable 1\n" + until("dda-card.0.error", "TRUE")
    + f"setp {S}.00.enable 0\n" + until("dda-card.0.error", "FALSE")
    + f"setp {S}.00.step_type 1\nsetp {S}.01.step_type 1\nsetp {S}.00.enable 1\n"
    + until("dda-card.0.fifo-level", "not:0") + f"setp {S}.00.position-cmd 20\n" + until(f"{S}.00.counts", "20")
    + note("dda-card.0.error")
)


def test_step_type_written_to_step_mode(linuxcnc_alone):
    """hostmot2's step_type per axis: the card makes one STEP_MODE for both axes, so
    different types are refused at enable (-8, naming the axis), as is a type the card
    does not make; up/down on both axes is written to STEP_MODE and the axis moves."""
    run = run_folder()
    output, notes, record = run_script(run, STEP_TYPES)
    assert notes["dda-card.0.error-code"] == ["-8"]
    assert "stepgen.01.step_type 0: the card makes 0 step/dir, 1 up/down or 2 quadrature" in output
    assert "stepgen.00.step_type 3" in output
    assert notes["dda-card.0.error"] == ["FALSE"]
    modes = [value for _, offset, value in record["writes"] if offset == regmap.offset("STEP_MODE")]
    assert modes == [regmap.STEP_MODES.index("UP_DOWN")]
    assert record["final"]["POS_X"] == 20
    shutil.rmtree(run, ignore_errors=True)


FAULT_BODY = (
    f"setp {S}.00.maxvel {STEPS_PER_PERIOD * 1000}\nsetp {S}.00.enable 1\nsetp {S}.00.position-cmd 300\n"
    + until(f"{S}.00.counts", "300") + until("dda-card.0.error", "TRUE")
    + note("dda-card.0.error-code", f"{S}.00.position-fb", f"{S}.00.counts")
    + "loadusr -w sleep 0.2\n" + note("dda-card.0.error", f"{S}.00.position-fb")
)
FAULTS = {  # --fail kind: (error-code, what the driver says once)
    "unplug": ("-5", "reads all-ones: it has left the bus"),
    "stall": ("-4", "no answer within 300 ms: the card server stalled"),
    "hang-up": ("-4", "the card server went away"),
    "freeze": ("-7", "the card's FIFO has room for"),
}


@pytest.mark.parametrize("kind", [pytest.param(kind, marks=[pytest.mark.slow(
    reason="hang-up fails the transport as a stall does (the socket's send or receive)")] if kind == "hang-up" else [])
    for kind in FAULTS])
def test_a_card_or_server_that_stops_answering(linuxcnc_alone, kind):
    """After 300 periods the card leaves the bus (reads all-ones), or its clock stops (the
    FIFO fills), or the server stalls or hangs up: error with a code of its own, said once,
    position-fb held at its last good value; an unplugged card gets no more FIFO bursts."""
    run = run_folder()
    code, message = FAULTS[kind]
    output, notes, record = run_script(run, FAULT_BODY, "--fail", f"{kind}@300", driver_options="sim_timeout_ms=300")
    assert notes["dda-card.0.error-code"] == [code]
    assert output.count(message) == 1, output[-2000:]
    assert notes["dda-card.0.error"] == ["TRUE"]
    assert notes[f"{S}.00.position-fb"] == ["300", "300"] and notes[f"{S}.00.counts"] == ["300"]
    if kind == "unplug":
        assert not [op for _, op in record["lost"] if op == 3], "FIFO bursts went to a card gone from the bus"
    shutil.rmtree(run, ignore_errors=True)


def silent_server(path, stop):
    """A server that takes the connection and never answers."""
    listener = listening_socket(path)
    try:
        connection, _ = listener.accept()
        stop.wait(60)
        connection.close()
    except OSError:
        pass
    finally:
        listener.close()


@pytest.mark.parametrize("options, message", [
    ("keep_ahead=0", "keep_ahead=0: give 1..63 periods"), ("keep_ahead=64", "keep_ahead=64: give 1..63 periods"),
    ("sim_timeout_ms=300", "no answer within 300 ms: the card server stalled"),
])
def test_refused_at_load(linuxcnc_alone, options, message):
    """keep_ahead outside the drift loop's ring, and a server that never answers: loadrt fails, saying why."""
    run = run_folder()
    stop = threading.Event()
    server = threading.Thread(target=silent_server, args=(run / "card.sock", stop))
    server.start()
    try:
        (run / "load.hal").write_text(f"loadrt dda_card sim={run / 'card.sock'} {options}\n")
        (run / "load.hal").chmod(0o666)
        result = as_user(["halrun", "-f", str(run / "load.hal")], run, 120)
    finally:
        stop.set()
        socket.socket(socket.AF_UNIX).connect_ex(str(run / "card.sock"))  # release a listener still waiting
        server.join()
    assert result.returncode != 0
    assert message in result.stdout + result.stderr
    shutil.rmtree(run, ignore_errors=True)



DIR_SETUP_CLOCKS = 200  # long enough to see on the pins at 1 MHz
VELOCITY_STEPS = 5  # a period, in velocity mode: velocity-cmd 5000 steps/s at position-scale 1
AXIS_PINS = (
    f"setp {S}.00.dirsetup {DIR_SETUP_CLOCKS * 1000}\nsetp {S}.00.maxvel 10000\n"
    + "".join(f"setp {S}.00.enable 1\n" + until("dda-card.0.fifo-level", "not:0")
              + f"setp {S}.00.position-cmd {target}\n" + until(f"{S}.00.counts", str(target))
              + f"setp {S}.00.enable 0\n" + until("dda-card.0.fifo-level", "0") for target in (100, 200))
    # position-reset: the axis stands at 0; then velocity mode at 5 steps a period
    + f"setp {S}.00.enable 1\n" + until("dda-card.0.fifo-level", "not:0")
    + f"setp {S}.00.position-reset 1\n" + until(f"{S}.00.counts", "0") + note(f"{S}.00.position-fb")
    + f"setp {S}.00.position-cmd 0\nsetp {S}.00.position-reset 0\n"
    + f"setp {S}.00.control-type 1\nsetp {S}.00.velocity-cmd {VELOCITY_STEPS * 1000}\n"
    + "loadusr -w sleep 0.2\n" + f"setp {S}.00.velocity-cmd 0\n" + "loadusr -w sleep 0.05\n"
    + note(f"{S}.00.counts", "dda-card.0.error")
)


def lines_after(record, clock):
    """dx of the LINEs queued after ``clock``."""
    return [command.dx for at, words in record["fifo"] if at > clock for command in decode_words(words)
            if isinstance(command, LineCommand)]


def test_dir_level_position_reset_and_velocity_mode(linuxcnc_alone):
    """Two forward moves, the queue stopped and started between them: the DIR pin keeps its
    level through the soft reset, so the second move's first period must not be planned
    with DIR_SETUP clocks the card does not spend (its steps would then come DIR_SETUP
    clocks early in every later period): the offset of each period's first step from the
    period's start stays put.  Then position-reset zeroes counts and position-fb, and in
    velocity mode (control-type 1) velocity-cmd becomes the same steps every period."""
    run = run_folder()
    output, notes, record = run_script(run, AXIS_PINS)
    starts = [clock for clock, words in record["fifo"] if isinstance(decode_words(words)[0], SetCommand)]
    ends = [after for _, after in record["advances"]]
    offsets = {}
    for clock in (r[0] for r in record["rises"] if r[1] and starts[1] < r[0] < starts[2]):
        k = max(i for i, end in enumerate(ends) if end < clock)
        offsets.setdefault(k, clock - ends[k])
    moving = list(offsets.values())
    assert len(moving) >= 10 and max(moving) - min(moving) <= 2, moving
    assert notes[f"{S}.00.position-fb"] == ["0"]
    velocity = lines_after(record, starts[2])
    assert len(velocity) >= 10 and set(velocity) == {VELOCITY_STEPS}, velocity
    assert notes[f"{S}.00.counts"] == [str(VELOCITY_STEPS * len(velocity))] and notes["dda-card.0.error"] == ["FALSE"]
    shutil.rmtree(run, ignore_errors=True)
