"""The card behind the PCI target: registers, FIFO, sequencer, pulse outputs and the DDA."""
from myhdl import ResetSignal, Signal, always_comb, block

from models.parameters import Build
from rtl.dda.dda_axes import dda_axes
from rtl.interfaces import AxesCommand, AxisPulses, DdaPort, LocalBus, MotorPins, card_reset
from rtl.regs_fifo import regs_fifo


@block
def card_core(clock, reset, local, irq, pins, *, build=Build()):
    """``regs_fifo`` and the interpolator (``dda_axes``: ``dda_arc`` in any plane, the N-axis line) wired together.

    Ports: ``local`` (the PCI target's back end), ``irq`` (to INTA#),
    ``pins`` (STEP/DIR of the build's ``axes``).  COMMAND.SOFT_RESET resets the DDA through its
    asynchronous reset, driven from a flip-flop of ``regs_fifo`` (no glitch)
    and combined with RST#.  Parameters: ``build`` (a ``Build``,
    ``models/parameters.py``): its ``coord_width`` and ``variants`` make the
    ``DdaPort`` here (the interpolator has only the variants named, the
    sequencer refuses an ARC for another, BUILD reports them); ``regs_fifo``
    takes the record whole (``fifo_depth``; ``clock_hz`` and ``device`` for
    the capability registers).

        clock       _/~\\_/~\\_/~\\_/~\\_
        local.we    _/~~~\\__________     COMMAND <- SOFT_RESET
        core_clear  _____/~~~\\______
        dda reset   ~~~~~\\___/~~~~~~
    """
    dda = DdaPort(build.coord_width, build.variants)
    axes_cmd = AxesCommand(build.axes, build.coord_width)
    steps = AxisPulses(build.axes)
    core_clear = Signal(bool(0))
    dda_reset = ResetSignal(1, active=0, isasync=True)

    @always_comb
    def combine_resets():
        dda_reset.next = reset and not core_clear

    registers = regs_fifo(clock, reset, local, dda, axes_cmd, steps, pins, irq, core_clear, build=build)
    interpolator = dda_axes(clock, dda_reset, dda, axes_cmd, steps)
    return combine_resets, registers, interpolator


def card_core_ports(axes=Build.axes, encoders=Build.encoders):
    """Fresh ports of ``card_core`` for conversion and benches: ``pins`` of ``axes`` axes."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), local=LocalBus(), irq=Signal(bool(0)),
                pins=MotorPins(axes, encoders))
