"""The register table's checks (``models/registers.py`` runs them as it loads)."""
from models import parameters
from models import registers as regmap
from models.axes import AXIS_NAMES


def _shape(reg):
    """What a register is to the hardware and the host: access, fields' places, widths, signs, range."""
    return (reg.access, tuple((f.name, f.lsb, f.width, f.signed) for f in reg.fields), reg.minimum, reg.maximum)


def check_table(registers=None):
    """Raise ValueError when the table (``registers``; default: ``REGISTERS`` and
    ``ENCODER_REGISTERS``) contradicts itself."""
    registers = regmap.REGISTERS + regmap.ENCODER_REGISTERS if registers is None else registers
    offsets, set_indices = set(), set()
    for reg in registers:
        if reg.access not in regmap.ACCESS_KINDS:
            raise ValueError(f"{reg.name}: unknown access {reg.access}")
        if reg.offset % regmap.WORD_BYTES or reg.offset in offsets:
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


def check_axis_block(axis_registers=None):
    """Raise ValueError when the per-axis block (``axis_registers``; default: ``AXIS_REGISTERS``)
    contradicts itself, differs from X's and Y's BAR0 registers or does not fit BAR2.  A block
    register is BAR0's for X and Y when BAR0 has <REG>_X and <REG>_Y (of the same shape), or the
    block's only when BAR0 has neither; the block keeps ``AXIS_FREE`` free."""
    axis_registers = regmap.AXIS_REGISTERS if axis_registers is None else axis_registers
    check_table(axis_registers)
    bar0 = {reg.name: reg for reg in regmap.REGISTERS + regmap.ENCODER_REGISTERS}
    for spec in axis_registers:
        if spec.offset >= regmap.AXIS_STRIDE or spec.set_index is not None or spec.offset in regmap.AXIS_FREE:
            raise ValueError(f"{spec.name}: outside its block, on a place kept free, or with a SET index")
        shared = [bar0.get(f"{spec.name}_{AXIS_NAMES[axis]}") for axis in range(regmap.BAR0_AXES)]
        if any(same is None for same in shared) and any(same is not None for same in shared):
            raise ValueError(f"{spec.name}: BAR0 has it for some of X and Y only")
        for same in shared:
            if same is not None and (_shape(same) != _shape(spec) or same.option != spec.option):
                raise ValueError(f"{same.name}: not the register {spec.name} of the block describes")
    blocks_end = regmap.AXIS_BLOCK_BASE + regmap.AXIS_STRIDE * len(AXIS_NAMES)
    if regmap.AXIS_BLOCK_BASE < 1 << regmap.IO_BAR_BITS or blocks_end > 1 << regmap.REG_BAR_BITS:
        raise ValueError("the per-axis blocks overlap BAR0's registers or leave BAR2")

