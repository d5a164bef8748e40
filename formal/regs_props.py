"""Register properties generated from the register table (models/registers.py),
as the RTL decoder, docs/registers.md and the C header are.

``register_offsets()`` returns the names of the offsets, SET indexes and
fields the harnesses use (``regs_offsets.vh``).  ``table_properties()``
returns the body that ``props/regs_fifo_harness.sv``
includes (``regs_table.vh``): for every register, reads return zero in the
bits outside its fields; ID reads its constant; every RW register has a model
that takes bus writes (byte enables honoured, the merged value clamped to
min..max, one clock after the bus transfer as docs/registers.md and
rtl/regs_fifo.py say) and SET commands (the value clamped), and every read
of it returns the model as it was in the read's wait clock; a bit of a write-one-to-clear register read as 1
reads 1 until a write of 1 to it; INT_STATUS.CLAMPED reads 1 only after a
write out of a register's range; offsets the table does not list read 0.
"""
from models import registers as regmap
from models.parameters import AXES

COMMAND_READS_ZERO = ("COMMAND",)   # "one-shot actions (read as 0)"
# The harness signal that clears each RW field with ``cleared`` (the condition
# rtl/regs_fifo.py drives the register's hw bits with): its model clears it too.
CLEARED_BY = {("MACHINE_CONTROL", "DRIVE_ENABLE"): "guard_stopped"}
# the registers as the proved build (gen/: the default axes) has them: the input
# registers keep the fields of its inputs only (``models.registers.built_register``)
BUILT = tuple(regmap.built_register(reg, AXES.default) for reg in regmap.REGISTERS)


def _mask(reg):
    mask = 0
    for item in reg.fields:
        mask |= item.mask
    return mask


def _bus_write(reg):
    """The condition of a bus write to ``reg`` in the last clock: at its offset, or at its
    alias in BAR2's per-axis blocks (X's and Y's registers, ``models.registers.axis_aliases``)."""
    offsets = [reg.offset] + [bar2 for bar2, bar0 in regmap.axis_aliases().items() if bar0 == reg.offset]
    at = " || ".join(f"stage_addr == 16'h{offset:04X}" for offset in offsets)
    return f"stage_write && ({at})" if len(offsets) > 1 else f"stage_write && {at}"


def _clamp_function(reg):
    """A Verilog function giving the value a 32-bit write leaves in ``reg``."""
    width = reg.width
    name = f"clamp_{reg.name.lower()}"
    lines = [f"    function [{width - 1}:0] {name}(input [31:0] value);"]
    if reg.minimum is None and reg.maximum is None:
        lines.append(f"        {name} = value[{width - 1}:0];")
    else:
        low = reg.minimum if reg.minimum is not None else 0
        high = reg.maximum if reg.maximum is not None else (1 << width) - 1
        lines += [f"        if (value < 32'd{low}) {name} = {width}'d{low};",
                  f"        else if (value > 32'd{high}) {name} = {width}'d{high};",
                  f"        else {name} = value[{width - 1}:0];"]
    lines.append("    endfunction")
    return lines


def _clamped_only_after_a_clamp():
    """INT_STATUS.CLAMPED reads 1 only after a write out of a register's
    min..max (docs/registers.md: such a write is clamped and sets it): a bus
    write whose merged value is out of range, a SET whose value is; a write to
    a WP register with a range counts whatever its value (its range is signed;
    counting more writes only weakens the rule, never fails it wrongly)."""
    causes = []
    for reg in BUILT:
        if reg.minimum is None and reg.maximum is None:
            continue
        write = _bus_write(reg)
        if reg.access != "RW":
            causes.append(f"({write})")
            continue
        upper, width = reg.name.lower(), reg.width
        merged = f"(({{{32 - width}'h0, model_{upper}}} & ~stage_mask) | (stage_data & stage_mask))"
        causes.append(f"({write} && clamp_{upper}({merged}) != {merged})")
        if reg.set_index is not None:
            causes.append(f"(set_strobe && set_index == 4'd{reg.set_index} "
                          f"&& {{{32 - width}'h0, clamp_{upper}(set_value)}} != set_value)")
    status = regmap.register("INT_STATUS")
    bit = status.field("CLAMPED").lsb
    return ["    // INT_STATUS.CLAMPED only after a write was clamped (a bus write or a SET out of range)",
            "    reg clamp_seen = 0;",
            "    always @(posedge clock) begin",
            "        if (!reset_n) clamp_seen <= 0;",
            "        else if (" + "\n                 || ".join(causes) + ") clamp_seen <= 1;",
            "    end",
            f"    always @(posedge clock) if (reset_n && read_now && l_addr == 16'h{status.offset:04X}) begin",
            f"        reg_int_status_clamped_after_a_clamp: assert(!l_rdata[{bit}] || clamp_seen);",
            "    end"]


def _cleared_mask(reg):
    """The Verilog expression of the bits the hardware clears in ``reg`` now ("" if none)."""
    terms = []
    for item in reg.fields:
        if item.cleared is None:
            continue
        try:
            signal = CLEARED_BY[(reg.name, item.name)]
        except KeyError:
            raise ValueError(f"{reg.name}.{item.name} is cleared by the hardware: CLEARED_BY names no signal") from None
        terms.append(f"({signal} ? {reg.width}'h{item.mask:X} : {reg.width}'h0)")
    return " | ".join(terms)


def register_offsets():
    """The generated include ``regs_offsets.vh``: each register's offset
    (REG_<NAME>), the SET index of those a SET command writes (SET_<NAME>),
    and each field's place (<REG>_<FIELD>_LSB, _WIDTH), for the harnesses
    that write and read the registers by name."""
    lines = ["// Generated from models/registers.py by formal/regs_props.py; do not edit.",
             "// Included into regs_fifo_harness and machine_harness."]
    for reg in regmap.REGISTERS:
        lines.append(f"    localparam [15:0] REG_{reg.name} = 16'h{reg.offset:04X};")
        if reg.set_index is not None:
            lines.append(f"    localparam [3:0] SET_{reg.name} = 4'd{reg.set_index};")
        for item in reg.fields:
            lines += [f"    localparam {reg.name}_{item.name}_LSB = {item.lsb};",
                      f"    localparam {reg.name}_{item.name}_WIDTH = {item.width};"]
    return "\n".join(lines) + "\n"


def table_properties():
    """The generated include: models and assertions for every register."""
    lines = ["// Generated from models/registers.py by formal/regs_props.py; do not edit.",
             "// Included into regs_fifo_harness: reads (read_now, l_addr, l_rdata), the",
             "// bus write of the last clock (stage_*), SET commands (set_strobe, set_index,",
             "// set_value)."]
    listed = []
    for reg in BUILT:
        listed.append(reg.offset)
        upper = reg.name.lower()
        mask = _mask(reg)
        lines.append(f"    // {reg.name} ({reg.offset:#04x}, {reg.access}): {reg.text}")
        if reg.access == "RW":
            width = reg.width
            lines += _clamp_function(reg)
            lines.append(f"    reg [{width - 1}:0] model_{upper} = {width}'d{reg.reset};")
            lines.append("    always @(posedge clock) begin")
            lines.append(f"        if (!reset_n) model_{upper} <= {width}'d{reg.reset};")
            if reg.set_index is not None:
                lines.append(f"        else if (set_strobe && set_index == 4'd{reg.set_index}) "
                             f"model_{upper} <= clamp_{upper}(set_value);")
            cleared = _cleared_mask(reg)
            keep = f" & ~({cleared})" if cleared else ""
            lines.append(f"        else if ({_bus_write(reg)})")
            lines.append(f"            model_{upper} <= clamp_{upper}(({{{32 - width}'h0, model_{upper}}} & ~stage_mask)"
                         f" | (stage_data & stage_mask)){keep};")
            if cleared:
                lines.append(f"        else model_{upper} <= model_{upper}{keep};   // the hardware clears it")
            lines.append("    end")
            lines.append(f"    reg [{width - 1}:0] model_{upper}_read = {width}'d{reg.reset};   // a read returns its wait clock's value")
            lines.append(f"    always @(posedge clock) model_{upper}_read <= model_{upper};")
        if reg.access == "W1C":
            lines += [f"    reg [31:0] {upper}_before = 0, {upper}_cleared = 0;   // last read, bits written 1 since",
                      f"    wire [31:0] {upper}_clearing = (stage_write && stage_addr == 16'h{reg.offset:04X})"
                      f" ? stage_data & stage_mask : 32'h0;",
                      "    always @(posedge clock) begin",
                      f"        {upper}_cleared <= (read_now && l_addr == 16'h{reg.offset:04X} ? 32'h0 : {upper}_cleared)"
                      f" | {upper}_clearing;",
                      f"        if (!reset_n) {upper}_before <= 0;",
                      f"        else if (read_now && l_addr == 16'h{reg.offset:04X}) {upper}_before <= l_rdata;",
                      "    end"]
        lines.append(f"    always @(posedge clock) if (reset_n && read_now && l_addr == 16'h{reg.offset:04X}) begin")
        if mask != 0xFFFFFFFF:
            lines.append(f"        reg_{upper}_reserved_zero: assert((l_rdata & 32'h{(~mask) & 0xFFFFFFFF:08X}) == 32'h0);")
        if reg.name == "ID":
            lines.append(f"        reg_{upper}_constant: assert(l_rdata == 32'h{reg.reset:08X});")
        if reg.name in COMMAND_READS_ZERO:
            lines.append(f"        reg_{upper}_reads_zero: assert(l_rdata == 32'h0);")
        if reg.access == "W1C":
            lines.append(f"        reg_{upper}_set_until_cleared: assert(({upper}_before & ~{upper}_cleared & ~l_rdata) == 32'h0);")
        if reg.access == "RW":
            lines.append(f"        reg_{upper}_reads_model: assert(l_rdata == {{{32 - reg.width}'h0, model_{upper}_read}});")
        lines.append("    end")
    lines += _clamped_only_after_a_clamp()
    size = 1 << regmap.IO_BAR_BITS
    unlisted = " && ".join(f"l_addr != 16'h{offset:04X}" for offset in listed)
    lines += ["    // offsets the table does not list read 0 (docs/registers.md)",
              f"    always @(posedge clock) if (reset_n && read_now && l_addr < 16'd{size} && {unlisted}) begin",
              "        reg_unlisted_reads_zero: assert(l_rdata == 32'h0);",
              "    end"]
    return "\n".join(lines) + "\n"
