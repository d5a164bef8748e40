"""The behavioural host against a behavioural target, the monitor watching.

These benches test the host's terminations, wait states and parity
handling without the RTL; the monitor must stay quiet on this legal traffic
(and report the parity errors the target was told to make).
"""
import random

import pytest

from sim.backends.waves import Waveform
from sim.pci.behavioural_target import BehaviouralTarget, TargetPlan, behavioural_target
from sim.pci.bench import CLOCK_PERIOD, PciBench
from sim.pci.bus import even_parity
from sim.pci.host import MEM_READ_LINE, MEM_WRITE_INVALIDATE, Termination, byte_enables, config_address, random_waits

BASE = 0x1000


def bench_with_target(plan=None, **options):
    target = BehaviouralTarget(base=BASE, size=0x1000, plan=plan)
    bench = PciBench(target=lambda b: (target.agent, [(behavioural_target, (b.clock, target))]),
                     **options)
    return bench, target


def sampled(wave, name, edge):
    """Value a rising edge at ``edge`` samples (the one before its changes)."""
    return wave.at(name, edge - 1)


def run(bench, scenario, name):
    results = []

    def wrapped(b):
        yield from scenario(b, results)

    vcd = bench.run(wrapped, name, trace=True)
    return results, vcd


def test_burst_write_then_read_returns_the_data():
    bench, target = bench_with_target()
    values = [0x11111111 * (i + 1) for i in range(8)]

    def scenario(b, out):
        out.append((yield from b.host.mem_write(BASE + 0x40, values)))
        out.append((yield from b.host.mem_read(BASE + 0x40, 8, command=MEM_READ_LINE)))

    (write, read), _ = run(bench, scenario, "host_burst")
    assert write.termination is Termination.NORMAL and write.complete
    assert read.data == values
    assert [target.memory[BASE + 0x40 + 4 * i] for i in range(8)] == values
    assert read.transactions[0].devsel_clock == 2  # the behavioural target is medium


@pytest.mark.parametrize("seed", [1, 2])
def test_master_and_target_wait_states_keep_the_data(seed):
    plan = lambda n: TargetPlan(trdy_waits=[(n + i) % 3 for i in range(16)])
    bench, _ = bench_with_target(plan, host_options={"irdy_waits": random_waits(seed, 7, 0.5)})
    values = list(range(100, 116))

    def scenario(b, out):
        out.append((yield from b.host.mem_write(BASE, values, command=MEM_WRITE_INVALIDATE)))
        out.append((yield from b.host.mem_read(BASE, 16)))

    (_, read), _ = run(bench, scenario, f"host_waits_{seed}")
    assert read.data == values


def test_retry_is_repeated_until_the_target_serves():
    plan = lambda n: TargetPlan(retry=n < 3)
    bench, _ = bench_with_target(plan)

    def scenario(b, out):
        out.append((yield from b.host.mem_write(BASE, [5, 6])))
        out.append((yield from b.host.mem_read(BASE, 1, resume=False)))

    (write, read), _ = run(bench, scenario, "host_retry")
    assert [t.termination for t in write.transactions] == [Termination.RETRY] * 3 + [Termination.NORMAL]
    assert write.transactions[0].data == [] and write.complete
    assert read.data == [5]


def test_disconnect_resumes_at_the_next_address():
    plan = lambda n: TargetPlan(disconnect_after=1 if n == 0 else None)
    bench, target = bench_with_target(plan)

    def scenario(b, out):
        out.append((yield from b.host.mem_write(BASE, [1, 2, 3, 4, 5])))

    (write,), _ = run(bench, scenario, "host_disconnect")
    first, second = write.transactions
    assert first.termination is Termination.DISCONNECT and first.data == [1, 2]
    assert second.address == BASE + 8 and second.data == [3, 4, 5]
    assert [target.memory[BASE + 4 * i] for i in range(5)] == [1, 2, 3, 4, 5]


def test_disconnect_without_resume_reports_it():
    plan = lambda n: TargetPlan(disconnect_after=0)
    bench, _ = bench_with_target(plan)

    def scenario(b, out):
        out.append((yield from b.host.mem_read(BASE, 4, resume=False)))

    (read,), _ = run(bench, scenario, "host_disconnect_once")
    assert read.termination is Termination.DISCONNECT and len(read.data) == 1 and not read.complete


def test_target_abort_ends_the_access():
    bench, _ = bench_with_target(lambda n: TargetPlan(target_abort=True))

    def scenario(b, out):
        out.append((yield from b.host.mem_read(BASE, 2)))

    (read,), _ = run(bench, scenario, "host_target_abort")
    assert read.termination is Termination.TARGET_ABORT and read.data == [] and len(read.transactions) == 1


@pytest.mark.parametrize("waits", [0, 6])
def test_master_abort_when_nobody_claims(waits):
    bench, _ = bench_with_target(host_options={"irdy_waits": waits})

    def scenario(b, out):
        out.append((yield from b.host.mem_read(0x9000, 1)))
        out.append((yield from b.host.mem_write(0x9000, [1, 2])))
        out.append((yield from b.host.config_read(3, 0)))

    results, _ = run(bench, scenario, f"host_master_abort_{waits}")
    assert [r.termination for r in results] == [Termination.MASTER_ABORT] * 3
    assert results[0].data == [0xFFFFFFFF] and results[2].value == 0xFFFFFFFF


@pytest.mark.parametrize("parity_response", [True, False])
def test_bad_read_parity_is_detected_and_reported(parity_response):
    plan = lambda n: TargetPlan(bad_par_phase=2)
    bench, _ = bench_with_target(plan, host_options={"parity_response": parity_response},
                                 allow_parity_errors=True)

    def scenario(b, out):
        out.append((yield from b.host.mem_read(BASE, 4)))

    (read,), vcd = run(bench, scenario, f"host_read_parity_{parity_response}")
    assert read.transactions[0].parity_errors == [2]
    assert [kind for _, kind in bench.checker.parity_errors] == ["read data"]
    perr_low = Waveform(vcd).edges("bus_perr", "0")
    assert bool(perr_low) == parity_response  # timing checked by the monitor


def test_address_phase_parity_follows_ad_and_cbe_in_the_waveform():
    bench, _ = bench_with_target()

    def scenario(b, out):
        out.append((yield from b.host.mem_write(BASE + 0x10, [0xA5A5A5A5])))

    (_,), vcd = run(bench, scenario, "host_address_parity")
    wave = Waveform(vcd)
    address_edge = wave.edges("bus_frame", "0")[0] + CLOCK_PERIOD
    ad, cbe = sampled(wave, "bus_ad", address_edge), sampled(wave, "bus_cbe", address_edge)
    assert ad == BASE + 0x10 and cbe == 0x7
    assert int(sampled(wave, "bus_par", address_edge + CLOCK_PERIOD)) == even_parity(ad, cbe)


def test_bad_write_parity_is_injected_on_the_chosen_phase_only():
    bench, _ = bench_with_target(allow_parity_errors=True)

    def scenario(b, out):
        out.append((yield from b.host.mem_write(BASE, [1, 2, 3], bad_data_parity={1})))
        out.append((yield from b.host.mem_write(BASE, [4], bad_address_parity=True)))

    run(bench, scenario, "host_write_parity")
    assert [kind for _, kind in bench.checker.parity_errors] == ["write data", "address"]


def test_address_and_byte_enable_functions_reject_bad_arguments():
    assert byte_enables(0x102, 2) == 0b1100 and byte_enables(0x101, 1) == 0b0010
    assert config_address(2, 0x10, 1) == (1 << 18) | 0x110
    with pytest.raises(ValueError):
        byte_enables(0x101, 2)
    with pytest.raises(ValueError):
        byte_enables(0, 3)
    with pytest.raises(ValueError):
        config_address(16, 0)
    with pytest.raises(ValueError):
        config_address(0, 0x42)


@pytest.mark.parametrize("seed", [3, 4])
def test_random_legal_traffic_keeps_the_monitor_quiet(seed):
    """Random plans on both sides (waits, retry, disconnect, abort): the
    monitor must accept all of it and the host must report what happened."""
    rng = random.Random(seed)

    def plan(number):
        roll = rng.random()
        return TargetPlan(trdy_waits=[rng.choice([0, 0, 1, 3]) for _ in range(64)],
                          retry=roll < 0.1, target_abort=0.1 <= roll < 0.15,
                          disconnect_after=rng.randrange(8) if 0.15 <= roll < 0.35 else None)

    bench, target = bench_with_target(plan, host_options={"irdy_waits": random_waits(seed, 7, 0.3),
                                                          "max_retries": 100})
    model = {}

    def scenario(b, results):
        terminations = set()
        for _ in range(60):
            start, length = BASE + 4 * rng.randrange(64), rng.randint(1, 16)
            values = [rng.getrandbits(32) for _ in range(length)]
            write = yield from b.host.mem_write(start, values)
            moved = sum(len(t.data) for t in write.transactions)
            model.update({start + 4 * i: values[i] for i in range(moved)})
            read = yield from b.host.mem_read(start, length)
            moved = sum(len(t.data) for t in read.transactions)
            assert read.data[:moved] == [model.get(start + 4 * i, 0) for i in range(moved)]
            terminations.update(t.termination for t in write.transactions + read.transactions)
        results.append(terminations)

    (terminations,), _ = run(bench, scenario, f"host_random_{seed}")
    assert terminations == {Termination.NORMAL, Termination.RETRY, Termination.DISCONNECT,
                            Termination.TARGET_ABORT}
    assert target.memory == model
