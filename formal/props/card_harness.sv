// The whole card (gen/card.v: PCI target, back end, sequencer and DDA in one
// netlist, what users synthesise) on a formal bus: a free initiator that
// keeps PCI's initiator rules (pci_rules.sv, CHECK_TARGET = 1: the
// initiator's rules assumed; the target's rules are proved on the target
// alone and dropped here).  Checked across the seam between target and back
// end, on the bus the host sees:
//   * FIFO order (issue 16: "every dword written with IRDY# and TRDY# both
//     asserted reaches the sequencer in order, none twice"): the N-th dword
//     written on the bus into BAR1 (N a free constant) is the N-th word the
//     sequencer takes from the FIFO, with its value; no word is taken that
//     was not written;
//   * STATUS truth (docs/registers.md STATUS, issue 16: "the status register
//     tells the truth about FIFO level and errors"): a read of STATUS
//     completed on the bus, through the I/O BAR0 or its memory alias BAR2,
//     carries a FIFO_LEVEL that the count of words
//     written on the bus minus words taken had during the transaction,
//     FIFO_EMPTY and FIFO_FULL as that level says, and the ERROR code of
//     docs/instructions.md for the first command.
// The register offsets, STATUS fields and error codes come from
// card_table.vh, generated from models/registers.py and models/instructions.py by
// formal/card_props.py, the opcodes from isa_table.vh (formal/isa_props.py).  Where the sequencer takes a word (its FIFO pop, the
// FIFO's empty flag and output register) is inside the card: yosys `expose`
// makes those signals ports, so the generated file is read unchanged.  The
// bus lines, PCI pins and bus model are pci_target_harness.sv's
// (pci_bus_lines.vh, pci_pins.vh, pci_bus_model.vh, with pci_table.vh).
// The card's per-axis pins (STEP/DIR, the machine inputs) are vectors over
// the build's AXES and INPUTS, wired by card_axes.vh (formal/axes_props.py).
//
// Limits of the environment (each a restriction of what the bus does):
//   * no register write (BAR0 or BAR2) to COMMAND (SOFT_RESET, CLEAR_ERROR
//     and CLEAR_STOP empty the FIFO, which the shadows do not follow);
//   * with MACHINE_RUNNING: machine inputs at rest and no register write to
//     MACHINE_CONTROL, INPUT_POLARITY, WATCHDOG or HOME, so the guard never
//     stops, holds or homes the card (the error properties need the
//     sequencer to run); otherwise the machine inputs are free.
`default_nettype none

module card_harness #(
    parameter IO_BITS = 8,
    parameter MEM_BITS = 12,
    parameter REG_BITS = 12,       // BAR2: 4 KiB, BAR0's registers then the per-axis blocks
    parameter DEPTH = 512,
    parameter ERROR_LATENCY = 4,   // clocks from a malformed command to STATUS.ERROR
    parameter AXES = 2,            // axes of the build (formal/axes_props.py)
    parameter INPUTS = 7           // its machine inputs: E-STOP, limits and home switches
) (
    input wire clock,
    input wire reset_n,
    // the initiator
    input wire [31:0] m_ad, input wire [3:0] m_cbe_n, input wire m_par,
    input wire m_frame_n, input wire m_irdy_n, input wire m_idsel
);
`include "card_table.vh"
`include "isa_table.vh"
`include "pci_table.vh"
    // the chosen data phase of the order shadow
    (* anyconst *) reg [3:0] chosen;

    // ------------------------------------------------------------ the card
    // this card is the only target: the lines are its drivers or the initiator's
    wire o_trdy_n = 1'b1, o_devsel_n = 1'b1, o_stop_n = 1'b1;
`include "pci_bus_lines.vh"
    wire [AXES-1:0] step, dir;
    wire drive_enable;
    // exposed signals of the card: the sequencer's pop, the FIFO's empty flag and output
    wire fifo_pop, fifo_empty;
    wire [31:0] fifo_dout;

`ifdef MACHINE_RUNNING
    wire [INPUTS-1:0] machine_in = 0;
`else
    (* anyseq *) wire [INPUTS-1:0] machine_in;
`endif

    card dut (
`include "pci_pins.vh"
        , .pins_drive_enable(drive_enable),
        .card_core0_regs_fifo1_fifo_pop(fifo_pop), .card_core0_regs_fifo1_fifo_empty(fifo_empty),
        .card_core0_regs_fifo1_fifo_dout(fifo_dout)
`include "card_axes.vh"
        );

`include "harness_reset.vh"

    // ------------------------------------------------------------ the bus
    // the configuration a target decodes with (6.2.2 Command, 6.2.5 BARs),
    // written by the configuration writes seen on the bus, and the
    // transaction (pci_bus_model.vh, shared with pci_target_harness.sv, where
    // the target's decode is proved against it)
`include "pci_bus_model.vh"
    // the register dword a transaction reaches: BAR0's offset, or BAR2's
    // whole (BAR2 is larger than BAR0: its offsets reach the back end whole)
    wire [31:0] reg_offset = txn_alias ? txn_address & ~ALIAS_WRITABLE : {16'h0, txn_address[15:0] & ~IO_WRITABLE};
    wire [29:0] io_dword = reg_offset[31:2];

    // the limits of the environment (above), on the address phase of a register write
    wire [5:0] address_dword = ad[IO_BITS-1:2];
    wire io_write_address = address_edge && (command == CMD_IO_WRITE || (alias_hit && command[0]));
    always @(*) begin
        if (io_write_address) assume(address_dword != DWORD_COMMAND);
`ifdef MACHINE_RUNNING
        if (io_write_address) assume(address_dword != DWORD_MACHINE_CONTROL
                                     && address_dword != DWORD_INPUT_POLARITY
                                     && address_dword != DWORD_WATCHDOG && address_dword != DWORD_HOME);
`endif
    end

    // ------------------------------------------------------------ words written and taken
    // docs/instructions.md: every data phase into BAR1 with at least one byte
    // enabled pushes one word into the FIFO
    wire bus_push = our_transfer && txn_write && !txn_regs && !txn_config && m_cbe_n != 4'hF;
    wire take = fifo_pop && !fifo_empty;   // the sequencer takes a word
    reg [7:0] written = 0, taken = 0;      // since reset (the bounded runs stay far below 256)
    wire [7:0] level = written - taken;    // words written on the bus and not taken
    reg [31:0] chosen_word = 0;
    reg arriving = 0;                      // the chosen word is on the FIFO's output now
    always @(posedge clock) begin
        if (!reset_n) begin
            written <= 0;
            taken <= 0;
            arriving <= 0;
        end else begin
            written <= written + bus_push;
            taken <= taken + take;
            if (bus_push && written == chosen)
                chosen_word <= ad;
            arriving <= take && taken == chosen;
        end
    end
    always @(posedge clock) if (reset_n) begin
        // issue 16: no word taken that was not written on the bus (the first
        // data phase of a write reaches the back end before its TRDY#,
        // docs/pci.md, so the sequencer may take it at the edge the phase completes)
        if (take) begin card_fifo_taken_was_written: assert(taken < written + bus_push); end
        // issue 16: the N-th dword written (IRDY# and TRDY#) is the N-th word
        // the sequencer takes, in order, none twice
        if (arriving) begin card_fifo_in_order: assert(fifo_dout == chosen_word); end
    end

    // ------------------------------------------------------------ STATUS
    // the level during the transaction: no word is written on the bus during
    // a register read (and the target delivers its posted dwords before a new
    // transaction, docs/pci.md), so it only falls from the address edge on
    reg [7:0] level_at_address = 0;
    always @(posedge clock) if (address_edge) level_at_address <= level;
    wire status_read = our_transfer && txn_regs && !txn_write && io_dword == DWORD_STATUS;
    wire [STATUS_FIFO_LEVEL_WIDTH-1:0] read_level = ad[STATUS_FIFO_LEVEL_LSB +: STATUS_FIFO_LEVEL_WIDTH];
    wire [STATUS_ERROR_WIDTH-1:0] read_error = ad[STATUS_ERROR_LSB +: STATUS_ERROR_WIDTH];
    wire read_empty = ad[STATUS_FIFO_EMPTY_LSB], read_full = ad[STATUS_FIFO_FULL_LSB];
    always @(posedge clock) if (reset_n && status_read) begin
        // docs/registers.md STATUS.FIFO_LEVEL: words in the FIFO
        card_status_level: assert(read_level <= level_at_address && read_level + take >= level);
        // STATUS.FIFO_EMPTY: the FIFO holds no word; STATUS.FIFO_FULL: it is full
        card_status_empty: assert(read_empty == (read_level == 0));
        card_status_full: assert(read_full == (read_level == DEPTH));
    end

    // ------------------------------------------------------------ STATUS.ERROR
    // The first word written after reset is the first header the sequencer
    // takes (no COMMAND write empties the FIFO).  docs/instructions.md: an
    // opcode not in the table gives BAD_OPCODE, a header bit outside the
    // opcode's fields RESERVED_BITS; the sequencer checks a command when its
    // operand words have arrived and executes it once CONTROL.ENABLE is set.
    reg [31:0] first_written = 0;   // the first word the host wrote: the first header
    reg [31:0] first_header = 0;    // that word, once the sequencer has taken its first word
    reg [3:0] operands_due = 0;     // operand words of the first command not yet taken
    reg first_taken = 0;            // the first command's words have all been taken
    reg control_enable = 0;         // CONTROL.ENABLE and not MODE, as written on the bus
    reg [4:0] ready_for = 0;        // clocks since the first command was taken with ENABLE set
    // (the sequencer may take it at the edge its data phase completes)
    wire [31:0] first_word = (bus_push && written == 0) ? ad : first_written;
    wire [3:0] first_opcode = first_header[31:OPCODE_LSB];
    wire first_bad_opcode = !opcode_known(first_opcode);
    wire first_reserved = !first_bad_opcode && (first_header & ~header_mask(first_opcode)) != 0;
    always @(posedge clock) begin
        if (!reset_n) begin
            operands_due <= 0;
            first_taken <= 0;
            control_enable <= 0;
            ready_for <= 0;
        end else begin
            if (bus_push && written == 0)
                first_written <= ad;
            if (take && taken == 0) begin
                first_header <= first_word;
                operands_due <= operand_words(first_word);
                first_taken <= !opcode_known(first_word[31:OPCODE_LSB])
                               || operand_words(first_word) == 0;
            end else if (take && operands_due != 0) begin
                operands_due <= operands_due - 1;
                if (operands_due == 1) first_taken <= 1;
            end
            if (our_transfer && txn_regs && txn_write && io_dword == DWORD_CONTROL && !m_cbe_n[0])
                control_enable <= ad[CONTROL_ENABLE] && !ad[CONTROL_MODE];
            if (!(first_taken && control_enable))
                ready_for <= 0;
            else if (ready_for != 5'h1f)
                ready_for <= ready_for + 1;
        end
    end
    reg [4:0] ready_at_address = 0;
    reg before_any_take = 0;
    always @(posedge clock) if (address_edge) begin
        ready_at_address <= ready_for;
        before_any_take <= taken == 0 && !take;
    end
    always @(posedge clock) if (reset_n && status_read) begin
        // STATUS.ERROR 0: none, while no command has been taken
        if (before_any_take) begin card_status_error_none: assert(read_error == ERROR_NONE); end
        if (ready_at_address >= ERROR_LATENCY) begin
            if (first_bad_opcode) begin card_status_error_bad_opcode: assert(read_error == ERROR_BAD_OPCODE); end
            if (first_reserved) begin card_status_error_reserved_bits: assert(read_error == ERROR_RESERVED_BITS); end
        end
    end

    // ------------------------------------------------------------ reachable within the depths
    // (group card_covers): a burst's second word taken in order, a STATUS
    // read with words in the FIFO, a STATUS read showing a malformed command
    always @(posedge clock) if (reset_n) begin
        card_cover_second_word: cover(arriving && chosen == 1 && fifo_dout == chosen_word);
        card_cover_status_with_words: cover(status_read && read_level != 0 && !read_empty);
        card_cover_status_through_bar2: cover(status_read && txn_alias && read_level != 0);
        card_cover_status_bad_opcode: cover(status_read && ready_at_address >= ERROR_LATENCY
                                            && read_error == ERROR_BAD_OPCODE);
        card_cover_status_reserved_bits: cover(status_read && ready_at_address >= ERROR_LATENCY
                                               && read_error == ERROR_RESERVED_BITS);
    end
endmodule
