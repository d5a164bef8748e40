"""The PCI host's clocked engine: plain Python, driven by any simulator.

``HostCore`` is a 32-bit PCI master's signal driver (layer 1 of the host).
It knows nothing of MyHDL, cocotb or Verilator: a front end calls it once
per rising edge of the PCI clock with the lines as sampled at that edge, and
copies its drive (``core.drive``) onto the bus for the clock that follows.
The transactions (layer 2, ``sim.pci.master``) queue ``Request`` objects on
it and yield them to wait; a small trampoline in each front end runs them.

Per-edge call (cheap: no allocation while a transaction runs)::

    core.step(time, ad, par, frame, irdy, trdy, devsel, stop)

``time``: the simulator's time of the edge (recorded in the transaction log).
The lines are ints, electrical levels as sampled: AD 32 bits, PAR 0/1, the
active-low FRAME#, IRDY#, TRDY#, DEVSEL#, STOP# 0 = asserted, 1 = idle (a
line nobody drives reads its pull-up, 1; a floating AD or PAR reads as
whatever the simulator gives, 0 in two-state ones).

Drive, read after each ``step`` (and after ``reset``) and applied until the
next edge: ``core.drive.<line>_out`` (value) and ``core.drive.<line>_oe``
(output enable; False: the host leaves the line floating) for ``ad``,
``cbe``, ``par``, ``frame``, ``irdy`` and ``perr``, same polarities.

RST#: call ``core.reset(time)`` when RST# is asserted (it releases every
line at once, as PCI wants, and cuts a running transaction short with
``Termination.RESET``) and do not call ``step`` while RST# stays asserted.

Request done: ``request.done`` turns True inside the ``step`` that ends the
request's bus transaction; ``core.completed`` counts finished requests, so a
front end that wakes waiting scenarios on an event can compare it after
each step.  ``core.quiet``: nothing queued, no transaction running and every
line released; while it holds, a front end may run clocks without calling
``step`` (the bus is then sampled afresh at the next call).

Scenarios yield two kinds of wait objects (``sim.pci.host_types``): a ``Request``
("resume when ``request.done``") and ``Clocks(n)`` ("resume after n rising
edges").  Everything else a scenario yields belongs to its front end (a MyHDL
edge, a cocotb trigger) and is passed through unchanged.
"""
from collections import deque

from sim.pci.host_types import BusTransaction, Clocks, HostError, Request, Termination
from sim.pci.lines import even_parity

MASTER_ABORT_EDGE = 4       # DEVSEL# not sampled by the 4th edge after the address: abort
TARGET_TIMEOUT_EDGES = 256  # a target that never ends a data phase stops the bench

DRIVEN_LINES = ("ad", "cbe", "par", "frame", "irdy", "perr")


class HostDrive:
    """What the host puts on the bus: ``<line>_out`` and ``<line>_oe`` for
    AD, C/BE#, PAR, FRAME#, IRDY# and PERR#."""

    __slots__ = tuple(f"{line}_{part}" for line in DRIVEN_LINES for part in ("out", "oe"))

    def __init__(self):
        self.release()

    def release(self):
        self.ad_out, self.cbe_out, self.par_out = 0, 0, 0
        self.frame_out, self.irdy_out, self.perr_out = 1, 1, 1
        self.ad_oe = self.cbe_oe = self.par_oe = self.frame_oe = self.irdy_oe = self.perr_oe = False


class _Run:
    """Progress of one bus transaction."""

    __slots__ = ("request", "transaction", "write", "index", "edges", "phase_edge", "waiting",
                 "stop_seen", "final")

    def __init__(self, request, transaction):
        self.request = request
        self.transaction = transaction
        self.write = bool(request.command & 1)
        self.index = 0          # data phase on the bus
        self.edges = 0          # rising edges since the address edge
        self.phase_edge = 0     # the edge at which the current data phase began
        self.waiting = 0        # IRDY# wait states left
        self.stop_seen = False
        self.final = False      # FRAME# is deasserted: this is the last phase


class HostCore:
    """The per-edge engine (see the module docstring).

    ``parity_response``: the master's Parity Error Response (PERR# two
    clocks after read data with bad parity).  ``queue``: requests not yet
    started; ``transaction``: the ``BusTransaction`` running or last run;
    ``parity_errors_seen``: (time, address, phase index) of bad read parity.
    """

    def __init__(self, parity_response=True):
        self.parity_response = parity_response
        self.drive = HostDrive()
        self.queue = deque()
        self.transaction = None
        self.parity_errors_seen = []
        self.edge = 0
        self.time = 0
        self.completed = 0
        self.ad = self.par = 0
        self.frame = self.irdy = self.trdy = self.devsel = self.stop = 1
        self._request = None
        self._bad_par = False
        self._par_check = None
        self._perr_phase = 0
        self._idle = False
        self._process = self._main()
        next(self._process)

    # ----- the front end's calls ----------------------------------------------------
    def submit(self, request):
        """Queue ``request``; a scenario then yields it to wait for it."""
        self.queue.append(request)
        return request

    @property
    def quiet(self):
        drive = self.drive
        return not (self.queue or self._request or self._perr_phase or drive.ad_oe or drive.cbe_oe
                    or drive.par_oe or drive.frame_oe or drive.irdy_oe or drive.perr_oe)

    def step(self, time, ad, par, frame, irdy, trdy, devsel, stop):
        """One rising edge: the lines as sampled there; updates ``drive``."""
        self.time = time
        self.edge += 1
        self.ad, self.par, self.frame, self.irdy = ad, par, frame, irdy
        self.trdy, self.devsel, self.stop = trdy, devsel, stop
        drive = self.drive
        # PAR for the AD driven in the clock that ended, one clock later
        if drive.ad_oe:
            drive.par_out = even_parity(drive.ad_out, drive.cbe_out) ^ self._bad_par
            drive.par_oe = True
        elif drive.par_oe:
            drive.par_oe = False
        if self._par_check is not None and self._read_parity_wrong() and self.parity_response:
            drive.perr_out, drive.perr_oe = 0, True
            self._perr_phase = 1
        elif self._perr_phase == 1:
            drive.perr_out = 1
            self._perr_phase = 2
        elif self._perr_phase == 2:
            drive.perr_oe = False
            self._perr_phase = 0
        self._idle = frame == 1 and irdy == 1
        self._process.send(None)

    def reset(self, time=None):
        """RST# asserted: release every line now, end a running transaction
        with ``Termination.RESET``; queued requests wait for the end of reset."""
        if time is not None:
            self.time = time
        self.drive.release()
        self._bad_par = False
        self._par_check = None
        self._perr_phase = 0
        request = self._request
        if request is not None:
            self.transaction.termination = Termination.RESET
            self.transaction.end = self.time
            self._complete(request)
        self._process.close()
        self._process = self._main()
        next(self._process)

    # ----- the driver ---------------------------------------------------------------
    def _main(self):
        while True:
            yield
            if self.queue and self._idle:
                request = self._request = self.queue.popleft()
                self.transaction = BusTransaction(request.command, request.address, len(request.phases))
                yield from self._run(request)
                self._complete(request)

    def _complete(self, request):
        request.transaction = self.transaction
        request.done = True
        self._request = None
        self.completed += 1

    def _read_parity_wrong(self):
        ad, cbe, transaction, index = self._par_check
        self._par_check = None
        if even_parity(ad, cbe) == self.par:
            return False
        transaction.parity_errors.append(index)
        self.parity_errors_seen.append((self.time, transaction.address, index))
        return True

    def _start_phase(self, run):
        """Put data phase ``run.index`` on the bus; return its IRDY# wait states."""
        drive = self.drive
        be, data = run.request.phases[run.index]
        drive.cbe_out, drive.cbe_oe = ~be & 0xF, True
        if run.write:
            drive.ad_out, drive.ad_oe = data, True
            self._bad_par = run.index in run.request.bad_data_parity
        else:
            drive.ad_oe = False
            self._bad_par = False
        waits = run.request.waits
        count = waits(run.index) if callable(waits) else waits
        if count < 0:
            raise ValueError(f"IRDY# wait states must be >= 0, not {count}")
        return count

    def _assert_irdy(self, run):
        """IRDY# now; FRAME# goes with it on the last phase or after STOP#."""
        drive = self.drive
        drive.irdy_out, drive.irdy_oe = 0, True
        if run.index == len(run.request.phases) - 1 or run.stop_seen:
            drive.frame_out, drive.frame_oe = 1, True
            run.final = True

    def _run(self, request):
        """Drive one bus transaction (the bus was sampled idle at the last edge)."""
        drive = self.drive
        run = _Run(request, self.transaction)
        drive.frame_out, drive.frame_oe = 0, True
        drive.irdy_out, drive.irdy_oe = 1, True
        drive.ad_out, drive.ad_oe = request.address, True
        drive.cbe_out, drive.cbe_oe = request.command, True
        self._bad_par = request.bad_address_parity
        yield
        run.transaction.start = self.time
        run.waiting = self._start_phase(run)
        if run.waiting == 0:
            self._assert_irdy(run)
        while True:
            yield
            abort = self._observe(run)
            if abort is not None:
                run.transaction.termination = abort
                if not (run.final and drive.irdy_oe and not drive.irdy_out):
                    drive.irdy_out, drive.irdy_oe = 0, True
                    drive.frame_out, drive.frame_oe = 1, True
                    yield
                break
            if self._advance(run):
                run.transaction.termination = self._stop_kind(run.stop_seen, run.transaction)
                break
        run.transaction.end = self.time
        drive.irdy_out = drive.frame_out = 1
        drive.irdy_oe = drive.frame_oe = True
        drive.ad_oe = drive.cbe_oe = False
        self._bad_par = False
        yield
        drive.frame_oe = drive.irdy_oe = False

    def _observe(self, run):
        """Record DEVSEL# and TRDY# of this edge; the abort it shows, if any."""
        run.edges += 1
        transaction = run.transaction
        if not self.devsel and transaction.devsel_clock is None:
            transaction.devsel_clock = run.edges
        if not self.trdy and transaction.first_trdy_clock is None:
            transaction.first_trdy_clock = run.edges
        claimed = transaction.devsel_clock is not None
        if claimed and self.devsel and not self.stop:
            return Termination.TARGET_ABORT
        if not claimed and run.edges >= MASTER_ABORT_EDGE:
            return Termination.MASTER_ABORT
        if run.edges - run.phase_edge > TARGET_TIMEOUT_EDGES:
            raise HostError(f"no end of data phase {run.index} within "
                            f"{run.edges - run.phase_edge} clocks at {self.time}", [transaction])
        return None

    def _advance(self, run):
        """Act on this edge's TRDY#/STOP#; True once the last data phase is over."""
        drive = self.drive
        trdy, stop = self.trdy, self.stop
        claimed = run.transaction.devsel_clock is not None
        if not (drive.irdy_oe and not drive.irdy_out):
            run.stop_seen = run.stop_seen or (claimed and not stop)
            run.waiting -= 1
            if run.waiting <= 0 or run.stop_seen:
                self._assert_irdy(run)
            return False
        if trdy and stop:
            return False
        if not trdy:
            self._accept(run)
            run.index += 1
            run.phase_edge = run.edges
        run.stop_seen = run.stop_seen or not stop
        if run.final:
            return True
        if run.stop_seen:
            if run.index < len(run.request.phases):
                self._start_phase(run)
            self._assert_irdy(run)
            return False
        run.waiting = self._start_phase(run)
        if run.waiting == 0:
            self._assert_irdy(run)
        else:
            drive.irdy_out, drive.irdy_oe = 1, True
        return False

    def _accept(self, run):
        """Data phase ``run.index`` moved: keep its datum, check read parity next edge."""
        transaction = run.transaction
        if run.write:
            transaction.data.append(run.request.phases[run.index][1])
        else:
            transaction.data.append(self.ad)
            self._par_check = (self.ad, self.drive.cbe_out, transaction, run.index)

    @staticmethod
    def _stop_kind(stop_seen, transaction):
        if not stop_seen:
            return Termination.NORMAL
        return Termination.DISCONNECT if transaction.data else Termination.RETRY


CLOCK = "clock"  # what ``scenario_steps`` yields for one rising edge to wait for


def scenario_steps(scenario, other=None, on_step=None):
    """The one engine that runs a scenario (a generator of the host's wait
    objects) for every front end; a generator that returns the scenario's value.

    It yields ``CLOCK`` for each rising edge a ``Clocks`` asks for and the
    ``Request`` itself for each wait until that request is done; a front end
    turns these into its simulator's waits (``run_scenario`` below, MyHDL's
    ``sim.pci.host.run_scenario``, cocotb's ``CocotbPciBus.run``, the
    Verilator bench).  Anything else the scenario yields goes to
    ``other(item)``, a generator whose waits are yielded as they are and
    whose value is sent back into the scenario; without ``other`` it is
    refused (``TypeError``).  ``on_step()``, if given, runs before each step
    of the scenario."""
    value = None
    while True:
        if on_step is not None:
            on_step()
        try:
            item = scenario.send(value)
        except StopIteration as stop:
            return stop.value
        value = None
        if isinstance(item, Request):
            while not item.done:
                yield item
        elif isinstance(item, Clocks):
            for _ in range(item.count):
                yield CLOCK
        elif other is not None:
            value = yield from other(item)
        else:
            raise TypeError(f"the scenario yielded {item!r}: only Request and Clocks are host waits")


def run_steps(steps, wait):
    """Run ``steps`` (from ``scenario_steps``) with ``wait(item)`` for each
    item it yields; its value."""
    while True:
        try:
            item = next(steps)
        except StopIteration as stop:
            return stop.value
        wait(item)


def run_scenario(scenario, clock_edge):
    """Run ``scenario`` for a front end that advances its simulator itself:
    ``clock_edge()`` runs the simulation up to and through the next rising
    edge, stepping the core there.  Returns the scenario's value; a scenario
    that yields anything but a ``Request`` or ``Clocks`` is refused
    (``TypeError``)."""
    return run_steps(scenario_steps(scenario), lambda _: clock_edge())
