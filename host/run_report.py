"""What ``python -m host run`` prints of a simulated card after a job: the pins'
path against the golden model's and the drawing (and the preview), and what
the encoders measured on every axis beside the pins (``host/encoder_path.py``).
"""
import dataclasses

from host import encoders
from host.encoder_path import encoder_samples, measure
from host.pin_measure import deviation, junction_gaps, pin_moves, pin_moves_of_points
from models.axes import names
from models.motor_model import round_ratio
from models.sim_machine import MOTOR_AXES

SETTLE_SECONDS = 1e-4   # card time between two looks at the encoders after the job, until they stand
SETTLE_LOOKS = 200


def pin_rises(pins, axes):
    """The STEP rises of a simulated card: (clock, x, y, dir x, dir y) on two axes; on more,
    (clock, point) with the point from the card's start (``PinLog.axis_rises``)."""
    return pins.rises if axes == 2 else pins.axis_rises(axes)


def pins_report(planned, model, transport, first_rise, preview, dir_setup, axes, encoder_path=None):
    """Print the pins' path against the golden model's and the drawing; the point it ended on
    (``encoder_path``: the encoders' path, a ``Measured``, drawn in the preview too)."""
    rises = pin_rises(transport.pins, axes)[first_rise:]
    if axes == 2:
        moves = pin_moves(planned, model, rises)
    else:
        before = pin_rises(transport.pins, axes)[first_rise - 1][1] if first_rise else (0,) * axes
        moves = pin_moves_of_points(model, [before] + [point for _, point in rises])
    ideal = [p for _, points in model.points for p in points[1:]]
    got = [p for _, points in moves for p in points[1:]]
    mm, steps, where = deviation(planned, moves)
    measured, over = junction_gaps(planned, model, rises, dir_setup)
    print(f"pins:       {len(rises)} STEP rises; the path {'is' if got == ideal else 'is NOT'} the golden "
          f"model's; max deviation {mm:.5f} mm = {steps:.3f} steps (at {where})")
    print(f"gaps:       {len(over)} of {measured} blended junctions slower than the move before them")
    if preview:
        from host.preview import draw

        pins = "the card's STEP/DIR pins" if encoder_path is None else "the pins"
        encoders_path = "" if encoder_path is None else ", the encoders (green)"
        draw(planned, dataclasses.replace(model, points=moves), preview,
             title=f"{pins} (blue: fed, orange: rapid){encoders_path} over the drawing (grey); "
                   f"max deviation {steps:.2f} steps", measured=None if encoder_path is None else encoder_path.moves)
        print(f"preview:    {preview}")
    return moves[-1][1][-1] if moves else None


def encoders_report(card, planned, model, transport, first_rise, motors, axes):
    """Print what the encoders measured (counts, ENC_FERROR, the path against the drawing and the pins on
    every axis, ``host/encoder_path.py``; whether the counts ended on the pins' steps times the counts per
    step) once they stand; the ``Measured``."""
    counts = None
    for _ in range(SETTLE_LOOKS):   # the last steps' counts come after the lag and the spacing
        transport.sleep(SETTLE_SECONDS)
        if transport.machine.state().counts == counts:
            break
        counts = transport.machine.state().counts
    readings = [encoders.read_encoder(card, axis) for axis in range(axes)]
    reason, which = card.stop_reason()
    ratios = [motors[name].ratio if name in motors else (1, 1) for name in MOTOR_AXES[:axes]]
    samples = encoder_samples(transport.encoder_changes(), ratios)
    all_rises = transport.pins.axis_rises(axes)
    rises = all_rises[first_rise:]
    start = all_rises[first_rise - 1][1] if first_rise else (0,) * axes
    result = measure(planned, model, [s for s in samples if s[0] >= (rises[0][0] if rises else 0)], rises, start)
    end = rises[-1][1] if rises else start
    expected = tuple(round_ratio(steps, *ratio) if name in motors else 0
                     for steps, ratio, name in zip(end, ratios, MOTOR_AXES))
    got = tuple(r.count for r in readings)
    print(f"encoders:   counts {got} (ENC_COUNT) = "
          f"({', '.join(f'{p:.3f}' for p in (samples[-1][1] if samples else (0,) * axes))}) steps; ENC_FERROR "
          f"{tuple(r.ferror for r in readings)} counts; stop {' '.join([reason, *which]) if which else reason}")
    print(f"counts end: {'exact' if got == expected else 'NOT exact'}: the pins' {end} steps x counts per step "
          f"= {expected}")
    print(f"measured:   {result.samples} encoder samples; max deviation from the drawing {result.drawing_mm:.5f} mm "
          f"(at {result.drawing_where or '-'}), from the pins {result.pins_mm:.5f} mm (at clock {result.pins_clock})")
    apart = ", ".join(f"{names([axis])} {steps:.3f}" for axis, steps in enumerate(result.pins_steps))
    print(f"per axis:   max |encoders - pins| {apart} steps")
    return result
