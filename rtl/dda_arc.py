"""DDA arc and line interpolator: setup, check and run, joined by their bundles.

The golden model is ``models/dda_model.py``; ``docs/dda.md`` gives the algorithm,
the hardware and the handshake.
"""
from myhdl import Signal, block

from rtl.dda.dda_check import dda_check
from rtl.dda.dda_run import dda_run
from rtl.dda.dda_setup import dda_setup
from rtl.interfaces import AxisPulses, DdaMove, DdaPlan, DdaPort, card_reset


@block
def dda_arc(clock, reset, cmd, steps):
    """Two-axis DDA interpolator (arcs of the paper's section 4 and the precise mode, lines).

    Ports:
        clock, reset  clock and reset (``card_reset()``: async, active low)
        cmd           ``DdaPort``: command lines, ``start``, ``blend``, ``advance``
                      in; ``ready``, ``busy``, ``done``, ``error``, ``quadrant``,
                      ``stop_left`` out
        steps         ``AxisPulses``: ``step_x``/``step_y`` one clock per step,
                      ``dir_x``/``dir_y`` valid with them
    Parameters: none; ``cmd.coord_width`` and ``cmd.variants`` (the build) say
    what is built.

        cmd --> dda_setup --DdaPlan--> dda_check --DdaMove--> dda_run --> steps
                  (latch, one adder,       (validation,         (two clocks
                   square root)             start values)        an iteration)

    Timing (an arc; a line has two setup clocks)::

        clock    _/~\\_/~\\_/~\\_ ... _/~\\_/~\\_/~\\_/~\\_/~\\_ ... _/~\\_/~\\_
        start    _/~~~\\______ ... ________________________________
        ready    ~~~~~\\______ ... _____/~~~~~~~~~~~~~~~~~ ... ~~~~~~~~
        busy     _____/~~~~~~ ... ~~~~~~~~~~~~~~~~~~~~~~~ ... ~~~\\___
        advance  ____________ ... ______/~~~\\___/~~~\\___ ... ~~~~~~~~
        step_x   ____________ ... __________/~~~\\___/~~~ ... ________
        done     ____________ ... ___________________________/~~~\\___
                      |<-- 4*W+26 -->|

    A ``start`` taken while a move runs (``ready`` high) is set up
    meanwhile; the run takes it at the edge that applies its last iteration,
    so the next ``advance`` iterates the new move.  ``error`` (a rejected
    move) and the ``done`` of a line of length 0 come once no move runs.
    """
    plan = DdaPlan(cmd)
    move = DdaMove(plan)
    setup = dda_setup(clock, reset, cmd, plan)
    check = dda_check(plan, move)
    run = dda_run(clock, reset, cmd, move, steps)
    return setup, check, run


def dda_arc_ports(coord_width=None, variants=None):
    """Fresh ports of ``dda_arc`` for conversion or a bench (the build's defaults unless given)."""
    options = {name: value for name, value in (("coord_width", coord_width), ("variants", variants))
               if value is not None}
    return dict(clock=Signal(bool(0)), reset=card_reset(), cmd=DdaPort(**options), steps=AxisPulses())
