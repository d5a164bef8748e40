"""The command set's constants for the harnesses, generated from
models/instructions.py as the sequencer, docs/instructions.md and the host's
encoder are.

``instruction_table()`` returns the body of ``isa_table.vh``, included by
``props/card_harness.sv`` and ``props/regs_fifo_harness.sv``: where the opcode
sits in a header, each opcode (OPCODE_<NAME>) and its header fields
(<NAME>_<FIELD>_LSB, _WIDTH), and per opcode whether it is in the table, its
header mask and its number of operand words.
"""
from models import instructions as isa


def instruction_table():
    """The generated include ``isa_table.vh``."""
    lines = ["// Generated from models/instructions.py by formal/isa_props.py; do not edit.",
             "// Included into card_harness and regs_fifo_harness.",
             f"    localparam OPCODE_LSB = {isa.OPCODE_LSB};"]
    for op in isa.OPCODES:
        lines.append(f"    localparam [3:0] OPCODE_{op.name} = 4'd{op.code};")
        for name, lsb, width, _ in op.header_fields:
            lines += [f"    localparam {op.name}_{name}_LSB = {lsb};", f"    localparam {op.name}_{name}_WIDTH = {width};"]
    lines += ["    // opcodes of the table: known, header mask, operand words",
              "    function opcode_known(input [3:0] opcode);",
              "        case (opcode)"]
    lines += [f"            OPCODE_{op.name}: opcode_known = 1;" for op in isa.OPCODES]
    lines += ["            default: opcode_known = 0;", "        endcase", "    endfunction",
              "    function [31:0] header_mask(input [3:0] opcode);", "        case (opcode)"]
    lines += [f"            OPCODE_{op.name}: header_mask = 32'h{op.header_mask:08X};" for op in isa.OPCODES]
    lines += ["            default: header_mask = 32'hFFFFFFFF;", "        endcase", "    endfunction",
              "    function [2:0] operand_words(input [3:0] opcode);", "        case (opcode)"]
    lines += [f"            OPCODE_{op.name}: operand_words = 3'd{len(op.operands)};" for op in isa.OPCODES]
    lines += ["            default: operand_words = 3'd0;", "        endcase", "    endfunction"]
    return "\n".join(lines) + "\n"
