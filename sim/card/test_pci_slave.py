"""Directed benches of the PCI target's configuration header, decoding and
memory bursts, each on the MyHDL design and on the generated Verilog in
Icarus, the monitor watching every clock (terminations, errors, interrupt,
reset: ``sim/card/test_pci_slave_terminations.py``).

Golden values come from the PCI 2.3 specification and the target's contract
(IDs, sizes, bit positions), never from the design.  Some checks read the
VCD back: the waveform a user opens is the one that was checked.
"""
import pytest

from models.parameters import Build
from sim.card.pci_slave_bench import (CLASS_CODE, DEVICE, DEVICE_ID, IMPLEMENTED_COMMAND, IO_BASE, IO_SIZE,
                                      MEDIUM_DEVSEL_EDGE, MEM_BASE, MEM_SIZE, STATUS_DEVSEL_MEDIUM, TARGETS, VENDOR_ID,
                                      address_edges, run, sampled, setup)
from sim.pci.bench import CLOCK_PERIOD
from sim.pci.bus import even_parity
from sim.pci.host import (COMMAND_IO, COMMAND_MEMORY, CONFIG_READ, DUAL_ADDRESS, INTERRUPT_ACK, MEM_READ, MEM_READ_LINE,
                          MEM_READ_MULTIPLE, MEM_WRITE, MEM_WRITE_INVALIDATE, SPECIAL_CYCLE, Termination,
                          config_address)


# ----- configuration space ------------------------------------------------------------
@pytest.mark.parametrize("target", TARGETS)
def test_identity_and_header(target):
    def scenario(b, out):
        for register in range(0, 0x100, 4):
            out[register] = (yield from b.host.config_read(DEVICE, register)).value

    regs, _, wave = run(target, scenario, "pci_identity", trace=True)
    assert regs[0x00] == DEVICE_ID << 16 | VENDOR_ID
    assert regs[0x08] >> 8 == CLASS_CODE
    assert (regs[0x0C] >> 16) & 0x7F == 0                 # header type 0
    assert (regs[0x3C] >> 8) & 0xFF == 1                  # interrupt pin INTA#
    assert (regs[0x04] >> 16) & (3 << 9) == STATUS_DEVSEL_MEDIUM
    assert (regs[0x04] >> 16) & (1 << 4) == 0             # no capabilities list
    assert regs[0x10] & 1 == 1 and regs[0x14] & 0xF == 0  # I/O BAR; 32-bit non-prefetchable
    assert regs[0x18] & 0xF == 0                          # BAR2 (the registers' alias) likewise
    implemented = {0x00, 0x04, 0x08, 0x0C, 0x10, 0x14, 0x18, 0x2C, 0x3C}
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

    regs, _, _ = run(target, scenario, "pci_parameters", build=Build(**params))
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
        (0, True, IO_SIZE, 0x2000), (1, False, MEM_SIZE, 0xC0000000), (2, False, IO_SIZE, 0xC0000000 + MEM_SIZE)]
    assert bench.memory.read(0, 8) == 0x11223344 and bench.memory.read(1, 0x10) == 0x55667788


@pytest.mark.parametrize("target", TARGETS)
def test_bar_sizes_follow_the_parameters(target):
    def scenario(b, out):
        out["devices"] = yield from b.host.enumerate_bus(devices=[DEVICE])

    out, _, _ = run(target, scenario, "pci_bar_sizes",
                    build=Build(io_bar_bits=4, mem_bar_bits=8))
    assert [bar["size"] for bar in out["devices"][0].bars] == [16, 256, 16]


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

    out, _, wave = run(target, scenario, "pci_devsel_timing", trace=True)
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

    out, bench, wave = run(target, scenario, f"pci_burst_{length}", trace=True)
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
