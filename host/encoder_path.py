"""The path the encoders measured on a simulated card with motors (docs/encoders.md, "The measured
path"), beside the one its STEP/DIR pins made.

The simulated machine's motors (``models/sim_machine.py``'s ``Motor``) turn the card's steps into
encoder pins; the simulated machine records every change of them (``SimTransport.encoder_changes``:
the clock after whose edge the word was set, the word: bit 3n axis n's A, 3n + 1 its B).

* ``encoder_samples(changes, ratios)``: the pins decoded (4x, as the card decodes them) into
  (clock, point) with the point in steps: each axis's count over its counts per step, one sample a
  change;
* ``measure(plan, samples, rises)``: each sample against the drawing and against the pins at the same
  clock.  A sample belongs to the move the pins were in at its clock (the rises of the golden model's
  moves, ``host.check``); the encoders lag the pins, so it is measured against that move's primitive
  and the one before it, the nearer counting.  Against the pins: the distance from the pins' point
  after the last STEP rise at or before the sample's clock (the following error, in mm), and per axis
  the largest difference in steps.
"""
from dataclasses import dataclass

from models.encoder_model import quadrature_delta
from host.pin_measure import move_rises


def _phase(word, axis):
    return word >> 3 * axis & 1, word >> 3 * axis + 1 & 1


def encoder_samples(changes, ratios, before=0):
    """[(clock, point in steps)] from the encoder word's ``changes`` ((clock, word), in order; the word
    ``before`` them: both A and B low at count 0); ``ratios``: (numerator, denominator) of each axis's
    counts per step.  ValueError on a change where A and B moved together (the motors never do that)."""
    counts, word, samples = [0] * len(ratios), before, []
    for clock, now in changes:
        for axis in range(len(ratios)):
            delta = quadrature_delta(_phase(word, axis), _phase(now, axis))
            if delta is None:
                raise ValueError(f"encoder {axis}: A and B changed together at clock {clock}")
            counts[axis] += delta
        word = now
        samples.append((clock, tuple(c * d / n for c, (n, d) in zip(counts, ratios))))
    return samples


@dataclass(frozen=True)
class Measured:
    """``samples`` measured; ``drawing_mm`` (where: ``drawing_where``) the largest distance of a sample
    from the drawing; ``pins_mm`` (at clock ``pins_clock``) the largest from the pins at its clock;
    ``moves``: [(primitive index, [points in steps])] of the samples, for a preview; ``pins_steps``: per
    axis the largest |sample - pins| in steps."""
    samples: int
    drawing_mm: float
    drawing_where: str
    pins_mm: float
    pins_clock: int
    moves: list
    pins_steps: tuple = ()


def _distance(machine, a, b):
    return sum((x - y) ** 2 for x, y in zip(machine.mm(a), machine.mm(b))) ** 0.5


def measure(plan, check, samples, rises, start):
    """``samples`` (``encoder_samples``, in the job's clocks) against ``plan``'s drawing and the pins:
    ``rises`` [(clock, point after it)] of the job, ``start`` the point before them (module docstring)."""
    machine = plan.machine
    ends, total = [], 0
    for (primitive, _), count in zip(check.points, move_rises(check)):
        total += count
        ends.append((total, primitive))
    moves, rise, move = [], 0, 0
    worst = [0.0, "", 0.0, 0]
    per_axis = [0.0] * len(start)
    for clock, point in samples:
        while rise < len(rises) and rises[rise][0] <= clock:
            rise += 1
        pins = rises[rise - 1][1] if rise else start
        while move + 1 < len(ends) and ends[move][0] < rise:
            move += 1
        near = [plan.drawing[ends[m][1]] for m in range(max(0, move - 1), move + 1)] if ends else []
        if near:
            distance, where = min((item.distance(machine.mm(point)), item.where) for item in near)
            if distance > worst[0]:
                worst[:2] = distance, where
        per_axis = [max(w, abs(a - b)) for w, a, b in zip(per_axis, point, pins)]
        apart = _distance(machine, point, pins)
        if apart > worst[2]:
            worst[2:] = apart, clock
        if ends and (not moves or moves[-1][0] != ends[move][1]):
            moves.append((ends[move][1], []))
        if moves:
            moves[-1][1].append(point)
    return Measured(len(samples), worst[0], worst[1], worst[2], worst[3], moves, tuple(per_axis))
