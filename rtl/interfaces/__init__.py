"""Signal bundles shared between the card's blocks, one module per side
(``pci``, ``dda``, ``card``, ``machine``, ``encoder``; ``bundle`` for what they share);
import them from here.

Every interface is a plain class whose attributes are MyHDL ``Signal``s.
Widths are constructor arguments.  When a block with an interface argument is
the top of a conversion, MyHDL names each port ``<argument>_<attribute>``.

Shared PCI lines are split into ``*_in`` / ``*_out`` / ``*_oe`` so that the
cores co-simulate and convert cleanly; only the pad wrapper at the top level
has tri-states.  All PCI ``*_out`` values keep the bus polarity (active-low
lines are 0 when asserted).
"""
from rtl.interfaces.bundle import axis_suffixes, card_reset, named
from rtl.interfaces.card import (ERROR_BITS, INPUT_ESTOP, MACHINE_INPUTS, MARK_TAG_BITS, PULSE_COUNT_BITS, SET_INDEX_BITS,
                                 TIMING_BITS, ENCODER_PINS, AxisBlock, CommandHeader, DirectPulseCommand, FeedPort,
                                 AliasBlock, FifoRead, MarkPort, MotorPins, PulseCommand, PulseControl, RampSettings, ReadChain, RegisterBus, RegisterWord,
                                 SequencerControl, SetPort, StatusWords, StepPositions, StepRequest, machine_inputs)
from rtl.interfaces.dda import (TARGET_END, TARGET_RADIUS, TARGET_ZERO, ArcProgress, AxesCommand, AxisPulses, DdaMove,
                                DdaPlan, DdaPort, DdaRoot, DdaStep, HelixPort, LinearPort, SetupControl, SetupSequence,
                                axis_index_bits)
from rtl.interfaces.encoder import EncoderPins, EncoderPort, EncoderRegisters, FollowingErrorPort, ProbePort, Timestamp
from rtl.interfaces.machine import Homing, InputConditioning, MachineGuard
from rtl.interfaces.pci import (ConfigSpace, LocalBus, PciBus, PciPins, TargetBoundary, TargetBuffers, TargetControlNext,
                                TargetDecode, TargetParity, TargetRequests, TargetState, TargetTransaction)

__all__ = [
    "card_reset", "axis_suffixes", "named", "PciBus", "LocalBus", "PciPins", "TargetControlNext", "ConfigSpace",
    "TargetState",
    "TargetDecode", "TargetParity", "TargetBuffers", "TargetRequests", "TargetTransaction", "TargetBoundary",
    "DdaPort", "DdaPlan", "DdaRoot", "SetupSequence", "SetupControl",
    "DdaMove", "DdaStep", "LinearPort", "HelixPort", "ArcProgress", "AxisPulses", "AxesCommand", "axis_index_bits", "TARGET_ZERO", "TARGET_RADIUS",
    "TARGET_END", "Homing", "InputConditioning",
    "MachineGuard", "MotorPins", "MACHINE_INPUTS", "SET_INDEX_BITS", "MARK_TAG_BITS", "ERROR_BITS",
    "PULSE_COUNT_BITS", "TIMING_BITS", "AxisBlock", "CommandHeader", "FifoRead", "SequencerControl", "PulseCommand",
    "SetPort",
    "AliasBlock", "MarkPort", "RegisterBus", "RegisterWord", "ReadChain", "PulseControl", "StepPositions",
    "RampSettings", "FeedPort", "DirectPulseCommand", "StepRequest", "StatusWords", "INPUT_ESTOP", "machine_inputs",
    "ENCODER_PINS", "EncoderPins", "EncoderPort", "EncoderRegisters", "Timestamp",
    "FollowingErrorPort", "ProbePort"
]
