"""The card behind the PCI target: registers, FIFO, sequencer, pulse outputs and the DDA."""
from myhdl import ResetSignal, Signal, always_comb, block

from rtl.dda_arc import dda_arc
from rtl.dda_build import COORD_WIDTH, DEFAULT_VARIANTS
from rtl.interfaces import AxisPulses, DdaPort, LocalBus, MotorPins, card_reset
from rtl.regs_fifo import regs_fifo


@block
def card_core(clock, reset, local, irq, pins, *, fifo_depth=512, coord_width=COORD_WIDTH,
              variants=DEFAULT_VARIANTS):
    """``regs_fifo`` and ``dda_arc`` wired together.

    Ports: ``local`` (the PCI target's back end), ``irq`` (to INTA#),
    ``pins`` (STEP/DIR).  COMMAND.SOFT_RESET resets the DDA through its
    asynchronous reset, driven from a flip-flop of ``regs_fifo`` (no glitch)
    and combined with RST#.  Parameters: ``fifo_depth``, ``coord_width``,
    ``variants`` (the DDA's step rules; the sequencer refuses an ARC that
    names another).

        clock       _/~\\_/~\\_/~\\_/~\\_
        local.we    _/~~~\\__________     COMMAND <- SOFT_RESET
        core_clear  _____/~~~\\______
        dda reset   ~~~~~\\___/~~~~~~
    """
    dda = DdaPort(coord_width, variants)
    steps = AxisPulses()
    core_clear = Signal(bool(0))
    dda_reset = ResetSignal(1, active=0, isasync=True)

    @always_comb
    def combine_resets():
        dda_reset.next = reset and not core_clear

    registers = regs_fifo(clock, reset, local, dda, steps, pins, irq, core_clear,
                          fifo_depth=fifo_depth, coord_width=coord_width)
    interpolator = dda_arc(clock, dda_reset, dda, steps)
    return combine_resets, registers, interpolator


def card_core_ports(fifo_depth=512, coord_width=COORD_WIDTH, variants=DEFAULT_VARIANTS):
    """Fresh ports of ``card_core`` for conversion and benches."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), local=LocalBus(), irq=Signal(bool(0)),
                pins=MotorPins())
