"""The kept conversions (``sim/backends/conversions.py``): one conversion per
sources and key, a new one when either changes, shared by every caller."""
import multiprocessing
import time

import pytest
from myhdl import ResetSignal, Signal, intbv

from sim.backends import conversions


@pytest.fixture
def sources(tmp_path, monkeypatch):
    """A tree of its own for the sources and for ``build/``, so the test converts nothing real."""
    for package in conversions.SOURCE_PACKAGES:
        (tmp_path / package).mkdir()
        (tmp_path / package / "unit.py").write_text(f"# {package}\n")
    monkeypatch.setattr(conversions, "ROOT", tmp_path)
    monkeypatch.setattr(conversions, "build_dir", lambda *parts: _made(tmp_path.joinpath("build", *parts)))
    conversions.sources_digest.cache_clear()
    yield tmp_path
    conversions.sources_digest.cache_clear()


def _made(folder):
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def _converter(calls):
    def convert(folder):
        calls.append(folder)
        (folder / "unit.v").write_text(f"module unit; // conversion {len(calls)}\nendmodule\n")
        return folder / "unit.v"

    return convert


def test_a_key_is_converted_once_and_kept(sources):
    calls = []
    first = conversions.converted("unit", "depth=16", _converter(calls))
    again = conversions.converted("unit", "depth=16", _converter(calls))
    assert first == again and len(calls) == 1
    assert "conversion 1" in first.read_text()
    assert not any(path.name.startswith(".") for path in first.parent.parent.iterdir()), "staging left behind"


@pytest.mark.parametrize("package", conversions.SOURCE_PACKAGES)
def test_a_changed_source_or_key_is_converted_afresh(sources, package):
    calls = []
    kept = conversions.converted("unit", "depth=16", _converter(calls))
    other_key = conversions.converted("unit", "depth=32", _converter(calls))
    (sources / package / "unit.py").write_text("# changed\n")
    conversions.sources_digest.cache_clear()
    changed = conversions.converted("unit", "depth=16", _converter(calls))
    assert len({kept, other_key, changed}) == 3 and len(calls) == 3


def _convert_slowly_in_process(log, queue):
    def convert(folder):
        with open(log, "a") as calls:
            calls.write("converted\n")
        time.sleep(0.5)  # long enough for the other process to ask while this one converts
        (folder / "unit.v").write_text("module unit;\nendmodule\n")
        return folder / "unit.v"

    queue.put(str(conversions.converted("unit", "depth=16", convert)))


def test_two_workers_asking_at_once_share_one_conversion(sources):
    # a second worker that asks while the first converts waits for it, converting nothing itself
    log, context = sources / "calls.txt", multiprocessing.get_context("fork")
    queue = context.Queue()
    workers = [context.Process(target=_convert_slowly_in_process, args=(log, queue)) for _ in range(2)]
    for worker in workers:
        worker.start()
    for worker in workers:
        worker.join(60)
    assert [w.exitcode for w in workers] == [0, 0]
    assert len({queue.get(timeout=5), queue.get(timeout=5)}) == 1
    assert log.read_text().splitlines() == ["converted"]
    assert not any(path.name.startswith(".") for path in (sources / "build" / "conv").iterdir()), "lock left behind"


def test_port_key_tells_widths_reset_values_and_reset_kinds_apart():
    def key(**ports):
        return conversions.port_key(ports)

    base = key(count=Signal(intbv(0)[8:]), reset=ResetSignal(0, active=1, isasync=False))
    assert base == key(count=Signal(intbv(0)[8:]), reset=ResetSignal(0, active=1, isasync=False))
    assert base != key(count=Signal(intbv(0)[9:]), reset=ResetSignal(0, active=1, isasync=False))
    assert base != key(count=Signal(intbv(3)[8:]), reset=ResetSignal(0, active=1, isasync=False))
    assert base != key(count=Signal(intbv(0, min=-128, max=128)), reset=ResetSignal(0, active=1, isasync=False))
    assert base != key(count=Signal(intbv(0)[8:]), reset=ResetSignal(0, active=0, isasync=False))
    assert base != key(count=Signal(intbv(0)[8:]), reset=ResetSignal(0, active=1, isasync=True))
