"""The card's interpolator over N axes: the arc DDA in any plane, and the N-axis line."""
from myhdl import Signal, always_comb, always_seq, block, concat, intbv

from rtl.dda.dda_helix import dda_helix
from rtl.dda.dda_linear import dda_linear
from rtl.dda_arc import dda_arc
from rtl.interfaces import AxesCommand, AxisPulses, DdaPort, HelixPort, LinearPort, card_reset, named

# the command lines the arc DDA reads as the sequencer drives them
_SHARED = ("line", "variant", "lambda_shift", "acc_bits", "ccw", "blend", "xs", "ys", "xe", "ye")


@block
def dda_axes(clock, reset, cmd, axes_cmd, steps):
    """The interpolator of a card of N axes (``steps.axes``), one port to the sequencer.

    Ports: ``cmd`` (``DdaPort``, as ``dda_arc`` takes it: ``start`` with the
    command lines, ``advance``; ``ready``, ``busy``, ``done``, ``error``,
    ``quadrant``, ``stop_left``, ``iterate``), ``axes_cmd``
    (``AxesCommand``: the plane, a LINE's or helix's displacements, an ARC's
    AREA; read with ``start``), ``steps`` (``AxisPulses`` of N axes).
    Parameters: none; widths and variants from ``cmd``.

    The arc DDA (``dda_arc``, unchanged) runs every ARC in its (u, v)
    coordinates; ``_plane_queue`` keeps the plane of the move it runs and of
    the one it sets up meanwhile, and ``_route_axis`` puts its x outputs on
    axis u, its y outputs on axis v (STEP and DIR).  On two axes it is
    ``dda_arc`` alone: arcs in X, Y only (a reversed plane would cost the
    two-axis card its area), lines on X, Y.  On more axes a LINE goes to ``dda_linear``
    (``_line_queue``: its magnitudes wait in the line unit's port until the
    moves before it have ended, then ``load``): the next ``advance`` after
    the last iteration of the move before iterates it, so chained lines and
    arcs leave no gap, exactly as chained arcs.  An ARC started while a line
    runs is set up meanwhile and taken by the arc DDA's run, which gets no
    ``advance`` until the line has ended.  ``stop_left``: the running
    line's iterations left (all ones while it blends), the arc DDA's
    otherwise; ``error`` of an arc rejected while a line runs comes when
    the line has ended, and holds ``ready`` low so that nothing starts
    after it.  A helix (an ARC with AREA W not 0) puts its other axes in
    ``dda_helix`` (``models.helix_area.AreaFollower``): their products
    build while the arc sets up, they load once its arc is the arc DDA's
    only or running move and step in the arc's iterations (``iterate``,
    following its decision, ``progress``); the move's ``done`` comes when
    the arc and every axis have ended, and axes still moving after the arc
    (a W larger than the arc's) go on at the feed's ``advance`` while the
    arc DDA waits.

        clock    _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        advance  _/~~~\\___/~~~\\___/~~~\\_     last line iteration, then the arc's first
        step_z   _____/~~~\\_______________     (the line's)
        load     _________/~~~\\___________     the next line waits for the arc: not yet
        step_x   _____________________/~~~     (the arc's u = X)
    """
    axes = steps.axes
    if axes_cmd.axes != axes:
        raise ValueError(f"dda_axes: axes_cmd of {axes_cmd.axes} axes, steps of {axes}")
    if axes == 2:
        # two axes: the arcs turn in X, Y only (the sequencer refuses another plane), the lines are the DDA's
        return dda_arc(clock, reset, cmd, steps)
    arc_steps = AxisPulses(2)
    u_run, v_run = Signal(intbv(0)[len(axes_cmd.u):]), Signal(intbv(1)[len(axes_cmd.v):])
    arc = DdaPort(cmd.coord_width, cmd.variants, progress=True)
    for name in _SHARED:
        setattr(arc, name, getattr(cmd, name))
    line = LinearPort(axes, cmd.coord_width)
    helix = HelixPort(line, arc.progress, cmd.xs, cmd.ys, axes_cmd.u, axes_cmd.v)
    moves = Signal(intbv(0, min=0, max=3))   # moves in the arc DDA: started and not ended
    line_steps, helix_steps = AxisPulses(axes), AxisPulses(axes)
    units = [dda_arc(clock, reset, arc, arc_steps),
             _plane_queue(clock, reset, arc, axes_cmd, u_run, v_run, moves),
             named("linear", dda_linear(clock, reset, line, line_steps)),
             named("helix", dda_helix(clock, reset, helix, helix_steps)),
             _line_queue(clock, reset, cmd, axes_cmd, arc, line, helix, moves)]
    units += [named(f"route_{axis}", _route_axis(arc_steps, u_run, v_run, axis, line_steps.step(axis),
                                                 line_steps.dir(axis), helix_steps.step(axis), helix_steps.dir(axis),
                                                 steps.step(axis), steps.dir(axis)))
              for axis in range(axes)]
    return units


@block
def _plane_queue(clock, reset, arc, axes_cmd, u_run, v_run, moves):
    """The plane (``u_run``, ``v_run``) of the move the arc DDA runs: a move's
    plane is taken at its ``start``, and becomes the running one then if no
    other move is in the arc DDA (or the one there ends in that clock), else
    at the ``done`` of the one before it.  A rejected move (``error``) ends
    without ``done``: nothing else is in the arc DDA then.  ``moves``: the
    moves in the arc DDA (started, not ended), 0 to 2."""
    u_next, v_next = Signal(intbv(0)[len(u_run):]), Signal(intbv(1)[len(v_run):])

    @always_seq(clock.posedge, reset=reset)
    def follow():
        held = intbv(0, min=0, max=3)
        if not arc.error:
            held[:] = moves
        if arc.done and held != 0:
            held[:] = held - 1
        if arc.start:
            moves.next = held + 1
            if held == 0:
                u_run.next = axes_cmd.u
                v_run.next = axes_cmd.v
            else:
                u_next.next = axes_cmd.u
                v_next.next = axes_cmd.v
        else:
            moves.next = held
            if arc.done and moves == 2:
                u_run.next = u_next
                v_run.next = v_next

    return follow


@block
def _route_axis(arc_steps, u_run, v_run, axis, line_step, line_dir, helix_step, helix_dir, step, direction):
    """Axis ``axis``'s ``step`` and ``direction``: the arc DDA's x outputs when
    it is the plane's u, its y outputs when it is v, the helix unit's
    (``helix_step``, ``helix_dir``) when it steps, the line unit's
    (``line_step``, ``line_dir``) otherwise."""

    @always_comb
    def route():
        step.next = ((arc_steps.step_x and u_run == axis) or (arc_steps.step_y and v_run == axis) or line_step
                     or helix_step)
        direction.next = line_dir
        if arc_steps.step_x and u_run == axis:
            direction.next = arc_steps.dir_x
        elif arc_steps.step_y and v_run == axis:
            direction.next = arc_steps.dir_y
        elif helix_step:
            direction.next = helix_dir

    return route


@block
def _line_queue(clock, reset, cmd, axes_cmd, arc, line, helix, moves):
    """A LINE, or an ARC's helix (``axes_cmd.area`` not 0), started on
    ``cmd`` waits in ``line``'s magnitudes and signs (``_line_magnitude``),
    ``largest`` (the sequencer's, found as the operands arrived) and
    ``helix.area`` until its unit is free, then loads: a line into
    ``dda_linear`` once the moves before it have ended (the arc DDA idle
    too), a helix into ``dda_helix`` once its products are built and its
    arc is the arc DDA's only move (``moves``) or becomes its running one
    (the ``done`` of the one before).  The rest of ``cmd``: the arc DDA's,
    merged with the units' (see ``dda_axes``).  A helix's axes (``own``)
    iterate in its arc's iterations (``arc.iterate``); those with steps
    left when the arc ends go on ``alone`` at the feed's ``advance``, the
    arc DDA waiting, and the move's ``done`` comes when they end."""
    waiting, waiting_helix, waiting_blend, blend, last, loaded, stale = (Signal(bool(0)) for _ in range(7))
    own, alone, following = (Signal(bool(0)) for _ in range(3))
    take, load_line, load_helix = (Signal(bool(0)) for _ in range(3))
    live_error = Signal(bool(0))
    stop_width = len(cmd.stop_left)
    pad = len(cmd.stop_left) - len(line.left)
    magnitudes = [_line_magnitude(clock, take, axes_cmd.delta(axis), line.magnitude(axis), line.positive(axis))
                  for axis in range(line.axes)]

    @always_comb
    def hand_on():
        take.next = cmd.start and (cmd.line or axes_cmd.area != 0)
        arc.start.next = cmd.start and not cmd.line
        following.next = line.following or helix.following
        load_line.next = waiting and not waiting_helix and not following and not arc.busy
        load_helix.next = (waiting and waiting_helix and not following and not alone and helix.built
                           and (moves == 1 or arc.done))
        arc.advance.next = cmd.advance and not line.busy and not alone and not (waiting and waiting_helix and moves == 1)
        line.advance.next = cmd.advance
        helix.advance.next = (own and arc.iterate) or (alone and cmd.advance)

    @always_comb
    def loading():
        line.load.next = load_line
        helix.load.next = load_helix
        helix.build.next = take and not cmd.line
        helix.alone.next = alone

    @always_seq(clock.posedge, reset=reset)
    def queue():
        if take:
            waiting.next = 1
            waiting_helix.next = not cmd.line
            waiting_blend.next = cmd.blend
            helix.area.next = axes_cmd.area
            line.largest.next = axes_cmd.largest
        elif load_line or load_helix or (waiting_helix and live_error):
            waiting.next = 0
        if load_line or load_helix:
            blend.next = waiting_blend
        # the line's last iteration, with its last steps (the unit registers them at this edge)
        last.next = line.advance and line.left == 1
        loaded.next = load_line
        # an arc's error stays until the arc DDA's next start: a line started since has seen it
        if cmd.start:
            stale.next = cmd.line
        # a helix's axes are its arc's until it ends; those still moving then go on alone
        if load_helix:
            own.next = 1
        elif arc.done:
            own.next = 0
        if own and arc.done and helix.following:
            alone.next = 1
        elif not helix.following:
            alone.next = 0

    @always_comb
    def status():
        live_error.next = arc.error and not stale
        cmd.ready.next = arc.ready and not waiting and not live_error
        cmd.busy.next = arc.busy or following or waiting
        cmd.done.next = ((arc.done and not (own and helix.following)) or last or (loaded and line.left == 0)
                         or (alone and not helix.following))
        cmd.error.next = live_error and not following
        cmd.iterate.next = arc.iterate
        cmd.quadrant.next = arc.quadrant
        cmd.stop_left.next = arc.stop_left
        if alone:   # a helix's axes after its arc (their iterations left are not counted)
            cmd.stop_left.next = 0
            if blend:
                cmd.stop_left.next = intbv(-1)[stop_width:]
        elif line.busy or last:   # the line runs, or its last steps leave (0 left)
            cmd.stop_left.next = intbv(-1)[stop_width:]
            if not blend:
                cmd.stop_left.next = concat(intbv(0)[pad:], line.left)

    return magnitudes, hand_on, loading, queue, status


@block
def _line_magnitude(clock, take, delta, magnitude, positive):
    """At ``take`` a LINE's ``delta`` of one axis as the line unit takes it: |delta| and its sign."""

    @always_seq(clock.posedge, reset=None)
    def split():
        if take:
            positive.next = delta >= 0
            if delta < 0:
                magnitude.next = -delta
            else:
                magnitude.next = delta

    return split


def dda_axes_ports(axes, coord_width=None, variants=None):
    """Fresh ports of ``dda_axes`` for conversion or a bench: ``axes`` axes."""
    options = {name: value for name, value in (("coord_width", coord_width), ("variants", variants))
               if value is not None}
    cmd = DdaPort(**options)
    return dict(clock=Signal(bool(0)), reset=card_reset(), cmd=cmd, axes_cmd=AxesCommand(axes, cmd.coord_width),
                steps=AxisPulses(axes))
