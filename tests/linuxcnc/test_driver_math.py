"""The dda_card driver's arithmetic (``linuxcnc/dda_math.h``) in a plain C program.

gcc builds a probe with every warning as an error; it answers one request a
line on stdin.  The expected values come from the card's rules and from
arbitrary-precision Python, not from the header: the worked examples of
docs/linuxcnc.md (2 us at 33.33 MHz is 67 clocks), the pulse outputs' rule
(STEP high STEP_WIDTH clocks, low at least STEP_WIDTH clocks and at least
stepspace), counters summed without wrapping, round half up, and the
limits a follower must keep.  No LinuxCNC needed.
"""
import math
import random
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
WARNINGS = ["-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wshadow", "-Werror"]
PCI_HZ = 33_333_333
TIMING_MAX = 255

PROBE = r"""
#include <stdio.h>
#include <string.h>
#include "dda_math.h"

int main(void)
{
    char op[16];
    while (scanf("%15s", op) == 1) {
        if (!strcmp(op, "clocks")) {
            unsigned long long ns; unsigned hz;
            if (scanf("%llu %u", &ns, &hz) != 2) return 2;
            printf("%llu\n", (unsigned long long)dda_clocks_of_ns(ns, hz));
        } else if (!strcmp(op, "timing")) {
            unsigned ns, hz; uint32_t clocks = 0;
            if (scanf("%u %u", &ns, &hz) != 2) return 2;
            if (dda_timing_clocks(ns, hz, &clocks) == 0)
                printf("%u\n", clocks);
            else
                printf("refused %llu\n", (unsigned long long)dda_timing_max_ns(hz));
        } else if (!strcmp(op, "cycle")) {
            unsigned len, space; int has;
            if (scanf("%u %u %d", &len, &space, &has) != 3) return 2;
            uint32_t cycle = dda_step_cycle(len, space, has);
            printf("%u %u\n", cycle, dda_iteration_clocks(cycle));
        } else if (!strcmp(op, "unwrap")) {
            long long previous; unsigned raw;
            if (scanf("%lld %u", &previous, &raw) != 2) return 2;
            printf("%lld\n", (long long)dda_unwrap(previous, raw));
        } else if (!strcmp(op, "steps")) {
            double position, scale; int64_t steps = 0;
            if (scanf("%lf %lf", &position, &scale) != 2) return 2;
            if (dda_steps_of(position, scale, &steps) == 0)
                printf("%lld\n", (long long)steps);
            else
                printf("refused\n");
        } else if (!strcmp(op, "follow")) {
            double maxvel, maxaccel, dt, target, target_velocity;
            int n;
            struct dda_follower f = {0.0, 0.0};
            if (scanf("%lf %lf %lf %d", &maxvel, &maxaccel, &dt, &n) != 4) return 2;
            for (int i = 0; i < n; i++) {
                if (scanf("%lf %lf", &target, &target_velocity) != 2) return 2;
                dda_follow(&f, target, target_velocity, maxvel, maxaccel, dt);
                printf("%.17g %.17g\n", f.position, f.velocity);
            }
        } else if (!strcmp(op, "velocity")) {
            double command, maxvel, maxaccel, dt;
            int n;
            struct dda_follower f = {0.0, 0.0};
            if (scanf("%lf %lf %lf %lf %d", &command, &maxvel, &maxaccel, &dt, &n) != 5) return 2;
            for (int i = 0; i < n; i++) {
                dda_follow_velocity(&f, command, maxvel, maxaccel, dt);
                printf("%.17g %.17g\n", f.position, f.velocity);
            }
        } else {
            return 3;
        }
    }
    return 0;
}
"""


@pytest.fixture(scope="module")
def probe(tmp_path_factory):
    compiler = shutil.which("gcc") or shutil.which("cc")
    if compiler is None:
        pytest.skip("no C compiler")
    folder = tmp_path_factory.mktemp("dda_math")
    (folder / "probe.c").write_text(PROBE)
    built = subprocess.run([compiler, "-std=c99", *WARNINGS, "-I", str(ROOT / "linuxcnc"), str(folder / "probe.c"),
                            "-o", str(folder / "probe"), "-lm"], capture_output=True, text=True)
    assert built.returncode == 0, built.stderr

    def ask(lines):
        result = subprocess.run([str(folder / "probe")], input="\n".join(lines) + "\n", capture_output=True,
                                text=True, check=True)
        return result.stdout.splitlines()
    return ask


def test_nanoseconds_become_whole_clocks_rounded_up(probe):
    # docs/linuxcnc.md: 2 us at 33.33 MHz is 66.67 clocks, so 67; a time asked for is a minimum
    cases = [(2000, PCI_HZ, 67), (5000, PCI_HZ, 167), (1000, PCI_HZ, 34), (30, PCI_HZ, 1), (0, PCI_HZ, 0),
             (1000, 1_000_000, 1), (1001, 1_000_000, 2), (4_000_000_000, 4_000_000_000, 16_000_000_000)]
    assert probe([f"clocks {ns} {hz}" for ns, hz, _ in cases]) == [str(c) for _, _, c in cases]


@pytest.mark.parametrize("ns, hz, answer", [
    (7650, PCI_HZ, "255"),                     # 254.99997 clocks: the most a register holds
    (7651, PCI_HZ, f"refused {TIMING_MAX * 10**9 // PCI_HZ}"),
    (9000, PCI_HZ, f"refused {TIMING_MAX * 10**9 // PCI_HZ}"),
    (0, PCI_HZ, "1"),                          # less than the card's shortest is its shortest
    (255_000, 1_000_000, "255"), (256_000, 1_000_000, "refused 255000"),
])
def test_timing_the_registers_cannot_hold_is_refused_with_the_limit(probe, ns, hz, answer):
    assert probe([f"timing {ns} {hz}"]) == [answer]


def card_cycle(steplen, stepspace, has_step_space):
    """The pulse outputs' rule (rtl/regs/pulse_out.py): STEP high STEP_WIDTH clocks, then
    low at least STEP_WIDTH clocks (or STEP_SPACE when the card has it); the drive
    needs low at least stepspace."""
    low = stepspace if has_step_space else max(steplen, stepspace)
    return steplen + low


@pytest.mark.parametrize("steplen, stepspace", [(67, 67), (167, 34), (34, 167), (1, 1), (4, 4), (5, 1), (255, 255)])
@pytest.mark.parametrize("has_step_space", [0, 1])
def test_iteration_period_covers_the_cards_step_cycle(probe, steplen, stepspace, has_step_space):
    cycle = card_cycle(steplen, stepspace, has_step_space)
    iteration = max(2, 1 << (cycle - 1).bit_length())
    assert probe([f"cycle {steplen} {stepspace} {has_step_space}"]) == [f"{cycle} {iteration}"]


def test_the_worked_example_of_the_docs(probe):
    """2 us + 2 us at 33.33 MHz: 67 + 67 clocks, so one iteration every 256 clocks."""
    assert probe(["cycle 67 67 0"]) == ["134 256"]
    assert probe(["cycle 167 34 0"]) == ["334 512"]  # 5 us / 1 us: the card's 334 clocks, not 256


@pytest.mark.parametrize("seed", [1, 2])
def test_counters_unwrap_across_both_ends_of_32_bits(probe, seed):
    """A walk of steps across 2^31 and 2^32 both ways: the unwrapped count is the plain sum."""
    rng = random.Random(seed)
    position = rng.choice([2**31 - 5000, -(2**31) + 5000, 2**32 - 3000, 3 * 2**32 + 17])
    unwrapped = position  # the driver starts from a count it knows
    lines, expected = [], []
    for _ in range(400):
        position += rng.randint(-(2**20), 2**20) if rng.random() < 0.2 else rng.randint(-3000, 3000)
        lines.append(f"unwrap {unwrapped} {position % 2**32}")
        expected.append(position)
        unwrapped = position  # the probe is asked afresh each time from the true previous count
    assert [int(v) for v in probe(lines)] == expected


def test_unwrapping_carries_the_count_over_many_wraps(probe):
    """Fed its own answers, period after period, the count goes past 2^33 steps."""
    count, true = 0, 0
    for _ in range(40):
        true += 2**30 - 7
        (answer,) = probe([f"unwrap {count} {true % 2**32}"])
        count = int(answer)
    assert count == true > 2**33


def half_up(x):
    return math.floor(x + 0.5)


def test_positions_in_steps_round_half_up_or_are_refused(probe):
    cases = [(1.005, 100.0), (-1.005, 100.0), (2.5, 1.0), (-2.5, 1.0), (21474.83648, 1e5), (1e9, 1e6),
             (-7.25, 4.0), (0.0, -3.0), (123.456, -100.0)]
    answers = probe([f"steps {p!r} {s!r}" for p, s in cases])
    assert answers == [str(half_up(p * s)) for p, s in cases]
    refused = ["nan 1", "inf 1", "-inf 100", "1e300 1e300", "9007199254740994 1", "-1e16 1", "1 nan"]
    assert probe([f"steps {case}" for case in refused]) == ["refused"] * len(refused)


def follow(probe, maxvel, maxaccel, dt, targets):
    """[(position, velocity)] after each period, targets [(target, its velocity)]."""
    lines = [f"follow {maxvel!r} {maxaccel!r} {dt!r} {len(targets)}"] + [f"{t!r} {v!r}" for t, v in targets]
    return [tuple(map(float, line.split())) for line in probe(lines)]


@pytest.mark.parametrize("seed", [3, 4])
def test_a_command_within_the_limits_is_followed_exactly(probe, seed):
    """A seeded trapezoid-ish path whose velocity and acceleration stay under the limits:
    every period's position is the command itself (nothing carried as error)."""
    rng = random.Random(seed)
    dt, maxvel, maxaccel = 0.001, 25.0, 250.0
    targets, position, velocity = [], 0.0, 0.0
    for _ in range(600):
        velocity = max(-20.0, min(20.0, velocity + rng.uniform(-0.2, 0.2)))
        position += velocity * dt
        targets.append((position, velocity))
    assert [p for p, _ in follow(probe, maxvel, maxaccel, dt, targets)] == [t for t, _ in targets]


@pytest.mark.parametrize("jump", [10.0, -3.0, 0.0371])
def test_a_jump_is_followed_within_maxvel_and_maxaccel_and_reached(probe, jump):
    dt, maxvel, maxaccel = 0.001, 20.0, 200.0
    trace = follow(probe, maxvel, maxaccel, dt, [(jump, 0.0)] * 3000)
    slack = 1e-9
    velocities = [0.0] + [v for _, v in trace]
    assert all(abs(v) <= maxvel * (1 + slack) for v in velocities)
    assert all(abs(b - a) <= maxaccel * dt * (1 + slack) for a, b in zip(velocities, velocities[1:]))
    positions = [p for p, _ in trace]
    overshoot = max((p - jump) * math.copysign(1, jump) for p in positions)
    assert overshoot <= maxaccel * dt * dt, f"overshot the target by {overshoot}"
    arrived = next(i for i, p in enumerate(positions) if p == jump)
    assert all(p == jump for p in positions[arrived:])
    # no slower than the bound: a trapezoid of maxvel and maxaccel, plus a few periods for the discrete law
    ramp = maxvel / maxaccel
    bound = (abs(jump) / maxvel + ramp) if abs(jump) > maxvel * ramp else 2 * math.sqrt(abs(jump) / maxaccel)
    assert arrived * dt <= bound + 5 * dt


@pytest.mark.parametrize("maxvel, reached", [(0.0, 5.0), (3.0, 3.0)])
def test_a_velocity_command_is_reached_at_maxaccel_up_to_maxvel(probe, maxvel, reached):
    """Velocity mode: 5 units/s asked from standstill; the velocity climbs by maxaccel * dt a
    period and stays at the command, or at maxvel when that is lower."""
    dt, maxaccel, command = 0.001, 100.0, 5.0
    lines = [f"velocity {command!r} {maxvel!r} {maxaccel!r} {dt!r} 200"]
    trace = [tuple(map(float, line.split())) for line in probe(lines)]
    velocities = [v for _, v in trace]
    climb = math.ceil(reached / (maxaccel * dt))
    assert all(abs(b - a) <= maxaccel * dt * (1 + 1e-9) for a, b in zip([0.0] + velocities, velocities))
    assert all(abs(v - reached) < 1e-9 for v in velocities[climb:])
    positions = [0.0] + [p for p, _ in trace]
    assert all(abs((b - a) / dt - v) < 1e-6 for a, b, v in zip(positions, positions[1:], velocities))
