"""Long random job on the Verilator card (``slow``): at least 10**8 clocks.

A seeded stream of LINE and ARC moves (BLEND at random), SET FEED_RATE from
one iteration in 2,048 clocks to the fastest, DWELLs and MARKs, streamed by
the host through the FIFO as host software does (``sim/card/card_jobs.py``), the
protocol monitor on every bus clock.  Judged against the models: every STEP
rise is the next step of ``models.dda_model``'s chained paths (axis and
direction), every pin edge keeps ``PulseOutModel``'s timing rules, every
MARK is reached in order at the model's position, the final position is
the model's, and no error is raised.
"""
import pytest

from models import registers as regmap
from sim.card.card_e2e import DEFAULT_FIFO, run_card
from sim.card.card_jobs import check_pin_timing, expected_steps, random_job, rise_steps, streaming_scenario

SOAK_CLOCKS = 10 ** 8


@pytest.mark.slow(reason="a soak of 10**8 clocks")
@pytest.mark.parametrize("seed", [2026])
def test_random_job_soak_on_verilator(seed):
    job = random_job(seed, 12000, feeds=(regmap.RATE_ONE // 2048, regmap.RATE_MAX), dwell=200000)
    results = {}
    _, log, _, _ = run_card("verilator", streaming_scenario(job, DEFAULT_FIFO, results), f"card_soak_{seed}",
                            DEFAULT_FIFO, trace=False)
    assert log.clock >= SOAK_CLOCKS, f"only {log.clock} clocks: lengthen the job"
    assert regmap.field_value("STATUS", "ERROR", results["status"]) == 0
    assert results["marks"] == list(job.marks.items())
    assert results["position"] == job.position == log.path()[-1]
    steps, wanted = rise_steps(log), expected_steps(job.moves)
    first_wrong = next((i for i, (a, b) in enumerate(zip(steps, wanted)) if a != b), None)
    assert first_wrong is None, f"step {first_wrong}: pins {steps[first_wrong]}, model {wanted[first_wrong]}"
    assert len(steps) == len(wanted)
    assert check_pin_timing(log.edges) is None
    print(f"soak seed {seed}: {log.clock} clocks, {len(steps)} STEP rises, {len(job.marks)} MARKs, "
          f"{len(job.moves)} moves, final position {results['position']}")
