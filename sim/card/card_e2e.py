"""End-to-end card bench on three back ends: the behavioural PCI host drives the
whole card with the protocol monitor watching every clock.

Back ends (``kind``):

* ``"myhdl"``: ``rtl/card.py`` (split PCI ports) in MyHDL's simulator;
* ``"icarus"``: the generated top level with its PCI pads (``top.v``, iCE40
  ``SB_IO`` cells from yosys's cell model) in Icarus, through
  ``sim/card/top_harness.py``; ``gen/top.v`` (``$DDA_CARD_GEN/top.v`` if set) for
  the default FIFO, a fresh conversion otherwise;
* ``"verilator"``: the generated ``card`` (``gen/card.v``, a fresh
  conversion for another FIFO depth) compiled by Verilator, on the host
  engine and the protocol checker with no simulator in Python
  (``sim/backends/verilator/pci_bus.py``); waits run in compiled code.

A scenario is written once for all three: a generator ``scenario(bench,
target, out)`` that calls the host's transactions and the helpers below;
``wait(bench, target, ...)`` is the one way to let clocks pass (a number of
clocks, INTA#, STEP rises), the same clock for clock on every back end.  The
STEP/DIR pins land in ``target.log`` (a ``PinLog``) with their clock numbers
(rising edges since the start).
"""
import functools

from myhdl import always, block

from models import registers as regmap
from models.commands import command_words
from models.parameters import AXES, CLOCK_HZ, ENCODERS, PARAMETERS, Build
from rtl.card import card, card_ports
from rtl.convert import GEN_DIR, convert_unit
from rtl.interfaces import MotorPins
from sim.backends.conversions import converted
from sim.backends.verilator.verilated_card import ArrayPinLog, CardWait, VerilatedCard, card_waiter
from sim.backends.verilator.model import Stop
from sim.backends.verilator.pci_bus import VerilatorBench
from sim.backends.waves import Waveform, trace_stem
from sim.card.card_bench import PinLog, pin_capture, write_motion_view
from sim.card.sim_machine import machine_process
from sim.card.top_harness import TopHarness, convert_top, generated_top, top_on_bus
from sim.pci.bench import TARGET_DEVICE, WAVE_GROUPS, PciBench

KINDS = ("myhdl", "icarus", "verilator")
DEVICE = 0
SMALL_FIFO = 16
DEFAULT_FIFO = PARAMETERS["fifo_depth"].default
INTA_LIMIT = 200000
# the card's BARs by role: the registers (I/O), the FIFO window, the registers again in memory space
BAR_ROLES = {"io": 0, "mem": 1, "alias": 2}


def card_verilog(fifo_depth, clock_hz=CLOCK_HZ.default, axes=AXES.default, encoders=ENCODERS.default):
    """``card.v`` for ``fifo_depth``, ``clock_hz`` (what CLOCK_HZ reports),
    ``axes`` and ``encoders``: ``gen/card.v`` for the defaults, else a conversion kept in
    ``build/conv`` (``sim/backends/conversions.py``)."""
    if (fifo_depth == DEFAULT_FIFO and clock_hz == CLOCK_HZ.default and axes == AXES.default
            and encoders == ENCODERS.default):
        return GEN_DIR / "card.v"
    params = {"fifo_depth": fifo_depth, "clock_hz": clock_hz}
    if axes != AXES.default:
        params["axes"] = AXES.check(axes)
    if encoders != ENCODERS.default:
        params["encoders"] = ENCODERS.check(encoders)
    return converted("card", repr(params), functools.partial(convert_unit, "card", params))


def card_bars(device):
    """{role: BAR as enumerated} of the card (``BAR_ROLES``); ``device`` a ``PciDevice``."""
    return {role: device.bar(index) for role, index in BAR_ROLES.items()}


class CardUnderTest:
    """The card under test, with what the scenario needs to see: ``log`` (its
    pins), ``wait`` (the bench's ``CardWait``), ``samples`` (MyHDL and
    Icarus: the bus of every clock, values and drivers), ``io`` / ``mem`` /
    ``alias`` (BAR0..2 bases, set once enumerated), ``axes`` (the build's), ``pins``
    (the motor pins, MyHDL and Icarus).  Called
    with a ``PciBench``, it is that bench's target (MyHDL, Icarus)."""

    def __init__(self, kind, fifo_depth, machine=None, axes=AXES.default, encoders=ENCODERS.default,
                 pin_driver=None):
        if kind not in KINDS:
            raise ValueError(f"unknown card kind {kind!r}: use one of {', '.join(KINDS)}")
        if kind == "icarus" and (encoders or pin_driver is not None):
            raise ValueError("the Icarus card bench runs the top without encoders only")
        self.kind, self.fifo_depth, self.axes = kind, fifo_depth, AXES.check(axes)
        # MyHDL: a card with encoders, and (block, *args): block(clock, reset, pins, *args) drives their pins
        self.encoders, self.pin_driver = ENCODERS.check(encoders), pin_driver
        self.machine = machine   # a SimMachine on the input pins (MyHDL, Icarus; Verilator: in the harness)
        self.encoder_changes = []   # its motors' encoder word: (clock, word) of each change (MyHDL)
        self.log = ArrayPinLog() if kind == "verilator" else PinLog()
        self.wait = CardWait(signal=kind != "verilator")
        self.samples = []
        self.io = self.mem = self.alias = None
        self.pins = None   # the MotorPins (MyHDL, Icarus), once the bench is built

    def __call__(self, bench):
        idsel_bit = 16 + TARGET_DEVICE
        if self.kind == "icarus":
            if (self.fifo_depth, self.axes) == (DEFAULT_FIFO, AXES.default):
                top = generated_top()
            else:
                params = {"fifo_depth": self.fifo_depth, **({"axes": self.axes} if self.axes != AXES.default else {})}
                top = convert_top(**params)
            harness = TopHarness(top, idsel_bit=idsel_bit)
            agent, motor = harness.card, MotorPins(self.axes)
            def core(b):  # the X/Z report needs the bus model, which exists only later
                return top_on_bus, (b.clock, b.reset, b.host.agent, harness, motor), {"segment": b.segment}
        else:
            ports = card_ports(self.axes, self.encoders)
            ports["clock"], ports["reset"] = bench.clock, bench.reset
            agent, motor = ports["pci"], ports["pins"]

            def core(_):
                return card, (), dict(ports, build=Build(fifo_depth=self.fifo_depth, axes=self.axes,
                                                         encoders=self.encoders))
        self.pins = motor
        capture = (pin_capture, (bench.clock, motor, self.log))
        waiter = (card_waiter, (bench.clock, self.wait, bench, self.log))
        extra = ([(machine_process, (bench.clock, motor, self.machine, self.encoder_changes))]
                 if self.machine is not None else [])
        if self.pin_driver is not None:
            driver, *more = self.pin_driver
            extra.append((driver, (bench.clock, bench.reset, motor, *more)))
        return agent, lambda b: [core(b), capture, (bus_record, (b, self.samples)), waiter, *extra]


@block
def bus_record(bench, samples):
    """Append the segment's sample (values and drivers) at every rising edge."""

    @always(bench.clock.posedge)
    def record():
        samples.append(bench.segment.sample())

    return record


def run_card(kind, scenario, name, fifo_depth=SMALL_FIFO, trace=None, card_trace=None, card_trace_window=None,
             monitor=True, axes=AXES.default):
    """Enumerate the card, run ``scenario(bench, target, out)``; (out, pin log,
    waveform or None, bench).  ``trace``: the bench's VCD (MyHDL, Icarus), as
    ``sim.backends.waves.run_traced`` takes it;
    ``card_trace`` ("vcd" or "fst", Verilator only): the card's own waves of
    the clocks ``card_trace_window`` (first, last), named as the other back
    ends name their bench's (``sim.backends.waves.trace_stem``; the path is
    ``bench.trace_path``, the VCD comes back as the waveform); ``monitor`` (Verilator only; the MyHDL benches always
    check): the protocol checker on every bus clock; ``axes``: the card's build."""
    target = CardUnderTest(kind, fifo_depth, axes=axes)
    host_options = dict(max_retries=1 << 20)
    verilated = None
    if kind == "verilator":
        verilated = VerilatedCard(card_verilog(fifo_depth, axes=axes), trace=card_trace, idsel_bit=16 + TARGET_DEVICE)
        bench = VerilatorBench(verilated, target, host_options=host_options, monitor=monitor)
        if card_trace:
            first, last = card_trace_window or (0, 1 << 62)
            folder, stem = trace_stem(f"{name}_{kind}")
            bench.trace_path = folder / f"{stem}.{card_trace}"
            verilated.model.trace(bench.trace_path, first, last)
    elif card_trace or not monitor:
        raise ValueError("card_trace and monitor=False are for the Verilator card")
    else:
        bench = PciBench(target=target, host_options=host_options)
    out = {}

    def wrapped(b):
        devices = yield from b.host.enumerate_bus(devices=[DEVICE])
        out["device"] = devices[0]
        bars = card_bars(devices[0])
        target.io, target.mem, target.alias = (bars[role]["base"] for role in ("io", "mem", "alias"))
        out["bars"] = bars
        yield from scenario(b, target, out)

    try:
        vcd = bench.run(wrapped, f"{name}_{kind}", trace=trace)
    finally:
        if verilated is not None:
            verilated.model.close()
    if vcd is None:
        traced = getattr(bench, "trace_path", None)
        return out, target.log, Waveform(traced) if card_trace == "vcd" else None, bench
    wave = Waveform(vcd)
    write_motion_view(vcd, WAVE_GROUPS, wave)
    return out, target.log, wave, bench


def wait(bench, target, clocks=INTA_LIMIT, inta=False, steps=0):
    """Let up to ``clocks`` clocks pass, fewer if INTA# is sampled low
    (``inta``) or ``steps`` more STEP rises are recorded; (clocks, ``Stop``)."""
    target.wait.ask(clocks, inta, steps)
    yield target.wait.event
    return target.wait.waited, target.wait.reason


def clocks(bench, target, count):
    """Exactly ``count`` clocks."""
    yield from wait(bench, target, count)


def wait_inta(bench, target, limit=INTA_LIMIT):
    """Clocks until INTA# is sampled low."""
    waited, reason = yield from wait(bench, target, limit, inta=True)
    if reason is not Stop.INTERRUPT:
        raise AssertionError(f"INTA# never asserted in {waited} clocks")
    return waited


def io_write(bench, target, name, value):
    result = yield from bench.host.io_write(target.io + regmap.offset(name), value & 0xFFFFFFFF)
    assert result.complete, f"I/O write of {name} ended {result.termination}"


def io_read(bench, target, name):
    result = yield from bench.host.io_read(target.io + regmap.offset(name))
    assert result.complete, f"I/O read of {name} ended {result.termination}"
    return result.value


def program(bench, target, feed=regmap.RATE_MAX, control=1, interrupts=("DONE",), ramp_start=None,
            ramp_step=None):
    """FEED_RATE (and the ramp, if given), INT_ENABLE, CONTROL."""
    yield from io_write(bench, target, "FEED_RATE", feed)
    for name, value in (("RAMP_START", ramp_start), ("RAMP_STEP", ramp_step)):
        if value is not None:
            yield from io_write(bench, target, name, value)
    yield from io_write(bench, target, "INT_ENABLE", regmap.field_of("INT_ENABLE", **{n: 1 for n in interrupts}))
    yield from io_write(bench, target, "CONTROL", control)


def read_position(bench, target):
    x = yield from io_read(bench, target, "POS_X")
    y = yield from io_read(bench, target, "POS_Y")
    return regmap.field_value("POS_X", "STEPS", x), regmap.field_value("POS_Y", "STEPS", y)


def finish(bench, target, out, limit=INTA_LIMIT):
    """Wait for INTA#, then read status and position; acknowledge."""
    out["inta_clocks"] = yield from wait_inta(bench, target, limit)
    out["status"] = yield from io_read(bench, target, "STATUS")
    out["int_status"] = yield from io_read(bench, target, "INT_STATUS")
    out["position"] = yield from read_position(bench, target)
    yield from io_write(bench, target, "INT_STATUS", out["int_status"])


def motion_scenario(commands, feed=regmap.RATE_MAX, **ramp):
    """Program, burst ``commands`` (model commands or word lists) into the FIFO, finish."""
    words = [w for c in commands for w in (c if isinstance(c, list) else command_words(c))]

    def scenario(bench, target, out):
        yield from program(bench, target, feed, **ramp)
        out["burst"] = yield from bench.host.mem_write(target.mem, words)
        yield from finish(bench, target, out)

    return scenario
