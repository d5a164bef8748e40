"""The register table's checks, on the table's data only (``models/registers.py`` runs them as it
loads, through its ``check_table`` and ``check_axis_block``)."""
from models import parameters
from models.axes import AXIS_NAMES


def _shape(reg):
    """What a register is to the hardware and the host: access, fields' places, widths, signs, range."""
    return (reg.access, tuple((f.name, f.lsb, f.width, f.signed) for f in reg.fields), reg.minimum, reg.maximum)


def check_table(registers, access_kinds, word_bytes):
    """Raise ValueError when the table ``registers`` contradicts itself (``access_kinds``: the
    access kinds there are, ``word_bytes``: a register's size)."""
    offsets, set_indices = set(), set()
    for reg in registers:
        if reg.access not in access_kinds:
            raise ValueError(f"{reg.name}: unknown access {reg.access}")
        if reg.offset % word_bytes or reg.offset in offsets:
            raise ValueError(f"{reg.name}: offset {reg.offset:#x} misaligned or used twice")
        offsets.add(reg.offset)
        used = 0
        for item in reg.fields:
            if item.mask & used or item.lsb + item.width > 32:
                raise ValueError(f"{reg.name}.{item.name}: overlaps or exceeds 32 bits")
            used |= item.mask
        if reg.reset & ~used & 0xFFFFFFFF:
            raise ValueError(f"{reg.name}: reset value sets bits outside its fields")
        if reg.set_index is not None:
            if reg.set_index in set_indices or reg.access != "RW":
                raise ValueError(f"{reg.name}: SET index reused or register not RW")
            set_indices.add(reg.set_index)
        if (reg.minimum is not None or reg.maximum is not None) and len(reg.fields) != 1:
            raise ValueError(f"{reg.name}: only one-field registers can clamp")
        if reg.access in ("RW", "WP") and len(reg.fields) == 1 and reg.fields[0].width > 1 and (
                reg.minimum is None or reg.maximum is None):
            # a number the host writes: without a range a too-large write would be cut to the
            # field's width (a WATCHDOG of 2**24 would read 0: off) instead of clamped and flagged
            raise ValueError(f"{reg.name}: a one-value register the host writes declares its range")
        option = parameters.PARAMETERS.get(reg.option)
        if reg.option is not None and (option is None or (option.minimum, option.maximum) != (0, 1)):
            raise ValueError(f"{reg.name}: option {reg.option!r} is no 0/1 build parameter")
        for item in reg.fields:
            if item.cleared is not None and reg.access != "RW":
                raise ValueError(f"{reg.name}.{item.name}: only an RW field is cleared by the hardware")
            if item.build is not None and (reg.access != "RO" or item.build not in parameters.PARAMETERS):
                raise ValueError(f"{reg.name}.{item.name}: a build field is read-only and names a "
                                 f"build parameter, not {item.build!r}")


def check_axis_block(axis_registers, bar0_registers, layout):
    """Raise ValueError when the per-axis block ``axis_registers`` contradicts itself, differs
    from X's and Y's registers among ``bar0_registers`` or does not fit BAR2 (``layout``: the
    table's ACCESS_KINDS, WORD_BYTES, AXIS_BLOCK_BASE, AXIS_STRIDE, AXIS_FREE, BAR0_AXES,
    IO_BAR_BITS, REG_BAR_BITS by name).  A block register is BAR0's for X and Y when BAR0 has
    <REG>_X and <REG>_Y (of the same shape), or the block's only when BAR0 has neither; the block
    keeps ``AXIS_FREE`` free."""
    check_table(axis_registers, layout["ACCESS_KINDS"], layout["WORD_BYTES"])
    bar0 = {reg.name: reg for reg in bar0_registers}
    for spec in axis_registers:
        if spec.offset >= layout["AXIS_STRIDE"] or spec.set_index is not None or spec.offset in layout["AXIS_FREE"]:
            raise ValueError(f"{spec.name}: outside its block, on a place kept free, or with a SET index")
        shared = [bar0.get(f"{spec.name}_{AXIS_NAMES[axis]}") for axis in range(layout["BAR0_AXES"])]
        if any(same is None for same in shared) and any(same is not None for same in shared):
            raise ValueError(f"{spec.name}: BAR0 has it for some of X and Y only")
        for same in shared:
            if same is not None and (_shape(same) != _shape(spec) or same.option != spec.option):
                raise ValueError(f"{same.name}: not the register {spec.name} of the block describes")
    blocks_end = layout["AXIS_BLOCK_BASE"] + layout["AXIS_STRIDE"] * len(AXIS_NAMES)
    if layout["AXIS_BLOCK_BASE"] < 1 << layout["IO_BAR_BITS"] or blocks_end > 1 << layout["REG_BAR_BITS"]:
        raise ValueError("the per-axis blocks overlap BAR0's registers or leave BAR2")

