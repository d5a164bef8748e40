"""A small behavioural PCI memory target, used to test the host and the
monitor independently of the RTL.

It claims memory reads and writes inside ``[base, base + size)`` with medium
DEVSEL# timing and serves them from a dict of dwords.  Each transaction can
be scripted by ``plan(transaction_number) -> TargetPlan``: TRDY# wait states
per data phase, retry, disconnect with data after N phases, target abort,
and a corrupted PAR on a chosen read data phase.
"""
from dataclasses import dataclass, field

from myhdl import block, instance

from sim.pci.bus import PciAgent, even_parity


@dataclass
class TargetPlan:
    """How the target ends one transaction (defaults: zero waits, normal)."""

    trdy_waits: list = field(default_factory=list)  # per data phase, default 0
    retry: bool = False
    disconnect_after: int = None   # STOP# with TRDY# on this data phase (0-based)
    target_abort: bool = False
    bad_par_phase: int = None       # read data phase whose PAR is inverted


class BehaviouralTarget:
    """State of the target: ``memory`` (dword address -> value),
    ``perr_reports`` (times it asserted PERR#: never, it does not check)."""

    def __init__(self, base=0x1000, size=0x1000, plan=None):
        self.agent = PciAgent()
        self.base = base
        self.size = size
        self.plan = plan or (lambda number: TargetPlan())
        self.memory = {}
        self.transactions = 0

    def hit(self, address, command):
        return command in (0x6, 0x7, 0xC, 0xE, 0xF) and self.base <= address < self.base + self.size


@block
def behavioural_target(clock, target):
    """Run ``target`` (a BehaviouralTarget) on its agent.

        clock   _/~\\_/~\\_/~\\_/~\\_/~\\_
        FRAME#  ~~\\_____/~~~~~~~~~~~
        DEVSEL# ~~~~~~~~\\_______/~~~    medium: sampled 2 edges after address
        TRDY#   ~~~~~~~~\\___/~~~~~~~
    """
    agent = target.agent

    def drive(line, value):
        getattr(agent, f"{line}_out").next = value
        getattr(agent, f"{line}_oe").next = True

    def release(*lines):
        for line in lines:
            getattr(agent, f"{line}_oe").next = False

    def sampled(line):
        return int(getattr(agent, f"{line}_in").val)

    @instance
    def run():
        previous_frame = 1
        while True:
            yield clock.posedge
            frame = sampled("frame")
            starts = previous_frame == 1 and frame == 0
            previous_frame = frame
            if not starts:
                continue
            address, command = sampled("ad"), sampled("cbe")
            if not target.hit(address, command):
                continue
            plan = target.plan(target.transactions)
            target.transactions += 1
            yield from serve(address, command, plan)
            previous_frame = sampled("frame")

    def serve(address, command, plan):
        write = bool(command & 1)
        yield clock.posedge
        drive("devsel", 0)
        drive("trdy", 1)
        drive("stop", 1)
        if not write:
            drive("ad", 0)
        phase, waits = 0, _waits(plan, 0)
        while True:
            signal_phase(plan, phase, waits, write, address)
            yield clock.posedge
            parity_duty(plan, phase, write)
            trdy, stop = agent.trdy_out.val == 0, agent.stop_out.val == 0
            if sampled("irdy") == 0 and (trdy or stop):
                if trdy and write:
                    target.memory[(address + 4 * phase) & ~3] = sampled("ad")
                if trdy:
                    phase += 1
                    waits = _waits(plan, phase)
                if sampled("frame") == 1:
                    break
                if stop:
                    drive("trdy", 1)
            elif waits > 0:
                waits -= 1
        drive("devsel", 1)
        drive("trdy", 1)
        drive("stop", 1)
        release("ad")
        yield clock.posedge
        parity_duty(plan, phase, write)
        release("devsel", "trdy", "stop")
        yield clock.posedge
        parity_duty(plan, phase, write)

    def parity_duty(plan, phase, write):
        """PAR for the AD this target drove in the clock that just ended."""
        if not agent.ad_oe.val:
            release("par")
            return
        bad = not write and plan.bad_par_phase == phase and agent.trdy_out.val == 0
        drive("par", even_parity(agent.ad_out.val, sampled("cbe")) ^ bad)

    def signal_phase(plan, phase, waits, write, address):
        if agent.stop_out.val == 0:
            return
        if plan.target_abort:
            if agent.devsel_out.val == 0:  # a target abort follows a claim
                drive("devsel", 1)
                drive("stop", 0)
            return
        if plan.retry:
            drive("stop", 0)
            return
        if waits > 0:
            drive("trdy", 1)
            return
        drive("trdy", 0)
        if plan.disconnect_after == phase:
            drive("stop", 0)
        if not write:
            drive("ad", target.memory.get((address + 4 * phase) & ~3, 0))

    return run


def _waits(plan, phase):
    return plan.trdy_waits[phase] if phase < len(plan.trdy_waits) else 0
