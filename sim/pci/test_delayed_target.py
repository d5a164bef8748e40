"""The host against a target with delayed reads and posted writes
(``sim.pci.delayed_target``), on the pure-Python bus loop with the protocol
checker on every clock: bursts of every length, many retries per dword,
random IRDY# waits, prefetch on and off, a small write FIFO; the retry and
clock budgets, abandoned delayed reads, target abort, reset settle time.
Golden data: what the test wrote (a dict model)."""
import random

import pytest

from sim.pci.delayed_target import DEVICE_ID, VENDOR_ID, DelayedTarget
from sim.pci.host_types import HostError, Termination
from sim.pci.loop import PythonBus
from sim.pci.master import PciMaster, random_waits

BASE = 0x80000000
UNLIMITED = 1 << 30


def make_bus(seed=0, waits=None, **target_options):
    target = DelayedTarget(base=BASE, size=0x1000, seed=seed, **target_options)
    host = PciMaster(irdy_waits=waits if waits is not None else random_waits(seed, 3, 0.3),
                     max_retries=UNLIMITED)
    bus = PythonBus(host, {"target": target})
    bus.reset()
    return bus, target


def move(bus, rng, length, model):
    """Write ``length`` random dwords at a random place, read them back."""
    start = BASE + 4 * rng.randrange(1024 - length + 1)
    values = [rng.getrandbits(32) for _ in range(length)]
    write = bus.run(bus.host.mem_write(start, values))
    model.update({start + 4 * i: v for i, v in enumerate(values)})
    read = bus.run(bus.host.mem_read(start, length))
    return write, read, [model[start + 4 * i] for i in range(length)]


def sweep(lengths, retries, prefetch, seed):
    """Move every length through a target retrying ``retries(length)`` times per delayed read."""
    rng = random.Random(seed)
    bursts = retried = 0
    for length in lengths:
        bus, target = make_bus(seed + length, read_retries=retries(rng), prefetch=prefetch,
                               fifo_depth=8, latency=(0, 6))
        model = {}
        write, read, expected = move(bus, rng, length, model)
        assert write.complete and read.complete, (length, write.termination, read.termination)
        assert read.data == expected, f"length {length}: data differ"
        bus.run(bus.host.clocks(8 * len(target.fifo)))  # let the back end drain
        assert target.memory == model
        reads = -(-length // max(1, prefetch))  # delayed reads the burst needs, at least
        assert read.retries >= target.read_retries * reads
        bursts += 2
        retried += read.retries + write.retries
    return bursts, retried


@pytest.mark.parametrize("prefetch", [0, 8])
def test_every_burst_length_with_a_few_retries_per_dword(prefetch):
    bursts, retried = sweep(range(1, 257), lambda rng: rng.randint(0, 2), prefetch, seed=prefetch)
    assert bursts == 512 and retried > 256


@pytest.mark.parametrize("length", [1, 33, 256])
def test_a_hundred_retries_per_delayed_read(length):
    bursts, retried = sweep([length], lambda rng: 100, 0, seed=length)
    assert retried >= 100 * length


@pytest.mark.slow(reason="up to a hundred retries per dword; a few retries per dword run by default")
@pytest.mark.parametrize("prefetch", [0, 8])
def test_every_burst_length_with_up_to_a_hundred_retries_per_dword(prefetch):
    sweep(range(1, 257), lambda rng: rng.randint(0, 100), prefetch, seed=100 + prefetch)


def test_the_retry_budget_counts_per_resumption_not_per_access():
    """Two retries per dword, 33 dwords: 66 retries in all, never more than
    two in a row; a budget of 2 suffices, one of 1 gives up with the log."""
    bus, target = make_bus(read_retries=2, latency=(0, 0), waits=0)
    bus.host.max_retries = 2
    read = bus.run(bus.host.mem_read(BASE, 33))
    assert read.complete and read.retries == 66
    bus.host.max_retries = 1
    with pytest.raises(HostError, match="2 retries in a row") as failure:
        bus.run(bus.host.mem_read(BASE + 0x200, 4))
    log = failure.value.transactions
    assert [t.termination for t in log] == [Termination.RETRY] * 2
    assert len(bus.host.abandoned) == 1 and target.pending is not None


def test_an_abandoned_delayed_read_blocks_the_target_until_the_host_finishes_it():
    bus, target = make_bus(read_retries=3, latency=(0, 0), waits=0)
    with pytest.raises(HostError):
        bus.run(bus.host.mem_read(BASE, 1, max_retries=1))
    with pytest.raises(HostError):  # the target holds the abandoned one: every other read is retried
        bus.run(bus.host.mem_read(BASE + 0x40, 1, max_retries=20))
    finished = bus.run(bus.host.finish_abandoned(max_retries=20))
    assert [r.complete for r in finished] == [True, True]  # the one the target held, then the other
    assert target.pending is None and bus.host.abandoned == []
    assert bus.run(bus.host.mem_read(BASE + 0x40, 1, max_retries=20)).complete


def test_the_host_can_finish_abandoned_reads_by_itself():
    bus, _ = make_bus(read_retries=3, latency=(0, 0), waits=0)
    bus.host.finish_abandoned_first = True
    with pytest.raises(HostError):
        bus.run(bus.host.mem_read(BASE, 1, max_retries=1))
    assert bus.run(bus.host.mem_read(BASE + 0x40, 1, max_retries=20)).complete


def test_the_clock_budget_bounds_one_access():
    bus, _ = make_bus(read_retries=50, latency=(0, 0), waits=0)
    with pytest.raises(HostError, match="clocks"):
        bus.run(bus.host.mem_read(BASE, 4, max_clocks=100))
    assert bus.edges < 150


def test_a_full_write_fifo_disconnects_and_the_host_resumes():
    bus, target = make_bus(latency=(20, 20), fifo_depth=4, waits=0)
    write = bus.run(bus.host.mem_write(BASE, list(range(10))))
    assert write.complete
    assert [t.termination for t in write.transactions][0] is Termination.DISCONNECT
    assert len(write.transactions[0].data) == 4 and target.stats["disconnects"] >= 1


@pytest.mark.parametrize("prefetch", [0, 8])
def test_target_abort_on_the_chosen_address(prefetch):
    bus, _ = make_bus(abort_address=BASE + 12, read_retries=0, prefetch=prefetch, waits=0)
    write = bus.run(bus.host.mem_write(BASE, [1, 2, 3, 4, 5]))
    assert write.termination is Termination.TARGET_ABORT and write.transactions[-1].data == [1, 2, 3]
    read = bus.run(bus.host.mem_read(BASE + 12, 2))
    assert read.termination is Termination.TARGET_ABORT and read.data == []


def test_enumeration_waits_for_a_target_that_wakes_up_late():
    """A target that claims nothing for 400 ns after reset: without settle
    time enumeration finds nobody, with it the device and its BAR."""
    bus, _ = make_bus(config=True, wake_clocks=13, waits=0)
    assert bus.run(bus.host.enumerate_bus(devices=[0])) == []
    bus, target = make_bus(config=True, wake_clocks=13, waits=0)
    (device,) = bus.run(bus.host.enumerate_bus(devices=[0], settle_clocks=64, mem_base=0xC0000000))
    assert (device.vendor_id, device.device_id) == (VENDOR_ID, DEVICE_ID)
    assert device.bars[0]["size"] == 0x1000 and target.base == 0xC0000000 and target.memory_enable
    assert bus.run(bus.host.mem_write(0xC0000000, [7])).complete


@pytest.mark.parametrize("settle_clocks", [2, 20])
def test_the_same_target_model_under_myhdl_needs_the_bench_settle_time(settle_clocks):
    """The delayed-transaction model on the MyHDL bus model (``edge_agent``)
    wakes 13 clocks (about 400 ns) after reset: the bench's default settle
    time is too short for it, 20 clocks are enough."""
    from sim.pci.bench import PciBench
    from sim.pci.bus import PciAgent, edge_agent

    model = DelayedTarget(base=BASE, size=0x1000, config=True, wake_clocks=13, read_retries=3)
    agent = PciAgent()
    bench = PciBench(target=lambda b: (agent, [(edge_agent, (b.clock, b.reset, agent, model))]),
                     settle_clocks=settle_clocks, host_options={"max_retries": 50})
    out = {}

    def scenario(b):
        out["devices"] = yield from b.host.enumerate_bus(devices=[0])
        if out["devices"]:
            out["write"] = yield from b.host.mem_write(BASE, [1, 2, 3])
            out["read"] = yield from b.host.mem_read(BASE, 3)

    bench.run(scenario, f"delayed_target_myhdl_settle_{settle_clocks}")
    assert len(out["devices"]) == (settle_clocks >= 20)
    if out["devices"]:
        assert out["read"].data == [1, 2, 3] and out["read"].retries >= 3
