"""The interpolator's bundles: the card's port to it and the ones between its units."""
from myhdl import Signal, intbv, modbv

from models.dda_build import (COORD_WIDTH, DEFAULT_VARIANTS, PRECISE, accumulator_width, check_coord_width, left_width,
                              threshold_width, variant_set)
from models.helix_area import area_width
from models.parameters import AXES
from rtl.interfaces.bundle import axis_suffixes


class DdaPort:
    """Command and status of the DDA interpolator (``rtl/dda_arc.py``).

    Inputs: ``start`` (one-clock pulse, taken when ``ready``), ``line`` (1: a
    straight move by (``xe``, ``ye``); 0: an arc about the origin from
    (``xs``, ``ys``) to (``xe``, ``ye``)), ``variant`` (0 traditional,
    1 weighted, 2 improved of the paper, 3 the project's precise mode; a card
    has the ``variants`` it was built with), ``lambda_shift`` (weighting
    factor 2**-lambda_shift), ``acc_bits`` (the paper's accumulator width n,
    threshold 2**(n + lambda_shift); 0: n is the bit length of the radius,
    i.e. left-shift normalisation; both only for variants 0..2), ``ccw``
    (direction), ``blend`` (1: the path goes on into the next move at speed,
    so ``stop_left`` does not count down for this one), ``advance`` (the feed
    rate: one iteration per pulse; pulses come at most every other clock).
    The command lines are read in the clock of ``start``; an arc spends a
    fixed number of setup clocks (its squares, root and checks) before its
    first iteration.  The setup of a move overlaps the run of the move before
    it, so chained moves leave no gap.
    Outputs: ``ready`` (a ``start`` would be taken: the setup stage is free),
    ``busy`` (a move is being set up or run), ``iterate`` (the run takes this
    clock's ``advance`` as an iteration of its move: its steps leave in the
    next clock; a helix's other axes iterate with it), ``done`` (one-clock pulse when a
    move has ended on its end point, with its last step), ``error`` (a move
    was rejected: end not within one step of the start radius, radius too
    large, a centre point, acc_bits + lambda_shift too wide, a variant the
    card was not built with; raised once the moves before it have ended,
    held until the next ``start``), ``quadrant`` (of the moving point, 0..3
    for I..IV), ``stop_left`` (a lower bound of the iterations left before
    the path stops: those of the running move when it was started with
    ``blend`` = 0, the all-ones value while the running move blends or none
    runs; the feed-rate ramp decelerates on it).

    ``progress`` (an ``ArcProgress``, or None): what a helix follows of the
    iteration the run takes (only a card of more than two axes asks for it).

    Build parameters (``models/parameters.py``), read by every block that takes
    the port: ``coord_width`` (``models.dda_build.check_coord_width``: the
    card's range, or narrower for the interpolator alone) and ``variants``
    (a set of variant codes; given as the parameter's choice,
    ``improved,precise`` or ``all``, or as its codes).
    """

    def __init__(self, coord_width=COORD_WIDTH, variants=DEFAULT_VARIANTS, progress=False):
        self.coord_width = check_coord_width(coord_width)
        self.progress = ArcProgress() if progress else None
        self.variants = variant_set(variants)
        low, high = -(1 << (coord_width - 1)), 1 << (coord_width - 1)
        self.start = Signal(bool(0))
        self.line = Signal(bool(0))
        self.variant = Signal(intbv(PRECISE)[2:])
        self.lambda_shift = Signal(intbv(0)[5:])
        self.acc_bits = Signal(intbv(0)[5:])
        self.ccw = Signal(bool(1))
        self.blend = Signal(bool(0))
        self.xs = Signal(intbv(0, min=low, max=high))
        self.ys = Signal(intbv(0, min=low, max=high))
        self.xe = Signal(intbv(0, min=low, max=high))
        self.ye = Signal(intbv(0, min=low, max=high))
        self.advance = Signal(bool(0))
        self.iterate = Signal(bool(0))
        self.busy = Signal(bool(0))
        self.done = Signal(bool(0))
        self.error = Signal(bool(0))
        self.quadrant = Signal(intbv(0)[2:])
        self.ready = Signal(bool(1))
        self.stop_left = Signal(intbv((1 << self.left_width) - 1)[self.left_width:])

    @property
    def left_width(self):
        """Width of ``stop_left``: four quadrant pieces of the largest radius, plus one."""
        return left_width(self.coord_width)


class ArcProgress:
    """What the arc DDA's run tells a helix of the iteration it takes
    (``DdaPort.iterate`` high): ``step_u``, ``step_v`` (its decision: the
    plane's axes step in this iteration, their pulses leave in the next
    clock) and ``u_inward`` (|u| shrinks and |v| grows on a step of this
    iteration; the other way round when low).  Valid only with ``iterate``."""

    def __init__(self):
        self.step_u, self.step_v, self.u_inward = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))


class DdaPlan:
    """What the DDA's setup stage (``rtl/dda/dda_setup.py``) knows of the move it prepared,
    for the check (``rtl/dda/dda_check.py``); every signal is a setup register.

    ``done`` says the rest is complete (it stays until ``taken``: the run
    takes the move at this edge; the check drives ``taken``).  The command: ``line``, ``variant``, ``ccw``, ``blend``, the
    magnitudes ``mag_xs``.. ``mag_ye`` and the end point's signs ``neg_xe``,
    ``neg_ye``.  Geometry: ``quadrant`` (of the start), ``crossings`` (axis
    crossings to the end, 4 for a full circle), ``ahead`` (the end lies ahead
    in the start's quadrant: one piece), ``x_inward`` (X moves towards its
    axis in the first piece).  Arithmetic: ``radius`` (Rq, the integer whose
    square is nearest to xs**2 + ys**2), ``threshold`` (T - 1 of the paper's
    variants, 2**(n + k) - 1; T of a line), ``totals_diff`` and
    ``totals_max`` (each axis' steps over the whole move: their difference
    and the larger; a line's both hold its iterations).  Checks, true when
    the move is bad: ``centre``, ``off_circle`` (end not within one step of
    the start radius), ``beyond`` (end beyond Rq on its inward axis),
    ``too_wide`` (n + k too large).  For the setup stage itself:
    ``start_below_x`` / ``start_same_x`` (|xs| < |xe|, |xs| == |xe|), the same
    for y, ``x_inward_end`` (X moves towards its axis in the last piece).
    """

    def __init__(self, port):
        width = port.coord_width
        self.coord_width = width
        self.variants = port.variants
        self.left_width = port.left_width
        self.threshold_width = threshold_width(width, port.variants)
        self.done, self.taken = Signal(bool(0)), Signal(bool(0))
        self.line = Signal(bool(0))
        self.variant = Signal(intbv(PRECISE)[2:])
        self.ccw = Signal(bool(0))
        self.blend = Signal(bool(0))
        self.mag_xs, self.mag_ys, self.mag_xe, self.mag_ye = (Signal(intbv(0)[width:]) for _ in range(4))
        self.neg_xe, self.neg_ye = Signal(bool(0)), Signal(bool(0))
        self.quadrant = Signal(intbv(0)[2:])
        self.crossings = Signal(intbv(0)[3:])
        self.ahead = Signal(bool(0))
        self.x_inward = Signal(bool(0))
        self.radius = Signal(intbv(0)[width + 1:])
        self.threshold = Signal(intbv(0)[self.threshold_width:])
        self.totals_diff = Signal(intbv(0, min=-(1 << (self.left_width - 1)), max=1 << (self.left_width - 1)))
        self.totals_max = Signal(intbv(0)[self.left_width:])
        self.centre = Signal(bool(0))
        self.off_circle = Signal(bool(0))
        self.beyond = Signal(bool(0))
        self.too_wide = Signal(bool(0))
        # the setup stage's own: the compares' results and the end's inward axis
        self.start_below_x, self.start_same_x = Signal(bool(0)), Signal(bool(0))
        self.start_below_y, self.start_same_y = Signal(bool(0)), Signal(bool(0))
        self.x_inward_end = Signal(bool(0))


class DdaRoot:
    """The setup stage's square root (``rtl/dda/dda_root.py``).

    ``load``: take ``radicand`` (2W bits) at this edge; the root then forms
    one bit a clock for W + 1 clocks, and ``root`` holds t = 2 isqrt + r
    (r = 1 when the radicand lies nearer the next square: Rq = (t + 1) >> 1).
    ``grows``: in this clock a bit of Rq's length appears (each root bit from
    the first 1 on, and one more when the rounding carries into a new bit).
    """

    def __init__(self, coord_width):
        self.coord_width = coord_width
        self.load = Signal(bool(0))
        self.radicand = Signal(intbv(0)[2 * coord_width:])
        self.root = Signal(intbv(0)[coord_width + 1:])
        self.grows = Signal(bool(0))


class SetupSequence:
    """The setup stage's phase (``rtl/dda/dda_sequence.py``): its registers
    ``state`` (``idle`` is the state enum's idle item), ``step`` (clocks
    into the phase, below ``step_max``) and ``square`` (which of the four
    squares), and their next values ``next_state``, ``next_step``,
    ``next_square``."""

    def __init__(self, idle, step_max):
        self.state, self.next_state = Signal(idle), Signal(idle)
        self.step = Signal(intbv(0, min=0, max=step_max))
        self.next_step = Signal(intbv(0, min=0, max=step_max))
        self.square, self.next_square = Signal(modbv(0)[2:]), Signal(modbv(0)[2:])


class SetupControl:
    """What the setup stage's micro-program (``rtl/dda/dda_setup_control.py``,
    which defines the codes) tells its adder (``rtl/dda/dda_setup.py``) each
    clock, and the flags it reads.

    From the program: ``gap_op`` (the accumulator ``gap``: ``G_HOLD``,
    ``G_ADD`` the sum, ``G_ZERO``, ``G_ONES``), ``operand_op`` (the operand
    register: ``M_HOLD``, ``M_SHIFT`` left, ``M_LOAD``), ``source`` (what it
    loads: ``SRC_XS``.. ``SRC_YE``, the magnitudes, or ``SRC_ROOT``, t),
    ``source_on`` (0: it loads 0), ``invert`` (it loads the source inverted,
    or shifts in a 1) and ``carry`` (the adder's carry-in, a register set a
    clock ahead).  From the datapath: ``multiplier`` (W bits, shifted right
    during a square: bit 0 says whether this clock adds), ``m_is_y`` (|xs| <
    |ys|: m is |ys|) and ``pick_x`` (X has the larger total)."""

    def __init__(self, coord_width):
        self.gap_op, self.operand_op = Signal(intbv(0)[2:]), Signal(intbv(0)[2:])
        self.source = Signal(intbv(0)[3:])
        self.source_on, self.invert = Signal(bool(0)), Signal(bool(0))
        self.carry = Signal(bool(0))
        self.multiplier = Signal(intbv(0)[coord_width:])
        self.m_is_y, self.pick_x = Signal(bool(0)), Signal(bool(0))


class DdaMove:
    """The checked move, from the check (``rtl/dda/dda_check.py``) to the run
    (``rtl/dda/dda_run.py``), and the handshake that hands it over.

    ``offer``: a checked move waits; ``take`` (from the run): the run takes it
    at this clock edge (the setup stage is then free).  ``error``: rejected
    (the run raises ``error`` instead of running it); ``zero``: a line of
    length 0 (the run gives ``done`` at once).  The rest are the run's start
    values: ``line``, ``variant``, ``ccw``, ``blend``, ``quadrant``,
    ``crossings``, ``x_inward``, ``target_x``/``target_y`` (what each axis
    stops at in the first piece: ``TARGET_ZERO``, ``TARGET_RADIUS`` or
    ``TARGET_END``), ``right``/``up`` (a line's directions), ``mag_x``,
    ``mag_y`` (the run's |x|, |y|; a line's |dy|, |dx|: the integrands),
    ``end_x``, ``end_y``, ``radius``, ``threshold`` (T - 1; T for a line, whose
    subtraction then takes a carry), ``acc_init`` (both accumulators' first
    value, A - T or A - T - 1), ``acc_carry`` (a line's first sum takes a
    carry: the initial load -ceil(T/2)), ``bias_in``, ``bias_out`` (the
    precise mode's P = 2b - a and Q = b - 2a, a and b the start's inward and
    outward magnitudes), ``totals_diff``, ``totals_max``.
    """

    def __init__(self, plan):
        width = plan.coord_width
        self.coord_width = width
        self.variants = plan.variants
        self.left_width = plan.left_width
        self.threshold_width = plan.threshold_width
        self.acc_width = accumulator_width(width, plan.variants)
        self.bias_width = width + 3
        self.offer, self.take = Signal(bool(0)), Signal(bool(0))
        self.error, self.zero = Signal(bool(0)), Signal(bool(0))
        self.line = Signal(bool(0))
        self.variant = Signal(intbv(PRECISE)[2:])
        self.ccw, self.blend = Signal(bool(0)), Signal(bool(0))
        self.quadrant = Signal(intbv(0)[2:])
        self.crossings = Signal(intbv(0)[3:])
        self.x_inward = Signal(bool(0))
        self.target_x, self.target_y = Signal(intbv(0)[2:]), Signal(intbv(0)[2:])
        self.right, self.up = Signal(bool(0)), Signal(bool(0))
        self.mag_x, self.mag_y = Signal(intbv(0)[width:]), Signal(intbv(0)[width:])
        self.end_x, self.end_y = Signal(intbv(0)[width:]), Signal(intbv(0)[width:])
        self.radius = Signal(intbv(0)[width:])
        self.threshold = Signal(intbv(0)[self.threshold_width:])
        self.acc_init = Signal(intbv(0, min=-(1 << (self.acc_width - 1)), max=1 << (self.acc_width - 1)))
        self.acc_carry = Signal(bool(0))
        bias = dict(min=-(1 << (self.bias_width - 1)), max=1 << (self.bias_width - 1))
        self.bias_in, self.bias_out = Signal(intbv(0, **bias)), Signal(intbv(0, **bias))
        self.totals_diff = Signal(intbv(0, min=-(1 << (self.left_width - 1)), max=1 << (self.left_width - 1)))
        self.totals_max = Signal(intbv(0)[self.left_width:])


TARGET_ZERO, TARGET_RADIUS, TARGET_END = range(3)


class DdaStep:
    """The run's iteration as its units share it (``rtl/dda/dda_run.py`` drives it).

    From the run: ``pending`` (the second clock of an iteration: the
    registered decision is applied at its end), the decision ``step_x``,
    ``step_y``, ``finished``, ``new_piece`` (the step ends a quadrant
    piece: the next begins when it is applied), the move's ``line`` and ``blend``,
    ``x_inward`` and the magnitudes ``mag_x``, ``mag_y``, all registers.
    To the run: ``inward_near`` and ``outward_near`` (the precise mode's
    choice, ``rtl/dda/dda_nearest.py``) and ``last`` (a line's last iteration,
    ``rtl/dda/dda_left.py``).
    """

    def __init__(self, move):
        width = move.coord_width
        self.coord_width = width
        self.left_width = move.left_width
        self.bias_width = move.bias_width
        self.pending = Signal(bool(0))
        self.step_x, self.step_y = Signal(bool(0)), Signal(bool(0))
        self.finished, self.new_piece = Signal(bool(0)), Signal(bool(0))
        self.line, self.blend, self.x_inward = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
        self.mag_x, self.mag_y = Signal(modbv(0)[width:]), Signal(modbv(0)[width:])
        self.inward_near, self.outward_near = Signal(bool(0)), Signal(bool(0))
        self.last = Signal(bool(0))


class AxisPulses:
    """Step requests for ``axes`` axes (``step_x``, ``step_y``, ...,
    ``dir_x``, ``dir_y``, ...; ``models/axes.py`` names them): ``step_*`` is
    high for one clock per step, ``dir_*`` (1: positive direction) is valid
    in that clock."""

    def __init__(self, axes=AXES.default):
        self.axes = axes
        for kind in ("step", "dir"):
            for suffix in axis_suffixes(axes):
                setattr(self, f"{kind}_{suffix}", Signal(bool(0)))

    def step(self, axis):
        """Axis ``axis``'s step request (0 X, 1 Y, ...)."""
        return getattr(self, f"step_{axis_suffixes(self.axes)[axis]}")

    def dir(self, axis):
        """Axis ``axis``'s direction."""
        return getattr(self, f"dir_{axis_suffixes(self.axes)[axis]}")


class LinearPort:
    """The N-axis line's port (``rtl/dda/dda_linear.py``), for ``axes`` axes
    of ``coord_width``-bit signed displacements.

    The driver gives ``load`` (one clock) with each axis's
    ``magnitude_<axis>`` (|d|, as wide as the coordinates: |-2**(W-1)| fits)
    and ``positive_<axis>`` (the sign: 1 for d >= 0), ``largest`` (max |d|,
    found before the load: the unit compares no magnitudes, its threshold),
    and ``advance`` (one iteration in each clock it is high while an axis
    has steps left: the feed rate's tick); the unit drives ``following`` (an
    axis has steps left), ``busy`` (iterations left) and ``left`` (how many:
    the threshold T = max |d| less those done).  The magnitudes and signs
    are the driver's registers: a helix (``HelixPort``) reads the same."""

    def __init__(self, axes=AXES.default, coord_width=COORD_WIDTH):
        self.axes = axes
        self.load, self.advance, self.busy = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
        self.following = Signal(bool(0))
        for suffix in axis_suffixes(axes):
            setattr(self, f"magnitude_{suffix}", Signal(intbv(0)[coord_width:]))
            setattr(self, f"positive_{suffix}", Signal(bool(0)))
        self.largest = Signal(intbv(0)[coord_width:])
        self.left = Signal(intbv(0)[coord_width:])

    def magnitude(self, axis):
        """Axis ``axis``'s |d| (0 X, 1 Y, ...)."""
        return getattr(self, f"magnitude_{axis_suffixes(self.axes)[axis]}")

    def positive(self, axis):
        """Axis ``axis``'s direction (1: d >= 0)."""
        return getattr(self, f"positive_{axis_suffixes(self.axes)[axis]}")


class HelixPort:
    """The helix axes' port (``rtl/dda/dda_helix.py``): ``line``'s
    magnitudes and signs (a ``LinearPort``'s, read as each axis's |h| and
    direction), an arc's ``progress`` (``ArcProgress``) and, from the driver:
    ``build`` (one clock, with the arc's ``start``: take |``xs``|,
    |``ys``|, the arc's start in its plane, and the plane ``u``, ``v``, and
    build the products of the waiting helix from the magnitudes registered
    at that edge), ``area``
    (the waiting helix's AREA W, ``area_width(coord_width)`` bits, held from
    the clock after ``build`` to its ``load``), ``load`` (one clock: the
    waiting helix becomes the running one), ``advance`` (one iteration),
    ``alone`` (the arc has ended: each axis with steps left steps on every
    ``advance``).  The unit drives ``built`` (the waiting helix's products
    are complete: ``load`` may come) and ``following`` (an axis of the
    running helix has steps left)."""

    def __init__(self, line, progress, xs, ys, u, v):
        self.line, self.progress = line, progress
        self.axes = line.axes
        self.coord_width = len(xs)
        self.xs, self.ys, self.u, self.v = xs, ys, u, v
        self.build, self.load, self.advance, self.alone = (Signal(bool(0)) for _ in range(4))
        self.area = Signal(intbv(0)[area_width(self.coord_width):])
        self.built, self.following = Signal(bool(1)), Signal(bool(0))


def axis_index_bits(axes):
    """Bits of an axis index on a card of ``axes`` axes (1 for two axes)."""
    return max(1, (axes - 1).bit_length())


class AxesCommand:
    """What the sequencer gives the N-axis interpolator (``rtl/dda/dda_axes.py``)
    beside ``DdaPort``, read in the clock of ``DdaPort.start`` like the rest:
    on a card of more than two axes, the plane ``u``, ``v`` (axis indices:
    an arc's (x, y) outputs step axes u and v; a card of two axes turns arcs
    in X, Y only), each axis's signed displacement (``delta_<axis>``,
    ``coord_width`` bits) of a LINE (the line runs through ``dda_linear``;
    on two axes a line is ``DdaPort``'s (``xe``, ``ye``)) or of an ARC's
    helix (0 on the axes it does not move), and an ARC's ``area`` (AREA W,
    ``area_width(coord_width)`` bits; 0: no helix), and ``largest``: a LINE's largest
    |displacement| (its iteration count T), which the sequencer finds as the
    operands arrive so that no comparison of the axes waits for the start
    (``rtl/regs/axis_operands.py``; of an ARC it is not read)."""

    def __init__(self, axes=AXES.default, coord_width=COORD_WIDTH):
        self.axes = axes
        if axes > 2:
            self.largest = Signal(intbv(0)[coord_width:])
            bits = axis_index_bits(axes)
            self.u, self.v = Signal(intbv(0)[bits:]), Signal(intbv(1)[bits:])
            self.area = Signal(intbv(0)[area_width(coord_width):])
            low, high = -(1 << (coord_width - 1)), 1 << (coord_width - 1)
            for suffix in axis_suffixes(axes):
                setattr(self, f"delta_{suffix}", Signal(intbv(0, min=low, max=high)))

    def delta(self, axis):
        """Axis ``axis``'s displacement of a LINE (cards of more than two axes)."""
        return getattr(self, f"delta_{axis_suffixes(self.axes)[axis]}")
