"""A helix's other axes: each follows the area its arc sweeps (docs/axes.md, ``models/helix_area.py``)."""
from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, concat, intbv, modbv

from models.helix_area import area_width
from rtl.interfaces import axis_suffixes, named


@block
def dda_helix(clock, reset, helix, steps):
    """The axes of a helix, moving with the area its arc sweeps, exactly as
    ``models.helix_area.AreaFollower``: axis j of displacement h keeps the
    remainder D of the way to AREA W (loaded with W - W // 2) and the
    running products |h| |u|, |h| |v| and |h| (|u| + |v|) of the plane's
    point before the iteration; it steps in an iteration when the product
    the arc's decision picks (|h| |v| when u alone steps, |h| |u| when v
    alone steps, the sum on a diagonal, 0 when neither does) is at least D
    and it has steps left, and D loses that product and gains W if it
    stepped (saturating at -2^area_width).  Once the arc has ended
    (``alone``) each axis with steps left steps on every ``advance``.

    Ports: ``helix`` (``HelixPort``: the waiting helix's |h| and signs are
    its ``line``'s magnitudes, ``build`` with the arc's start, ``area``,
    ``load``, ``advance``, ``alone``, the arc's ``progress``; ``built``,
    ``following`` out), ``steps`` (``AxisPulses``: an axis's step high in
    the clock after the ``advance`` it steps in, as the arc's own, with its
    direction).  Parameters: none; widths from ``helix``.

    ``axes - 2`` channels (``channel_0``, ...): channel k runs the k-th axis
    outside the helix's plane (ascending), which is axis k, k + 1 or k + 2
    (``_channel_axis``: the plane, ``helix.u``, ``helix.v``, is read with
    ``build``, the running helix's at ``load``), so each channel picks its
    |h| from three axes and each axis its step from three channels.
    The products' start values |h| |us|, |h| |vs| and their sum are built
    by shift and add over the start point's magnitudes, most significant
    bit first, in the ``coord_width`` clocks after ``build`` (an arc's
    set-up takes ``4 coord_width + 26``), into the waiting helix's registers,
    which ``load`` moves into the running ones, so that a helix chained
    after another starts with no gap.  An iteration takes two clocks, as
    the arc's: the first decides from registers (three comparisons with D
    beside each other, the arc's decision picking one), the second applies
    it (D, and the products following |u| and |v| by +- |h|).

        clock    _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        build    _/~~~\\_______ ... ____________     (c clocks of shift and add)
        built    ~~~~~\\_______ ... _/~~~~~~~~~~
        load     ______________ ... _/~~~\\______
        advance  ______________ ... _____/~~~\\__     an iteration of the arc
        step_z   ______________ ... _________/~~     with the plane's steps
    """
    axes = helix.axes
    width = helix.coord_width
    if steps.axes != axes:
        raise ValueError(f"dda_helix: helix has {axes} axes, steps {steps.axes}")
    area_bits = area_width(width)
    start_u, start_v = Signal(intbv(0)[width:]), Signal(intbv(0)[width:])
    bits_left = Signal(intbv(0, min=0, max=width + 1))
    building = Signal(bool(0))
    area_run = Signal(intbv(0)[area_bits:])
    first_remainder = Signal(intbv(0)[area_bits:])
    pending, took_u, took_v, u_inward = (Signal(bool(0)) for _ in range(4))
    count = axes - 2
    moving = [Signal(bool(0)) for _ in range(count)]
    moving_any = ConcatSignal(*reversed(moving)) if count > 1 else moving[0]   # bit k: channel k has steps left
    line, progress = helix.line, helix.progress
    rises = [Signal(intbv(0)[width:]) for _ in range(count)]
    signs = [Signal(bool(0)) for _ in range(count)]
    running = [Signal(intbv(0, min=0, max=3)) for _ in range(count)]   # the axis a channel runs: k + this
    channel_steps = [Signal(bool(0)) for _ in range(count)]
    channel_dirs = [Signal(bool(0)) for _ in range(count)]
    units = []
    for k in range(count):
        units.append(named(f"pick_{k}", _channel_axis(
            clock, reset, helix, k, line.magnitude(k), line.magnitude(k + 1), line.magnitude(k + 2),
            line.positive(k), line.positive(k + 1), line.positive(k + 2), rises[k], signs[k], running[k])))
        units.append(named(f"channel_{k}", _axis_helix(
            clock, reset, helix, rises[k], signs[k], building, start_u(width - 1), start_v(width - 1),
            first_remainder, area_run, pending, took_u, took_v, u_inward, channel_steps[k], channel_dirs[k],
            moving[k])))
    for axis, suffix in enumerate(axis_suffixes(axes)):
        feeding = [k for k in range(max(0, axis - 2), min(axis, count - 1) + 1)]
        units.append(named(f"route_{suffix}", _axis_route(
            [(channel_steps[k], channel_dirs[k], running[k], axis - k) for k in feeding], steps.step(axis),
            steps.dir(axis))))

    @always_comb
    def status():
        helix.built.next = bits_left == 0
        helix.following.next = moving_any != 0
        building.next = bits_left != 0
        first_remainder.next = helix.area - helix.area[area_bits:1]

    @always_seq(clock.posedge, reset=reset)
    def start_point():
        # the start point's magnitudes, shifted out most significant bit first while the products build
        if helix.build:
            bits_left.next = width
            start_u.next = -helix.xs if helix.xs < 0 else helix.xs
            start_v.next = -helix.ys if helix.ys < 0 else helix.ys
        elif bits_left != 0:
            bits_left.next = bits_left - 1
            start_u.next = concat(start_u[width - 1:], False)
            start_v.next = concat(start_v[width - 1:], False)

    @always_seq(clock.posedge, reset=reset)
    def iteration():
        # the arc's decision, registered with the iteration for its second clock
        pending.next = helix.advance and not helix.alone
        if helix.advance:
            took_u.next = progress.step_u
            took_v.next = progress.step_v
            u_inward.next = progress.u_inward
        if helix.load:
            area_run.next = helix.area

    return units, status, start_point, iteration


@block
def _channel_axis(clock, reset, helix, index, magnitude_0, magnitude_1, magnitude_2, positive_0, positive_1,
                  positive_2, rise, sign, running):
    """Which axis channel ``index`` runs: the ``index``-th outside the plane,
    axis ``index`` + 0, 1 or 2.  At ``build`` it is found from the plane
    (``helix.u``, ``helix.v``) and kept (``waiting``); ``rise`` and ``sign``
    are that axis's |h| and direction (``magnitude_<n>``, ``positive_<n>``
    of axis ``index`` + n), ``running`` the running helix's, taken at
    ``load``."""
    waiting = Signal(intbv(0, min=0, max=3))

    @always_seq(clock.posedge, reset=reset)
    def find():
        low = helix.u
        high = helix.v
        if helix.v < helix.u:
            low = helix.v
            high = helix.u
        if helix.build:
            if index < low:
                waiting.next = 0
            elif index + 1 < high:
                waiting.next = 1
            else:
                waiting.next = 2
        if helix.load:
            running.next = waiting

    @always_comb
    def pick():
        rise.next = magnitude_0
        sign.next = positive_0
        if waiting == 1:
            rise.next = magnitude_1
            sign.next = positive_1
        elif waiting == 2:
            rise.next = magnitude_2
            sign.next = positive_2

    return find, pick


@block
def _axis_route(feeding, step, direction):
    """An axis's step and direction from the channels that can run it, ``feeding``: one to three
    (step, direction, the axis it runs as an offset from its own index, the offset that is this axis)."""
    (step_0, dir_0, running_0, offset_0), = feeding[:1]
    if len(feeding) == 1:
        @always_comb
        def route():
            step.next = step_0 and running_0 == offset_0
            direction.next = dir_0
        return route
    (step_1, dir_1, running_1, offset_1), = feeding[1:2]
    if len(feeding) == 2:
        @always_comb
        def route_two():
            step.next = (step_0 and running_0 == offset_0) or (step_1 and running_1 == offset_1)
            direction.next = dir_1
            if step_0 and running_0 == offset_0:
                direction.next = dir_0
        return route_two
    (step_2, dir_2, running_2, offset_2), = feeding[2:]

    @always_comb
    def route_three():
        step.next = ((step_0 and running_0 == offset_0) or (step_1 and running_1 == offset_1)
                     or (step_2 and running_2 == offset_2))
        direction.next = dir_2
        if step_0 and running_0 == offset_0:
            direction.next = dir_0
        elif step_1 and running_1 == offset_1:
            direction.next = dir_1
    return route_three


@block
def _axis_helix(clock, reset, helix, magnitude, positive, building, bit_u, bit_v, first_remainder, area_run,
                pending, took_u, took_v, u_inward, step, direction, moving):
    """One axis of ``dda_helix``: the waiting products built from
    ``magnitude`` (|h|) and the start point's bits ``bit_u``, ``bit_v``
    while ``building``; at ``load`` the running helix (|h|, steps left,
    ``direction``, products, D = ``first_remainder``); the decision at
    each ``helix.advance``, applied the clock after (``pending``) with the
    arc's registered ``took_u``, ``took_v``, ``u_inward`` and ``area_run``
    (W).  ``moving``: steps are left.  A step leaves the count at the edge
    after its own (``step``, registered, is the count's enable, so the
    decision reaches one flip-flop only); ``moving`` counts it at once,
    from the flags beside the count (zero, one) and ``step``, so no zero
    test of the count lies before the decision or ``following``."""
    width = len(magnitude)
    area_bits = len(area_run)
    product_bits = 2 * width
    pad = area_bits - product_bits
    wait_u, wait_v, wait_uv = (Signal(intbv(0)[product_bits:]) for _ in range(3))
    prod_u, prod_v, prod_uv = (Signal(intbv(0)[product_bits:]) for _ in range(3))
    next_u, next_v, next_uv = (Signal(intbv(0)[product_bits:]) for _ in range(3))
    # D in two's complement, area_bits + 1 bits: it lies in [-2^area_bits, W]
    remainder = Signal(modbv(0)[area_bits + 1:])
    next_remainder = Signal(modbv(0)[area_bits + 1:])
    rise = Signal(intbv(0)[width:])
    steps_left = Signal(intbv(0)[width:])
    left_zero, left_one = Signal(bool(1)), Signal(bool(0))   # steps_left == 0, == 1
    covers_u, covers_v, covers_uv, covers_none, stepping = (Signal(bool(0)) for _ in range(5))
    progress = helix.progress

    @always_comb
    def compare():
        # a product covers D: D <= 0, or the product at least D's magnitude
        covers_u.next = remainder[area_bits] or concat(intbv(0)[pad:], prod_u) >= remainder[area_bits:]
        covers_v.next = remainder[area_bits] or concat(intbv(0)[pad:], prod_v) >= remainder[area_bits:]
        covers_uv.next = remainder[area_bits] or concat(intbv(0)[pad:], prod_uv) >= remainder[area_bits:]
        covers_none.next = remainder[area_bits] or remainder == 0

    @always_comb
    def decide():
        # the arc's decision picks the product: u alone sweeps |v|, v alone |u|, a diagonal both
        picked = covers_none
        if progress.step_u and progress.step_v:
            picked = covers_uv
        elif progress.step_u:
            picked = covers_v
        elif progress.step_v:
            picked = covers_u
        stepping.next = moving and (picked or helix.alone)

    @always_comb
    def apply():
        # D - the picked product + W if the axis stepped, saturating at -2^area_bits
        chosen = intbv(0)[product_bits:]
        gain = intbv(0)[area_bits:]
        total = modbv(0)[area_bits + 2:]
        if took_u and took_v:
            chosen[:] = prod_uv
        elif took_u:
            chosen[:] = prod_v
        elif took_v:
            chosen[:] = prod_u
        if step:
            gain[:] = area_run
        total[:] = concat(remainder[area_bits], remainder) - concat(intbv(0)[pad + 2:], chosen) + \
            concat(intbv(0)[2:], gain)
        next_remainder.next = total[area_bits + 1:]
        if total[area_bits + 1] and not total[area_bits]:
            next_remainder.next = concat(True, intbv(0)[area_bits:])

    @always_comb
    def follow():
        # the products +- |h|, each one adder: a + ~b + 1 as {a, 1} + {~b, 1}, the low bit dropped
        rise_plus = modbv(0)[product_bits:]
        rise_minus = modbv(0)[product_bits:]
        grows_uv = bool(took_u != u_inward)
        wide_u = modbv(0)[product_bits + 1:]
        wide_v = modbv(0)[product_bits + 1:]
        wide_uv = modbv(0)[product_bits + 1:]
        rise_plus[:] = rise
        rise_minus[:] = ~rise_plus
        if u_inward:
            wide_u[:] = concat(prod_u, True) + concat(rise_minus, True)
            wide_v[:] = concat(prod_v, False) + concat(rise_plus, False)
        else:
            wide_u[:] = concat(prod_u, False) + concat(rise_plus, False)
            wide_v[:] = concat(prod_v, True) + concat(rise_minus, True)
        if grows_uv:
            wide_uv[:] = concat(prod_uv, False) + concat(rise_plus, False)
        else:
            wide_uv[:] = concat(prod_uv, True) + concat(rise_minus, True)
        next_u.next = wide_u[product_bits + 1:1]
        next_v.next = wide_v[product_bits + 1:1]
        next_uv.next = wide_uv[product_bits + 1:1]

    @always_seq(clock.posedge, reset=reset)
    def build():
        # |h| |us|, |h| |vs| and their sum by shift and add, most significant bit first
        if helix.build:
            wait_u.next = 0
            wait_v.next = 0
            wait_uv.next = 0
        elif building:
            add_u = intbv(0)[product_bits:]
            add_v = intbv(0)[product_bits:]
            add_uv = intbv(0)[product_bits:]
            if bit_u:
                add_u[:] = magnitude
            if bit_v:
                add_v[:] = magnitude
            if bit_u and bit_v:
                add_uv[:] = concat(magnitude, False)
            elif bit_u or bit_v:
                add_uv[:] = magnitude
            wait_u.next = concat(wait_u[product_bits - 1:], False) + add_u
            wait_v.next = concat(wait_v[product_bits - 1:], False) + add_v
            wait_uv.next = concat(wait_uv[product_bits - 1:], False) + add_uv

    @always_comb
    def count_flags():
        # steps_left less the step of the clock before, which leaves it at this edge
        moving.next = not left_zero and not (left_one and step)

    @always_seq(clock.posedge, reset=reset)
    def run():
        step.next = 0
        if step:
            steps_left.next = steps_left - 1
            left_zero.next = left_one
            left_one.next = steps_left == 2
        if helix.load:
            rise.next = magnitude
            steps_left.next = magnitude
            left_zero.next = magnitude == 0
            left_one.next = magnitude == 1
            direction.next = positive
            prod_u.next = wait_u
            prod_v.next = wait_v
            prod_uv.next = wait_uv
            remainder.next = first_remainder
        elif helix.advance:
            step.next = stepping
        elif pending:
            remainder.next = next_remainder
            # the products follow |u| and |v|: each +- |h| on a step of its coordinate; a diagonal keeps the sum
            if took_u:
                prod_u.next = next_u
            if took_v:
                prod_v.next = next_v
            if took_u != took_v:
                prod_uv.next = next_uv

    return compare, decide, apply, follow, build, count_flags, run
