"""When a bench writes its waves (``sim/backends/waves.py``): always when its caller reads
the VCD back, for every bench under ``--waves``, never when the caller says so."""
import pytest
from myhdl import Signal, StopSimulation, block, instance, now

from sim.backends import waves
from sim.backends.clocking import clock_source


@pytest.fixture
def every_bench(request):
    """``--waves`` (param True) or not (False) for one test, whatever the run was started with."""
    before = waves.traced()
    waves.trace_every_bench(request.param)
    yield request.param
    waves.trace_every_bench(before)


@block
def ticking_bench(clock, ticks):
    ticking = clock_source(clock, 10)

    @instance
    def counting():
        while len(ticks) < 20:
            yield clock.posedge
            ticks.append(now())
        raise StopSimulation

    return ticking, counting


PROBE_FOLDER = ("sim", "backends", "test_waves_policy")


def _counter_run(trace, probe):
    """Run the ticking bench as if test ``probe`` of this module ran it, its files removed
    first; (VCD or None, ticks run, the files the run left under the probe's name)."""
    folder = waves.waves_dir().joinpath(*PROBE_FOLDER)
    for stale in folder.glob(f"{probe}.*"):
        stale.unlink()
    ticks = []
    with waves.named_after(f"{'/'.join(PROBE_FOLDER)}.py::{probe}"):
        vcd = waves.run_traced(ticking_bench(Signal(bool(0)), ticks), "policy", trace=trace)
    return vcd, len(ticks), sorted(path.name for path in folder.glob(f"{probe}.*"))


@pytest.mark.parametrize("every_bench", [False], indirect=True)
@pytest.mark.parametrize("trace", [None, False])
def test_without_waves_a_bench_the_caller_does_not_read_runs_untraced(trace, every_bench):
    vcd, ticks, files = _counter_run(trace, f"untraced_{trace}")
    assert vcd is None and ticks == 20, "the bench ran to its end"
    assert not files, "an untraced run wrote waves"


@pytest.mark.parametrize("every_bench", [False, True], ids=["default", "waves"], indirect=True)
def test_a_bench_whose_vcd_is_read_back_is_always_traced(every_bench):
    vcd, ticks, files = _counter_run(True, f"read_back_{every_bench}")
    assert ticks == 20 and waves.end_time(vcd) > 0
    assert files == [f"read_back_{every_bench}.gtkw", f"read_back_{every_bench}.vcd"]


@pytest.mark.parametrize("every_bench", [True], indirect=True)
def test_with_waves_every_bench_is_traced_but_those_never_to_be(every_bench):
    vcd, _, files = _counter_run(None, "every_bench")
    assert vcd is not None and waves.declarations(vcd) and files == ["every_bench.gtkw", "every_bench.vcd"]
    assert _counter_run(False, "never")[::2] == (None, [])
