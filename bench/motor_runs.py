"""Moves on a card built with encoders with the simulated machine's motors following
(``models/sim_machine.py``'s ``Motor``, run in the Verilator harness's clock loop), driven through the
host API, against the golden encoder model.

``motor_run`` opens the card (``SimTransport(..., encoders=1, machine=config)``), sets each motor's
axis ENC_SCALE to its counts per step and FERROR_LIMIT to ``limit`` (while nothing has moved: count
and POS 0 align there), enables the drives, runs ``moves`` at ``feed_rate``, reading ENC_FERROR over
PCI every ``read_every`` clocks while the card is busy; with ``stall_after`` (STEP rises), it stalls
X's motor then.  Then it replays the pins the harness recorded (the STEP/DIR edges, the encoder pins
the motors drove) through ``models.encoder_model.EncoderModel`` with the same scale and limit: the
model's following error at every edge and the edge its stop flag rose.  ``MotorRun`` has both sides.

Timing of the replay (docs/encoders.md): the model's clock for edge n takes the encoder pins and the
step position as they were after edge n - 1; POS counts a step at the edge its STEP rises on the pin
(``rtl/regs/pulse_out.py``), so the rises recorded up to clock n - 1.  The card's guard latches one edge
after the flag, and DRIVE_ENABLE falls there unless a STEP pulse is high: then at the edge after it
fell (docs/machine.md), at most STEP_WIDTH + 2 clocks later.
"""
from dataclasses import dataclass

from host import encoders
from host.card import Card
from host.machine_io import MachineStopped
from host.transports.simulated import SimTransport
from models import registers as regmap
from models.encoder_model import SCALE_FRACTION_BITS, EncoderModel
from models.sim_machine import MOTOR_AXES
from sim.backends.verilator.model import DRIVE_BIT

STEP_BITS, DIR_BITS = (1, 4), (2, 8)   # the pin log's bits of STEP_X, STEP_Y and DIR_X, DIR_Y
GUARD_CLOCKS = 1   # the guard latches the edge after the following-error flag


@dataclass(frozen=True)
class MotorRun:
    """What ``motor_run`` saw.  Card: ``counts`` and ``ferror`` (ENC_COUNT, ENC_FERROR per axis
    after the run), ``positions`` (POS), ``ferror_reads`` (ENC_FERROR read during the moves, per
    axis), ``stop_reason`` (STOP_REASON), ``drive_low_at`` (the clock DRIVE_ENABLE was first seen low
    after the drives came on, None if never), ``stall_at`` (the first clock the stalled motor did
    not turn), ``step_width`` (STEP's high clocks), ``x_rises`` (the clocks of STEP_X's rises).
    Model: ``model_ferror`` (its following error after the run), ``model_worst`` (its largest
    |error| over the run, per axis), ``model_stop_at`` (the edge its stop flag rose, None if never).  ``machine``: the machine's ``MachineState``."""
    counts: tuple
    ferror: tuple
    positions: tuple
    ferror_reads: tuple
    stop_reason: int
    drive_low_at: object
    stall_at: object
    step_width: int
    x_rises: tuple
    model_ferror: tuple
    model_worst: tuple
    model_stop_at: object
    machine: object

    @property
    def stall_to_stop(self):
        """Clocks from the stall to DRIVE_ENABLE low (None without both)."""
        return None if self.stall_at is None or self.drive_low_at is None else self.drive_low_at - self.stall_at + 1


def _scale(motor):
    numerator, denominator = motor.ratio
    return round(numerator * (1 << SCALE_FRACTION_BITS) / denominator)


def _drive_low(changes, since):
    return next((int(c) for c, w in zip(*changes) if c >= since and not int(w) >> DRIVE_BIT & 1), None)


def motor_run(config, moves, limit, feed_rate=1000, read_every=2000, stall_after=None, settle=4000):
    """Run ``moves`` ((dx, dy) LINEs) with ``config``'s motors following (module docstring)."""
    axes = [MOTOR_AXES.index(name) for name in config.motors]
    with SimTransport("verilator", machine=config, encoders=1) as transport:
        card = Card(transport)
        card.configure()
        model = transport.session._runner.card.model
        for axis in axes:
            encoders.set_following_error(card, axis, _scale(config.motors[MOTOR_AXES[axis]]) / 65536, limit)
        card.start(interrupts=("ERROR", "DONE"))
        card.set("FEED_RATE", feed_rate)
        card.drive(True)
        first = transport.clocks
        for dx, dy in moves:
            card.line(dx, dy)
        reads, stall_at = [[] for _ in MOTOR_AXES], None
        if stall_after is not None:
            transport.session.wait(1 << 30, steps=stall_after)
            transport.machine.stall(0)
            stall_at = transport.clocks + 1
        try:
            while True:
                transport.session.wait(read_every)
                reads = [r + [encoders.read_encoder(card, axis).ferror] if axis in axes else r
                         for axis, r in enumerate(reads)]
                status = card.status()
                card.check(status)
                if not card.field("STATUS", "BUSY", status) and card.field("STATUS", "FIFO_EMPTY", status):
                    break
        except MachineStopped:
            pass
        transport.session.wait(settle)
        last = transport.clocks
        readings = [encoders.read_encoder(card, axis) for axis in range(card.identity.axes)]
        run = dict(counts=tuple(r.count for r in readings), ferror=tuple(r.ferror for r in readings),
                   positions=tuple(card.position()), ferror_reads=tuple(tuple(r) for r in reads),
                   stop_reason=card.read("STOP_REASON"), drive_low_at=_drive_low(model.take_machine_changes(), first),
                   stall_at=stall_at, step_width=card.timing["STEP_WIDTH"], machine=transport.machine.state())
        encoder_changes = list(zip(*(a.tolist() for a in model.take_encoder_changes())))
        edges = list(transport.pins.edges)
    scales = [_scale(config.motors[name]) if name in config.motors else 0 for name in MOTOR_AXES[:2]]
    worst, final, stop_at = replay(edges, encoder_changes, last, scales, limit)
    x_rises = tuple(clock for (clock, state), before in zip(edges, [0] + [s for _, s in edges])
                    if state & STEP_BITS[0] and not before & STEP_BITS[0])
    return MotorRun(**run, x_rises=x_rises, model_ferror=final, model_worst=worst, model_stop_at=stop_at)


def replay(edges, encoder_changes, last, scales, limit):
    """The golden encoders on the recorded pins up to clock ``last``: (largest |ENC_FERROR| per axis,
    the final ENC_FERROR per axis, the first edge a stop flag was up or None)."""
    models = []
    for scale in scales:
        encoder = EncoderModel()
        encoder.set_scale(scale, pos=0)
        encoder.limit = limit if scale else 0
        models.append(encoder)
    edge_at, changes = dict(edges), dict(encoder_changes)
    pins, word, positions = 0, 0, [0, 0]
    worst, stop_at = [0, 0], None
    for clock in range(1, last + 1):
        for axis, encoder in enumerate(models):   # edge ``clock`` takes the pins after edge clock - 1
            encoder.clock(word >> 3 * axis & 1, word >> 3 * axis + 1 & 1, word >> 3 * axis + 2 & 1, positions[axis])
            worst[axis] = max(worst[axis], abs(encoder.ferror))
            if encoder.stop and stop_at is None:
                stop_at = clock
        state = edge_at.get(clock, pins)
        for axis in range(len(models)):
            if state & STEP_BITS[axis] and not pins & STEP_BITS[axis]:
                positions[axis] += 1 if state & DIR_BITS[axis] else -1
        pins, word = state, changes.get(clock, word)
    return tuple(worst), tuple(e.ferror for e in models), stop_at


def stop_reason(word):
    """(reason name, axis) of a STOP_REASON word."""
    reason = regmap.STOP_REASONS[regmap.field_value("STOP_REASON", "REASON", word)]
    return reason, regmap.field_value("STOP_REASON", "AXIS", word)
