"""BAR2, the memory alias of the function registers (BAR0), on the MyHDL
design and on the generated Verilog in Icarus, the monitor watching every
clock.

Golden values come from PCI 2.3 (6.2.5.1: a memory BAR's bits [3:0] are
its type, sizing by writing ones; 3.5.1: disconnect with data) and the
target's contract (docs/pci.md): BAR2 is BAR0's size, 16 bytes at least,
and reaches the back end's space 0 at BAR0's offsets with the PCI byte
enables, one data phase per transaction.
"""
import pytest

from models.parameters import Build
from sim.card.pci_slave_bench import (ALIAS_BASE, ALIAS_SIZE, DEVICE, IO_BASE, IO_SIZE, MEM_BASE, MEM_SIZE,
                                      TARGETS, run, setup)
from sim.pci.host import COMMAND_IO, COMMAND_MEMORY, MEM_READ_LINE, MEM_WRITE_INVALIDATE, Termination

MEMORY_32_NOT_PREFETCHABLE = 0x0   # BAR bits [3:0]: memory, anywhere in 32 bits, not prefetchable


@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("io_bar_bits, alias_size", [(6, 64), (2, 16)])
def test_bar2_is_sized_and_placed_like_a_memory_bar(target, io_bar_bits, alias_size):
    def scenario(b, out):
        yield from b.host.config_write(DEVICE, 0x18, 0xFFFFFFFF)
        out["probe"] = (yield from b.host.config_read(DEVICE, 0x18)).value
        out["devices"] = yield from b.host.enumerate_bus(devices=range(2), io_base=0x2000, mem_base=0xC0000000)

    out, _, _ = run(target, scenario, f"pci_alias_bar_{io_bar_bits}", build=Build(io_bar_bits=io_bar_bits))
    assert out["probe"] == (0xFFFFFFFF & ~(alias_size - 1)) | MEMORY_32_NOT_PREFETCHABLE
    (device,) = out["devices"]
    # the verification IP's enumeration places BAR2 after BAR1 in memory space
    assert [(bar["index"], bar["io"], bar["size"], bar["base"], bar["prefetchable"]) for bar in device.bars] == [
        (0, True, 1 << io_bar_bits, 0x2000, False), (1, False, MEM_SIZE, 0xC0000000, False),
        (2, False, alias_size, 0xC0000000 + MEM_SIZE, False)]


@pytest.mark.parametrize("target", TARGETS)
def test_bar2_reaches_the_registers_at_bar0_offsets_with_byte_enables(target):
    def scenario(b, out):
        host = b.host
        yield from setup(host)
        out["dword"] = yield from host.mem_write(ALIAS_BASE + 0x8, [0x11223344])
        yield from host.mem_write(ALIAS_BASE + 0xD, 0xAA, size=1)
        yield from host.mem_write(ALIAS_BASE + 0xC, [0x55667788], be=[0x9])   # not contiguous: memory allows it
        yield from host.mem_write(ALIAS_BASE + 0x10, [0x12345678], be=[0x0])  # no byte: a data phase all the same
        out["alias read"] = yield from host.mem_read(ALIAS_BASE + 0x8)
        out["word"] = yield from host.mem_read(ALIAS_BASE + 0xE, size=2, command=MEM_READ_LINE)
        out["io read"] = yield from host.io_read(IO_BASE + 0xC)
        yield from host.io_write(IO_BASE + 0x14, 0xCAFEF00D)
        out["io written"] = yield from host.mem_read(ALIAS_BASE + 0x14)

    out, bench, _ = run(target, scenario, "pci_alias_registers")
    assert out["dword"].complete and out["dword"].transactions[0].devsel_clock == 2
    assert bench.memory.read(0, 0x8) == 0x11223344
    assert bench.memory.read(0, 0xC) == 0x5500AA88 and out["io read"].value == 0x5500AA88
    assert bench.memory.read(0, 0x10) == 0
    assert out["alias read"].value == 0x11223344 and out["word"].value == 0x5500
    assert out["io written"].value == 0xCAFEF00D
    # space 0 (the registers), BAR0's offsets, the bus's byte enables; reads included
    alias_transfers = [(space, addr, be, kind) for _, space, addr, be, kind, _ in bench.memory.log]
    assert alias_transfers == [(0, 0x8, 0xF, "w"), (0, 0xC, 0x2, "w"), (0, 0xC, 0x9, "w"), (0, 0x10, 0x0, "w"),
                               (0, 0x8, 0xF, "r"), (0, 0xC, 0xC, "r"), (0, 0xC, 0xF, "r"),
                               (0, 0x14, 0xF, "w"), (0, 0x14, 0xF, "r")]
    assert all(result.complete for result in out.values())   # no target abort, no retry


@pytest.mark.parametrize("target", TARGETS)
def test_bar2_bursts_move_one_dword_then_disconnect(target):
    def scenario(b, out):
        host = b.host
        yield from setup(host)
        out["write"] = yield from host.mem_write(ALIAS_BASE + 0x20, [1, 2, 3], resume=False)
        out["resumed"] = yield from host.mem_write(ALIAS_BASE + 0x24, [4, 5, 6], command=MEM_WRITE_INVALIDATE)
        out["read"] = yield from host.mem_read(ALIAS_BASE + 0x24, 3, resume=False)
        out["read resumed"] = yield from host.mem_read(ALIAS_BASE + 0x20, 4)

    out, bench, _ = run(target, scenario, "pci_alias_bursts")
    records = {record.start: record for record in bench.checker.transactions}
    for case in ("write", "read"):
        assert out[case].termination is Termination.DISCONNECT and len(out[case].data) == 1, case
        record = records[out[case].transactions[0].start]
        assert record.first_stop_clock == record.first_trdy_clock, f"{case}: STOP# with TRDY#"
    assert len(out["resumed"].transactions) == 3 and out["resumed"].complete
    assert [bench.memory.read(0, 0x20 + 4 * i) for i in range(4)] == [1, 4, 5, 6]
    assert out["read"].data == [4] and out["read resumed"].data == [1, 4, 5, 6]
    # no read-ahead: each register is read once per data phase (read side effects happen once)
    reads = [addr for _, space, addr, _, kind, _ in bench.memory.log if kind == "r"]
    assert reads == [0x24, 0x20, 0x24, 0x28, 0x2C]


@pytest.mark.parametrize("target", TARGETS)
def test_bar2_claimed_only_inside_and_with_memory_space_enabled(target):
    def scenario(b, out):
        host = b.host
        yield from setup(host, command=COMMAND_IO)
        out["memory disabled"] = yield from host.mem_read(ALIAS_BASE)
        yield from host.config_write(DEVICE, 0x04, COMMAND_IO | COMMAND_MEMORY, be=0x3)
        out["first"] = yield from host.mem_read(ALIAS_BASE)
        out["last"] = yield from host.mem_read(ALIAS_BASE + ALIAS_SIZE - 4)
        out["above"] = yield from host.mem_read(ALIAS_BASE + ALIAS_SIZE)
        out["below"] = yield from host.mem_read(ALIAS_BASE - 4)
        # a host that lets BAR1 and BAR2 overlap: BAR1 answers
        yield from host.config_write(DEVICE, 0x18, MEM_BASE)
        out["overlap"] = yield from host.mem_write(MEM_BASE + 0x4, [0x77])

    out, bench, _ = run(target, scenario, "pci_alias_decode")
    claimed = {case: r.termination is Termination.NORMAL for case, r in out.items()}
    assert claimed == {"memory disabled": False, "first": True, "last": True, "above": False, "below": False,
                       "overlap": True}
    assert bench.memory.read(1, 0x4) == 0x77 and bench.memory.read(0, 0x4) == 0
    assert IO_SIZE == ALIAS_SIZE
