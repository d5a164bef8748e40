"""Moves on the Verilator card built with encoders with the simulated machine's motors following
(``bench/motor_runs.py``): the encoders end on the steps times the counts per step, the
following error stays within its limit, and a motor stalled mid-move trips the following-error stop
at the step the spec says, with DRIVE_ENABLE low within the stated clocks."""
import pytest

from models.sim_machine import MachineConfig, Motor
from bench.motor_runs import GUARD_CLOCKS, motor_run, stop_reason

pytestmark = [pytest.mark.xdist_group("encoder_card"),
              pytest.mark.slow(reason="the Verilator card with encoders (a build of its own, about a minute of "
                                      "CPU); the MyHDL card runs the motors and a stall trip in the default set "
                                      "(tests/sim/test_sim_machine_motors.py)")]

FERROR_CLOCKS_FROM_POS = 2   # POS changes at the STEP rise's edge; ENC_FERROR an edge later, the flag the next


@pytest.mark.parametrize("x,y,moves,limit", [
    (Motor(counts_per_step=4, lag=40, spacing=3), Motor(counts_per_step=(5, 2), jitter=2, seed=3, index_period=100),
     [(300, -200), (-100, 150)], 20),
    (Motor(counts_per_step=1, lag=200, spacing=5, jitter=4, seed=8), Motor(counts_per_step=8, spacing=3, lag=15),
     [(-120, 90), (60, 60)], 40)])
def test_encoders_follow_a_move_within_the_limit_and_end_on_steps_times_counts_per_step(x, y, moves, limit):
    run = motor_run(MachineConfig(motors={"X": x, "Y": y}), moves, limit)
    steps = tuple(sum(move[axis] for move in moves) for axis in (0, 1))
    expected = tuple((2 * s * n + d) // (2 * d) for s, (n, d) in zip(steps, (x.ratio, y.ratio)))
    assert run.positions == steps == run.machine.positions and run.machine.lost == (0, 0)
    assert run.counts == expected == run.machine.counts
    assert stop_reason(run.stop_reason) == ("NONE", 0) and run.drive_low_at is None
    reads = [abs(value) for axis in run.ferror_reads for value in axis]
    assert len(reads) >= 10 and max(reads) <= limit and max(run.model_worst) <= limit
    assert max(reads) > 0, "the motors lagged: the reads saw an error"
    assert run.ferror == run.model_ferror == (0, 0)


@pytest.mark.parametrize("counts_per_step,limit,feed_rate", [(4, 8, 1000), (1, 5, 3000), ((5, 2), 6, 600)])
def test_a_stall_mid_move_stops_the_card_at_the_step_beyond_the_limit(counts_per_step, limit, feed_rate):
    motor = Motor(counts_per_step=counts_per_step, spacing=3)
    run = motor_run(MachineConfig(motors={"X": motor}), [(1000, 0)], limit, feed_rate=feed_rate, stall_after=60)
    numerator, denominator = motor.ratio
    # the counts stop at the stall; the k-th step after it makes the error round(k * ratio) > limit
    k = next(k for k in range(1, 100) if (2 * k * numerator + denominator) // (2 * denominator) > limit)
    crossing = [clock for clock in run.x_rises if clock >= run.stall_at][k - 1]
    assert stop_reason(run.stop_reason) == ("FOLLOWING_ERROR", 0)
    assert run.model_stop_at == crossing + FERROR_CLOCKS_FROM_POS
    # the guard an edge after the flag; a STEP pulse high holds DRIVE_ENABLE to the edge after it fell
    assert run.drive_low_at == max(run.model_stop_at + GUARD_CLOCKS, crossing + run.step_width + 1)
    assert run.machine.lost == (run.positions[0] - run.machine.positions[0], 0) and run.machine.lost[0] >= k
    assert run.positions[0] < 1000 and run.counts == run.machine.counts[:1] + (0,)
