"""Directed benches of the PCI target, each on the MyHDL design and on the
generated Verilog in Icarus, the monitor watching every clock.

Golden values come from the PCI 2.3 specification and the target's contract
(IDs, sizes, bit positions), never from the design.  Some checks read the
VCD back: the waveform a user opens is the one that was checked.
"""
import pytest

from sim.local_memory import LocalMemory
from sim.pci_bench import CLOCK_PERIOD, PciBench
from sim.pci_bus import even_parity
from sim.pci_host import (COMMAND_INTERRUPT_DISABLE, COMMAND_IO, COMMAND_MEMORY,
                          COMMAND_PARITY_RESPONSE, COMMAND_SERR_ENABLE, CONFIG_READ,
                          DUAL_ADDRESS, INTERRUPT_ACK, MEM_READ, MEM_READ_LINE,
                          MEM_READ_MULTIPLE, MEM_WRITE, MEM_WRITE_INVALIDATE, SPECIAL_CYCLE,
                          Termination, config_address)
from sim.waves import Waveform

TARGETS = ["myhdl", "verilog"]
DEVICE = 0
IO_BASE, MEM_BASE = 0x1000, 0x80000000
IO_SIZE, MEM_SIZE = 64, 4096          # contract defaults: io_bar_bits=6, mem_bar_bits=12
VENDOR_ID, DEVICE_ID, CLASS_CODE = 0x1234, 0xDDA0, 0x088000
IMPLEMENTED_COMMAND = (COMMAND_IO | COMMAND_MEMORY | COMMAND_PARITY_RESPONSE
                       | COMMAND_SERR_ENABLE | COMMAND_INTERRUPT_DISABLE)
STATUS_INTERRUPT = 1 << 3
STATUS_DEVSEL_MEDIUM = 1 << 9
STATUS_SIGNALED_TARGET_ABORT = 1 << 11
STATUS_SIGNALED_SYSTEM_ERROR = 1 << 14
STATUS_DETECTED_PARITY_ERROR = 1 << 15
MEDIUM_DEVSEL_EDGE = 2   # DEVSEL# sampled two edges after the address edge


def run(target, scenario, name, **options):
    """Run ``scenario(bench, out)``; return (out, bench, waveform)."""
    bench = PciBench(target=target, **options)
    out = {}

    def wrapped(b):
        yield from scenario(b, out)

    vcd = bench.run(wrapped, f"{name}_{target}")
    return out, bench, Waveform(vcd)


def setup(host, command=COMMAND_IO | COMMAND_MEMORY):
    """Place BAR0 at IO_BASE and BAR1 at MEM_BASE, enable ``command``."""
    yield from host.config_write(DEVICE, 0x10, IO_BASE)
    yield from host.config_write(DEVICE, 0x14, MEM_BASE)
    yield from host.config_write(DEVICE, 0x04, command, be=0x3)


def status(host):
    return ((yield from host.config_read(DEVICE, 0x04)).value >> 16) & 0xFFFF


def sampled(wave, name, edge):
    """Value the rising edge at time ``edge`` samples."""
    return wave.at(name, edge - 1)


def address_edges(wave):
    """Times of the rising edges that sample an address phase."""
    return [t + CLOCK_PERIOD for t in wave.edges("bus_frame", "0")]


# ----- configuration space ------------------------------------------------------------
@pytest.mark.parametrize("target", TARGETS)
def test_identity_and_header(target):
    def scenario(b, out):
        for register in range(0, 0x100, 4):
            out[register] = (yield from b.host.config_read(DEVICE, register)).value

    regs, _, wave = run(target, scenario, "pci_identity")
    assert regs[0x00] == DEVICE_ID << 16 | VENDOR_ID
    assert regs[0x08] >> 8 == CLASS_CODE
    assert (regs[0x0C] >> 16) & 0x7F == 0                 # header type 0
    assert (regs[0x3C] >> 8) & 0xFF == 1                  # interrupt pin INTA#
    assert (regs[0x04] >> 16) & (3 << 9) == STATUS_DEVSEL_MEDIUM
    assert (regs[0x04] >> 16) & (1 << 4) == 0             # no capabilities list
    assert regs[0x10] & 1 == 1 and regs[0x14] & 0xF == 0  # I/O BAR; 32-bit non-prefetchable
    implemented = {0x00, 0x04, 0x08, 0x0C, 0x10, 0x14, 0x2C, 0x3C}
    assert all(regs[r] == 0 for r in range(0, 0x100, 4) if r not in implemented)
    for edge in address_edges(wave)[:3]:
        assert sampled(wave, "bus_devsel", edge + CLOCK_PERIOD) == "1"
        assert sampled(wave, "bus_devsel", edge + MEDIUM_DEVSEL_EDGE * CLOCK_PERIOD) == "0"


@pytest.mark.parametrize("target", TARGETS)
def test_parameters_reach_the_header(target):
    params = dict(vendor_id=0xABCD, device_id=0x0123, revision_id=0x5A, class_code=0x0B4001,
                  subsystem_vendor_id=0x1AF4, subsystem_id=0x7777)

    def scenario(b, out):
        for register in (0x00, 0x08, 0x2C):
            out[register] = (yield from b.host.config_read(DEVICE, register)).value

    regs, _, _ = run(target, scenario, "pci_parameters", slave_params=params)
    assert regs[0x00] == 0x0123ABCD and regs[0x08] == 0x0B40015A and regs[0x2C] == 0x77771AF4


@pytest.mark.parametrize("target", TARGETS)
def test_read_only_fields_ignore_writes_and_byte_enables_count(target):
    def scenario(b, out):
        for register in (0x00, 0x08, 0x0C, 0x2C):
            yield from b.host.config_write(DEVICE, register, 0xFFFFFFFF)
        yield from b.host.config_write(DEVICE, 0x3C, 0xFFFFFF5A, be=0x1)
        out["line"] = (yield from b.host.config_read(DEVICE, 0x3C)).value
        yield from b.host.config_write(DEVICE, 0x3C, 0x0000A500, be=0x2)
        yield from b.host.config_write(DEVICE, 0x3C, 0x00000000, be=0x0)
        out["after"] = (yield from b.host.config_read(DEVICE, 0x3C)).value
        yield from b.host.config_write(DEVICE, 0x04, 0xFFFFFFFF, be=0x3)
        out["command"] = (yield from b.host.config_read(DEVICE, 0x04)).value & 0xFFFF
        yield from b.host.config_write(DEVICE, 0x14, 0x12345678)
        yield from b.host.config_write(DEVICE, 0x14, 0xABFFFFFF, be=0x8)
        out["bar1"] = (yield from b.host.config_read(DEVICE, 0x14)).value
        for register in (0x00, 0x08, 0x0C, 0x2C):
            out[register] = (yield from b.host.config_read(DEVICE, register)).value

    regs, _, _ = run(target, scenario, "pci_read_only")
    assert regs["line"] == 0x15A and regs["after"] == 0x15A  # pin stays 1, line takes byte 0
    assert regs["command"] == IMPLEMENTED_COMMAND
    assert regs["bar1"] == 0xAB345000  # 4 KiB BAR: bits 11:0 read 0; only byte 3 written
    assert regs[0x00] == DEVICE_ID << 16 | VENDOR_ID and regs[0x08] >> 8 == CLASS_CODE
    assert (regs[0x0C] >> 16) & 0x7F == 0


@pytest.mark.parametrize("target", TARGETS)
def test_enumeration_sizes_and_places_the_bars(target):
    def scenario(b, out):
        out["devices"] = yield from b.host.enumerate_bus(devices=range(4), io_base=0x2000,
                                                         mem_base=0xC0000000)
        out["io"] = yield from b.host.io_write(0x2000 + 8, 0x11223344)
        out["mem"] = yield from b.host.mem_write(0xC0000000 + 0x10, [0x55667788])

    out, bench, _ = run(target, scenario, "pci_enumeration")
    (device,) = out["devices"]
    assert (device.device, device.vendor_id, device.device_id) == (DEVICE, VENDOR_ID, DEVICE_ID)
    assert device.interrupt_pin == 1 and device.class_code == CLASS_CODE
    assert [(bar["index"], bar["io"], bar["size"], bar["base"]) for bar in device.bars] == [
        (0, True, IO_SIZE, 0x2000), (1, False, MEM_SIZE, 0xC0000000)]
    assert bench.memory.read(0, 8) == 0x11223344 and bench.memory.read(1, 0x10) == 0x55667788


@pytest.mark.parametrize("target", TARGETS)
def test_bar_sizes_follow_the_parameters(target):
    def scenario(b, out):
        out["devices"] = yield from b.host.enumerate_bus(devices=[DEVICE])

    out, _, _ = run(target, scenario, "pci_bar_sizes",
                    slave_params={"io_bar_bits": 4, "mem_bar_bits": 8})
    assert [bar["size"] for bar in out["devices"][0].bars] == [16, 256]


@pytest.mark.parametrize("target", TARGETS)
def test_configuration_claimed_only_for_its_idsel_type_and_function(target):
    def scenario(b, out):
        host = b.host
        out["other device"] = yield from host.config_read(DEVICE + 1, 0)
        out["function 1"] = yield from host.config_read(DEVICE, 0, function=1)
        out["type 1"] = yield from host.transfer(CONFIG_READ, config_address(DEVICE, 0) | 1,
                                                 [(0xF, None)])
        out["own"] = yield from host.config_read(DEVICE, 0)

    out, _, _ = run(target, scenario, "pci_config_decode")
    for case in ("other device", "function 1", "type 1"):
        assert out[case].termination is Termination.MASTER_ABORT, case
    assert out["own"].termination is Termination.NORMAL


@pytest.mark.parametrize("target", TARGETS)
def test_configuration_and_io_bursts_disconnect_after_one_phase(target):
    def scenario(b, out):
        yield from setup(b.host)
        out["config"] = yield from b.host.config_read(DEVICE, 0x00, count=2, resume=False)
        out["io"] = yield from b.host.io_write(IO_BASE, [1, 2, 3], resume=False)
        out["config resumed"] = yield from b.host.config_read(DEVICE, 0x00, count=3)

    out, bench, _ = run(target, scenario, "pci_single_phase_bursts")
    records = {record.start: record for record in bench.checker.transactions}
    for case in ("config", "io"):
        assert out[case].termination is Termination.DISCONNECT, case
        assert len(out[case].data) == 1, case
        record = records[out[case].transactions[0].start]
        assert record.first_stop_clock == record.first_trdy_clock, f"{case}: STOP# with TRDY#"
    assert bench.memory.read(0, 0) == 1 and bench.memory.read(0, 4) == 0
    assert out["config resumed"].data[0] == DEVICE_ID << 16 | VENDOR_ID
    assert out["config resumed"].data[2] >> 8 == CLASS_CODE


# ----- decoding -------------------------------------------------------------------------
@pytest.mark.parametrize("target", TARGETS)
def test_spaces_claimed_only_when_enabled(target):
    def scenario(b, out):
        host = b.host
        yield from setup(host, command=0)
        out["none io"] = yield from host.io_read(IO_BASE)
        out["none mem"] = yield from host.mem_read(MEM_BASE)
        yield from host.config_write(DEVICE, 0x04, COMMAND_MEMORY, be=0x3)
        out["mem only io"] = yield from host.io_read(IO_BASE)
        out["mem only mem"] = yield from host.mem_read(MEM_BASE)
        yield from host.config_write(DEVICE, 0x04, COMMAND_IO, be=0x3)
        out["io only io"] = yield from host.io_read(IO_BASE)
        out["io only mem"] = yield from host.mem_read(MEM_BASE)

    out, _, _ = run(target, scenario, "pci_space_enables")
    claimed = {case: r.termination is Termination.NORMAL for case, r in out.items()}
    assert claimed == {"none io": False, "none mem": False, "mem only io": False,
                       "mem only mem": True, "io only io": True, "io only mem": False}


@pytest.mark.parametrize("target", TARGETS)
def test_other_commands_and_addresses_are_not_claimed(target):
    def scenario(b, out):
        host = b.host
        yield from setup(host)
        for command in (INTERRUPT_ACK, SPECIAL_CYCLE, 0x4, 0x5, 0x8, 0x9, DUAL_ADDRESS):
            out[f"command {command:x}"] = yield from host.transfer(
                command, MEM_BASE, [(0xF, 0 if command & 1 else None)])
        out["below io"] = yield from host.io_read(IO_BASE - 4)
        out["above io"] = yield from host.io_read(IO_BASE + IO_SIZE)
        out["above mem"] = yield from host.mem_read(MEM_BASE + MEM_SIZE)
        out["below mem"] = yield from host.mem_read(MEM_BASE - 4)

    out, bench, _ = run(target, scenario, "pci_not_claimed")
    for case, result in out.items():
        assert result.termination is Termination.MASTER_ABORT, case
    assert not bench.memory.log


@pytest.mark.parametrize("target", TARGETS)
def test_devsel_is_medium_for_every_claimed_command(target):
    commands = (MEM_READ, MEM_WRITE, MEM_READ_LINE, MEM_READ_MULTIPLE, MEM_WRITE_INVALIDATE)

    def scenario(b, out):
        host = b.host
        yield from setup(host)
        out["config"] = yield from host.config_read(DEVICE, 0)
        out["io read"] = yield from host.io_read(IO_BASE)
        out["io write"] = yield from host.io_write(IO_BASE, 7)
        for command in commands:
            out[f"mem {command:x}"] = yield from host.transfer(
                command, MEM_BASE, [(0xF, 5 if command & 1 else None)] * 2)

    out, _, wave = run(target, scenario, "pci_devsel_timing")
    for case, result in out.items():
        assert result.transactions[0].devsel_clock == MEDIUM_DEVSEL_EDGE, case
        assert result.complete, case
    for edge in address_edges(wave):
        assert sampled(wave, "bus_devsel", edge + CLOCK_PERIOD) == "1"
        assert sampled(wave, "bus_devsel", edge + 2 * CLOCK_PERIOD) == "0"


# ----- memory -------------------------------------------------------------------------------
@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("length", [1, 4, 16, 64])
def test_memory_bursts_move_every_dword(target, length):
    values = [(0x01010101 * (i + 1) + length) & 0xFFFFFFFF for i in range(length)]

    def scenario(b, out):
        yield from setup(b.host)
        out["write"] = yield from b.host.mem_write(MEM_BASE + 0x100, values)
        out["read"] = yield from b.host.mem_read(MEM_BASE + 0x100, length, command=MEM_READ_MULTIPLE)

    out, bench, wave = run(target, scenario, f"pci_burst_{length}")
    assert out["write"].complete and out["read"].data == values
    assert [bench.memory.read(1, 0x100 + 4 * i) for i in range(length)] == values
    write_edge, read_edge = address_edges(wave)[-2:]
    assert data_phases(wave, write_edge) == length
    assert data_phases(wave, read_edge) == length
    check_read_turnaround_and_parity(wave, read_edge)


def data_phases(wave, address_edge):
    """Edges of one transaction at which IRDY# and TRDY# are both low."""
    count, edge = 0, address_edge + CLOCK_PERIOD
    while True:
        irdy, trdy = sampled(wave, "bus_irdy", edge), sampled(wave, "bus_trdy", edge)
        count += irdy == "0" and trdy == "0"
        if irdy == "0" and sampled(wave, "bus_frame", edge) == "1" and (
                trdy == "0" or sampled(wave, "bus_stop", edge) == "0"):
            return count
        edge += CLOCK_PERIOD


def check_read_turnaround_and_parity(wave, address_edge):
    """The target leaves AD alone in the turnaround clock; PAR covers each
    read data phase one clock later."""
    assert sampled(wave, "target_ad_oe", address_edge + CLOCK_PERIOD) == "0"
    edge = address_edge + CLOCK_PERIOD
    while not (sampled(wave, "bus_irdy", edge) == "0" and sampled(wave, "bus_frame", edge) == "1"
               and sampled(wave, "bus_trdy", edge) == "0"):
        if sampled(wave, "bus_trdy", edge) == "0":
            expected = even_parity(sampled(wave, "bus_ad", edge), sampled(wave, "bus_cbe", edge))
            assert int(sampled(wave, "bus_par", edge + CLOCK_PERIOD)) == expected
        edge += CLOCK_PERIOD


@pytest.mark.parametrize("target", TARGETS)
def test_zero_wait_states_once_data_flows(target):
    def scenario(b, out):
        yield from setup(b.host)
        out["write"] = yield from b.host.mem_write(MEM_BASE, list(range(32)))
        out["read"] = yield from b.host.mem_read(MEM_BASE, 32)

    out, bench, _ = run(target, scenario, "pci_zero_wait")
    for record in bench.checker.transactions[-2:]:
        completions = record.completions
        assert len(completions) == 32
        assert completions[-1] - completions[0] == 31  # one data phase per clock


@pytest.mark.parametrize("target", TARGETS)
def test_a_burst_of_a_thousand_dwords_is_one_transaction(target):
    # stops short of the BAR's end, where the target disconnects by design
    values = [(0x9E3779B9 * (i + 1)) & 0xFFFFFFFF for i in range(1000)]

    def scenario(b, out):
        yield from setup(b.host)
        out["write"] = yield from b.host.mem_write(MEM_BASE, values)
        out["read"] = yield from b.host.mem_read(MEM_BASE, len(values))

    out, bench, _ = run(target, scenario, "pci_long_burst")
    for result in (out["write"], out["read"]):
        assert result.termination is Termination.NORMAL and len(result.transactions) == 1
    assert out["read"].data == values
    assert [bench.memory.read(1, 4 * i) for i in range(len(values))] == values


@pytest.mark.parametrize("target", TARGETS)
def test_byte_and_word_writes_honour_byte_enables(target):
    def scenario(b, out):
        host = b.host
        yield from setup(host)
        yield from host.mem_write(MEM_BASE + 0x20, [0x11223344])
        yield from host.mem_write(MEM_BASE + 0x21, 0xAA, size=1)
        yield from host.mem_write(MEM_BASE + 0x22, 0xBBCC, size=2)
        yield from host.mem_write(MEM_BASE + 0x24, [0xDDDDDDDD, 0xEEEEEEEE], be=[0x9, 0x0])
        out["byte"] = yield from host.mem_read(MEM_BASE + 0x21, size=1)
        out["word"] = yield from host.mem_read(MEM_BASE + 0x22, size=2)
        yield from host.io_write(IO_BASE + 0x3, 0x5A, size=1)
        out["io word"] = yield from host.io_read(IO_BASE + 0x2, size=2)

    out, bench, _ = run(target, scenario, "pci_byte_enables")
    assert bench.memory.read(1, 0x20) == 0xBBCCAA44
    assert bench.memory.read(1, 0x24) == 0xDD0000DD and bench.memory.read(1, 0x28) == 0
    assert out["byte"].value == 0xAA and out["word"].value == 0xBBCC
    assert out["io word"].value == 0x5A00 and bench.memory.read(0, 0) == 0x5A000000


@pytest.mark.parametrize("target", TARGETS)
def test_burst_disconnects_at_the_end_of_the_bar(target):
    def scenario(b, out):
        yield from setup(b.host)
        out["write"] = yield from b.host.mem_write(MEM_BASE + MEM_SIZE - 8, [1, 2, 3, 4])
        out["read"] = yield from b.host.mem_read(MEM_BASE + MEM_SIZE - 4, 3, resume=False)

    out, bench, _ = run(target, scenario, "pci_bar_end")
    first, second = out["write"].transactions
    assert first.termination is Termination.DISCONNECT and first.data == [1, 2]
    assert second.termination is Termination.MASTER_ABORT  # resumed past the BAR: nobody
    assert bench.memory.read(1, MEM_SIZE - 8) == 1 and bench.memory.read(1, MEM_SIZE - 4) == 2
    assert out["read"].termination is Termination.DISCONNECT and out["read"].data == [2]


# ----- I/O and target abort ---------------------------------------------------------------------
@pytest.mark.parametrize("target", TARGETS)
def test_io_access_with_byte_enables_below_the_address_is_target_aborted(target):
    def scenario(b, out):
        host = b.host
        yield from setup(host)
        yield from host.io_write(IO_BASE + 4, 0x01020304)
        out["clean"] = yield from status(host)
        out["read"] = yield from host.io_read(IO_BASE + 6, be=0x1)    # byte 0 below AD[1:0]=2
        out["write"] = yield from host.io_write(IO_BASE + 5, 0xFF, be=0x3)
        out["legal"] = yield from host.io_read(IO_BASE + 6, be=0x0)   # no byte: legal
        out["after"] = yield from status(host)
        yield from host.config_write(DEVICE, 0x04, STATUS_SIGNALED_TARGET_ABORT << 16 |
                                     COMMAND_IO | COMMAND_MEMORY)
        out["cleared"] = yield from status(host)

    out, bench, _ = run(target, scenario, "pci_target_abort")
    assert out["read"].termination is Termination.TARGET_ABORT
    assert out["write"].termination is Termination.TARGET_ABORT
    assert out["legal"].termination is Termination.NORMAL
    assert bench.memory.read(0, 4) == 0x01020304
    assert not out["clean"] & STATUS_SIGNALED_TARGET_ABORT
    assert out["after"] & STATUS_SIGNALED_TARGET_ABORT
    assert not out["cleared"] & STATUS_SIGNALED_TARGET_ABORT


# ----- back-end stalls --------------------------------------------------------------------------
def schedule_of(plans):
    """A LocalMemory schedule: request number -> (latency, retry), default (0, False)."""
    return lambda number, space, addr, is_write: plans.get(number, (0, False))


def no_promise(rng, edge, promised):
    """A LocalMemory room policy: no write promised, each one may be refused."""
    return promised


@pytest.mark.parametrize("target", TARGETS)
def test_back_end_retry_on_the_first_request_retries_the_transaction(target):
    memory = LocalMemory(IO_SIZE, MEM_SIZE, schedule=schedule_of({0: (0, True), 1: (2, True)}),
                         room=no_promise)

    def scenario(b, out):
        yield from setup(b.host)
        out["write"] = yield from b.host.mem_write(MEM_BASE, [9, 8])

    out, bench, _ = run(target, scenario, "pci_backend_retry", memory=memory)
    terminations = [t.termination for t in out["write"].transactions]
    assert terminations[:2] == [Termination.RETRY, Termination.RETRY]
    assert out["write"].complete and bench.memory.read(1, 0) == 9 and bench.memory.read(1, 4) == 8


@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("promise", [1, 3, 4, 6])
def test_a_burst_takes_only_what_the_back_end_promised(target, promise):
    """The back end promises ``promise`` writes at first, then none until
    edge 150, then every one: the first burst moves no more than promised
    (at least its first dword, a handshake) and disconnects, later ones a
    dword each (the handshake only) until the promise comes; the room audit
    of the bench checks every clock."""
    def room(rng, edge, promised):
        if edge == 1:
            return promise
        return promised if edge < 150 else max(promised, 1 << 20)

    memory = LocalMemory(IO_SIZE, MEM_SIZE, room=room)
    values = [0x100 + i for i in range(12)]

    def scenario(b, out):
        yield from setup(b.host)
        out["write"] = yield from b.host.mem_write(MEM_BASE + 0x40, values)

    out, bench, _ = run(target, scenario, f"pci_backend_room_{promise}", memory=memory)
    transactions = out["write"].transactions
    first = transactions[0]
    assert first.termination is Termination.DISCONNECT
    assert 1 <= len(first.data) <= promise and first.data == values[:len(first.data)]
    early = [t for t in transactions[1:] if t.end < 150 * CLOCK_PERIOD]
    assert early and all(len(t.data) == 1 for t in early)
    assert transactions[-1].termination is Termination.NORMAL
    assert out["write"].complete
    assert [bench.memory.read(1, 0x40 + 4 * i) for i in range(12)] == values


@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("write", [False, True])
def test_slow_back_end_keeps_the_latency_rules(target, write):
    """20 clocks for the first request break the 16-clock rule, 12 for a
    later one the 8-clock rule: the target must retry / disconnect (the
    monitor checks the clocks) and the data must still arrive intact."""
    memory = LocalMemory(IO_SIZE, MEM_SIZE, schedule=schedule_of({0: (20, False), 3: (12, False)}))
    values = [0xA0 + i for i in range(8)]

    def scenario(b, out):
        host = b.host
        if write:
            out["access"] = yield from host.mem_write(MEM_BASE, values)
        else:
            for i, value in enumerate(values):
                b.memory.write(1, 4 * i, value)
            out["access"] = yield from host.mem_read(MEM_BASE, 8)

    def prepared(b, out):
        yield from setup(b.host)
        yield from scenario(b, out)

    out, bench, _ = run(target, prepared, f"pci_slow_backend_{'write' if write else 'read'}",
                        memory=memory)
    access = out["access"]
    assert access.transactions[0].termination is Termination.RETRY
    assert access.complete and len(access.transactions) >= 2
    assert (access.data if not write else [bench.memory.read(1, 4 * i) for i in range(8)]) == values


# ----- parity -----------------------------------------------------------------------------------
@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("respond", [True, False])
def test_write_data_parity_error(target, respond):
    """PERR# two clocks after the bad data phase only with Parity Error
    Response (the monitor checks it); Detected Parity Error either way."""
    command = COMMAND_IO | COMMAND_MEMORY | (COMMAND_PARITY_RESPONSE if respond else 0)

    def scenario(b, out):
        yield from setup(b.host, command)
        out["clean"] = yield from status(b.host)
        yield from b.host.mem_write(MEM_BASE, [1, 2, 3, 4], bad_data_parity={2})
        out["after"] = yield from status(b.host)
        yield from b.host.config_write(DEVICE, 0x04, STATUS_DETECTED_PARITY_ERROR << 16 | command)
        out["cleared"] = yield from status(b.host)

    out, bench, wave = run(target, scenario, f"pci_write_parity_{respond}",
                           allow_parity_errors=True)
    assert [kind for _, kind in bench.checker.parity_errors] == ["write data"]
    assert not out["clean"] & STATUS_DETECTED_PARITY_ERROR
    assert out["after"] & STATUS_DETECTED_PARITY_ERROR
    assert not out["cleared"] & STATUS_DETECTED_PARITY_ERROR
    assert bool(wave.edges("bus_perr", "0")) == respond


@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("serr_enabled", [True, False])
def test_address_parity_error(target, serr_enabled):
    command = COMMAND_IO | COMMAND_MEMORY | COMMAND_PARITY_RESPONSE | (
        COMMAND_SERR_ENABLE if serr_enabled else 0)

    def scenario(b, out):
        yield from setup(b.host, command)
        out["access"] = yield from b.host.mem_write(MEM_BASE, [1], bad_address_parity=True)
        out["after"] = yield from status(b.host)
        out["next"] = yield from b.host.mem_write(MEM_BASE + 4, [2])

    out, bench, wave = run(target, scenario, f"pci_address_parity_{serr_enabled}",
                           allow_parity_errors=True)
    assert [kind for _, kind in bench.checker.parity_errors] == ["address"]
    assert out["after"] & STATUS_DETECTED_PARITY_ERROR
    assert bool(out["after"] & STATUS_SIGNALED_SYSTEM_ERROR) == serr_enabled
    assert bool(wave.edges("bus_serr", "0")) == serr_enabled
    assert out["next"].complete and bench.memory.read(1, 4) == 2


# ----- interrupt ----------------------------------------------------------------------------------
@pytest.mark.parametrize("target", TARGETS)
def test_interrupt_drives_inta_unless_disabled(target):
    def scenario(b, out):
        host = b.host
        yield from setup(host)
        out["idle"] = (int(b.segment.lines.inta.val), (yield from status(host)))
        b.irq.next = True
        yield from b.clocks(3)
        out["raised"] = (int(b.segment.lines.inta.val), (yield from status(host)))
        yield from host.config_write(DEVICE, 0x04, COMMAND_INTERRUPT_DISABLE | COMMAND_IO, be=0x3)
        yield from b.clocks(3)
        out["disabled"] = (int(b.segment.lines.inta.val), (yield from status(host)))
        yield from host.config_write(DEVICE, 0x04, COMMAND_IO, be=0x3)
        yield from b.clocks(3)
        out["enabled"] = int(b.segment.lines.inta.val)
        b.irq.next = False
        yield from b.clocks(3)
        out["lowered"] = int(b.segment.lines.inta.val)

    out, _, _ = run(target, scenario, "pci_interrupt")
    assert out["idle"][0] == 1 and not out["idle"][1] & STATUS_INTERRUPT
    assert out["raised"][0] == 0 and out["raised"][1] & STATUS_INTERRUPT
    assert out["disabled"][0] == 1 and out["disabled"][1] & STATUS_INTERRUPT
    assert out["enabled"] == 0 and out["lowered"] == 1


# ----- master wait states --------------------------------------------------------------------------
@pytest.mark.parametrize("target", TARGETS)
def test_master_wait_states_on_bursts(target):
    pattern = [0, 3, 1, 7, 0, 0, 2, 5]
    values = [0x5000 + i for i in range(16)]

    def scenario(b, out):
        yield from setup(b.host)
        waits = lambda index: pattern[index % len(pattern)]
        out["write"] = yield from b.host.mem_write(MEM_BASE, values, irdy_waits=waits)
        out["read"] = yield from b.host.mem_read(MEM_BASE, 16, irdy_waits=waits)

    out, _, _ = run(target, scenario, "pci_master_waits")
    assert out["write"].complete and out["read"].data == values


# ----- reset ------------------------------------------------------------------------------------
@pytest.mark.parametrize("target", TARGETS)
def test_reset_in_the_middle_of_a_burst_releases_the_bus_and_the_configuration(target):
    """RST# while the target drives a read burst: every line is released at
    once (the monitor checks each reset clock), the configuration returns to
    its reset values, and the target works again once set up."""
    def scenario(b, out):
        yield from setup(b.host)
        out["cut"] = yield from b.host.mem_read(MEM_BASE, 64)
        yield from b.clocks(4)
        out["command"] = (yield from b.host.config_read(DEVICE, 0x04)).value & 0xFFFF
        out["bar1"] = (yield from b.host.config_read(DEVICE, 0x14)).value
        out["disabled"] = yield from b.host.mem_read(MEM_BASE)
        yield from setup(b.host)
        out["again"] = yield from b.host.mem_write(MEM_BASE, [0xFEED, 0xBEEF])

    def reset_during_burst(b):
        while not (b.host.transaction is not None and b.host.transaction.command == MEM_READ
                   and len(b.host.transaction.data) >= 5):
            yield from b.clocks(1)
        yield b.clock.negedge
        b.reset.next = b.reset.active
        yield from b.clocks(3)
        b.reset.next = not b.reset.active

    bench = PciBench(target=target)
    out = {}

    def wrapped(b):
        yield from scenario(b, out)

    bench.run(wrapped, f"pci_reset_{target}", background=reset_during_burst)
    assert out["cut"].termination is Termination.RESET and 0 < len(out["cut"].data) < 64
    assert out["command"] == 0 and out["bar1"] == 0
    assert out["disabled"].termination is Termination.MASTER_ABORT
    assert out["again"].complete and bench.memory.read(1, 4) == 0xBEEF
