"""The whole card on one back end, driven by plain calls: "do this access now".

The end-to-end benches (``sim/card/card_e2e.py``) hand the simulator one scenario
and let it run to the end.  Host software works the other way round: it
calls, one access at a time, and decides what to do next from the answer.
``CardSession`` gives it that shape on every back end, with the same host
engine, the same protocol checker on every bus clock and the same pin log:

    session = CardSession("verilator")            # reset, enumeration
    status = session.call(session.host.io_read(session.io + 0x0C)).value
    waited, reason = session.wait(100_000, inta=True)
    session.close()

``call(scenario)`` runs a generator of the host's wait objects (any
``PciMaster`` transaction, ``card_e2e``'s ``wait``) to its end and returns
its value; simulated time moves only inside calls.  ``read``, ``write``,
``fifo_write``, ``mem_read`` and ``config_read`` are the register-level
accesses host software makes (the host's simulated transport and the card
server are built on them): each runs one access to its end, refuses one the
bus cannot carry (ValueError, ``models.pci.check_access``) and raises
``AccessError`` when the card does not complete it.

* ``verilator``: ``VerilatorBench`` is stepped from Python anyway; a call is
  its trampoline (``VerilatorBench.call``), waits run in compiled code.
* ``myhdl`` and ``icarus``: the ``PciBench`` runs a server scenario that
  waits one clock at a time for work; a call hands it the generator and
  resumes the simulation (``run_sim`` for one clock at a time) until the
  server has finished it.  MyHDL allows one simulation at a time, so one
  such session at a time.
"""
from myhdl import now

from models.parameters import AXES, CLOCK_HZ, ENCODERS
from models.pci import CONFIG_BYTES, check_access, check_value
from sim.backends.verilator.verilated_card import VerilatedCard
from sim.backends.verilator.pci_bus import VerilatorBench
from sim.backends.waves import trace_stem
from models.sim_machine import SimMachine
from sim.card.card_e2e import DEFAULT_FIFO, DEVICE, CardUnderTest, card_bars, card_verilog, wait
from sim.card.sim_machine import MachineHandle
from sim.pci.bench import CLOCK_PERIOD, TARGET_DEVICE, PciBench, pci_testbench
from sim.pci.host_types import Clocks, HostError

RETRIES = 4096  # retries in a row before an access gives up (a FIFO that stays full)
REGISTER_BARS = (0, 2)   # the function registers: BAR0 (I/O) or its alias BAR2 (memory)


class AccessError(RuntimeError):
    """An access the card did not complete: what it was and how it ended."""


class CardSession:
    """The card of ``kind`` (``sim.card.card_e2e.KINDS``) with ``fifo_depth`` words of
    FIFO, reset and enumerated.  ``host_options``: ``PciMaster`` keyword
    arguments (default: ``max_retries`` = ``RETRIES``); ``trace``: the bench's
    VCD (MyHDL, Icarus; ``name`` names it); ``monitor``: the protocol checker
    on Verilator (always on for the others); ``clock_hz``: what the card's
    CLOCK_HZ reports (Verilator; the others build the default); ``machine``: a
    ``models.sim_machine.MachineConfig``, the simulated machine on the card's
    input pins (``self.machine``, a ``sim.card.sim_machine.MachineHandle``;
    None without one: the inputs stay low); ``register_bar``: the BAR
    ``read`` and ``write`` use, 0 (I/O) or 2 (the same registers at the same
    offsets in memory space, as a host maps them where it has no port I/O);
    offsets beyond BAR0 (the per-axis register blocks) go through BAR2
    either way; ``axes``: the card's build (``--axes N``; the others of
    ``Build`` as by default); ``encoders``: a build with encoders (Verilator,
    MyHDL; the machine's motors drive their inputs); ``card_options``: more
    of ``CardUnderTest``'s keywords (MyHDL: ``pin_driver``).

    ``host`` (a ``PciMaster``), ``target`` (a ``CardUnderTest``: ``log``,
    ``io``, ``mem``, ``alias``), ``device`` (``PciDevice``), ``bars`` (by
    role: ``io``, ``mem``, ``alias``), ``io`` / ``mem`` / ``alias`` (BAR0..2
    bases), ``clocks`` (card clocks so far).
    """

    def __init__(self, kind, fifo_depth=DEFAULT_FIFO, host_options=None, trace=False, name="card_session",
                 monitor=True, clock_hz=CLOCK_HZ.default, machine=None, register_bar=0, axes=AXES.default,
                 encoders=ENCODERS.default, card_options=None):
        if register_bar not in REGISTER_BARS:
            raise ValueError(f"register_bar must be 0 (I/O) or 2 (memory), not {register_bar!r}")
        self.kind = kind
        self.register_bar = register_bar
        if machine is not None:
            machine.check_axes(axes)   # before anything is built
        simulated = SimMachine(machine, axes) if machine is not None and kind != "verilator" else None
        card_options = dict(card_options or {})
        if kind != "verilator":
            card_options["encoders"] = card_options.get("encoders", encoders)
        self.target = CardUnderTest(kind, fifo_depth, machine=simulated, axes=axes, **card_options)
        options = dict(max_retries=RETRIES)
        options.update(host_options or {})
        if kind == "verilator":
            self._runner = _VerilatorRunner(self.target, fifo_depth, options, monitor, clock_hz, axes, encoders)
            if machine is not None:
                self._runner.card.start_machine(machine)
        else:
            self._runner = _MyhdlRunner(self.target, options, trace, f"{name}_{kind}")
        self.machine = None if machine is None else MachineHandle(
            machine, model=self._runner.card.model if kind == "verilator" else None, machine=simulated,
            encoder_changes=self.target.encoder_changes)
        self.host = self._runner.bench.host
        self.bench = self._runner.bench
        self.closed = False
        try:
            (self.device,) = self.call(self.host.enumerate_bus(devices=[DEVICE]))
        except BaseException:
            self.close()
            raise
        self.bars = card_bars(self.device)
        self.io = self.target.io = self.bars["io"]["base"]
        self.mem = self.target.mem = self.bars["mem"]["base"]
        self.alias = self.target.alias = self.bars["alias"]["base"]

    @property
    def log(self):
        """The STEP/DIR pins so far (a ``PinLog``)."""
        return self.target.log

    @property
    def clocks(self):
        """Rising edges of the card clock so far."""
        return self._runner.clocks()

    def call(self, scenario):
        """Run ``scenario`` (a generator of the host's wait objects) to its end now."""
        if self.closed:
            raise RuntimeError("the session is closed")
        return self._runner.call(scenario)

    def _complete(self, access, what):
        """Run ``access`` (a ``PciMaster`` generator) now; its complete ``Result``."""
        try:
            result = self.call(access)
        except HostError as error:
            raise AccessError(f"{what}: {error}") from None
        if not result.complete:
            raise AccessError(f"{what} ended with {result.termination.value} "
                              f"({len(result.data)} of {result.requested} data phases)")
        return result

    def _through_bar2(self, offset):
        """True when an access at ``offset`` goes through BAR2: ``register_bar``
        says so, or BAR0 ends before ``offset`` (BAR2's per-axis blocks)."""
        return self.register_bar == 2 or offset >= self.bars["io"]["size"]

    def read(self, offset, size=4):
        """``size`` bytes of the function registers at ``offset`` (through
        ``register_bar``; beyond BAR0, through BAR2)."""
        bar2 = self._through_bar2(offset)
        check_access(offset, size, self.bars["alias" if bar2 else "io"]["size"], "BAR2" if bar2 else "BAR0")
        if bar2:
            return self._complete(self.host.mem_read(self.alias + offset, size=size),
                                  f"BAR2 read at {offset:#x}").value
        return self._complete(self.host.io_read(self.io + offset, size), f"I/O read at {offset:#x}").value

    def write(self, offset, value, size=4):
        """Write ``size`` bytes of the function registers at ``offset`` (through
        ``register_bar``; beyond BAR0, through BAR2)."""
        bar2 = self._through_bar2(offset)
        check_access(offset, size, self.bars["alias" if bar2 else "io"]["size"], "BAR2" if bar2 else "BAR0")
        check_value(value, size)
        if bar2:
            self._complete(self.host.mem_write(self.alias + offset, value, size), f"BAR2 write at {offset:#x}")
        else:
            self._complete(self.host.io_write(self.io + offset, value, size), f"I/O write at {offset:#x}")

    def fifo_write(self, words):
        """All of ``words`` as one burst into the memory BAR (resumed after a
        disconnect); a FIFO that stays full past the host's retry budget is an
        ``AccessError`` saying how many words were taken."""
        words = list(words)
        if not words:
            return
        for word in words:
            check_value(word, 4)
        try:
            result = self.call(self.host.mem_write(self.mem, words))
        except HostError as error:
            taken = sum(len(t.data) for t in error.transactions)
            raise AccessError(f"the FIFO stayed full: {taken} of {len(words)} words taken ({error})") from None
        if not result.complete:
            raise AccessError(f"FIFO write ended with {result.termination.value} "
                              f"({len(result.data)} of {result.requested} data phases)")

    def mem_read(self, offset, count=1):
        """``count`` dwords of the memory BAR from ``offset``."""
        check_access(offset, 4, self.bars["mem"]["size"], "BAR1")
        return self._complete(self.host.mem_read(self.mem + offset, count),
                              f"memory read at {offset:#x}").data[:count]

    def config_read(self, register, size=4):
        """``size`` bytes of the card's configuration space at ``register``."""
        check_access(register, size, CONFIG_BYTES, "configuration space")
        result = self._complete(self.host.config_read(self.device.device, register & ~3),
                                f"configuration read at {register:#x}")
        return (result.value >> (8 * (register & 3))) & ((1 << (8 * size)) - 1)

    def pin(self, name):
        """The level of the motor pin ``name`` (``step_z``, ``dir_a``, ...:
        ``MotorPins``) after the last clock."""
        if self.kind == "verilator":
            return bool(self._runner.card.model[f"pins_{name}"])
        return bool(getattr(self.target.pins, name))

    def set_input(self, name, level):
        """Set the machine input pin ``name`` (``estop``, ``limit_pos_z``, ``enc_a_x``, ...: ``MotorPins``)
        to ``level``, taken by the next rising edge; a session with a simulated machine drives its
        switches and E-stop itself (and the encoder pins of its motors)."""
        if self.machine is not None and not name.startswith(("enc_", "probe")):
            raise RuntimeError("the simulated machine drives the input pins")
        if self.kind == "verilator":
            self._runner.card.model[f"pins_{name}"] = int(bool(level))
        else:
            self.call(_drive_pin(getattr(self.target.pins, name), level))

    def wait(self, clocks, inta=False, steps=0):
        """Up to ``clocks`` clocks, fewer when INTA# is sampled low (``inta``)
        or ``steps`` more STEP rises came; (clocks waited, ``Stop``)."""
        return self.call(wait(self.bench, self.target, clocks, inta, steps))

    def close(self):
        """End the simulation (and its trace); the session is unusable afterwards."""
        if not self.closed:
            self.closed = True
            self._runner.close()


def _drive_pin(pin, level):
    """A scenario that sets ``pin`` at once (no clock passes)."""
    pin.next = bool(level)
    yield from ()


class _VerilatorRunner:
    def __init__(self, target, fifo_depth, host_options, monitor, clock_hz, axes, encoders):
        self.card = VerilatedCard(card_verilog(fifo_depth, clock_hz, axes, encoders), idsel_bit=16 + TARGET_DEVICE)
        self.bench = VerilatorBench(self.card, target, host_options=host_options, monitor=monitor)
        self.bench.start()

    def clocks(self):
        return self.card.model.clocks

    def call(self, scenario):
        return self.bench.call(scenario)

    def close(self):
        try:
            self.bench.finish()
        finally:
            self.card.model.close()


class _MyhdlRunner:
    """A ``PciBench`` whose scenario serves calls: it waits a clock at a time
    until ``call`` leaves it a generator, runs it, and keeps the outcome."""

    def __init__(self, target, host_options, trace, name):
        self.bench = PciBench(target=target, host_options=host_options)
        self._job = self._outcome = None
        self.top = pci_testbench(self.bench, self._serve)
        if trace:
            folder, stem = trace_stem(name)
            self.top.config_sim(trace=True, directory=str(folder), name=name, filename=stem, tracebackup=False)

    def _serve(self, bench):
        while True:
            job = self._job
            if job is None:
                yield Clocks(1)
                continue
            try:
                value = yield from job
            except Exception as error:  # handed back to the caller, the simulation goes on
                self._outcome = (False, error)
            else:
                self._outcome = (True, value)
            self._job = None

    def clocks(self):
        return now() // CLOCK_PERIOD

    def call(self, scenario):
        self._job, self._outcome = scenario, None
        while self._outcome is None:
            self.top.run_sim(CLOCK_PERIOD, quiet=1)
        ok, value = self._outcome
        if not ok:
            raise value
        return value

    def close(self):
        if self.top.sim is not None and not self.top.sim._finished:
            self.top.quit_sim()
