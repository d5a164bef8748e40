"""The commands of the card's stream as Python objects, the one encoder of their FIFO words, and its decoder.

``LineCommand``, ``AxesLineCommand`` and ``ArcCommand`` are the DDA's moves
(``models/dda_plan.py``; N axes: docs/axes.md); ``PulseCommand``,
``SetCommand``, ``DwellCommand`` and ``MarkCommand`` are the sequencer's
other commands.  ``command_words`` turns any of them into the words the host
writes into the data FIFO (``models/instructions.py`` lays them out): the
planner, the benches and the figure scripts all encode through it.  A move or
pulse on X and Y alone is encoded in the two-axis form (every axis field 0),
word for word what a two-axis host writes.  ``decode_words`` reads a word
stream back into commands (the N-axis form), for the golden card model and
the tests.
"""
from dataclasses import dataclass

from models.axes import XY, XY_MASK, axes_of, moving_mask
from models.dda_plan import ArcCommand, AxesLineCommand, LineCommand
from models.instructions import encode, split_words
from models.registers import SET_TARGETS, register


@dataclass(frozen=True)
class PulseCommand:
    """PULSE: direct pulses, a signed count per axis (indexed by axis)."""
    counts: tuple


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


def _axis_form(name, values, **header):
    """``name`` with one operand per axis of ``values`` that is not 0, in the
    two-axis form when only X and Y have one."""
    mask = moving_mask(values)
    if not mask & ~XY_MASK:
        padded = tuple(values) + (0, 0)
        return encode(name, padded[0], padded[1], **header)
    return encode(name, *(values[axis] for axis in axes_of(mask)), AXES=mask, **header)


def area_words(area):
    """An ARC's AREA as its two operand words: AREA_LO (bits 31:0), AREA_HI (the bits above)."""
    return area & 0xFFFFFFFF, area >> 32


def _arc_words(command):
    header = dict(CCW=int(command.ccw), VARIANT=command.variant, LAMBDA=command.lambda_shift,
                  ACC_BITS=command.acc_bits, BLEND=int(command.blend))
    if tuple(command.plane) != XY:
        header.update(U_AXIS=command.plane[0], V_AXIS=command.plane[1])
    operands = [command.xs, command.ys, command.xe, command.ye]
    helix = command.helix_axes
    if helix:
        if command.area is None:
            raise ValueError("a helical ARC needs its AREA (models.dda_axes.with_area)")
        header["HELIX"] = moving_mask(command.helix)
        operands += list(area_words(command.area)) + [command.helix[axis] for axis in helix]
    return encode("ARC", *operands, **header)


def command_words(command):
    """The FIFO words of one command (header, then operands)."""
    if isinstance(command, LineCommand):
        return encode("LINE", command.dx, command.dy, BLEND=int(command.blend))
    if isinstance(command, AxesLineCommand):
        return _axis_form("LINE", command.deltas, BLEND=int(command.blend))
    if isinstance(command, ArcCommand):
        return _arc_words(command)
    if isinstance(command, PulseCommand):
        return _axis_form("PULSE", command.counts)
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


def _per_axis(mask, operands):
    """Operands of the axes in ``mask`` (ascending) as a tuple indexed by axis, at least X and Y."""
    axes = axes_of(mask)
    values = [0] * max(2, axes[-1] + 1)
    for axis, value in zip(axes, operands):
        values[axis] = value
    return tuple(values)


def _decoded(op, fields, operands):
    if op.name == "LINE":
        if not fields["AXES"]:
            return LineCommand(*operands, blend=bool(fields["BLEND"]))
        return AxesLineCommand(_per_axis(fields["AXES"], operands), blend=bool(fields["BLEND"]))
    if op.name == "ARC":
        plane = (fields["U_AXIS"], fields["V_AXIS"]) if fields["U_AXIS"] or fields["V_AXIS"] else XY
        helix, area = (), None
        if fields["HELIX"]:
            area, helix = operands[4] | operands[5] << 32, _per_axis(fields["HELIX"], operands[6:])
        return ArcCommand(*operands[:4], ccw=bool(fields["CCW"]), variant=fields["VARIANT"],
                          lambda_shift=fields["LAMBDA"], acc_bits=fields["ACC_BITS"], blend=bool(fields["BLEND"]),
                          plane=plane, helix=helix, area=area)
    if op.name == "PULSE":
        return PulseCommand(_per_axis(fields["AXES"] or XY_MASK, operands))
    if op.name == "SET":
        target = SET_TARGETS.get(fields["INDEX"])
        if target is None:
            raise ValueError(f"RANGE: SET index {fields['INDEX']} has no register")
        return SetCommand(target.name, operands[0])
    if op.name == "DWELL":
        return DwellCommand(operands[0])
    return MarkCommand(fields["TAG"])


def decode_words(words):
    """The commands of a word stream (the N-axis form; ``instructions.split_words`` frames it):
    LINE with AXES 0 is a ``LineCommand``, with AXES not 0 an ``AxesLineCommand``."""
    return [_decoded(op, fields, operands) for op, fields, operands in split_words(words)]
