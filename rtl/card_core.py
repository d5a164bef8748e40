"""The card behind the PCI target: registers, FIFO, sequencer, pulse outputs and the DDA."""
from myhdl import ResetSignal, Signal, always_comb, block

from models import parameters
from models.parameters import CLOCK_HZ, COORD_WIDTH, DEVICE, FIFO_DEPTH, VARIANTS
from rtl.dda_arc import dda_arc
from rtl.interfaces import AxisPulses, DdaPort, LocalBus, MotorPins, card_reset
from rtl.regs_fifo import regs_fifo

CORE_PARAMETERS = ("fifo_depth", "coord_width", "clock_hz", "variants", "device")


@block
def card_core(clock, reset, local, irq, pins, *, fifo_depth=FIFO_DEPTH.default, coord_width=COORD_WIDTH.default,
              clock_hz=CLOCK_HZ.default, variants=VARIANTS.default, device=DEVICE.default):
    """``regs_fifo`` and ``dda_arc`` wired together.

    Ports: ``local`` (the PCI target's back end), ``irq`` (to INTA#),
    ``pins`` (STEP/DIR).  COMMAND.SOFT_RESET resets the DDA through its
    asynchronous reset, driven from a flip-flop of ``regs_fifo`` (no glitch)
    and combined with RST#.  Parameters (``models/parameters.py``):
    ``fifo_depth``, ``coord_width`` and ``variants`` (the build of the
    ``DdaPort`` made here: the interpolator has only the variants named, the
    sequencer refuses an ARC for another, BUILD reports them); ``clock_hz``
    and ``device`` go to the capability registers.

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

    registers = regs_fifo(clock, reset, local, dda, steps, pins, irq, core_clear, fifo_depth=fifo_depth,
                          clock_hz=clock_hz, device=device)
    interpolator = dda_arc(clock, dda_reset, dda, steps)
    return combine_resets, registers, interpolator


def card_core_ports(**build):
    """Fresh ports of ``card_core`` for conversion and benches (``build``: its
    parameters, checked; none of them changes a port)."""
    parameters.check_unit("card_core", CORE_PARAMETERS, build)
    return dict(clock=Signal(bool(0)), reset=card_reset(), local=LocalBus(), irq=Signal(bool(0)),
                pins=MotorPins())
