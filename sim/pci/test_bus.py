"""The bench's own building blocks: the bus model's resolution and driver
record, and the memory back end's latency, retry, room promise and errors."""
import pytest
from myhdl import Signal, StopSimulation, block, instance

from rtl.interfaces import LocalBus, card_reset
from sim.backends.clocking import clock_source
from sim.backends.waves import run_traced
from sim.card.local_memory import NOT_READY_DATA, LocalMemory, local_memory
from sim.pci.bus import PciAgent, PciSegment, even_parity, pci_segment, scripted_agent


@block
def two_agents(clock, segment, scripts, samples):
    """Play a script on each agent, keep one sample of the segment per edge."""
    players = [scripted_agent(clock, segment.agents[name], script)
               for name, script in scripts.items()]
    bus = pci_segment(clock, segment)
    length = max(len(script) for script in scripts.values())

    clock_driver = clock_source(clock, 2 * 15)

    @instance
    def sampler():
        for _ in range(length + 1):
            yield clock.posedge
            samples.append(segment.sample())
        raise StopSimulation()

    return players, bus, clock_driver, sampler


def play(scripts, idsel=None):
    segment = PciSegment({name: PciAgent() for name in scripts}, idsel=idsel)
    samples = []
    run_traced(two_agents(Signal(bool(0)), segment, scripts, samples), "bus_model")
    return segment, samples[1:]  # samples[k]: the clock script step k drove


def test_resolution_pull_ups_and_floating_lines():
    segment, samples = play({"a": [{"frame": 0, "ad": 0x1234, "cbe": 0x6}, {"frame": None, "ad": None}],
                       "b": [{}, {}]})
    first, second = samples[0], samples[1]
    assert first.frame == 0 and first.ad == 0x1234 and first.drivers["ad"] == {"a"}
    assert second.frame == 1 and second.ad is None and second.drivers["ad"] == frozenset()
    assert first.irdy == 1 and first.par is None  # undriven: pulled up / floating
    recorded = list(segment.history)[-len(samples):]
    assert [r.drivers for r in recorded] == [s.drivers for s in samples]


def test_open_drain_lines_are_wired_or_and_contention_is_recorded():
    _, samples = play({"a": [{"serr": 0, "trdy": 0}, {"serr": None}],
                       "b": [{"serr": 0, "trdy": 1}, {"serr": 1}]})
    assert samples[0].serr == 0 and samples[0].drivers["serr"] == {"a", "b"}
    assert samples[0].drivers["trdy"] == {"a", "b"}
    assert samples[1].serr == 1  # b lets go (drives 1: not asserted)


def test_idsel_follows_its_ad_line():
    segment, _ = play({"host": [{"ad": 1 << 17}, {"ad": 1 << 16}], "dev": [{}, {}]},
                      idsel={"dev": 17})
    assert segment.agents["dev"].idsel_in.val == 0  # AD[17] low in the last clock
    with pytest.raises(ValueError):
        PciSegment({"dev": PciAgent()}, idsel={"dev": 3})
    with pytest.raises(ValueError):
        PciSegment({"dev": PciAgent()}, idsel={"nobody": 20})


def test_even_parity():
    assert even_parity(0, 0) == 0 and even_parity(1, 0) == 1
    assert even_parity(0xFFFFFFFF, 0xF) == 0 and even_parity(0x80000000, 0x1) == 0


@block
def local_requests(clock, reset, local, memory, requests, log, misdirect=False):
    """Present each (kind, space, addr, data, be) request until it is answered
    (``misdirect``: announce the opposite direction on ``local.write``); log
    (kind, clocks waited, retry, rdata, room shown while it was answered)."""
    back_end = local_memory(clock, reset, local, memory)

    clock_driver = clock_source(clock, 2 * 15)

    @instance
    def driver():
        reset.next = reset.active
        yield clock.posedge
        reset.next = not reset.active
        for kind, space, addr, data, be in requests:
            yield clock.negedge
            local.space.next, local.addr.next, local.be.next = space, addr, be
            local.wdata.next, local.we.next, local.re.next = data, kind == "w", kind == "r"
            local.write.next = (kind == "w") != misdirect
            waited = 0
            while True:
                yield clock.posedge
                if local.ready or local.retry:
                    log.append((kind, waited, bool(local.retry), int(local.rdata), bool(local.room)))
                    break
                waited += 1
            local.we.next = local.re.next = False
        yield clock.posedge  # the back end acts on the last answer at that same edge
        raise StopSimulation()

    return back_end, clock_driver, driver


def serve(memory, requests, misdirect=False):
    log = []
    local = LocalBus(12)
    run_traced(local_requests(Signal(bool(0)), card_reset(), local, memory, requests, log, misdirect),
               "local_memory")
    return log


def test_latency_and_data():
    memory = LocalMemory(64, 4096, latency=3)
    log = serve(memory, [("w", 1, 0x10, 0xAABBCCDD, 0xF), ("w", 1, 0x10, 0x11223344, 0x6),
                         ("r", 1, 0x10, 0, 0xF), ("r", 0, 0x3C, 0, 0xF)])
    assert [entry[1] for entry in log] == [3, 3, 3, 3]
    assert log[2][3] == 0xAA2233DD and log[3][3] == 0
    assert memory.read(1, 0x10) == 0xAA2233DD


def test_retry_injection_is_seeded():
    requests = [("r", 1, 4 * i, 0, 0xF) for i in range(40)]
    first = serve(LocalMemory(retry_rate=0.3, latency=(0, 2), seed=5), requests)
    again = serve(LocalMemory(retry_rate=0.3, latency=(0, 2), seed=5), requests)
    assert first == again
    assert 0 < sum(entry[2] for entry in first) < 40
    assert all(entry[3] == NOT_READY_DATA for entry in first if entry[2])


def no_promise(rng, edge, promised):
    return promised


def test_schedule_overrides_latency_and_retry():
    memory = LocalMemory(schedule=lambda n, space, addr, write: (n, n == 1), room=no_promise)
    log = serve(memory, [("w", 1, 0, 5, 0xF), ("w", 1, 4, 6, 0xF), ("w", 1, 8, 7, 0xF)])
    assert [(entry[1], entry[2]) for entry in log] == [(0, False), (1, True), (2, False)]
    assert memory.read(1, 4) == 0 and memory.read(1, 8) == 7


def test_promised_writes_are_taken_whatever_the_plan():
    """Four writes promised at the first edge (which answers the read), none
    later; the plan refuses everything: room is high while three or more
    are promised, the four promised space-1 writes are taken, the fifth and
    the write to space 0 are refused."""
    memory = LocalMemory(schedule=lambda n, space, addr, write: (0, True),
                         room=lambda rng, edge, promised: 4 if edge == 1 else promised)
    writes = [("w", 1, 4 * i, 5 + i, 0xF) for i in range(5)]
    log = serve(memory, [("r", 1, 0, 0, 0xF), *writes, ("w", 0, 0, 8, 0xF)])
    assert [(entry[2], entry[4]) for entry in log] == [(True, False), (False, True), (False, True),
                                                       (False, False), (False, False), (True, False),
                                                       (True, False)]
    assert [memory.read(1, 4 * i) for i in range(5)] == [5, 6, 7, 8, 0] and memory.read(0, 0) == 0
    assert memory.promised == 0 and memory.space1_writes == 4


def test_unbounded_room_refuses_only_reads_and_space_0():
    memory = LocalMemory(retry_rate=1.0)
    log = serve(memory, [("w", 1, 0, 5, 0xF), ("r", 1, 0, 0, 0xF), ("w", 0, 0, 1, 0xF)])
    assert [(entry[2], entry[4]) for entry in log] == [(False, True), (True, True), (True, True)]
    assert memory.promised is None and memory.read(1, 0) == 5


def test_a_promise_cannot_be_taken_back():
    memory = LocalMemory(room=lambda rng, edge, promised: 3 if edge < 4 else 1)
    with pytest.raises(ValueError, match="took back a promise"):
        serve(memory, [("r", 1, 0, 0, 0xF)] * 6)


def test_misuse_is_reported():
    with pytest.raises(ValueError, match="disagrees"):
        serve(LocalMemory(), [("w", 1, 0, 5, 0xF)], misdirect=True)
    with pytest.raises(ValueError, match="outside"):
        serve(LocalMemory(64, 64), [("r", 1, 0x40, 0, 0xF)])
    with pytest.raises(ValueError, match="aligned"):
        serve(LocalMemory(), [("w", 0, 0x2, 0, 0xF)])
    with pytest.raises(ValueError):
        LocalMemory(io_bytes=6)
    with pytest.raises(ValueError):
        LocalMemory(retry_rate=2)
