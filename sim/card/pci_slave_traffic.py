"""Seeded random PCI traffic against a scoreboard, the monitor watching
(the generator of ``sim/card/test_pci_slave_traffic.py`` and ``bench/vip_figures.py``).

Every command, bursts of 1..64 dwords (some running off the end of the
BAR), random byte enables, random master wait states, a back end with random
latency (now and then beyond the 16/8-clock rules), random retries and a
room for memory writes that comes and goes.  The scoreboard is a plain model
of the two BARs: reads must return it, the back end must hold it at the end
(nothing the target acknowledged got lost); the bench's room audit checks
every clock that the target acknowledged no write the back end had not
promised to take.
"""
import random
from collections import Counter

from sim.card.local_memory import LocalMemory
from sim.pci.bench import PciBench
from sim.pci.host import (COMMAND_IO, COMMAND_MEMORY, COMMAND_PARITY_RESPONSE, DUAL_ADDRESS, INTERRUPT_ACK, MEM_READ,
                          MEM_READ_LINE, MEM_READ_MULTIPLE, MEM_WRITE, MEM_WRITE_INVALIDATE, SPECIAL_CYCLE, Termination,
                          random_waits)

DEVICE = 0
IO_BASE, MEM_BASE = 0x1000, 0x80000000
IO_SIZE, MEM_SIZE = 64, 4096
VENDOR_DEVICE = 0xDDA0 << 16 | 0x1234
KINDS = {"mem write": 6, "mem read": 6, "io write": 3, "io read": 3, "io abort": 1,
         "config read": 1, "config write": 1, "not claimed": 1}


def back_end_latency(rng, space, addr, is_write):
    """Mostly fast, sometimes slow, now and then beyond the latency rules."""
    roll = rng.random()
    if roll < 0.75:
        return 0
    if roll < 0.97:
        return rng.randint(1, 4)
    return rng.randint(9, 20)


def write_room(rng, edge, promised):
    """Places for memory writes free up now and then, at most eight at a
    time, and for one stretch in five none does."""
    if (edge // 300) % 5 == 4:
        return promised
    return max(promised, min(promised + (rng.random() < 0.4), 8))


def byte_mask(be):
    return sum(0xFF << (8 * byte) for byte in range(4) if be >> byte & 1)


class Scoreboard:
    """The BARs as the host should see them, and what was checked."""

    def __init__(self):
        self.spaces = [[0] * (IO_SIZE // 4), [0] * (MEM_SIZE // 4)]
        self.stats = Counter()
        self.interrupt_line = 0

    def count(self, result):
        for transaction in result.transactions:
            self.stats[transaction.termination.value] += 1

    def write(self, space, index, value, be):
        mask = byte_mask(be)
        self.spaces[space][index] = (self.spaces[space][index] & ~mask) | (value & mask)

    def check_read(self, space, index, value, be, where):
        mask = byte_mask(be)
        expected = self.spaces[space][index] & mask
        assert value & mask == expected, (
            f"{where}: dword {index} of space {space} read {value:#010x}, expected "
            f"{expected:#010x} under byte enables {be:#x}")
        self.stats["dwords checked"] += 1


def transferred(result):
    return sum(len(t.data) for t in result.transactions)


def burst_length(rng):
    return rng.choice([1, 1, 2, 3, 4, 8, 16, rng.randint(1, 64)])


def traffic(count, seed, board):
    """Scenario: ``count`` random accesses checked against ``board``."""
    rng = random.Random(seed)

    def scenario(bench, out):
        host = bench.host
        yield from host.config_write(DEVICE, 0x10, IO_BASE)
        yield from host.config_write(DEVICE, 0x14, MEM_BASE)
        yield from host.config_write(DEVICE, 0x04, COMMAND_IO | COMMAND_MEMORY |
                                     COMMAND_PARITY_RESPONSE, be=0x3)
        for number in range(count):
            kind = rng.choices(list(KINDS), weights=list(KINDS.values()))[0]
            yield from ACCESSES[kind](host, rng, board, f"access {number} ({kind})")
            board.stats[kind] += 1
        out["stats"] = board.stats

    return scenario


def memory_write(host, rng, board, where):
    length, start = burst_length(rng), rng.randrange(MEM_SIZE // 4)
    command = rng.choice([MEM_WRITE, MEM_WRITE_INVALIDATE])
    enables = [0xF if command == MEM_WRITE_INVALIDATE else rng.randrange(16) for _ in range(length)]
    values = [rng.getrandbits(32) for _ in range(length)]
    result = yield from host.mem_write(MEM_BASE + 4 * start, values, command=command, be=enables)
    board.count(result)
    expect_claimed_prefix(result, start, length, MEM_SIZE // 4, where)
    for i in range(transferred(result)):
        board.write(1, start + i, values[i], enables[i])
    board.stats["write dwords"] += transferred(result)


def memory_read(host, rng, board, where):
    length, start = burst_length(rng), rng.randrange(MEM_SIZE // 4)
    command = rng.choice([MEM_READ, MEM_READ_LINE, MEM_READ_MULTIPLE])
    be = 0xF if rng.random() < 0.8 else rng.randrange(16)
    result = yield from host.mem_read(MEM_BASE + 4 * start, length, command=command, be=be)
    board.count(result)
    expect_claimed_prefix(result, start, length, MEM_SIZE // 4, where)
    for i in range(transferred(result)):
        board.check_read(1, start + i, result.data[i], be, where)


def expect_claimed_prefix(result, start, length, dwords, where):
    """Inside the BAR everything moves; past its end nobody answers."""
    inside = min(length, dwords - start)
    assert transferred(result) == inside, f"{where}: {transferred(result)} of {inside} dwords moved"
    if inside == length:
        assert result.termination is not Termination.MASTER_ABORT, where
    else:
        assert result.termination is Termination.MASTER_ABORT, where


def io_access(rng):
    size = rng.choice([1, 2, 4])
    offset = rng.randrange(0, IO_SIZE, size)
    be = ((1 << size) - 1) << (offset & 3)
    return size, offset, be


def io_write(host, rng, board, where):
    size, offset, be = io_access(rng)
    value = rng.getrandbits(8 * size)
    result = yield from host.io_write(IO_BASE + offset, value, size=size)
    assert result.complete and result.termination is not Termination.TARGET_ABORT, where
    board.write(0, offset // 4, value << (8 * (offset & 3)), be)


def io_read(host, rng, board, where):
    size, offset, be = io_access(rng)
    result = yield from host.io_read(IO_BASE + offset, size=size)
    assert result.complete, where
    board.check_read(0, offset // 4, result.data[0], be, where)


def io_abort(host, rng, board, where):
    """Byte enables below the byte AD[1:0] addresses: target abort, no effect."""
    low_bits = rng.randint(1, 3)
    below = (1 << low_bits) - 1
    be = rng.randint(1, below) | (rng.randrange(16) & ~below & 0xF)
    offset = rng.randrange(0, IO_SIZE, 4) + low_bits
    write = rng.random() < 0.5
    if write:
        result = yield from host.io_write(IO_BASE + offset, rng.getrandbits(8), size=1, be=be)
    else:
        result = yield from host.io_read(IO_BASE + offset, be=be)
    assert result.termination is Termination.TARGET_ABORT, where


def config_read(host, rng, board, where):
    result = yield from host.config_read(DEVICE, 0x00)
    assert result.value == VENDOR_DEVICE, where
    line = yield from host.config_read(DEVICE, 0x3C)
    assert line.value & 0xFFFF == 0x100 | board.interrupt_line, where


def config_write(host, rng, board, where):
    board.interrupt_line = rng.randrange(256)
    yield from host.config_write(DEVICE, 0x3C, board.interrupt_line | rng.getrandbits(24) << 8,
                                 be=0x1)


def not_claimed(host, rng, board, where):
    command = rng.choice([INTERRUPT_ACK, SPECIAL_CYCLE, 0x4, 0x5, 0x8, 0x9, DUAL_ADDRESS, None])
    if command is None:
        result = yield from host.mem_read(MEM_BASE + MEM_SIZE + 4 * rng.randrange(1024))
    else:
        result = yield from host.transfer(command, MEM_BASE + 4 * rng.randrange(MEM_SIZE // 4),
                                          [(0xF, 0 if command & 1 else None)])
    assert result.termination is Termination.MASTER_ABORT, where


ACCESSES = {"mem write": memory_write, "mem read": memory_read, "io write": io_write,
            "io read": io_read, "io abort": io_abort, "config read": config_read,
            "config write": config_write, "not claimed": not_claimed}


def run_random(target, count, seed):
    memory = LocalMemory(IO_SIZE, MEM_SIZE, latency=back_end_latency, retry_rate=0.03, seed=seed,
                         room=write_room)
    bench = PciBench(target=target, memory=memory,
                     host_options={"irdy_waits": random_waits(seed, 7, 0.2), "max_retries": 1000})
    board = Scoreboard()
    out = {}

    def scenario(b):
        yield from traffic(count, seed, board)(b, out)

    bench.run(scenario, f"pci_random_{target}_{seed}", trace=count <= 1000)
    assert sum(out["stats"][kind] for kind in KINDS) == count
    assert memory.spaces == board.spaces, "the back end lost or corrupted acknowledged data"
    return bench, board
