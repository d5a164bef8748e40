"""The card's probe input: on its edge, every axis's count and step position latched once per arm."""
from myhdl import Signal, always_comb, always_seq, block

from models.parameters import AXES
from rtl.encoder.conditioner import conditioner
from rtl.interfaces import ProbePort, axis_suffixes, card_reset, named


@block
def probe(clock, reset, port):
    """The probe (LinuxCNC's G38), clock for clock ``models.encoder_model.ProbeModel``.

    Ports: ``port`` (``ProbePort``).  The pin goes through a
    ``conditioner`` (two flip-flops, ``invert``, the filter of ``filter``);
    ``arm`` arms (at the edge that ends its clock, already for that edge's
    sample); at the first armed sample where the filtered probe rose, every
    axis's ``latched_count_*`` and ``latched_pos_*`` take ``count_*`` and
    ``pos_*`` as they were before that edge, ``armed`` clears and
    ``fired`` is high for the clock after.  Each axis is an
    ``_axis_latch`` (``axis_x``, ...).

    filter 0, armed:
        edge        e     e+1   e+2   e+3
        pin        _/~~~~~~~~~~~~~~~~~~~~~~
        level      ____________/~~~~~~~~~~~
        armed      ~~~~~~~~~~~~~~~~~~\\_____
        latched_*  ==old=============X=count, pos before e+3
        fired      __________________/~~~\\_
    """
    level, seen, fire, armed_now = (Signal(bool(0)) for _ in range(4))
    filtered = named("conditioner", conditioner(clock, reset, port.pin, port.invert, port.filter, level))
    latches = [named(f"axis_{suffix}", _axis_latch(clock, reset, fire, port.signals("count", axis),
                                                    port.signals("pos", axis), port.signals("latched_count", axis),
                                                    port.signals("latched_pos", axis)))
               for axis, suffix in enumerate(axis_suffixes(port.axes))]

    @always_comb
    def arming():
        armed_now.next = port.armed or port.arm

    @always_comb
    def decide():
        fire.next = armed_now and level and not seen

    @always_seq(clock.posedge, reset=reset)
    def watch():
        seen.next = level
        port.fired.next = fire
        port.armed.next = armed_now and not fire

    return filtered, latches, arming, decide, watch


@block
def _axis_latch(clock, reset, fire, count, pos, latched_count, latched_pos):
    """One axis's PROBE_ENC and PROBE_POS: ``count`` and ``pos`` at ``fire``."""

    @always_seq(clock.posedge, reset=reset)
    def latch():
        if fire:
            latched_count.next = count
            latched_pos.next = pos

    return latch


def probe_ports(axes=AXES.default):
    """Fresh ports of ``probe`` for conversion and benches: ``axes`` axes."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), port=ProbePort(axes))
