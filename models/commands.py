"""The commands of the card's stream as Python objects, and the one encoder of their FIFO words.

``LineCommand`` and ``ArcCommand`` are the DDA's moves (``models/dda_plan.py``);
``SetCommand``, ``DwellCommand`` and ``MarkCommand`` are the sequencer's
other commands.  ``command_words`` turns any of them into the words the host
writes into the data FIFO (``models/instructions.py`` lays them out): the
planner, the benches and the figure scripts all encode through it.
"""
from dataclasses import dataclass

from models.dda_plan import ArcCommand, LineCommand
from models.instructions import encode
from models.registers import register


@dataclass(frozen=True)
class SetCommand:
    """SET: write ``value`` into the register named ``register`` at this point of the stream."""
    register: str
    value: int


@dataclass(frozen=True)
class DwellCommand:
    """DWELL: wait ``clocks`` clocks before the next command."""
    clocks: int


@dataclass(frozen=True)
class MarkCommand:
    """MARK: set INT_STATUS.MARK and MARK_TAG to ``tag`` when reached."""
    tag: int


def command_words(command):
    """The FIFO words of one command (header, then operands)."""
    if isinstance(command, LineCommand):
        return encode("LINE", command.dx, command.dy, BLEND=int(command.blend))
    if isinstance(command, ArcCommand):
        return encode("ARC", command.xs, command.ys, command.xe, command.ye, CCW=int(command.ccw),
                      VARIANT=command.variant, LAMBDA=command.lambda_shift, ACC_BITS=command.acc_bits,
                      BLEND=int(command.blend))
    if isinstance(command, SetCommand):
        return encode("SET", command.value, INDEX=register(command.register).set_index)
    if isinstance(command, DwellCommand):
        return encode("DWELL", command.clocks)
    if isinstance(command, MarkCommand):
        return encode("MARK", TAG=command.tag)
    raise ValueError(f"not a command: {command!r}")


def stream_words(commands):
    """The FIFO words of ``commands``, one after the other."""
    return [word for command in commands for word in command_words(command)]
