"""The encoder inputs in the whole card: a build with encoders on Verilator, its encoder and probe pins
driven every clock from a seeded waveform, the golden models of ``models/encoder_model.py`` clocked in
step with the card, the registers read over PCI and compared with them; and the following-error stop,
timed from the pin edge to DRIVE_ENABLE low.

``EncoderCard`` is the card on the bus with its pins: ``feed`` queues samples (one a clock, per axis
``(a, b, index)`` and the probe level), ``idle`` clocks while the bus is quiet, ``read``/``write`` are
register accesses (BAR0 below its end, else BAR2's blocks).  On Verilator every bus clock goes
through ``clock_edge``, so the pins change between any two edges, in a transaction or not (the
bench's compiled waits, ``CardWait``, are not used here); on MyHDL (``kind`` "myhdl", slower: short
runs) a process beside the card (``_pin_process``) sets the pins a time unit after each edge and
clocks the models for that edge.
"""
import random

from myhdl import block, delay, instance

from models import registers as regmap
from models.encoder_model import FERROR_CLOCKS, FILTER_MAX, FILTER_RESET, EncoderModel, ProbeModel, pin_to_count
from models.parameters import AXES
from sim.backends.verilator.pci_bus import VerilatorBench
from sim.backends.verilator.verilated_card import VerilatedCard
from sim.card.card_e2e import DEFAULT_FIFO, DEVICE, CardUnderTest, card_bars, card_verilog
from sim.card.card_session import CardSession
from sim.card.encoder_waves import encoder_waves
from sim.pci.bench import TARGET_DEVICE
from sim.pci.host_types import Clocks

GUARD_CLOCKS = 1   # the guard's flag to DRIVE_ENABLE low (rtl/machine/machine_guard.py: the latch's edge)
# pin edge to DRIVE_ENABLE low: conditioning and decoding, the error and its flag, the guard
REACTION_CLOCKS = pin_to_count(FILTER_RESET) + FERROR_CLOCKS + GUARD_CLOCKS


class _PinBench(VerilatorBench):
    """The Verilator bench with the encoder pins set before every edge after reset, the models after it."""

    def __init__(self, card, target, pins):
        super().__init__(card, target)
        self.pins = pins

    def clock_edge(self, in_reset=False):
        if not in_reset:
            self.pins.before_edge()
        super().clock_edge(in_reset)
        if not in_reset:
            self.pins.after_edge()


@block
def _pin_process(clock, reset, pins, owner):
    """MyHDL: after every edge the card took out of reset, the models clocked for it and the next pins set."""

    @instance
    def drive():
        owner.model = _MyhdlPins(pins)
        running = False   # RST# was high before this edge: the card's flip-flops took it
        while True:
            yield clock.posedge
            yield delay(1)   # the edge's outputs settled
            if running:
                owner.after_edge()
                owner.before_edge()
            running = bool(reset)

    return drive


class _MyhdlPins:
    """The MyHDL card's pins (``MotorPins``) by the Verilator model's port names (``pins_enc_a_x``, ...)."""

    def __init__(self, pins):
        self.pins = pins

    def __getitem__(self, name):
        return int(getattr(self.pins, name[len("pins_"):]))

    def __setitem__(self, name, value):
        getattr(self.pins, name[len("pins_"):]).next = value


class EncoderCard:
    """A card of ``axes`` axes built with encoders, reset and enumerated, its pins and models (module
    docstring); ``kind``: "verilator" or "myhdl"."""

    def __init__(self, axes=AXES.default, kind="verilator"):
        self.axes, self.kind = axes, kind
        self._init_models()
        if kind == "myhdl":
            self.model = None   # _pin_process sets it as the simulation starts
            self.session = CardSession("myhdl", axes=axes, name="encoder_card", card_options=dict(
                encoders=1, pin_driver=(_pin_process, self)))
            self.bench = self.session.bench   # the process set self.model
            self.bars = self.session.bars
            return
        self.session = None
        card = VerilatedCard(card_verilog(DEFAULT_FIFO, axes=axes, encoders=1), idsel_bit=16 + TARGET_DEVICE)
        self.model = card.model
        self.bench = _PinBench(card, CardUnderTest("verilator", DEFAULT_FIFO, axes=axes), self)
        self.bench.start()
        (device,) = self.call(self.bench.host.enumerate_bus(devices=[DEVICE]))
        self.bars = card_bars(device)

    def _init_models(self):
        axes = self.axes
        self.encoders = [EncoderModel() for _ in range(axes)]
        self.probe = ProbeModel()
        self.levels = [(0, 0, 0)] * axes
        self.probe_level = 0
        self.queue = []
        self.edges = 0          # rising edges since RST# went high
        self.drive_low_at = None   # the first edge after which DRIVE_ENABLE read low, once it was high
        self._drive_seen = False

    # ----- pins and models ------------------------------------------------------
    def _pin(self, name, axis):
        return f"pins_{name}_{'xyzabc'[axis]}"

    def before_edge(self):
        if self.queue:
            self.levels, self.probe_level = self.queue.pop(0)
        for axis, (a, b, index) in enumerate(self.levels):
            for name, level in zip(("enc_a", "enc_b", "enc_index"), (a, b, index)):
                self.model[self._pin(name, axis)] = level
        self.model["pins_probe"] = self.probe_level

    def after_edge(self):
        # the pins as they were in the clock before the edge; no steps move here: POS stays 0
        self.edges += 1
        self.probe.clock(self.probe_level, self.encoders, [0] * self.axes)
        for encoder, (a, b, index) in zip(self.encoders, self.levels):
            encoder.clock(a, b, index, 0)
        drive = bool(self.model["pins_drive_enable"])
        if drive:
            self._drive_seen = True
        elif self._drive_seen and self.drive_low_at is None:
            self.drive_low_at = self.edges

    def feed(self, samples):
        """Queue ``samples`` (each: a list of ``(a, b, index)`` per axis, and the probe level), one a clock."""
        self.queue.extend(samples)

    # ----- the bus ----------------------------------------------------------------
    def call(self, scenario):
        return self.session.call(scenario) if self.session is not None else self.bench.call(scenario)

    def idle(self, clocks):
        def wait():
            yield Clocks(clocks)
        self.call(wait())

    def drain(self):
        """Clock until every queued sample has reached the pins."""
        while self.queue:
            self.idle(len(self.queue))

    def read(self, offset):
        if offset < self.bars["io"]["size"]:
            return self.call(self.bench.host.io_read(self.bars["io"]["base"] + offset)).value
        return self.call(self.bench.host.mem_read(self.bars["alias"]["base"] + offset)).value

    def write(self, offset, value):
        if offset < self.bars["io"]["size"]:
            self.call(self.bench.host.io_write(self.bars["io"]["base"] + offset, value))
        else:
            self.call(self.bench.host.mem_write(self.bars["alias"]["base"] + offset, value))

    def axis_read(self, name, axis):
        return self.read(regmap.axis_register(name, axis).offset)

    def axis_write(self, name, axis, value):
        self.write(regmap.axis_register(name, axis).offset, value)

    def close(self):
        if self.session is not None:
            self.session.close()
            return
        self.bench.finish()
        self.model.close()


def _field(name, field_name, word):
    item = regmap.axis_spec(name).field(field_name)
    return (word >> item.lsb) & ((1 << item.width) - 1)


def waveform(seed, clocks, axes):
    """Per clock, every axis's ``(a, b, index)`` from its own seeded ``encoder_waves`` (legal
    walks at every spacing, glitches, illegal samples, noise, index pulses) and a probe pulse in the
    middle; the settings the waves change are not applied (the card and the models keep theirs)."""
    rng = random.Random(seed)
    waves = [[(s.a, s.b, s.index) for s, _ in encoder_waves(random.Random(rng.random()), clocks, host=False)]
             for _ in range(axes)]
    length = min(len(w) for w in waves)
    probe_at = rng.randrange(length // 4, length // 2)
    return [([w[i] for w in waves], int(probe_at <= i < probe_at + 8)) for i in range(length)]


def compare_counts(seed, clocks=600, axes=AXES.default, kind="verilator"):
    """Run ``waveform(seed, clocks)`` into a card with both latches armed; return ``(card words, model
    words)``: {register name: value} for every axis's ENC_COUNT, ENC_TIME, ENC_STATUS fields,
    ENC_INDEX_LATCH, INDEX_ARM, PROBE_ENC, and PROBE_CONTROL.ARM and INT_STATUS's INDEX and PROBE."""
    card = EncoderCard(axes, kind)
    try:
        for axis in range(axes):
            card.axis_write("ENC_CONTROL", axis, regmap.axis_spec("ENC_CONTROL").reset
                            | regmap.axis_spec("ENC_CONTROL").field("INDEX_ARM").mask)
            card.encoders[axis].arm_index()
        card.write(regmap.offset("PROBE_CONTROL"), regmap.register("PROBE_CONTROL").reset | 1)
        card.probe.arm()
        card.idle(4)   # the arms taken (the pins are still): the models armed at the same time
        card.feed(waveform(seed, clocks, axes))
        card.drain()
        card.idle(FILTER_MAX + 8)   # the last edges through the filters: nothing changes while the reads run
        got, want = {}, {}
        for axis, model in enumerate(card.encoders):
            status, control = card.axis_read("ENC_STATUS", axis), card.axis_read("ENC_CONTROL", axis)
            got.update({(axis, "ENC_COUNT"): card.axis_read("ENC_COUNT", axis),
                        (axis, "ENC_TIME"): card.axis_read("ENC_TIME", axis),
                        (axis, "ENC_INDEX_LATCH"): card.axis_read("ENC_INDEX_LATCH", axis),
                        (axis, "QUAD_ERROR"): _field("ENC_STATUS", "QUAD_ERROR", status),
                        (axis, "ERROR_COUNT"): _field("ENC_STATUS", "ERROR_COUNT", status),
                        (axis, "DIRECTION"): _field("ENC_STATUS", "DIRECTION", status),
                        (axis, "INDEX_ARM"): _field("ENC_CONTROL", "INDEX_ARM", control),
                        (axis, "PROBE_ENC"): card.axis_read("PROBE_ENC", axis)})
            want.update({(axis, "ENC_COUNT"): model.count, (axis, "ENC_TIME"): model.time,
                         (axis, "ENC_INDEX_LATCH"): model.index_latch, (axis, "QUAD_ERROR"): int(model.quad_error),
                         (axis, "ERROR_COUNT"): model.error_count, (axis, "DIRECTION"): model.direction,
                         (axis, "INDEX_ARM"): int(model.index_armed),
                         (axis, "PROBE_ENC"): card.probe.counts[axis] if card.probe.counts else 0})
        int_status = card.read(regmap.offset("INT_STATUS"))
        got["PROBE_ARM"] = card.read(regmap.offset("PROBE_CONTROL")) & 1
        want["PROBE_ARM"] = int(card.probe.armed)
        got["INT_INDEX"] = regmap.field_value("INT_STATUS", "INDEX", int_status)
        want["INT_INDEX"] = int(any(not model.index_armed for model in card.encoders))
        got["INT_PROBE"] = regmap.field_value("INT_STATUS", "PROBE", int_status)
        want["INT_PROBE"] = int(not card.probe.armed)
        return got, want
    finally:
        card.close()


def _quadrature(edges, spacing, axes, axis):
    """``edges`` legal quadrature edges up on ``axis``, ``spacing`` clocks apart (the others still)."""
    phases = ((0, 0), (1, 0), (1, 1), (0, 1))
    samples = []
    for edge in range(1, edges + 1):
        levels = [(0, 0, 0)] * axes
        a, b = phases[edge % 4]
        levels[axis] = (a, b, 0)
        samples += [(list(levels), 0)] * spacing
    return samples


def following_error_trip(axis, limit=3, spacing=6, axes=AXES.default):
    """Trip axis ``axis``'s following error: ENC_SCALE 0 (the step position counts 0) and
    FERROR_LIMIT ``limit``, the drives enabled, then ``limit`` + 2 counts up.  Returns
    ``(clocks, stop_reason, model_clocks)``: edges from the pin change of the count that went beyond
    the limit to DRIVE_ENABLE low, STOP_REASON, and the same to the model's stop flag."""
    card = EncoderCard(axes)
    try:
        card.axis_write("ENC_SCALE", axis, 0)
        card.encoders[axis].set_scale(0, 0)
        card.axis_write("FERROR_LIMIT", axis, limit)
        card.encoders[axis].limit = limit
        card.write(regmap.offset("MACHINE_CONTROL"), regmap.field_of("MACHINE_CONTROL", DRIVE_ENABLE=1))
        card.idle(4)
        if not card.model["pins_drive_enable"]:
            raise AssertionError("DRIVE_ENABLE did not rise")
        samples = _quadrature(limit + 2, spacing, axes, axis)
        crossing = card.edges + limit * spacing + 1   # the edge after the pins took count limit + 1
        model_stop_at = None
        card.feed(samples)
        while card.queue:
            card.idle(1)
            if model_stop_at is None and card.encoders[axis].stop:
                model_stop_at = card.edges
        card.idle(16)
        reason = card.read(regmap.offset("STOP_REASON"))
        return card.drive_low_at - crossing + 1, reason, model_stop_at - crossing + 1
    finally:
        card.close()
