"""Scoreboard pieces of the card benches that overfill its FIFO (``sim/card/card_overfill.py``).

* A command stream whose execution the pins give back exactly: LINE
  commands along X with alternating sign (``x_lines``), each one run of
  STEP_X pulses between DIR_X changes (``x_runs``).
* The card as a ``PciBench`` target (``card_target``): ``rtl.card`` in
  MyHDL with its FIFO's write port recorded word for word
  (``recorded_card``), or the generated top level with its pads in Icarus
  (``gen/top.v``, or one fresh conversion per FIFO depth and process:
  ``converted_top``); its STEP/DIR pins into a ``PinLog``.
* ``run_bench``: enumerate the card, run a scenario, collect pins and the
  FIFO's record.
"""
from myhdl import always, block

from models import instructions as isa
from models.parameters import FIFO_DEPTH, Build
from rtl.card import card, card_ports
from rtl.interfaces import MotorPins
from sim.card.card_bench import PinLog, pin_capture
from sim.card.top_harness import TopHarness, convert_top, generated_top, top_on_bus
from sim.pci.bench import TARGET_DEVICE, PciBench

DEFAULT_FIFO = FIFO_DEPTH.default
LINE_WORDS = len(isa.encode("LINE", 1, 0))
_converted_tops = {}


def x_lines(rng, words, longest):
    """LINE commands along X of ``words`` words in all (rounded up), signed
    lengths 1..``longest`` alternating in sign: (lengths, words)."""
    lengths = [(1 if i % 2 == 0 else -1) * rng.randint(1, longest) for i in range(-(-words // LINE_WORDS))]
    return lengths, [w for dx in lengths for w in isa.encode("LINE", dx, 0)]


def x_runs(log):
    """Signed lengths of the runs of STEP_X rises between DIR_X changes
    (DIR_X high: positive, as ``PinLog.path``); a STEP_Y rise is an error."""
    runs = []
    direction = None
    for _, step_x, step_y, dir_x, _ in log.rises:
        if step_y:
            raise AssertionError("a STEP_Y pulse: the stream has moves along X only")
        sign = 1 if dir_x else -1
        if step_x and sign == direction:
            runs[-1] += sign
        elif step_x:
            runs.append(sign)
            direction = sign
    return runs


def converted_top(fifo_depth):
    """``top.v`` for ``fifo_depth``: ``gen/`` for the default, else one
    fresh conversion per process."""
    if fifo_depth == DEFAULT_FIFO:
        return generated_top()
    if fifo_depth not in _converted_tops:
        _converted_tops[fifo_depth] = convert_top(fifo_depth=fifo_depth)
    return _converted_tops[fifo_depth]


def _sub_block(instance, prefix):
    """The first block under ``instance`` whose name starts with ``prefix``."""
    for sub in getattr(instance, "subs", ()):
        if getattr(sub, "name", "").startswith(prefix):
            return sub
        found = _sub_block(sub, prefix)
        if found is not None:
            return found
    return None


@block
def recorded_card(clock, reset, pci, pins, taken, fifo_depth):
    """``rtl.card`` with its FIFO's write port recorded: ``taken`` gets the
    word of every push, at the edge that stores it."""
    core = card(clock, reset, pci, pins, build=Build(fifo_depth=fifo_depth))
    registers = _sub_block(core, "regs_fifo").sigdict
    push, wdata = registers["push"], registers["local_wdata"]

    @always(clock.posedge)
    def record():
        if push:
            taken.append(int(wdata))

    return core, record


def card_target(kind, fifo_depth, log, taken):
    """A PciBench target: the card on the bus, its pins into ``log``
    ("myhdl": ``rtl.card`` with ``taken`` recorded; "verilog": ``top.v`` in
    Icarus with its pads)."""

    def build(bench):
        if kind == "myhdl":
            ports = card_ports()
            agent, motor = ports["pci"], ports["pins"]
            core = (recorded_card, (bench.clock, bench.reset, agent, motor, taken, fifo_depth))
        elif kind == "verilog":
            harness = TopHarness(converted_top(fifo_depth), idsel_bit=16 + TARGET_DEVICE)
            agent, motor = harness.card, MotorPins()
            # the segment (which reports an X/Z drive) exists only once the target does
            core = (top_on_bus, (bench.clock, bench.reset, bench.host.agent, harness, motor), {})
        else:
            raise ValueError(f"unknown card kind {kind!r}: use 'myhdl' or 'verilog'")

        def blocks(b):
            cosim = [(core[0], core[1], {"segment": b.segment})] if kind == "verilog" else [core]
            return cosim + [(pin_capture, (b.clock, motor, log))]

        return agent, blocks

    return build


def run_bench(kind, fifo_depth, scenario, run, name, trace=False):
    """Enumerate the card (``kind`` "myhdl" or "verilog"), run
    ``scenario(bench, io base, memory base)``; fill in ``run`` (its
    ``taken``: the FIFO's record or None, ``runs``: ``x_runs`` of the pins,
    ``clocks``: from the scenario's start) and return it."""
    log = PinLog()
    taken = [] if kind == "myhdl" else None
    bench = PciBench(target=card_target(kind, fifo_depth, log, taken))

    def wrapped(b):
        devices = yield from b.host.enumerate_bus(devices=[TARGET_DEVICE])
        start = b.host.core.edge
        yield from scenario(b, devices[0].bar(0)["base"], devices[0].bar(1)["base"])
        run.clocks = b.host.core.edge - start

    bench.run(wrapped, name, trace=trace)
    run.taken = taken
    run.runs = x_runs(log)
    return run
