"""Behavioural PCI host, MyHDL front end.

The host has three layers; only this front end knows MyHDL:

1. ``HostCore`` (``sim.pci.host_core``): the clocked signal driver, plain
   Python, stepped once per rising edge.  Waits for an idle bus, drives
   FRAME#, IRDY#, C/BE#, AD and PAR phase by phase, counts DEVSEL# up to
   clock 5 (master abort after that), honours TRDY# and STOP# (retry,
   disconnect with or without data, target abort), checks the parity of
   read data and drives PERR# as a master does when its Parity Error
   Response is on.  One bus transaction per request.
2. and 3. ``PciMaster`` (``sim.pci.master``): transactions and enumeration,
   generators that yield only the core's wait objects.

Here: ``PciHost`` (a ``PciMaster`` with a ``PciAgent`` of MyHDL Signals),
the ``pci_host`` block that steps the core on the bench clock, and
``run_scenario``, the trampoline that lets a MyHDL process ``yield from``
the host's transactions next to its own MyHDL waits.

Configuration addresses are Type 0 with IDSEL of device ``d`` on AD[16+d]
(wire the target's IDSEL with ``PciSegment(idsel={name: 16 + d})``).
"""
from myhdl import Signal, block, instance, now

from sim.pci.bus import PciAgent
from sim.pci.host_core import CLOCK, MASTER_ABORT_EDGE, TARGET_TIMEOUT_EDGES, HostCore, scenario_steps  # noqa: F401
from sim.pci.host_types import (CONFIG_READ, CONFIG_WRITE, DUAL_ADDRESS, INTERRUPT_ACK, IO_READ, IO_WRITE,  # noqa: F401
                                MEM_READ, MEM_READ_LINE, MEM_READ_MULTIPLE, MEM_WRITE, MEM_WRITE_INVALIDATE,
                                MEMORY_READS, MEMORY_WRITES, SPECIAL_CYCLE, BusTransaction, Clocks, HostError, Request,
                                Termination)
from sim.pci.master import (COMMAND_INTERRUPT_DISABLE, COMMAND_IO, COMMAND_MEMORY,  # noqa: F401
                            COMMAND_PARITY_RESPONSE, COMMAND_SERR_ENABLE, PciDevice, PciMaster, Result, byte_enables,
                            config_address, io_address_bits, random_waits)


class PciHost(PciMaster):
    """A PCI master on a ``PciAgent`` (``agent``); instantiate
    ``pci_host(clock, reset, host)`` in the bench and run the transaction
    generators from a process through ``run_scenario`` (``PciBench`` does).
    Options as ``PciMaster``."""

    def __init__(self, clock, **options):
        super().__init__(**options)
        self.clock = clock
        self.agent = PciAgent()
        self.completion = Signal(bool(0))  # toggles whenever a request is done

    @property
    def queue(self):
        return self.core.queue


def run_scenario(host, scenario):
    """Run the generator ``scenario`` inside a MyHDL process (``yield from
    run_scenario(host, scenario)``): the host core's wait objects become
    MyHDL waits on ``host``'s clock, anything else is yielded as it is."""
    steps = scenario_steps(scenario, other=_as_it_is)
    while True:
        try:
            item = next(steps)
        except StopIteration as stop:
            return stop.value
        if isinstance(item, Request):
            yield host.completion
        else:
            yield host.clock.posedge if item is CLOCK else item


def _as_it_is(item):
    yield item


@block
def pci_host(clock, reset, host):
    """The host's signal driver: steps ``host.core`` at every rising edge.

    clock: PCI clock; reset: RST# (active low ResetSignal) or None;
    host: a ``PciHost``.  Everything is released as soon as RST# falls and
    while it is low; a transaction it cuts short ends with ``RESET``.

        clock  _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        FRAME# ~~~\\_____/~~~~~~~~~~~~~
        AD     ---<ADR><D0 ><D1>-------   (write, no wait states)
        IRDY#  ~~~~~~~\\_________/~~~~~~
    """
    core, agent = host.core, host.agent
    drive = core.drive
    ports = [(getattr(agent, f"{line}_out"), getattr(agent, f"{line}_oe"), f"{line}_out", f"{line}_oe")
             for line in ("ad", "cbe", "par", "frame", "irdy", "perr")]
    ad, par, frame, irdy = agent.ad_in, agent.par_in, agent.frame_in, agent.irdy_in
    trdy, devsel, stop = agent.trdy_in, agent.devsel_in, agent.stop_in

    def apply():
        for out, enable, out_name, enable_name in ports:
            out.next = getattr(drive, out_name)
            enable.next = getattr(drive, enable_name)

    @instance
    def driver():
        core.reset(now())
        apply()
        completed = core.completed
        while True:
            if reset is None:
                yield clock.posedge
            else:
                yield clock.posedge, reset.negedge
            if reset is not None and reset.val == reset.active:
                core.reset(now())
            else:
                core.step(now(), int(ad.val), int(par.val), int(frame.val), int(irdy.val),
                          int(trdy.val), int(devsel.val), int(stop.val))
            apply()
            if core.completed != completed:
                completed = core.completed
                host.completion.next = not host.completion

    return driver
