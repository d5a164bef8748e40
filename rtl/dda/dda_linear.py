"""The N-axis line: per-axis accumulators against the threshold T = max |d_i|, one iteration a clock."""
from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, concat, intbv

from models.dda_build import COORD_WIDTH
from models.parameters import AXES
from rtl.interfaces import AxisPulses, LinearPort, axis_suffixes, card_reset, named


@block
def dda_linear(clock, reset, line, steps):
    """A straight move of every axis at once, exactly the golden model's line
    rule (``models.dda_axes.Follower``, docs/axes.md): threshold
    T = max_i |d_i|, every accumulator loaded with T // 2, integrand |d_i|;
    axis i steps in an iteration when acc_i + |d_i| >= T and it has steps
    left (then acc_i -= T).  The major axis steps every iteration, every axis
    ends on its end point on iteration T.

    Ports: ``line`` (``LinearPort``: ``load`` takes the magnitudes, signs
    and ``helix``, ``advance`` runs one iteration while ``following``;
    ``left`` is a line's T less the iterations done, 0 for a helix);
    ``steps`` (``AxisPulses`` of as many axes: the steps of an iteration
    high for the clock after its edge, with their directions).  ``load``
    wins over an iteration in the same clock.  A line's threshold is
    ``line.largest``, the largest magnitude as the driver found it before
    the load (the sequencer, as the operands arrive): no comparison of the
    axes lies between the load and the accumulators; each axis is an
    ``_axis_line`` (``axis_x``, ...).

    A line (3, -1, 2), advance high from the clock after the load:
        clock    _/~\\_/~\\_/~\\_/~\\_/~\\_
        load     _/~~~\\_____________
        left     ==0==X=3=X=2=X=1=X=0=
        step_x   _________/~~~~~~~~~~~
        step_y   _____________/~~~\\___
        step_z   _________/~~~\\___/~~~
    """
    axes = line.axes
    if steps.axes != axes:
        raise ValueError(f"dda_linear: line has {axes} axes, steps {steps.axes}")
    width = len(line.left)
    # the accumulators' side is one bit wider than the threshold (max |d|): a sum of two values below it
    thr_width = width + 1
    magnitudes = [line.magnitude(axis) for axis in range(axes)]
    largest = line.largest
    threshold, half = Signal(intbv(0)[thr_width:]), Signal(intbv(0)[thr_width:])
    iterate = Signal(bool(0))
    moving = [Signal(bool(0)) for _ in range(axes)]
    moving_any = ConcatSignal(*reversed(moving))   # bit i: axis i has steps left
    lines = [named(f"axis_{suffix}", _axis_line(clock, reset, line.load, iterate, magnitudes[axis],
                                                 line.positive(axis), half, threshold, steps.step(axis),
                                                 steps.dir(axis), moving[axis]))
             for axis, suffix in enumerate(axis_suffixes(axes))]

    @always_comb
    def iterating():
        line.following.next = moving_any != 0
        line.busy.next = line.left != 0
        iterate.next = line.advance and moving_any != 0
        half.next = concat(intbv(0)[thr_width + 1 - width:], largest[width:1])

    @always_seq(clock.posedge, reset=reset)
    def count_iterations():
        if line.load:
            threshold.next = concat(intbv(0)[thr_width - width:], largest)
            line.left.next = largest
        elif iterate and line.left != 0:
            line.left.next = line.left - 1

    return lines, iterating, count_iterations


@block
def _axis_line(clock, reset, load, iterate, magnitude, positive, half, threshold, step, direction, moving):
    """One axis of ``dda_linear``: at ``load`` its accumulator takes
    ``half`` (T // 2), its steps left and integrand ``magnitude`` and its
    ``direction`` ``positive``; at each ``iterate`` it steps (``step`` high
    the next clock) when the sum reaches ``threshold`` and steps are left.
    ``moving``: steps are left."""
    width = len(magnitude)
    steps_left = Signal(intbv(0)[width:])
    # the accumulator stays below T (docs/axes.md); as wide as the sum, like the integrand
    acc, integrand, total = (Signal(intbv(0)[len(threshold):]) for _ in range(3))
    stepping = Signal(bool(0))

    @always_comb
    def add():
        total.next = acc + integrand

    @always_comb
    def decide():
        stepping.next = total >= threshold and steps_left != 0
        moving.next = steps_left != 0

    @always_seq(clock.posedge, reset=reset)
    def accumulate():
        step.next = 0
        if load:
            acc.next = half
            integrand.next = concat(intbv(0)[len(threshold) - width:], magnitude)
            steps_left.next = magnitude
            direction.next = positive
        elif iterate:
            step.next = stepping
            if stepping:
                acc.next = total - threshold
                steps_left.next = steps_left - 1
            else:
                acc.next = total

    return add, decide, accumulate


def dda_linear_ports(axes=AXES.default, coord_width=COORD_WIDTH):
    """Fresh ports of ``dda_linear`` for conversion and benches: ``axes`` axes of ``coord_width``-bit moves."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), line=LinearPort(axes, coord_width),
                steps=AxisPulses(axes))
