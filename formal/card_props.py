"""Constants of the whole-card properties, generated from the register table
(models/registers.py) and the command set (models/instructions.py), as the RTL
decoder, docs and C header are.

``card_constants()`` returns the body that ``props/card_harness.sv``
includes (``card_table.vh``): the dword offsets of CONTROL, COMMAND, STATUS
and the machine registers the harness keeps at rest, the STATUS fields, the
error codes, and per opcode whether it is in the table, its header mask and
its number of operand words.
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
    lines.append(f"    localparam OPCODE_LSB = {isa.OPCODE_LSB};")
    lines += ["    // opcodes of the table: known, header mask, operand words",
              "    function opcode_known(input [3:0] opcode);",
              "        case (opcode)"]
    lines += [f"            4'd{op.code}: opcode_known = 1;   // {op.name}" for op in isa.OPCODES]
    lines += ["            default: opcode_known = 0;", "        endcase", "    endfunction",
              "    function [31:0] header_mask(input [3:0] opcode);", "        case (opcode)"]
    lines += [f"            4'd{op.code}: header_mask = 32'h{op.header_mask:08X};" for op in isa.OPCODES]
    lines += ["            default: header_mask = 32'hFFFFFFFF;", "        endcase", "    endfunction",
              "    function [2:0] operand_words(input [3:0] opcode);", "        case (opcode)"]
    lines += [f"            4'd{op.code}: operand_words = 3'd{len(op.operands)};" for op in isa.OPCODES]
    lines += ["            default: operand_words = 3'd0;", "        endcase", "    endfunction"]
    return "\n".join(lines) + "\n"
