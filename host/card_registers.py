"""Register access of the card API: by name, checked against the register
table (models/registers.py) before anything is written.

``host.card.Card`` takes these methods from ``CardRegisters``: ``read``,
``write``, ``field`` (BAR0's registers by name), ``axis_read`` and
``axis_write`` (an axis's per-axis register: BAR0's own for X and Y, BAR2's
block for the others).  They use the card's ``transport`` and ``identity``.
"""
from models.axes import names
from models import registers as regmap


class CardRegisters:
    """The registers of a ``Card`` by name, values checked against their ranges."""

    def read(self, name):
        reg = regmap.register(name)
        if reg.option is not None and not getattr(self.identity, reg.option):
            raise ValueError(f"{name}: the card was built without {reg.option} (BUILD)")
        return self.transport.read(reg.offset)

    def write(self, name, value):
        """Write register ``name``; a value outside its range is refused (the card would clamp it)."""
        reg = regmap.register(name)
        if reg.access == "RO":
            raise ValueError(f"{name} is read only")
        low = reg.minimum if reg.minimum is not None else (-(1 << (reg.width - 1)) if reg.signed else 0)
        high = reg.maximum if reg.maximum is not None else (1 << reg.width) - 1
        if not low <= value <= high:
            raise ValueError(f"{name} = {value} is outside {low}..{high}")
        self.transport.write(reg.offset, value & 0xFFFFFFFF)

    def field(self, reg, name, word=None):
        return regmap.field_value(reg, name, self.read(reg) if word is None else word)

    def _axis_register(self, name, axis):
        """The per-axis register ``name`` of ``axis`` (0 X), if the card has that axis: BAR0's
        own for X and Y (POS_X, ...), in BAR2's block for the others (docs/registers.md)."""
        if not isinstance(axis, int) or not 0 <= axis < self.identity.axes:
            raise ValueError(f"axis {axis!r}: the card has {self.identity.axes} axes "
                             f"({names(range(self.identity.axes))})")
        reg = regmap.axis_register(name, axis)
        if reg.option is not None and not getattr(self.identity, reg.option):
            raise ValueError(f"{reg.name}: the card was built without {reg.option} (BUILD)")
        return reg

    def axis_read(self, name, axis):
        """The per-axis register ``name`` (POS, PULSE_PERIOD, PULSE_COUNT) of ``axis``."""
        return self.transport.read(self._axis_register(name, axis).offset)

    def axis_write(self, name, axis, value):
        """Write the per-axis register ``name`` of ``axis``; a value outside its range is refused."""
        reg = self._axis_register(name, axis)
        if reg.access == "RO":
            raise ValueError(f"{reg.name} is read only")
        low = reg.minimum if reg.minimum is not None else 0
        high = reg.maximum if reg.maximum is not None else (1 << reg.width) - 1
        if not low <= value <= high:
            raise ValueError(f"{reg.name} = {value} is outside {low}..{high}")
        self.transport.write(reg.offset, value & 0xFFFFFFFF)
