"""The command set's constants for the harnesses, generated from
models/instructions.py as the sequencer, docs/instructions.md and the host's
encoder are.

``instruction_table()`` returns the body of ``isa_table.vh``, included by
``props/card_harness.sv`` and ``props/regs_fifo_harness.sv``: where the opcode
sits in a header, each opcode (OPCODE_<NAME>) and its header fields
(<NAME>_<FIELD>_LSB, _WIDTH), and per opcode whether it is in the table and
its header mask; the number of operand words a header frames (the N-axis
form, docs/axes.md: the fixed operands, then those an axis mask stands for).
"""
from models import instructions as isa
from models.axes import axes_of


def instruction_table():
    """The generated include ``isa_table.vh``."""
    lines = ["// Generated from models/instructions.py by formal/isa_props.py; do not edit.",
             "// Included into card_harness and regs_fifo_harness.",
             f"    localparam OPCODE_LSB = {isa.OPCODE_LSB};"]
    for op in isa.OPCODES:
        lines.append(f"    localparam [3:0] OPCODE_{op.name} = 4'd{op.code};")
        for name, lsb, width, _ in op.fields:
            lines += [f"    localparam {op.name}_{name}_LSB = {lsb};", f"    localparam {op.name}_{name}_WIDTH = {width};"]
    lines += ["    // opcodes of the table: known, header mask, operand words",
              "    function opcode_known(input [3:0] opcode);",
              "        case (opcode)"]
    lines += [f"            OPCODE_{op.name}: opcode_known = 1;" for op in isa.OPCODES]
    lines += ["            default: opcode_known = 0;", "        endcase", "    endfunction",
              "    function [31:0] header_mask(input [3:0] opcode);", "        case (opcode)"]
    lines += [f"            OPCODE_{op.name}: header_mask = 32'h{op.axis_header_mask:08X};" for op in isa.OPCODES]
    lines += ["            default: header_mask = 32'hFFFFFFFF;", "        endcase", "    endfunction",
              "    function [3:0] operand_words(input [31:0] header);",
              f"        reg [{isa.AXIS_MASK_WIDTH - 1}:0] axis_mask;", "        integer index;", "        begin",
              f"            axis_mask = header[{isa.AXIS_MASK_LSB + isa.AXIS_MASK_WIDTH - 1}:{isa.AXIS_MASK_LSB}];",
              "            case (header[31:OPCODE_LSB])"]
    for op in isa.OPCODES:
        fixed, spec = len(op.fixed_operands), op.axis_operands
        if spec is None:
            lines.append(f"                OPCODE_{op.name}: operand_words = 4'd{fixed};")
            continue
        lines += [f"                OPCODE_{op.name}: begin",
                  f"                    operand_words = 4'd{fixed + len(axes_of(spec.zero_mask))};",
                  f"                    if (axis_mask != 0) begin",
                  f"                        operand_words = 4'd{fixed + len(spec.lead)};",
                  f"                        for (index = 0; index < {isa.AXIS_MASK_WIDTH}; index = index + 1)",
                  "                            operand_words = operand_words + axis_mask[index];",
                  "                    end", "                end"]
    lines += ["                default: operand_words = 4'd0;", "            endcase", "        end", "    endfunction"]
    return "\n".join(lines) + "\n"
