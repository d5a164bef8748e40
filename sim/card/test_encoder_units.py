"""The encoder units (``rtl/encoder/``) against ``models/encoder_model.py`` every clock.

Seeded random encoder waveforms (``sim/card/encoder_waves.py``: legal walks
down to the closest spacing the filter passes, glitches it must remove,
illegal samples, noise, step/dir, index arm and zero, the host's writes)
on the MyHDL blocks and on their Verilog in Icarus and Verilator; defects
put by hand into copies of the Verilog must fail the same benches.
"""
import pytest
from myhdl import block

from models.encoder_model import MASK32
from rtl.encoder.encoder import encoder, encoder_ports
from rtl.encoder.following_error import following_error, following_error_ports
from rtl.encoder.probe import probe, probe_ports
from rtl.encoder.timestamp import timestamp, timestamp_ports
from sim.backends.clocking import clock_source, reset_then_step
from sim.backends.icarus import convert_and_cosimulate, convert_module
from sim.backends.waves import run_traced
from sim.card.encoder_bench import run_encoder, run_following_error, run_probe
from sim.card.encoder_defects import DEFECTS, with_defect
from sim.card.backend_unit import HALF_PERIOD

BACKENDS = ["myhdl", "icarus"]
# a Verilator model takes about 8 s to build (cached in build/vlt/ after): every one in the slow set
SLOW_BUILD = pytest.mark.slow(reason="a Verilator build of its own, about 8 s")
CLOCKS = 4000   # a few hundred count edges, every segment kind several times


@pytest.mark.parametrize("seed, backend", [(1, "myhdl"), (1, "icarus"), pytest.param(1, "verilator", marks=SLOW_BUILD), (2, "myhdl"),
                                           (2, "icarus")])
def test_encoder_counts_as_the_model_every_clock(seed, backend):
    model, seen = run_encoder(seed, CLOCKS, backend)
    # the waveform did what it is for: counts, illegal samples, index latches
    assert seen["counts"] > 200 and seen["errors"] > 0 and seen["fires"] > 3, seen


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("seed", [3, 4])
def test_legal_walks_with_glitches_are_counted_exactly(seed, backend):
    """Only legal transitions, at the closest spacing half the time, with
    glitches of up to ENC_FILTER clocks: the unit (equal to the model every
    clock) ends on the walk's position, no quadrature error."""
    model, seen = run_encoder(seed, CLOCKS, backend, kinds=("walk",), host=False)
    walk = seen["walk"]
    assert walk.legal_only and abs(walk.position) > 20
    assert model.signed_count == walk.position and not model.quad_error


@pytest.mark.parametrize("seed, backend", [(1, "myhdl"), (1, "icarus"), pytest.param(1, "verilator", marks=SLOW_BUILD),
                                           (2, "myhdl"), (2, "icarus")])
def test_following_error_as_the_model_every_clock(seed, backend):
    state = run_following_error(seed, CLOCKS, backend)
    assert state["stops"] > 2 and state["aligns"] > 2, state


@pytest.mark.parametrize("axes, backend", [(2, "myhdl"), (2, "icarus"), (3, "myhdl"), (3, "icarus"),
                                           pytest.param(3, "verilator", marks=SLOW_BUILD)])
def test_probe_latches_as_the_model_every_clock(axes, backend):
    state = run_probe(axes, CLOCKS, axes, backend)
    assert state["fires"] > 5, state


@pytest.mark.slow(reason="long random runs: 200,000 clocks per unit and seed, several minutes on two cores")
@pytest.mark.parametrize("backend", [*BACKENDS, "verilator"])
@pytest.mark.parametrize("seed", [11, 12, 13])
def test_long_random_runs_as_the_model(seed, backend):
    run_encoder(seed, 200_000, backend)
    run_following_error(seed, 200_000, backend)
    run_probe(seed, 50_000, 3, backend)


@block
def _timestamp_bench(ports, cosim, step, cycles):
    clock, reset = ports["clock"], ports["reset"]
    dut = convert_and_cosimulate(timestamp, "timestamp", ports) if cosim else timestamp(**ports)
    return dut, clock_source(clock, 2 * HALF_PERIOD), reset_then_step(clock, reset, cycles, step)


@pytest.mark.parametrize("backend", BACKENDS)
def test_timestamp_counts_every_edge_from_reset(backend):
    ports = timestamp_ports()
    stamp = ports["stamp"]
    values = []

    def step(index):
        values.append((int(stamp.value), int(stamp.coming)))

    run_traced(_timestamp_bench(ports, backend == "icarus", step, 20), f"timestamp_{backend}")
    # one edge after the reset's release before the first step
    assert values == [(n, (n + 1) & MASK32) for n in range(1, 21)]


FACTORIES = {"encoder": (encoder, encoder_ports), "following_error": (following_error, following_error_ports),
             "probe": (probe, lambda: probe_ports(3))}
RUNS = {"encoder": lambda path: run_encoder(1, CLOCKS, path),
        "following_error": lambda path: run_following_error(1, CLOCKS, path),
        "probe": lambda path: run_probe(1, CLOCKS, 3, path)}


@pytest.mark.parametrize("defect", sorted(DEFECTS))
def test_a_defect_put_in_by_hand_fails_the_bench(defect, tmp_path):
    unit = DEFECTS[defect][0]
    factory, ports = FACTORIES[unit]
    mutant = with_defect(defect, convert_module(factory, unit, ports()), tmp_path)
    with pytest.raises(AssertionError, match="clock"):
        RUNS[unit](str(mutant))
