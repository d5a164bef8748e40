"""Directed benches of the PCI target's terminations and errors (target
abort, back-end retries and stalls, parity errors), its interrupt, master
wait states and reset, each on the MyHDL design and on the generated Verilog
in Icarus, the monitor watching every clock.  Configuration, decoding and
memory bursts: ``sim/card/test_pci_slave.py``.

Golden values come from the PCI 2.3 specification and the target's contract,
never from the design.
"""
import pytest

from sim.card.local_memory import LocalMemory
from sim.card.pci_slave_bench import (DEVICE, IO_BASE, IO_SIZE, MEM_BASE, MEM_SIZE, STATUS_DETECTED_PARITY_ERROR,
                                      STATUS_INTERRUPT, STATUS_SIGNALED_SYSTEM_ERROR, STATUS_SIGNALED_TARGET_ABORT,
                                      TARGETS, run, setup, status)
from sim.pci.bench import CLOCK_PERIOD, PciBench
from sim.pci.host import (COMMAND_INTERRUPT_DISABLE, COMMAND_IO, COMMAND_MEMORY, COMMAND_PARITY_RESPONSE,
                          COMMAND_SERR_ENABLE, MEM_READ, Termination)


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

    out, bench, wave = run(target, scenario, f"pci_write_parity_{respond}", trace=True,
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

    out, bench, wave = run(target, scenario, f"pci_address_parity_{serr_enabled}", trace=True,
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
