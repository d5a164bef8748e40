"""Directed benches of the PCI target's own design choices, the monitor
watching every clock: the ``io_registers`` build, posted writes under a
refusing back end, read-ahead bounds, parameter checks.

Golden values come from the host's requests (the data it wrote), the PCI
rules the monitor enforces and the contract, never from the design.
"""
import pytest
from myhdl import Signal, always_comb, always_seq, block

from models.parameters import Build
from rtl.interfaces import LocalBus, PciBus
from rtl.pci.pci_slave_build import local_addr_width
from rtl.pci_slave import pci_slave, pci_slave_ports
from sim.card.local_memory import LocalMemory, local_memory
from sim.pci.bench import PciBench
from sim.pci.host import COMMAND_IO, COMMAND_MEMORY, COMMAND_PARITY_RESPONSE, MEM_READ, Termination

DEVICE = 0
IO_BASE, MEM_BASE = 0x1000, 0x80000000
IO_SIZE, MEM_SIZE = 64, 4096


def setup(host):
    yield from host.config_write(DEVICE, 0x10, IO_BASE)
    yield from host.config_write(DEVICE, 0x14, MEM_BASE)
    yield from host.config_write(DEVICE, 0x04, COMMAND_IO | COMMAND_MEMORY | COMMAND_PARITY_RESPONSE,
                                 be=0x3)


@block
def io_cell_registers(clock, bus, core):
    """What ``pci_pads(io_registers=True)`` does, as a bench model: AD, C/BE#
    and IDSEL sampled into registers, AD, TRDY#, DEVSEL#, STOP#, PERR#
    leaving from registers fed with the core's next values; enables, PAR,
    FRAME#, IRDY#, SERR#, INTA# straight through.  No reset, like the iCE40
    I/O-cell registers."""

    @always_seq(clock.posedge, reset=None)
    def registers():
        core.ad_in.next = bus.ad_in
        core.cbe_in.next = bus.cbe_in
        core.idsel_in.next = bus.idsel_in
        bus.ad_out.next = core.ad_out
        bus.trdy_out.next = core.trdy_out
        bus.devsel_out.next = core.devsel_out
        bus.stop_out.next = core.stop_out
        bus.perr_out.next = core.perr_out

    @always_comb
    def straight():
        core.par_in.next = bus.par_in
        bus.par_out.next = core.par_out
        core.frame_in.next = bus.frame_in
        core.irdy_in.next = bus.irdy_in
        bus.ad_oe.next = core.ad_oe
        bus.par_oe.next = core.par_oe
        bus.trdy_oe.next = core.trdy_oe
        bus.devsel_oe.next = core.devsel_oe
        bus.stop_oe.next = core.stop_oe
        bus.perr_oe.next = core.perr_oe
        bus.serr_out.next = core.serr_out
        bus.serr_oe.next = core.serr_oe
        bus.inta_out.next = core.inta_out
        bus.inta_oe.next = core.inta_oe

    return registers, straight


def io_register_target(memory):
    """A PciBench target: ``pci_slave(io_registers=True)`` behind I/O-cell registers."""

    def build(bench):
        bus, core = PciBus(), PciBus()
        local = LocalBus(local_addr_width())
        blocks = [(io_cell_registers, (bench.clock, bus, core)),
                  (local_memory, (bench.clock, bench.reset, local, memory)),
                  (pci_slave, (bench.clock, bench.reset, core, local, bench.irq),
                   {"io_registers": True})]
        return bus, blocks

    return build


def mixed_traffic(b, out):
    """Every kind of access, bursts, a back-end retry and slow answers."""
    host = b.host
    yield from setup(host)
    values = [0x01010101 * (i + 1) for i in range(20)]
    out.append((yield from host.mem_write(MEM_BASE + 0x100, values)))
    out.append((yield from host.mem_read(MEM_BASE + 0x100, 20)))
    out.append((yield from host.io_write(IO_BASE + 6, 0xBEEF, size=2)))
    out.append((yield from host.io_read(IO_BASE + 4)))
    out.append((yield from host.mem_read(MEM_SIZE - 8 + MEM_BASE, 4)))
    out.append((yield from host.config_read(DEVICE, 0x04)))


def transaction_trace(results):
    return [(t.command, t.address, t.data, t.termination, t.devsel_clock, t.first_trdy_clock,
             t.start, t.end) for result in results for t in result.transactions]


def traffic_memory():
    # latency 0 mostly, a slow answer and a retry now and then, room for
    # writes now and then (deterministic)
    return LocalMemory(IO_SIZE, MEM_SIZE, latency=lambda rng, s, a, w: rng.choice([0, 0, 0, 2, 9]),
                       retry_rate=0.1, seed=3,
                       room=lambda rng, edge, promised: max(promised, rng.choice([0, 0, 1, 3])))


def test_io_registers_build_behaves_like_the_default_clock_for_clock():
    default_results, registered_results = [], []
    default = PciBench(target="myhdl", memory=traffic_memory())
    default.run(lambda b: mixed_traffic(b, default_results), "pci_directed_default_build")
    memory = traffic_memory()
    registered = PciBench(target=io_register_target(memory), memory=memory)
    registered.run(lambda b: mixed_traffic(b, registered_results), "pci_directed_io_registers")
    assert default_results[1].data == [0x01010101 * (i + 1) for i in range(20)]
    assert transaction_trace(registered_results) == transaction_trace(default_results)
    assert memory.log == default.memory.log


@pytest.mark.parametrize("retry_rate", [0.3, 0.6])
def test_posted_writes_reach_the_back_end_exactly_once(retry_rate):
    """A back end that refuses often and promises little: every dword the
    host wrote is written once, in order, nothing twice (a FIFO behind BAR1
    must not repeat)."""
    def room(rng, edge, promised):
        return promised + (rng.random() > retry_rate) if edge % 4 == 0 else promised

    memory = LocalMemory(IO_SIZE, MEM_SIZE, latency=(0, 2), retry_rate=retry_rate, seed=11,
                         room=room)
    values = [0xC0DE0000 + i for i in range(64)]
    out = []

    def scenario(b):
        yield from setup(b.host)
        out.append((yield from b.host.mem_write(MEM_BASE, values)))
        yield from b.clocks(100)   # posted dwords may still wait for the back end's latency

    bench = PciBench(target="myhdl", memory=memory)
    bench.run(scenario, f"pci_directed_posted_{int(retry_rate * 10)}")
    assert out[0].complete
    writes = [(addr, data) for _, space, addr, _, kind, data in memory.log
              if kind == "w" and space == 1]
    assert writes == [(4 * i, value) for i, value in enumerate(values)]
    assert any(t.termination is not Termination.NORMAL for t in out[0].transactions)


def test_read_ahead_stops_at_the_end_of_the_bar():
    """A burst to the last dwords of BAR1: no back-end request outside the
    BAR (LocalMemory raises on one), STOP# with the last dword."""
    memory = LocalMemory(IO_SIZE, MEM_SIZE)
    out = []

    def scenario(b):
        yield from setup(b.host)
        for i in range(4):
            b.memory.write(1, MEM_SIZE - 16 + 4 * i, 0x7000 + i)
        out.append((yield from b.host.mem_read(MEM_BASE + MEM_SIZE - 16, 4, command=MEM_READ,
                                               resume=False)))

    PciBench(target="myhdl", memory=memory).run(scenario, "pci_directed_read_ahead_end")
    transaction = out[0].transactions[0]
    assert transaction.data == [0x7000 + i for i in range(4)]
    assert all(addr < MEM_SIZE for _, space, addr, *_ in memory.log if space == 1)


@pytest.mark.parametrize("values, message", [
    ({"vendor_id": 0x10000}, "vendor_id"),
    ({"class_code": -1}, "class_code"),
    ({"io_bar_bits": 9}, "io_bar_bits"),
    ({"mem_bar_bits": 3}, "mem_bar_bits"),
    ({"bar_bits": 6}, "unknown"),
])
def test_a_bad_build_of_the_target_is_refused(values, message):
    with pytest.raises(ValueError, match=message):
        Build().replace(**values)


def test_io_registers_other_than_true_or_false_is_refused():
    with pytest.raises(ValueError, match="io_registers"):
        pci_slave(**pci_slave_ports(), io_registers=1)


def test_local_bus_of_the_wrong_width_is_refused():
    ports = pci_slave_ports()
    ports["local"] = LocalBus(16)
    with pytest.raises(ValueError, match="local.addr"):
        pci_slave(**ports)


def test_ports_follow_the_bar_sizes():
    assert len(pci_slave_ports(mem_bar_bits=16)["local"].addr) == 16
    assert len(pci_slave_ports(io_bar_bits=2, mem_bar_bits=4)["local"].addr) == 8
    assert isinstance(pci_slave_ports()["irq"], type(Signal(bool(0))))


def test_smallest_bars_keep_the_whole_configuration_header():
    """BAR1 of 16 bytes has fewer offset bits than the header has dwords:
    every register must still be reachable (values from the parameters)."""
    params = {"io_bar_bits": 2, "mem_bar_bits": 4, "subsystem_vendor_id": 0xABCD,
              "subsystem_id": 0x1357}
    out = {}

    def scenario(b):
        host = b.host
        yield from host.config_write(DEVICE, 0x3C, 0x5A)
        for register in (0x00, 0x2C, 0x3C):
            out[register] = (yield from host.config_read(DEVICE, register)).value
        out["devices"] = yield from host.enumerate_bus(devices=[DEVICE])

    PciBench(target="myhdl", build=Build(**params)).run(scenario, "pci_directed_small_bars")
    assert out[0x00] == 0xDDA0 << 16 | 0x1234
    assert out[0x2C] == 0x1357 << 16 | 0xABCD
    assert out[0x3C] == 1 << 8 | 0x5A
    assert [bar["size"] for bar in out["devices"][0].bars] == [4, 16, 16]   # BAR2: a memory BAR's 16 bytes at least
