"""The host core on its own, stepped from plain Python as a front end of any
simulator would step it: no MyHDL, no HDL.  A few lines of target answer
with medium DEVSEL# and no wait states; the checks are the PCI 2.3 phase
timing of the host's drive (FRAME#, IRDY#, AD, C/BE#, PAR one clock after
its AD) and the data moved."""
import pytest

from sim.pci.host_core import HostCore, run_scenario
from sim.pci.host_types import MEM_READ, MEM_WRITE, Request, Termination
from sim.pci.lines import even_parity
from sim.pci.master import PciMaster

BASE = 0x4000


class EdgeTarget:
    """Claims memory commands in ``[BASE, BASE + 0x1000)``: DEVSEL# and
    TRDY# driven from the clock after the address edge (sampled two edges
    after it), one dword a clock, PAR a clock after its AD, then DEVSEL# and
    TRDY# high for a clock and released."""

    def __init__(self):
        self.memory = {}
        self.driving = self.ending = self.write = False
        self.devsel = self.trdy = 1
        self.ad, self.ad_oe, self.par, self.par_oe = 0, False, 0, False
        self.address = 0
        self.previous_frame = 1

    def step(self, ad, cbe, frame, irdy):
        """One rising edge, with the lines sampled there."""
        self.par, self.par_oe = even_parity(self.ad, cbe), self.ad_oe
        if self.ending:
            self.driving = self.ending = False
        elif self.driving:
            if irdy == 0 and self.trdy == 0:
                if self.write:
                    self.memory[self.address] = ad
                self.address += 4
                self.ending = frame == 1
            if self.ending:
                self.devsel = self.trdy = 1
                self.ad_oe = False
            else:
                self.devsel = self.trdy = 0
                if not self.write:
                    self.ad, self.ad_oe = self.memory.get(self.address, 0), True
        elif self.previous_frame == 1 and frame == 0 and cbe in (MEM_READ, MEM_WRITE) \
                and BASE <= ad < BASE + 0x1000:
            self.driving, self.address, self.write = True, ad, cbe == MEM_WRITE
        self.previous_frame = frame


class Loop:
    """Host and target on one clock; ``trace`` keeps the host's drive after each edge."""

    def __init__(self):
        self.core = HostCore()
        self.master = PciMaster(self.core)
        self.target = EdgeTarget()
        self.time = 0
        self.trace = []

    def edge(self):
        self.time += 30
        host, target = self.core.drive, self.target
        ad = target.ad if target.ad_oe else (host.ad_out if host.ad_oe else 0)
        par = target.par if target.par_oe else (host.par_out if host.par_oe else 0)
        cbe = host.cbe_out if host.cbe_oe else 0
        frame = host.frame_out if host.frame_oe else 1
        irdy = host.irdy_out if host.irdy_oe else 1
        trdy, devsel = (target.trdy, target.devsel) if target.driving else (1, 1)
        self.core.step(self.time, ad, par, frame, irdy, trdy, devsel, 1)
        target.step(ad, cbe, frame, irdy)
        self.trace.append({name: getattr(host, name) for name in type(host).__slots__})

    def run(self, scenario):
        return run_scenario(scenario, self.edge)


def test_a_burst_write_is_driven_phase_by_phase_and_parity_follows_one_clock_later():
    loop = Loop()
    values = [0x11111111, 0x22222222, 0x33333333]
    result = loop.run(loop.master.mem_write(BASE, values))
    assert result.complete and result.termination is Termination.NORMAL
    assert [loop.target.memory[BASE + 4 * i] for i in range(3)] == values
    trace = loop.trace
    start = next(i for i, d in enumerate(trace) if d["frame_oe"] and d["frame_out"] == 0)
    address = trace[start]
    assert (address["ad_out"], address["cbe_out"], address["irdy_out"]) == (BASE, MEM_WRITE, 1)
    first = trace[start + 1]
    assert first["ad_out"] == values[0] and first["cbe_out"] == 0x0 and first["irdy_out"] == 0
    for before, after in zip(trace, trace[1:]):  # PAR covers the AD/C/BE# of the clock before
        if before["ad_oe"]:
            assert after["par_oe"] and after["par_out"] == even_parity(before["ad_out"], before["cbe_out"])
        else:
            assert not after["par_oe"]
    last = max(i for i, d in enumerate(trace) if d["irdy_oe"] and d["irdy_out"] == 0)
    assert trace[last]["frame_out"] == 1 and trace[last - 1]["frame_out"] == 0
    assert trace[last + 1]["irdy_out"] == 1 and trace[last + 1]["irdy_oe"]  # driven high a clock
    assert not trace[last + 2]["irdy_oe"] and not trace[last + 2]["frame_oe"]
    assert result.transactions[0].devsel_clock == 2 and loop.core.quiet


@pytest.mark.parametrize("count", [1, 5])
def test_a_read_returns_what_the_target_drove(count):
    loop = Loop()
    loop.target.memory.update({BASE + 4 * i: 0xA0 + i for i in range(count)})
    result = loop.run(loop.master.mem_read(BASE, count))
    assert result.data == [0xA0 + i for i in range(count)] and result.parity_errors == 0


def test_nobody_claims_a_master_abort():
    loop = Loop()
    result = loop.run(loop.master.mem_read(0x9000_0000, 2))
    assert result.termination is Termination.MASTER_ABORT and result.data == [0xFFFFFFFF] * 2


def test_reset_releases_every_line_at_once_and_ends_the_transaction():
    loop = Loop()
    request = loop.core.submit(Request(MEM_WRITE, BASE, [(0xF, 1), (0xF, 2)] * 4))
    for _ in range(4):
        loop.edge()
    assert loop.core.drive.frame_oe and not request.done
    loop.core.reset(loop.time + 10)
    drive = loop.core.drive
    assert not any(getattr(drive, f"{line}_oe") for line in ("ad", "cbe", "par", "frame", "irdy", "perr"))
    assert request.done and request.transaction.termination is Termination.RESET
    assert loop.core.quiet


def test_a_scenario_may_only_yield_host_waits():
    loop = Loop()

    def scenario():
        yield from loop.master.clocks(3)
        yield "something else"

    with pytest.raises(TypeError):
        loop.run(scenario())
    assert loop.core.edge == 3
