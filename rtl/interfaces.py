"""Signal bundles shared between the card's blocks.

Every interface is a plain class whose attributes are MyHDL ``Signal``s.
Widths are constructor arguments.  When a block with an interface argument is
the top of a conversion, MyHDL names each port ``<argument>_<attribute>``.

Shared PCI lines are split into ``*_in`` / ``*_out`` / ``*_oe`` so that the
cores co-simulate and convert cleanly; only the pad wrapper at the top level
has tri-states.  All PCI ``*_out`` values keep the bus polarity (active-low
lines are 0 when asserted).
"""
from myhdl import ResetSignal, Signal, TristateSignal, intbv, modbv

from rtl import instructions as isa
from rtl import registers as regmap
from rtl.dda_build import (COORD_WIDTH, DEFAULT_VARIANTS, PRECISE, accumulator_width, check_coord_width,
                            left_width, threshold_width, variant_set)


class PciBus:
    """The target's view of a 32-bit PCI bus.

    ``*_in`` is what the target samples from the line, ``*_out`` what it would
    drive and ``*_oe`` whether it drives.  SERR# and INTA# are open-drain: the
    target drives them low (``*_oe`` high, ``*_out`` low) or not at all.
    """

    def __init__(self):
        self.ad_in = Signal(intbv(0)[32:])
        self.ad_out = Signal(intbv(0)[32:])
        self.ad_oe = Signal(bool(0))
        self.cbe_in = Signal(intbv(0xF)[4:])
        self.par_in = Signal(bool(0))
        self.par_out = Signal(bool(0))
        self.par_oe = Signal(bool(0))
        self.frame_in = Signal(bool(1))
        self.irdy_in = Signal(bool(1))
        self.idsel_in = Signal(bool(0))
        self.trdy_out = Signal(bool(1))
        self.trdy_oe = Signal(bool(0))
        self.devsel_out = Signal(bool(1))
        self.devsel_oe = Signal(bool(0))
        self.stop_out = Signal(bool(1))
        self.stop_oe = Signal(bool(0))
        self.perr_out = Signal(bool(1))
        self.perr_oe = Signal(bool(0))
        self.serr_out = Signal(bool(1))
        self.serr_oe = Signal(bool(0))
        self.inta_out = Signal(bool(1))
        self.inta_oe = Signal(bool(0))


class LocalBus:
    """The PCI target's back-end bus (one per card, both BARs).

    A request (``we`` or ``re``) with ``space``, ``addr``, ``be`` and, for a
    write, ``wdata`` is held until the clock edge at which the back end answers
    ``ready`` (the transfer happens at that edge; ``rdata`` is valid while
    ``ready`` is high) or ``retry`` (nothing happens: the back end cannot serve
    the request now and the target terminates with retry or disconnect).

    ``space`` 0 is the I/O BAR (function registers), 1 the memory BAR (data
    FIFO window).  ``addr`` is the byte offset inside the BAR, dword aligned.
    ``be`` are active-high byte enables.  ``write`` gives the direction of a
    request (1: ``we``) from the target's flip-flops, ahead of ``we``/``re``:
    a back end answers from it, ``space`` and its own state, so that the
    target's request logic and its reaction to the answer do not form one
    combinational loop through the back end.

    ``room`` (from the back end's flip-flops) is the back end's promise for
    space 1: while it is high, the next ``ROOM_PLACES`` writes to space 1
    will be answered ``ready``, not ``retry`` (possibly after wait clocks),
    whatever else happens.  A promise is never taken back: only the writes
    the back end takes use it up (``room`` may fall then), and a back end
    answers ``retry`` to a space-1 write only when no promise is open.  The
    target acknowledges a posted memory-write data phase on the bus only
    while ``room`` is high: the dwords it may still hold and the one it
    acknowledges are never more than ``ROOM_PLACES``.

        clock    _/~\\_/~\\_/~\\_/~\\_
        we       __/~~~~~~~~~~~\\___
        addr     --<  A0 >< A1 >---
        ready    ________/~~~~~\\___     A0 waits one clock, A1 none
        room     ~~~~~~~~~~~~~\\____     space 1 with four places at first: two left
    """

    ROOM_PLACES = 3   # writes a high ``room`` promises: what the target may have in flight

    def __init__(self, addr_width=16):
        self.addr_width = addr_width
        self.space = Signal(bool(0))
        self.addr = Signal(intbv(0)[addr_width:])
        self.be = Signal(intbv(0)[4:])
        self.wdata = Signal(intbv(0)[32:])
        self.we = Signal(bool(0))
        self.re = Signal(bool(0))
        self.write = Signal(bool(0))
        self.rdata = Signal(intbv(0)[32:])
        self.ready = Signal(bool(0))
        self.retry = Signal(bool(0))
        self.room = Signal(bool(0))


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
    ``busy`` (a move is being set up or run), ``done`` (one-clock pulse when a
    move has ended on its end point, with its last step), ``error`` (a move
    was rejected: end not within one step of the start radius, radius too
    large, a centre point, acc_bits + lambda_shift too wide, a variant the
    card was not built with; raised once the moves before it have ended,
    held until the next ``start``), ``quadrant`` (of the moving point, 0..3
    for I..IV), ``stop_left`` (a lower bound of the iterations left before
    the path stops: those of the running move when it was started with
    ``blend`` = 0, the all-ones value while the running move blends or none
    runs; the feed-rate ramp decelerates on it).

    Build parameters (``rtl/parameters.py``), read by every block that takes
    the port: ``coord_width`` (``rtl.dda_build.check_coord_width``: the
    card's range, or narrower for the interpolator alone) and ``variants``
    (a set of variant codes; given as the parameter's choice,
    ``improved,precise`` or ``all``, or as its codes).
    """

    def __init__(self, coord_width=COORD_WIDTH, variants=DEFAULT_VARIANTS):
        self.coord_width = check_coord_width(coord_width)
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


class DdaPlan:
    """What the DDA's setup stage (``rtl/dda_setup.py``) knows of the move it prepared,
    for the check (``rtl/dda_check.py``); every signal is a setup register.

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
    """The setup stage's square root (``rtl/dda_root.py``).

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


class DdaMove:
    """The checked move, from the check (``rtl/dda_check.py``) to the run
    (``rtl/dda_run.py``), and the handshake that hands it over.

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
    """The run's iteration as its units share it (``rtl/dda_run.py`` drives it).

    From the run: ``pending`` (the second clock of an iteration: the
    registered decision is applied at its end), the decision ``step_x``,
    ``step_y``, ``finished``, ``new_piece`` (the step ends a quadrant
    piece: the next begins when it is applied), the move's ``line`` and ``blend``,
    ``x_inward`` and the magnitudes ``mag_x``, ``mag_y``, all registers.
    To the run: ``inward_near`` and ``outward_near`` (the precise mode's
    choice, ``rtl/dda_nearest.py``) and ``last`` (a line's last iteration,
    ``rtl/dda_left.py``).
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
    """Step requests for the two axes: ``step_*`` is high for one clock per
    step, ``dir_*`` (1: positive direction) is valid in that clock."""

    def __init__(self):
        self.step_x = Signal(bool(0))
        self.step_y = Signal(bool(0))
        self.dir_x = Signal(bool(0))
        self.dir_y = Signal(bool(0))


def card_reset():
    """The card's reset: PCI RST#, asynchronous, active low."""
    return ResetSignal(1, active=0, isasync=True)


class MotorPins:
    """The machine's pins: STEP and DIR of the two axes as they leave the
    card (levels, straight from flip-flops; ``dir_*`` already carries the
    polarity), ``drive_enable`` (out, from a flip-flop: the drives may
    run), and the machine's inputs, in the order of ``MACHINE_INPUTS``
    (E-stop, the limit switches, the home switches: pin levels as wired,
    asynchronous; ``rtl/input_filter.py`` conditions them)."""

    def __init__(self):
        self.step_x = Signal(bool(0))
        self.dir_x = Signal(bool(0))
        self.step_y = Signal(bool(0))
        self.dir_y = Signal(bool(0))
        self.drive_enable = Signal(bool(0))
        for name in MACHINE_INPUTS:
            setattr(self, name, Signal(bool(0)))

    def inputs(self):
        """The input pins, in the order of ``MACHINE_INPUTS``."""
        return [getattr(self, name) for name in MACHINE_INPUTS]


# The machine's inputs, bit n of INPUT_POLARITY and MACHINE_STATUS is input n.
MACHINE_INPUTS = tuple(f.name.lower() for f in regmap.register("INPUT_POLARITY").fields)
INPUT_ESTOP, INPUT_LIMIT_POS_X, INPUT_LIMIT_NEG_X, INPUT_LIMIT_POS_Y, INPUT_LIMIT_NEG_Y = range(5)


class PciPins:
    """The card's PCI pins, as the top level's ports (bus polarity).

    Every line is a ``TristateSignal``, as on the bus: an agent drives it or
    leaves it (the bench's bus model resolves the drivers and the pull-ups),
    and every pin can be the ``PACKAGE_PIN`` of an iCE40 I/O cell.  The
    target drives AD, PAR, TRDY#, DEVSEL#, STOP#, PERR#, SERR# and INTA#;
    it only reads C/BE#, FRAME#, IRDY# and IDSEL.  Only ``rtl/pci_pads.py``
    joins these to a ``PciBus``.
    """

    def __init__(self):
        self.ad = TristateSignal(intbv(0)[32:])
        self.cbe = TristateSignal(intbv(0xF)[4:])
        self.par = TristateSignal(bool(0))
        self.frame = TristateSignal(bool(1))
        self.irdy = TristateSignal(bool(1))
        self.idsel = TristateSignal(bool(0))
        self.trdy = TristateSignal(bool(1))
        self.devsel = TristateSignal(bool(1))
        self.stop = TristateSignal(bool(1))
        self.perr = TristateSignal(bool(1))
        self.serr = TristateSignal(bool(1))
        self.inta = TristateSignal(bool(1))


class TargetControlNext:
    """Next state and control lines of the PCI target (``rtl/pci_slave.py``)
    for one case of the FRAME# and IRDY# pins; ``idle`` is the state enum's
    idle item.  The target computes one bundle per case from registers only,
    and the pins choose among them."""

    FIELDS = ("state", "trdy", "stop", "devsel", "drive", "ad_oe")

    def __init__(self, idle):
        self.state = Signal(idle)
        self.trdy = Signal(bool(1))
        self.stop = Signal(bool(1))
        self.devsel = Signal(bool(1))
        self.drive = Signal(bool(0))
        self.ad_oe = Signal(bool(0))



class ConfigSpace:
    """The PCI target's configuration header (``rtl/pci_config.py``) and the
    transaction logic around it (``rtl/pci_slave.py``).

    To the header: ``write`` (a configuration write data phase completed at
    the last edge), ``index`` (its dword, 0..63), ``data`` and ``cbe_n`` (AD
    and C/BE# of that phase, bus polarity), the Status events
    ``target_abort`` (the target signals one now), ``system_error`` (SERR#
    driven) and ``parity_error`` (a parity error was detected at the last
    edge), and ``irq`` (Status.Interrupt Status).  From it: the Command bits
    the target obeys, the BARs as written (``bar0`` 16 bits of PC I/O space,
    ``bar1`` 32), and ``rdata``, the dword ``index`` names as a configuration
    read returns it."""

    def __init__(self):
        self.write = Signal(bool(0))
        self.index = Signal(intbv(0)[6:])
        self.data = Signal(intbv(0)[32:])
        self.cbe_n = Signal(intbv(0xF)[4:])
        self.target_abort = Signal(bool(0))
        self.system_error = Signal(bool(0))
        self.parity_error = Signal(bool(0))
        self.irq = Signal(bool(0))
        self.io_enable = Signal(bool(0))
        self.mem_enable = Signal(bool(0))
        self.parity_response = Signal(bool(0))
        self.serr_enable = Signal(bool(0))
        self.interrupt_disable = Signal(bool(0))
        self.bar0 = Signal(intbv(0)[16:])
        self.bar1 = Signal(intbv(0)[32:])
        self.rdata = Signal(intbv(0)[32:])


# Widths of the bundles below, each from the table that defines it.
def _header_width(op_name, field_name):
    return {name: width for name, _, width, _ in isa.BY_NAME[op_name].header_fields}[field_name]


SET_INDEX_BITS = _header_width("SET", "INDEX")
MARK_TAG_BITS = _header_width("MARK", "TAG")
ERROR_BITS = regmap.register("STATUS").field("ERROR").width
PULSE_COUNT_BITS = regmap.register("PULSE_COUNT_X").width
TIMING_BITS = regmap.register("STEP_WIDTH").width


def _adopt(bundle, given, **fresh):
    """Set the signals ``fresh`` on ``bundle``, each one replaced by the signal
    of its name in ``given`` (the card wires signals it already has into a
    bundle); a given signal must be as wide as the fresh one."""
    unknown = set(given) - set(fresh)
    if unknown:
        raise TypeError(f"{type(bundle).__name__} has no signal {', '.join(sorted(unknown))}")
    for name, signal in fresh.items():
        if name in given:
            if len(given[name]) != len(signal):
                raise ValueError(f"{type(bundle).__name__}.{name}: {len(signal)} bits, not {len(given[name])}")
            signal = given[name]
        setattr(bundle, name, signal)


class FifoRead:
    """The read side of the data FIFO: the FIFO drives ``dout`` (the word
    popped the clock before) and ``empty``; the reader (the sequencer) drives
    ``pop`` (one word per clock while high)."""

    def __init__(self, **given):
        _adopt(self, given, dout=Signal(intbv(0)[32:]), empty=Signal(bool(1)), pop=Signal(bool(0)))


class SequencerControl:
    """The sequencer's controls and status, seen from the registers.

    The registers drive ``enable`` (CONTROL.ENABLE outside direct mode),
    ``clear`` (COMMAND.SOFT_RESET, one clock) and ``clear_error`` (COMMAND.CLEAR_ERROR,
    one clock); the sequencer drives ``error_code`` (STATUS.ERROR), ``busy``
    (a command runs or is queued), ``motion_run`` (a path is under way: the
    feed-rate ramp runs) and ``discard_on_clear`` (the FIFO empties itself on
    the next CLEAR_ERROR).
    """

    def __init__(self, **given):
        _adopt(self, given, enable=Signal(bool(0)), clear=Signal(bool(0)), clear_error=Signal(bool(0)),
               error_code=Signal(intbv(0)[ERROR_BITS:]), busy=Signal(bool(0)), motion_run=Signal(bool(0)),
               discard_on_clear=Signal(bool(0)))


class PulseCommand:
    """The PULSE command's seam: the sequencer drives ``load`` (one clock) with
    the signed counts ``count_x``/``count_y``; the direct pulse generators
    drive ``busy`` (pulses still to go) and the pulse outputs ``outputs_busy``
    (a step request is pending or the last step has not yet left the pins)."""

    def __init__(self, **given):
        bounds = dict(min=-(1 << (PULSE_COUNT_BITS - 1)), max=1 << (PULSE_COUNT_BITS - 1))
        _adopt(self, given, load=Signal(bool(0)), count_x=Signal(intbv(0, **bounds)),
               count_y=Signal(intbv(0, **bounds)), busy=Signal(bool(0)), outputs_busy=Signal(bool(0)))


class SetPort:
    """The SET command's write port into the registers: the sequencer drives
    ``strobe`` (one clock) with ``index`` (the register's SET index) and
    ``value``; the register of that index takes ``value`` like a bus write."""

    def __init__(self, **given):
        _adopt(self, given, strobe=Signal(bool(0)), index=Signal(intbv(0)[SET_INDEX_BITS:]),
               value=Signal(intbv(0)[32:]))


class MarkPort:
    """The MARK command's report: the sequencer drives ``strobe`` (one clock,
    when the MARK is reached) with ``tag``; the registers latch it in
    MARK_TAG and raise INT_STATUS.MARK."""

    def __init__(self, **given):
        _adopt(self, given, strobe=Signal(bool(0)), tag=Signal(intbv(0)[MARK_TAG_BITS:]))


class RegisterBus:
    """The function registers' side of the I/O BAR, driven by ``regs_fifo``:
    ``addr`` (byte offset of reads, straight from the local bus),
    ``write_addr`` (byte offset of the write), ``write`` (an I/O write
    happens at this clock edge), ``byte_mask`` (the write's byte enables as
    a bit mask) and ``wdata``; every ``reg_word`` reads them."""

    def __init__(self, addr_width=16, **given):
        _adopt(self, given, addr=Signal(intbv(0)[addr_width:]), write_addr=Signal(intbv(0)[addr_width:]),
               write=Signal(bool(0)), byte_mask=Signal(intbv(0)[32:]), wdata=Signal(intbv(0)[32:]))


class RegisterWord:
    """One function register's signals to the hardware, as wide as the
    register ``spec`` (a ``rtl.registers.Register``): the hardware drives
    ``hw`` (RO and WP: what reads return; W1C: bits it sets; W1S: bits it
    clears; ``hw_reset``: its value before the hardware drives it, the build
    word of a capability register); the register drives ``value``
    (RW/W1C/W1S: the register; WP: the last value written) and ``strobe``
    (WP: one clock per write)."""

    def __init__(self, spec, hw_reset=0):
        self.spec = spec
        self.hw = Signal(intbv(hw_reset)[spec.width:])
        self.value = Signal(intbv(spec.reset)[spec.width:])
        self.strobe = Signal(bool(0))


class ReadChain:
    """One link of the registers' read and clamp chain: each ``reg_word``
    drives the link after it with the link before it, its read data OR'ed
    into ``data`` when the bus reads it, and its one-clock flag into
    ``clamped`` when a write to it was out of range."""

    def __init__(self):
        self.data = Signal(intbv(0)[32:])
        self.clamped = Signal(bool(0))


class PulseControl:
    """Settings and status of the pulse outputs (``rtl/pulse_out.py``).

    The registers drive ``clear`` (drop the queue), ``clear_position``
    (zero the positions), ``width``, ``setup`` and ``hold`` (STEP_WIDTH,
    DIR_SETUP, DIR_HOLD, in clocks) and ``polarity_x``/``polarity_y``
    (DIR_POLARITY); the pulse outputs drive ``ready`` (the queue takes the
    steps on their way) and ``active`` (a step is queued or on the pins).
    """

    def __init__(self, **given):
        _adopt(self, given, clear=Signal(bool(0)), clear_position=Signal(bool(0)),
               width=Signal(intbv(1)[TIMING_BITS:]), setup=Signal(intbv(1)[TIMING_BITS:]),
               hold=Signal(intbv(1)[TIMING_BITS:]), polarity_x=Signal(bool(0)), polarity_y=Signal(bool(0)),
               ready=Signal(bool(1)), active=Signal(bool(0)))


class StepPositions:
    """The step counters of the two axes, driven by the pulse outputs:
    ``x``, ``y`` (signed 32 bits, wrapping), counted at the edge where a
    STEP pin rises."""

    def __init__(self):
        self.x = Signal(modbv(0, min=-(1 << 31), max=1 << 31))
        self.y = Signal(modbv(0, min=-(1 << 31), max=1 << 31))


class RampSettings:
    """The feed rate's settings, driven by the registers FEED_RATE
    (``target``), RAMP_START (``ramp_start``) and RAMP_STEP (``ramp_step``);
    the feed rate (``rtl/feed_rate.py``) reads them."""

    def __init__(self, **given):
        def rate(name):
            spec = regmap.register(name)
            return Signal(intbv(spec.reset)[spec.width:])
        _adopt(self, given, target=rate("FEED_RATE"), ramp_start=rate("RAMP_START"), ramp_step=rate("RAMP_STEP"))


class FeedPort:
    """The feed rate's seam with the motion: the card drives ``run`` (a path
    is under way) and ``hold`` (the pulse outputs are full), the DDA
    ``stop_left`` (``DdaPort.stop_left`` of ``coord_width``); the feed rate
    drives ``tick`` (one clock per iteration)."""

    def __init__(self, coord_width=COORD_WIDTH, **given):
        _adopt(self, given, run=Signal(bool(0)), hold=Signal(bool(0)), stop_left=DdaPort(coord_width).stop_left,
               tick=Signal(bool(0)))


class DirectPulseCommand:
    """One axis's direct pulses, seen from the card: it drives ``load`` (one
    clock) with ``count`` (signed pulses, the sign their direction),
    ``period`` (clocks between pulses, PULSE_PERIOD_*) and ``clear`` (soft
    reset); the generator drives ``remaining`` (pulses still to go) and
    ``busy`` (from ``load`` until the last request)."""

    def __init__(self, **given):
        bounds = dict(min=-(1 << (PULSE_COUNT_BITS - 1)), max=1 << (PULSE_COUNT_BITS - 1))
        period = regmap.register("PULSE_PERIOD_X")
        _adopt(self, given, load=Signal(bool(0)), count=Signal(intbv(0, **bounds)),
               period=Signal(intbv(period.reset)[period.width:]), clear=Signal(bool(0)),
               remaining=Signal(intbv(0)[PULSE_COUNT_BITS:]), busy=Signal(bool(0)))


class StepRequest:
    """One axis's step requests into the pulse outputs: the source drives
    ``step`` (one clock per step) with ``dir`` (1: positive); the pulse
    outputs drive ``ready`` (they take a step now)."""

    def __init__(self, **given):
        _adopt(self, given, step=Signal(bool(0)), dir=Signal(bool(0)), ready=Signal(bool(1)))


class TargetState:
    """What the PCI target's next-state logic (``rtl/pci_control.py``) reads:
    the target's registers and its back end's answer, all settled before the
    FRAME# and IRDY# pins arrive.  ``state`` is the state enum (``idle`` its
    idle item); the target wires in the signals it has (``given``).

    Transaction: ``state``, ``single`` (one data phase only), ``at_last`` /
    ``before_last`` (the data phase is at / one before BAR1's last dword),
    ``is_read``, ``is_config``, ``first_phase``, ``fetching`` (reads: more
    dwords may be requested), ``timeout`` (the latency budget is spent),
    ``fatal`` (target abort now).  Its lines as driven: ``trdy_q``,
    ``stop_q``, ``devsel_q``, ``drive`` (DEVSEL#, TRDY#, STOP# driven),
    ``ad_oe``.  Claim: ``claim``, ``claim_config``, ``claim_io``,
    ``read_command`` (C/BE#[0] low in the address phase).  Data: ``b_valid``
    (the skid register holds a dword), ``burst_got`` (read data arrive in a
    burst), ``buffered`` (posted dwords held after this edge), ``room`` (the
    back end's write credit), ``hold_got``, ``hold_accepted``, ``hold_retry``
    (the first request answered read data, write taken, retry)."""

    BOOLS = ("single", "at_last", "before_last", "is_read", "is_config", "first_phase", "fetching",
             "timeout", "fatal", "trdy_q", "stop_q", "devsel_q", "drive", "ad_oe", "claim",
             "claim_config", "claim_io", "read_command", "b_valid", "burst_got", "room", "hold_got",
             "hold_accepted", "hold_retry")

    def __init__(self, idle, **given):
        _adopt(self, given, state=Signal(idle), buffered=Signal(intbv(0, min=0, max=4)),
               **{name: Signal(bool(0)) for name in self.BOOLS})



class TargetParity:
    """The PCI target's parity (``rtl/pci_parity.py``).

    From the target's registers: ``ad``, ``cbe`` (the input registers, bus
    polarity), ``frame_q`` / ``frame_qq`` (FRAME# one and two edges back),
    ``serr_enable``, ``parity_response`` (Command bits), ``write_done`` (the
    input register holds a completed write data phase), ``perr_q`` (PERR# as
    driven), ``ad_out`` and ``ad_out_parity_q`` (the AD output register and
    the parity it had one clock before).  To them: ``address_phase`` (the
    input register holds an address), ``ad_out_parity``, ``par_out`` (PAR as
    driven), and the next values the PAR pin decides: ``perr_next``,
    ``perr_oe_next``, ``serr_oe_next``, ``address_fault_next`` (address
    parity error, Parity Error Response set), ``parity_error_next`` (Status:
    a parity error was detected)."""

    def __init__(self, **given):
        _adopt(self, given, ad=Signal(intbv(0)[32:]), cbe=Signal(intbv(0xF)[4:]),
               frame_q=Signal(bool(1)), frame_qq=Signal(bool(1)), serr_enable=Signal(bool(0)),
               parity_response=Signal(bool(0)), write_done=Signal(bool(0)), perr_q=Signal(bool(1)),
               ad_out=Signal(intbv(0)[32:]), ad_out_parity_q=Signal(bool(0)),
               address_phase=Signal(bool(0)), ad_out_parity=Signal(bool(0)), par_out=Signal(bool(0)),
               perr_next=Signal(bool(1)), perr_oe_next=Signal(bool(0)), serr_oe_next=Signal(bool(0)),
               address_fault_next=Signal(bool(0)), parity_error_next=Signal(bool(0)))


class TargetBuffers:
    """The PCI target's data buffers (``rtl/pci_buffers.py``); ``idle`` is
    the state enum's idle item, the target wires in the signals it has.

    From the target: ``ad``, ``cbe`` (input registers, bus polarity),
    ``state``, ``is_read``, ``trdy_q``, ``first_phase``, ``space_mem``, ``got``
    (read data arrive at this edge), ``accepted`` (the back end takes a
    write at this edge), the back end's ``re``, ``ready``, ``rdata``, and the
    next values the IRDY# pin decides: ``b_valid_next``, ``wq_valid_next``,
    ``write_done_next``, ``config_write_next``.  The buffers' registers:
    ``b_valid`` (the skid register holds a dword), ``wq_valid`` (``ad``
    holds a posted dword), ``h_valid``/``h_data``/``h_be`` (head entry),
    ``s_valid``/``spare_data``/``s_be`` (second entry; ``spare_data`` is also
    the skid register), ``write_done_q``, ``config_write_q`` (``ad`` holds
    the data of a completed write / configuration write phase).  To the
    target: ``b_kept``, ``posting`` (conditions for the IRDY# pin's LUTs) and
    ``buffered`` (posted dwords held after this edge)."""

    def __init__(self, idle, **given):
        bools = ("is_read", "trdy_q", "first_phase", "space_mem", "got", "accepted", "re", "ready",
                 "b_valid_next", "wq_valid_next", "write_done_next", "config_write_next", "b_valid",
                 "wq_valid", "h_valid", "s_valid", "write_done_q", "config_write_q", "b_kept", "posting")
        _adopt(self, given, ad=Signal(intbv(0)[32:]), cbe=Signal(intbv(0xF)[4:]), state=Signal(idle),
               rdata=Signal(intbv(0)[32:]), h_data=Signal(intbv(0)[32:]), spare_data=Signal(intbv(0)[32:]),
               h_be=Signal(intbv(0)[4:]), s_be=Signal(intbv(0)[4:]), buffered=Signal(intbv(0, min=0, max=4)),
               **{name: Signal(bool(0)) for name in bools})


class TargetRequests:
    """The PCI target's request logic (``rtl/pci_requests.py``); ``idle`` is
    the state enum's idle item, ``width`` the bits of a dword address; the
    target wires in the signals it has.

    From the target's registers: ``req_addr`` (dword of the next request),
    ``state``, ``address_fault``, ``io_byte`` (AD[1:0] of an I/O access),
    ``cbe``, ``ad`` (input registers), ``first_pending``, ``is_config``,
    ``req_addr_stale``, ``is_read``, ``fetching``, ``b_valid``, ``trdy_q``,
    ``frame_q``, ``irdy_q``, ``h_valid``, ``wq_valid``, ``space_mem``,
    ``h_data``, ``h_be`` (as in ``TargetState`` and ``TargetBuffers``).  To
    the target: ``fatal`` (target abort now), ``first_ready``,
    ``fetch_more`` (the request's conditions without the state),
    ``draining`` (posted data wait for the back end), ``got``, ``accepted``,
    and the answers ``hold_got``, ``hold_accepted``, ``hold_retry``,
    ``burst_got``."""

    def __init__(self, idle, width, **given):
        bools = ("address_fault", "first_pending", "is_config", "req_addr_stale", "is_read", "fetching",
                 "b_valid", "trdy_q", "frame_q", "irdy_q", "h_valid", "wq_valid", "space_mem", "fatal",
                 "first_ready", "fetch_more", "draining", "got", "accepted", "hold_got", "hold_accepted",
                 "hold_retry", "burst_got")
        _adopt(self, given, req_addr=Signal(intbv(0)[width:]), state=Signal(idle),
               io_byte=Signal(intbv(0)[2:]), cbe=Signal(intbv(0xF)[4:]), ad=Signal(intbv(0)[32:]),
               h_data=Signal(intbv(0)[32:]), h_be=Signal(intbv(0)[4:]),
               **{name: Signal(bool(0)) for name in bools})


class InputConditioning:
    """The machine inputs' conditioning (``rtl/input_filter.py``).

    The card drives ``pins`` (the input pins as one vector, bit n the input
    n of ``MACHINE_INPUTS``), ``polarity`` (INPUT_POLARITY: 1 inverts that
    input, for switches active low), ``samples`` (INPUT_FILTER) and
    ``tick`` (INPUT_TICK, clocks per sample, >= 1); the filter drives
    ``raw`` (the pins after the two-flip-flop synchroniser, as wired),
    ``active`` (filtered, polarity applied: 1 active) and ``changed`` (one
    clock after an ``active`` bit changed)."""

    def __init__(self, **given):
        count = len(MACHINE_INPUTS)
        samples, tick = regmap.register("INPUT_FILTER"), regmap.register("INPUT_TICK")
        _adopt(self, given, pins=Signal(intbv(0)[count:]), polarity=Signal(intbv(0)[count:]),
               samples=Signal(intbv(samples.reset)[samples.width:]), tick=Signal(intbv(tick.reset)[tick.width:]),
               raw=Signal(intbv(0)[count:]), active=Signal(intbv(0)[count:]), changed=Signal(bool(0)))


class MachineGuard:
    """The machine guard's seam with the registers (``rtl/machine_guard.py``).

    The card drives ``active`` (the filtered inputs, ``InputConditioning``),
    ``drive_request`` (MACHINE_CONTROL.DRIVE_ENABLE), ``clear_stop``
    (COMMAND.CLEAR_STOP, one clock), ``watchdog_load`` (one clock per
    WATCHDOG write) with ``watchdog_timeout`` (its value, clocks; 0: off).
    The guard drives ``halt`` (no new STEP edge, no command, no direct
    pulse: stopped, or the E-stop input active), ``stopped`` (the latch),
    ``stop_event`` (one clock, as the latch sets), ``reason`` and ``limits``
    (STOP_REASON), ``drive_enable`` (the pin, from a flip-flop) and
    ``watchdog_left`` (clocks before the watchdog expires)."""

    def __init__(self, **given):
        reason, watchdog = regmap.register("STOP_REASON"), regmap.register("WATCHDOG")
        _adopt(self, given, active=Signal(intbv(0)[len(MACHINE_INPUTS):]), drive_request=Signal(bool(0)),
               clear_stop=Signal(bool(0)), watchdog_load=Signal(bool(0)),
               watchdog_timeout=Signal(intbv(0)[watchdog.width:]), halt=Signal(bool(0)),
               stopped=Signal(bool(0)), stop_event=Signal(bool(0)),
               reason=Signal(intbv(0)[reason.field("REASON").width:]),
               limits=Signal(intbv(0)[reason.field("LIMITS").width:]), drive_enable=Signal(bool(0)),
               watchdog_left=Signal(intbv(0)[watchdog.width:]))
