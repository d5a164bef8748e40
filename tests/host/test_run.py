"""``python -m host run / info / selftest`` on the simulated card: the
examples end to end (the pins against the golden model and the drawing),
Ctrl-C, bad options, a selftest that sees a fault."""
import re
import signal
import subprocess
import sys
import time

import pytest

from host.card import Card
from host.selftest import selftest
from host.transports.simulated import SimTransport
from models import registers as regmap
from models.sim_machine import MachineConfig, Switch
from rtl.convert import ROOT

EXAMPLES = ROOT / "examples"
FAST = ("--feed-override", "100000", "--steps-per-mm", "40", "--acceleration", "2000000", "--start-feed", "60000")
DEVIATION_BOUND = 0.5 + 2 ** 0.5 / 2  # steps: the DDA's half step plus the drawing's rounding onto the lattice


def run_host(*args, timeout=900):
    return subprocess.run([sys.executable, "-m", "host", *map(str, args)], cwd=ROOT, capture_output=True,
                          text=True, timeout=timeout)


def figure(text, label, pattern):
    match = re.search(rf"^{label}:\s+.*?{pattern}", text, re.M)
    assert match, text
    return match.groups()


@pytest.mark.parametrize("example", ["part.ngc", pytest.param("drawing.svg", marks=pytest.mark.slow(
    reason="the SVG front end's planning is tested in tests/host/test_svg.py; this runs the same pins check"))])
def test_examples_run_on_verilator_as_planned(example, tmp_path):
    picture = tmp_path / "pins.png"
    result = run_host("run", EXAMPLES / example, "--sim", "verilator", *FAST, "--preview", picture)
    assert result.returncode == 0, result.stderr
    out = result.stdout
    position, end = figure(out, "position", r"\((-?\d+, -?\d+)\) steps \(plan: \((-?\d+, -?\d+)\)\)")
    assert position == end
    assert "the path is the golden model's" in out
    (steps,) = figure(out, "pins", r"= ([\d.]+) steps")
    assert float(steps) <= DEVIATION_BOUND
    (over,) = figure(out, "gaps", r"(\d+) of")
    assert over == "0"
    planned, card_time = map(float, figure(out, "job time", r"([\d.]+) s planned; ([\d.]+) s of card time"))
    assert planned <= card_time <= 1.05 * planned  # arc set-up clocks the planner leaves out
    (clocks,) = figure(out, "simulated", r"(\d+) clocks")
    assert int(clocks) >= card_time * 33e6
    assert picture.stat().st_size > 10_000


@pytest.mark.parametrize("kind", ["verilator", *(pytest.param(kind, marks=pytest.mark.slow(
    reason="half a minute of MyHDL or Icarus clocks; these transports are tested in tests/host/test_transports.py"))
    for kind in ("myhdl", "icarus"))])
def test_info_and_selftest_on_every_simulator(kind):
    info = run_host("info", "--card", kind)
    assert info.returncode == 0, info.stderr
    assert f"registers:   version {regmap.VERSION >> 8}.{regmap.VERSION & 0xFF}" in info.stdout
    assert "FIFO:        512 words" in info.stdout
    test = run_host("selftest", "--sim", kind)
    assert test.returncode == 0, test.stdout + test.stderr
    assert test.stdout.count(" ok\n") == 3 and "selftest:    passed" in test.stdout


class StuckBit(SimTransport):
    """A card whose FEED_RATE bit 3 reads as 0: the walk must see it."""

    def read(self, offset, size=4):
        value = super().read(offset, size)
        return value & ~8 if offset == regmap.offset("FEED_RATE") else value


def test_selftest_reports_a_stuck_bit():
    with StuckBit("verilator") as transport:
        results = dict(selftest(Card(transport)))
    assert "FEED_RATE: wrote 0x8, read 0x0" in results["register walk"]
    assert results["short move"] is None


def test_ctrl_c_stops_the_card_and_reports_the_position():
    process = subprocess.Popen([sys.executable, "-u", "-m", "host", "run", EXAMPLES / "drawing.svg", "--sim",
                                "verilator"], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        for line in process.stdout:
            if line.startswith("job:"):
                break
        time.sleep(2)  # the job takes 54 s of card time: it is under way
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=300)
    finally:
        process.kill()
    assert process.returncode == 130, out + err
    assert "Traceback" not in err
    (state, position) = figure(out, "stopped", r"soft reset; ([^)]*)\) at \((-?\d+, -?\d+)\) steps")
    assert state == "idle, FIFO empty"
    assert position != "0, 0"


@pytest.mark.parametrize("args, text", [
    (("--card", "modelsim"), "--card modelsim"),
    (("--sim", "ghdl"), "invalid choice"),
    (("--card", "pci", "--preview", "x.png"), "needs a simulated card"),
    (("--feed-override", "0"), "not a positive number"),
    (("--low-water", "0"), "not a positive whole number"),
])
def test_bad_run_options_are_refused_before_the_card_is_opened(args, text):
    result = run_host("run", EXAMPLES / "part.ngc", *args, timeout=60)
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert result.returncode == 2 and len(lines) == 1 and text in lines[0], result.stderr
    assert result.stdout == ""


def test_a_missing_file_is_refused():
    result = run_host("run", ROOT / "none.ngc", timeout=60)
    assert result.returncode == 2 and "no such file" in result.stderr


# MyHDL (the machine as a MyHDL process) is slow: Verilator (the compiled harness) by default
@pytest.mark.parametrize("kind", ["verilator", pytest.param("myhdl", marks=pytest.mark.slow)])
def test_info_shows_the_machine_side_with_a_simulated_machine(tmp_path, kind):
    """``info --machine``: HOME_X's switch
    closed where the axis stands reads active through the filter, and the guard,
    drives, watchdog and homing lines say the card is at rest."""
    machine = tmp_path / "machine.json"
    machine.write_text(MachineConfig(switches={"HOME_X": Switch(0, positive=False)}).to_json())
    info = run_host("info", "--card", kind, "--machine", machine)
    assert info.returncode == 0, info.stderr
    for line in ("inputs:      active HOME_X (after INPUT_POLARITY and the filter); pins high HOME_X",
                 "guard:       running", "drives:      DRIVE_ENABLE pin low, MACHINE_CONTROL.DRIVE_ENABLE 0; hold off",
                 "watchdog:    off", "homing:      idle; last HOME axis X: none",
                 "sim machine: positions (0, 0), steps lost to a disabled drive (0, 0), E-stop released"):
        assert line in info.stdout, info.stdout
    bad = tmp_path / "bad.json"
    bad.write_text('{"switches": {"HOME_X": {"position": "here"}}}')
    for card, path, message in (("pci", machine, "--machine needs a simulated card"),
                                ("verilator", bad, "HOME_X: position, hysteresis, bounce, longest_run and seed are whole"),
                                ("verilator", tmp_path / "none.json", "no such file")):
        refused = run_host("info", "--card", card, "--machine", path)
        assert refused.returncode == 2 and message in refused.stderr, refused.stderr
