"""Constants of the whole-card properties, generated from the register table
(models/registers.py) and the command set's error codes
(models/instructions.py), as the RTL decoder, docs and C header are.

``card_constants()`` returns the body that ``props/card_harness.sv``
includes (``card_table.vh``): the dword offsets of CONTROL, COMMAND, STATUS
and the machine registers the harness keeps at rest, the STATUS fields and
the error codes.  The opcode table is ``isa_table.vh`` (formal/isa_props.py),
which the back end's harness reads too.
"""
from models import instructions as isa
from models import registers as regmap

STATUS_FIELDS = ("ERROR", "FIFO_EMPTY", "FIFO_FULL", "FIFO_LEVEL")
# registers whose writes could stop, hold or home the card (docs/machine.md)
MACHINE_REGISTERS = ("MACHINE_CONTROL", "INPUT_POLARITY", "WATCHDOG", "HOME")


def _dword(name):
    return regmap.offset(name) // regmap.WORD_BYTES


def card_constants():
    """The generated include of card_harness.sv."""
    lines = ["// Generated from models/registers.py and models/instructions.py by formal/card_props.py;",
             "// do not edit.  Included into card_harness."]
    for name in ("CONTROL", "COMMAND", "STATUS", *MACHINE_REGISTERS):
        lines.append(f"    localparam [5:0] DWORD_{name} = 6'd{_dword(name)};   // {regmap.offset(name):#04x}")
    enable = regmap.register("CONTROL").field("ENABLE")
    mode = regmap.register("CONTROL").field("MODE")
    lines += [f"    localparam CONTROL_ENABLE = {enable.lsb};", f"    localparam CONTROL_MODE = {mode.lsb};"]
    status = regmap.register("STATUS")
    for name in STATUS_FIELDS:
        item = status.field(name)
        lines += [f"    localparam STATUS_{name}_LSB = {item.lsb};",
                  f"    localparam STATUS_{name}_WIDTH = {item.width};"]
    for code, name, _ in isa.ERRORS:
        lines.append(f"    localparam [3:0] ERROR_{name} = 4'd{code};")
    return "\n".join(lines) + "\n"
