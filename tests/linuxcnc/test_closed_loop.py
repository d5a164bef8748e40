"""LinuxCNC closed loop on the encoders (linuxcnc/config/dda_xy_encoders.ini, .hal) on the simulated
card built with encoders, whose simulated machine has a motor with an encoder on X and on Y
(``models.sim_machine.Motor``: 4 counts a step, a lag, an index every INDEX_PERIOD counts).

The joints home on their encoders' index (HOME_USE_INDEX), then a program runs with each joint's
feedback from its encoder; a motor stalled mid-program trips the card's following-error stop and
LinuxCNC goes to E-stop.  Golden values come from the machine model's motors (where the index is,
the counts a step) and the card's record, not from the driver.  docs/linuxcnc.md, "Encoders".
"""
import json
import shutil

import pytest

from models import registers as regmap
from models import sim_machine
from tests.linuxcnc.session import PERIOD_CLOCKS, as_user, card_server, configure, missing, run_folder

pytestmark = [pytest.mark.linuxcnc, pytest.mark.xdist_group("linuxcnc"),
              pytest.mark.skipif(missing() is not None, reason=str(missing()))]

COUNTS_PER_STEP = 4        # the sample configuration's ENCODER_SCALE 400 over SCALE 100
ENCODER_SCALE = 400.0      # counts per mm
INDEX_PERIOD = 100         # counts: an index every 0.25 mm
CARD_FERROR = 0.2          # mm: the sample configuration's CARD_FERROR
MIN_FERROR = 0.5           # mm: the joints' MIN_FERROR (LinuxCNC's own limit at rest; FERROR 1 at speed)
# each axis's motor: its encoder edges at least 3 clocks apart (the card counts them with filter
# FALSE, ENC_FILTER 2) and 10 clocks behind the steps
MOTORS = sim_machine.MachineConfig(motors={axis: sim_machine.Motor(counts_per_step=COUNTS_PER_STEP, lag=10, spacing=3,
                                                                             index_period=INDEX_PERIOD)
                                           for axis in ("X", "Y")})
# the simulated card runs at 1 MHz: hostmot2's 15-clock filter would be 15 us there, slower than a
# motor at full speed (80 counts in the first 80 clocks of a period); a real card's 33 MHz is not
ENCODER_HAL = "setp dda-card.0.encoder.00.filter 0\nsetp dda-card.0.encoder.01.filter 0\n"


def read_encoder_samples(path):
    """[(x_cmd, y_cmd, x_fb, y_fb, x_ferror, y_ferror, card clock, card fault, motion enabled,
    stop-reason, x homed, y homed)] from ``halsampler -t`` (session.ENCODER_RECORD_HAL)."""
    samples = []
    for line in open(path):
        fields = line.split()[1:]
        samples.append((*map(float, fields[:6]), int(fields[6]), int(fields[7]), int(fields[8]), int(fields[9]),
                        int(fields[10]), int(fields[11])))
    return samples


def run_closed_loop(run, jobs, *server_options):
    """LinuxCNC on dda_xy_encoders with the motors on the card server; (LinuxCNC's output and exit
    code, samples, the card's record)."""
    configure(run, "dda_xy_encoders")
    with open(run / "record.hal", "a") as hal:
        hal.write(ENCODER_HAL)
    (run / "machine.json").write_text(MOTORS.to_json())
    (run / "machine.json").chmod(0o666)
    server = card_server(run, "--encoders", "--machine", str(run / "machine.json"), *server_options)
    try:
        lcnc = as_user(["linuxcnc", "-r", str(run / "dda_xy_encoders.ini"), *jobs], run, 300)
        server.wait(timeout=60)
    finally:
        server.kill()
    return lcnc, read_encoder_samples(run / "samples.txt"), json.loads((run / "card.json").read_text())


def _field(register, name, value):
    item = regmap.register(register).field(name)
    return (value & item.mask) >> item.lsb


@pytest.mark.slow(reason="LinuxCNC homing on the index and a 5.5 s program on the card with encoders and motors: "
                         "about 100 s (its Verilator build the first time: 3 min more)")
def test_index_homing_then_a_program_with_the_motors_following(linuxcnc_alone):
    """Both joints home on their encoder's index (creeping at HOME_LATCH_VEL until the index's
    rising edge, the count zeroed there); the program (lines, arcs, a full circle) then runs
    with each joint's feedback from its encoder: within MIN_FERROR of the command at every
    servo period, no card stop; back at X0 Y0 each motor stands at the index it homed on: its
    first index, INDEX_PERIOD counts from where it started (within a step)."""
    run = run_folder()
    lcnc, samples, record = run_closed_loop(run, [str(run / "lcnc_path.ngc")])
    assert lcnc.returncode == 0, lcnc.stdout[-3000:] + lcnc.stderr[-3000:]
    homed = next(k for k, s in enumerate(samples) if s[10] and s[11])
    running = samples[homed:]
    worst = [max(abs(s[4 + axis]) for s in running) for axis in range(2)]
    moved = [max(abs(s[axis]) for s in running) for axis in range(2)]
    print(f"\nclosed loop: {len(running)} periods after homing, worst following error X {worst[0] * 1000:.1f} um, "
          f"Y {worst[1] * 1000:.1f} um (card stop at {CARD_FERROR * 1000:.0f} um, LinuxCNC's at "
          f"{MIN_FERROR * 1000:.0f}..1000 um); machine counts {record['machine']['counts']}, "
          f"positions {record['machine']['positions']} steps")
    assert min(moved) >= 4, f"the program hardly moved: {moved} mm"
    assert max(worst) <= MIN_FERROR
    assert not any(s[7] for s in samples), "the card or the driver faulted"
    assert record["machine"]["lost"] == [0, 0]
    # the index homing: X0 Y0 is where each encoder's index came, its first rising edge, within the
    # step the stepgen places to (COUNTS_PER_STEP counts)
    assert all(abs(count - INDEX_PERIOD) <= COUNTS_PER_STEP for count in record["machine"]["counts"]), record["machine"]
    shutil.rmtree(run, ignore_errors=True)


STALL_AT = 3_500_000   # card clock: X's motor stalls, well into the program


@pytest.mark.slow(reason="a LinuxCNC run to mid-program on the card with encoders and motors: about 90 s")
def test_a_stalled_motor_trips_the_card_and_linuxcnc_goes_to_estop(linuxcnc_alone):
    """X's motor stalls mid-program (card server --stall): its encoder stops while the steps go on,
    the card's following error passes CARD_FERROR and the card stops itself (STOP_REASON
    FOLLOWING_ERROR on X, DRIVE_ENABLE low) within the steps that limit allows; the driver reports
    it (error, stop-reason 4) in the next period, LinuxCNC goes to E-stop: motion off (motion-enabled
    low), the machine no longer on (headless stops saying so)."""
    run = run_folder()
    lcnc, samples, record = run_closed_loop(run, [str(run / "lcnc_path.ngc")], "--stall", f"X@{STALL_AT}")
    assert "the machine went off during" in lcnc.stdout + lcnc.stderr, lcnc.stdout[-3000:]
    final = record["final"]
    assert _field("STOP_REASON", "REASON", final["STOP_REASON"]) == regmap.STOP_REASONS.index("FOLLOWING_ERROR")
    assert _field("STOP_REASON", "AXIS", final["STOP_REASON"]) == 0
    drive_low = next(clock for clock, level in record["drive"] if clock > STALL_AT and level == 0)
    x_steps = [r[0] for r in record["rises"] if r[1] and STALL_AT < r[0] <= drive_low]
    limit_steps = CARD_FERROR * ENCODER_SCALE / COUNTS_PER_STEP
    assert len(x_steps) <= limit_steps + 1, f"{len(x_steps)} X steps after the stall before the card stopped"
    fault = next(s for s in samples if s[7])
    estop = next(s for s in samples if s[6] >= fault[6] and not s[8])
    assert fault[9] == regmap.STOP_REASONS.index("FOLLOWING_ERROR")
    # the period's clock is its end; the card stopped within the period before the driver's read
    assert drive_low < fault[6] <= drive_low + 2 * PERIOD_CLOCKS, "the driver saw the stop later than its next period"
    # (the server samples DRIVE_ENABLE at the end of each request: drive_low is the end of the ADVANCE
    # in which it fell; the card's own reaction, 9 clocks, is docs/encoders.md's)
    print(f"\nstall at clock {STALL_AT}: {len(x_steps)} X steps later the card stopped (DRIVE_ENABLE low by "
          f"{drive_low}, {drive_low - STALL_AT} clocks after the stall), the driver's error at the period ending {fault[6]} "
          f"(+{fault[6] - drive_low}), LinuxCNC's E-stop (motion-enabled low) at {estop[6]} "
          f"(+{estop[6] - drive_low} clocks)")
    shutil.rmtree(run, ignore_errors=True)
