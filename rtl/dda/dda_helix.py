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

    One channel per axis (``axis_x``, ...; the plane's two have |h| = 0).
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
    moving = [Signal(bool(0)) for _ in range(axes)]
    moving_any = ConcatSignal(*reversed(moving))   # bit i: axis i has steps left
    line, progress = helix.line, helix.progress
    channels = [named(f"axis_{suffix}", _axis_helix(
        clock, reset, helix, line.magnitude(axis), line.positive(axis), building, start_u(width - 1),
        start_v(width - 1), first_remainder, area_run, pending, took_u, took_v, u_inward, steps.step(axis),
        steps.dir(axis), moving[axis]))
        for axis, suffix in enumerate(axis_suffixes(axes))]

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

    return channels, status, start_point, iteration


@block
def _axis_helix(clock, reset, helix, magnitude, positive, building, bit_u, bit_v, first_remainder, area_run,
                pending, took_u, took_v, u_inward, step, direction, moving):
    """One axis of ``dda_helix``: the waiting products built from
    ``magnitude`` (|h|) and the start point's bits ``bit_u``, ``bit_v``
    while ``building``; at ``load`` the running helix (|h|, steps left,
    ``direction``, products, D = ``first_remainder``); the decision at
    each ``helix.advance``, applied the clock after (``pending``) with the
    arc's registered ``took_u``, ``took_v``, ``u_inward`` and ``area_run``
    (W).  ``moving``: steps are left."""
    width = len(magnitude)
    area_bits = len(area_run)
    product_bits = 2 * width
    pad = area_bits - product_bits
    wait_u, wait_v, wait_uv = (Signal(intbv(0)[product_bits:]) for _ in range(3))
    prod_u, prod_v, prod_uv = (Signal(intbv(0)[product_bits:]) for _ in range(3))
    # D in two's complement, area_bits + 1 bits: it lies in [-2^area_bits, W]
    remainder = Signal(modbv(0)[area_bits + 1:])
    next_remainder = Signal(modbv(0)[area_bits + 1:])
    rise = Signal(intbv(0)[width:])
    steps_left = Signal(intbv(0)[width:])
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
        stepping.next = steps_left != 0 and (picked or helix.alone)
        moving.next = steps_left != 0

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

    @always_seq(clock.posedge, reset=reset)
    def run():
        step.next = 0
        if helix.load:
            rise.next = magnitude
            steps_left.next = magnitude
            direction.next = positive
            prod_u.next = wait_u
            prod_v.next = wait_v
            prod_uv.next = wait_uv
            remainder.next = first_remainder
        elif helix.advance:
            step.next = stepping
            if stepping:
                steps_left.next = steps_left - 1
        elif pending:
            remainder.next = next_remainder
            # the products follow |u| and |v|: each +- |h| on a step of its coordinate; a diagonal keeps the sum
            if took_u:
                if u_inward:
                    prod_u.next = prod_u - rise
                else:
                    prod_u.next = prod_u + rise
            if took_v:
                if u_inward:
                    prod_v.next = prod_v + rise
                else:
                    prod_v.next = prod_v - rise
            if took_u != took_v:
                if took_u != u_inward:
                    prod_uv.next = prod_uv + rise
                else:
                    prod_uv.next = prod_uv - rise

    return compare, decide, apply, build, run
