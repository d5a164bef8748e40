"""LinuxCNC with the dda_card driver on the simulated card, end to end.

The card server (``sim.card.card_server``) runs the Verilator card built to
report 1 MHz in CLOCK_HZ; the driver advances it by one servo period of
card clocks per period (lock-step), so the driver's timing math runs as on
a real card.  LinuxCNC runs headless as an ordinary user; ``sampler``
records the commanded joint positions and the card clock every period.
The pins' position keep_ahead - 1 periods after a period's end (the
queue's delay, docs/linuxcnc.md) must be within one step of that period's command, and
equal to it wherever the command stands still; E-stop drops the card's
DRIVE_ENABLE pin at once.  The machine I/O's other tests and the drift
loop's: test_linuxcnc_machine.py.
"""
import shutil
import time

import pytest

from host.transports.base import TransportError
from host.transports.sysfs import find_card
from tests.linuxcnc.compare import deviations
from tests.linuxcnc.session import (KEEP_AHEAD, PERIOD_CLOCKS, SCALE, as_user, configure, missing,
                                    run_folder, run_linuxcnc)

DELAY_PERIODS = KEEP_AHEAD - 1  # the period's command is done at the end of period k + keep_ahead - 1
STEP_CYCLE_CLOCKS = 4  # the card's step cycle for the sample configuration (2000 + 2000 ns) at CLOCK_HZ

# one LinuxCNC per host: every LinuxCNC test runs on one xdist worker, in turn
pytestmark = [pytest.mark.linuxcnc, pytest.mark.xdist_group("linuxcnc"),
              pytest.mark.skipif(missing() is not None, reason=str(missing()))]


def test_without_a_card_the_driver_says_what_the_host_software_says(linuxcnc_alone):
    """The real-card path on a machine without the card: rtapi_pci finds none, and the
    driver refuses to load with the words of host/transports/sysfs.py."""
    try:
        find_card()
    except TransportError as error:
        expected = str(error)
    else:
        pytest.skip("a DDA card is in this machine")
    run = run_folder()
    (run / "card.hal").write_text("loadrt dda_card\n")
    (run / "card.hal").chmod(0o666)
    result = as_user(["halrun", "-f", str(run / "card.hal")], run, 120)
    assert result.returncode != 0
    assert f"dda_card: {expected}" in result.stdout + result.stderr
    shutil.rmtree(run, ignore_errors=True)


def test_gcode_path_from_the_pins(linuxcnc_alone):
    run = run_folder()
    configure(run)
    started = time.monotonic()
    samples, pins, record = run_linuxcnc(run, [str(run / "lcnc_path.ngc"), f"{run / 'lcnc_stop.ngc'}@1.5"])
    rises = record["rises"]
    assert len(samples) > 1000 and len(pins[0]) > 1000
    deviation = deviations(samples, pins, SCALE, DELAY_PERIODS * PERIOD_CLOCKS)
    worst = max(max(abs(dx), abs(dy)) for dx, dy in deviation)
    assert worst <= 1.0, f"the pins left the commanded path by {worst:.3f} steps"
    standstills = 0
    for k in range(1, len(samples) - DELAY_PERIODS - 1):
        if samples[k][:2] == samples[k - 1][:2] == samples[k + 1][:2]:
            x_cmd, y_cmd = samples[k][:2]
            dx, dy = deviation[k]
            assert abs(dx) <= 0.5 and abs(dy) <= 0.5, f"at rest at period {k} the pins are off by ({dx}, {dy})"
            standstills += 1
    assert standstills > 100
    for axis in (1, 2):
        clocks = [r[0] for r in rises if r[axis]]
        closest = min(b - a for a, b in zip(clocks, clocks[1:]))
        assert closest >= STEP_CYCLE_CLOCKS, f"steps {closest} clocks apart, under steplen + stepspace"
    assert samples[-1][:2] != (0.0, 0.0), "the second program was to be stopped before its end at (0, 0)"
    assert not any(s[7] for s in samples), "the drift loop trimmed a card that does not drift"
    drive = record["drive"]  # on with the machine, off at its end; every step in between
    assert [level for _, level in drive] == [0, 1, 0], drive
    assert drive[1][0] < rises[0][0] and rises[-1][0] < drive[2][0]
    running = [s for s in samples if s[3] > 0]
    levels = [s[3] for s in running[1:]]
    underruns = samples[-1][4]
    assert underruns == 0
    print(f"\nLinuxCNC: {len(samples)} servo periods recorded, {len(pins[0])} steps, largest deviation "
          f"{worst:.3f} steps, FIFO level {min(levels)}..{max(levels)} words, {underruns} underruns, "
          f"{time.monotonic() - started:.0f} s")
    shutil.rmtree(run, ignore_errors=True)


def test_estop_from_linuxcnc_stops_the_card_at_once(linuxcnc_alone):
    """E-stop mid-move: the driver sees enable and drive-enable fall (LinuxCNC's E-stop
    chain, the sample HAL) and soft-resets the card and clears MACHINE_CONTROL.DRIVE_ENABLE:
    the card's DRIVE_ENABLE pin, high while the program ran, is low from within the period
    after the one E-stop reached the HAL, and no step comes after it, though the queue held more."""
    run = run_folder()
    configure(run)
    samples, pins, record = run_linuxcnc(run, [f"{run / 'lcnc_stop.ngc'}@1.5:estop"])
    rises = record["rises"]
    on = [k for k, sample in enumerate(samples) if sample[5] and sample[6]]
    assert on and on[-1] < len(samples) - 1, "the machine was never on, or never stopped"
    stop = on[-1] + 1  # the first period with enable or drive-enable low
    moving = [s[0] for s in samples[stop - 20:stop]]
    assert len(set(moving)) > 1, "E-stop came when the machine was not moving"
    assert rises[-1][0] <= samples[stop][2], "steps came after the period E-stop reached the driver"
    drive = record["drive"]
    assert [level for _, level in drive][-2:] == [1, 0], f"DRIVE_ENABLE did not go high, then low: {drive}"
    raised, fell = drive[-2][0], drive[-1][0]
    assert raised < rises[0][0], "steps before DRIVE_ENABLE rose"
    # amp-enable and motion-enabled (drive-enable) fall in the same period, which the driver acts on
    assert samples[stop - 1][2] < fell <= samples[stop][2]
    assert rises[-1][0] <= fell, "a step after DRIVE_ENABLE fell"
    queued = abs(samples[stop - 1][0] * SCALE - pins[1][-1])
    print(f"\nE-stop: DRIVE_ENABLE low {fell - samples[stop - 1][2]} clocks after the start of the period "
          f"E-stop reached the HAL, last step {fell - rises[-1][0]} clocks before; the card stopped "
          f"{queued:.1f} steps short of the command")
    shutil.rmtree(run, ignore_errors=True)
