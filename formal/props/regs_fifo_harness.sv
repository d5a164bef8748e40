// The card's back end (gen/regs_fifo.v: function registers, data FIFO,
// sequencer, pulse outputs) behind a free requester that keeps the LocalBus
// rules, with a free interpolator on its DDA port.  Checked here:
//   * the LocalBus responder rules (local_bus_rules.sv, back-end side);
//   * register accesses never retry; a write is answered at once, a read
//     after one wait clock, as rtl/regs_fifo.py documents (either waits one
//     clock more in the clock after an I/O write); a read returns the
//     registers as they were in its wait clock (`*_read` below);
//   * the FIFO: a model counts the words the bus pushed (a memory-BAR write
//     answered ready with a byte enabled) and the sequencer took; STATUS
//     tells the truth about level, empty and full; no acknowledged word is
//     lost (a push is answered ready only with room, and not dropped by a
//     flush in the same clock); words reach the sequencer in order, none
//     twice (a chosen-one shadow);
//   * every register as the table says (regs_table.vh, generated from
//     models/registers.py by formal/regs_props.py);
//   * the pulse outputs: STEP widths, DIR set-up and hold, no STEP without a
//     request, every request on its pin (the modules of pulse_rules.sv), on
//     every axis of the build, and POS_X counting the STEP pulses.
// The consumer side of the FIFO (the sequencer's pop, the flush) and the SET
// command's write port are registers inside the unit: yosys `expose` makes
// them ports, so the generated file is read unchanged.  The environment
// (requester, register stage and models, FIFO level, interpolator) and the
// unit's common ports are machine_harness.sv's too: regs_fifo_env.vh,
// regs_fifo_ports.vh.  The per-axis signals are vectors over the build's
// AXES (0 X, 1 Y, 2 Z, ...), wired by regs_fifo_axes.vh, which
// formal/axes_props.py generates for the build (AXES and INPUTS, the
// machine inputs, are set to match).
`default_nettype none

module regs_fifo_harness #(
    parameter DEPTH = 512,
    parameter COORD_WIDTH = 24,
    parameter AXES = 2,             // axes of the build (formal/axes_props.py)
    parameter INPUTS = 7            // its machine inputs: E-STOP, limits and home switches
) (
    input wire clock,
    input wire reset_n,
    // the requester (the PCI target)
    input wire l_space, input wire [15:0] l_addr, input wire [3:0] l_be, input wire [31:0] l_wdata,
    input wire l_we, input wire l_re, input wire l_write,
    // the interpolator
    input wire dda_busy, input wire dda_done, input wire dda_error, input wire [1:0] dda_quadrant,
    input wire dda_ready, input wire [COORD_WIDTH+2:0] dda_stop_left,
    input wire [AXES-1:0] steps_step, input wire [AXES-1:0] steps_dir,
    // free choice of the order shadow: follow the word pushed at this edge;
    // of the command shadow: follow the command whose header arrives now
    input wire choose_push, input wire choose_command
);
`include "regs_offsets.vh"
`include "isa_table.vh"
    wire [31:0] fifo_dout;      // exposed: the FIFO's output register

    // The machine inputs (E-STOP, limits, home): free, or with
    // MACHINE_RUNNING at rest, with their polarity and the watchdog left as
    // reset (no write to INPUT_POLARITY or WATCHDOG), so the guard never
    // stops the card, MACHINE_CONTROL.HOLD never set, so the feed never
    // holds, and no HOME (0x7C), which holds the commands while it homes:
    // the groups that follow every command or every step to its end judge a
    // running machine (docs/machine.md for the stops, the hold and homing).
`ifdef MACHINE_RUNNING
    wire [INPUTS-1:0] machine_in = 0;
    always @(*) assume(!(l_we && !l_space && (l_offset == REG_INPUT_POLARITY || l_offset == REG_WATCHDOG || l_offset == REG_HOME)));
    always @(*) assume(!(l_we && !l_space && l_offset == REG_MACHINE_CONTROL && l_be[0] && l_wdata[MACHINE_CONTROL_HOLD_LSB]));
`else
    (* anyseq *) wire [INPUTS-1:0] machine_in;
`endif

`include "regs_fifo_env.vh"

    regs_fifo dut (
`include "regs_fifo_ports.vh"
        , .fifo_dout(fifo_dout)
`ifdef REGS_FIFO_INVARIANTS
        , .sync_fifo0_count(sync_fifo0_count), .sync_fifo0_is_empty(sync_fifo0_is_empty),
`ifdef LOCAL_ROOM
        .sync_fifo0_free(sync_fifo0_free), .sync_fifo0_free_beyond(sync_fifo0_free_beyond),
`else
        .sync_fifo0_is_full(sync_fifo0_is_full),
`endif
        .io_written(io_written), .read_waited(read_waited)
`endif
        );
`ifdef REGS_FIFO_INVARIANTS
    wire [9:0] sync_fifo0_count;
    wire sync_fifo0_is_empty, sync_fifo0_is_full, io_written, read_waited;
    wire [2:0] sync_fifo0_free;
    wire sync_fifo0_free_beyond;
`endif

    // ------------------------------------------------------------ register access
    // a register read asked in the last clock, not in the clock after an I/O write
    reg read_asked = 0;
    always @(posedge clock) read_asked <= reset_n && l_re && !l_space && !l_ready && !stage_write;
    always @(posedge clock) if (reset_n) begin
        if ((l_we || l_re) && !l_space) begin
            rf_registers_never_retry: assert(!l_retry);
            if (l_we) begin rf_registers_write_at_once: assert(l_ready || stage_write); end
            if (l_re) begin rf_registers_read_after_one_wait: assert(l_ready == read_asked); end
        end
    end

    // ------------------------------------------------------------ the FIFO
    // (level, push, pop: regs_fifo_env.vh)
    reg [10:0] level_read = 0;  // a read returns STATUS of its wait clock
    always @(posedge clock) level_read <= level;
    always @(posedge clock) if (reset_n) begin
        rf_level_at_most_depth: assert(level <= DEPTH);
        if (push) begin rf_push_only_with_room: assert(level < DEPTH || pop); end
        if (push) begin rf_push_not_flushed: assert(!fifo_flush); end
        if (l_we && l_space && !stage_write) begin rf_full_answers_retry: assert(l_retry == (level == DEPTH) && l_ready == !l_retry); end
        if (read_now && l_offset == REG_STATUS) begin
            rf_status_level: assert(l_rdata[STATUS_FIFO_LEVEL_LSB +: STATUS_FIFO_LEVEL_WIDTH] == level_read);
            rf_status_empty: assert(l_rdata[STATUS_FIFO_EMPTY_LSB] == (level_read == 0));
            rf_status_full: assert(l_rdata[STATUS_FIFO_FULL_LSB] == (level_read == DEPTH));
        end
    end

    // in order, none twice: the chosen word leaves the FIFO after the ones ahead
    reg tracking = 0, arriving = 0;
    reg [10:0] ahead = 0;
    reg [31:0] tracked = 0;
    always @(posedge clock) begin
        arriving <= 0;
        if (!reset_n || fifo_flush) begin
            tracking <= 0;
        end else if (tracking) begin
            if (pop) begin
                if (ahead == 0) begin
                    tracking <= 0;
                    arriving <= 1;
                end else
                    ahead <= ahead - 1;
            end
        end else if (push && choose_push) begin
            tracking <= 1;
            tracked <= l_wdata;
            ahead <= level - pop;
        end
    end
    always @(posedge clock) if (reset_n) begin
        if (arriving) begin rf_fifo_in_order: assert(fifo_dout == tracked); end
    end
    // ------------------------------------------------------------ commands as written
    // The words leave the FIFO in order (rf_fifo_in_order); here the commands
    // they frame (docs/instructions.md: a header, opcode in bits 31:28, then
    // its operand words) are followed to where the sequencer executes them:
    // the n-th LINE/ARC gives the n-th DDA start with its operands and header
    // fields, the n-th SET the n-th SET strobe with its index and value; no
    // command after a DWELL n executes within n clocks of its operand.  A
    // malformed command stops execution (STATUS.ERROR), so the commands after
    // it never execute and need no check of their own.  A chosen-index shadow
    // keeps the words of one command.
    reg word_in = 0;                    // fifo_dout: a word popped in the last clock
    reg [3:0] words_left = 0;           // operand words still to come
    reg framing_lost = 0;               // an unknown opcode: no framing until a flush
    reg [4:0] moves_seen = 0, moves_started = 0, sets_seen = 0, sets_done = 0;
    reg picked = 0, picked_whole = 0;
    reg [3:0] picked_opcode = 0;
    reg [4:0] picked_number = 0;
    reg [3:0] picked_words = 0;
    reg [31:0] picked_header = 0, picked_0 = 0, picked_1 = 0, picked_2 = 0, picked_3 = 0;
    reg [4:0] moves_before_dwell = 0, sets_before_dwell = 0;
    reg [31:0] dwell_elapsed = 0;       // clocks since the picked command's last word arrived
    wire [3:0] arriving_opcode = fifo_dout[31:OPCODE_LSB];
    wire header_in = word_in && words_left == 0 && !framing_lost;
    wire is_move = arriving_opcode == OPCODE_LINE || arriving_opcode == OPCODE_ARC;
    always @(posedge clock) begin
        word_in <= reset_n && !fifo_flush && pop;
        if (!reset_n || fifo_flush) begin
            words_left <= 0; framing_lost <= 0; picked <= 0; picked_whole <= 0; dwell_elapsed <= 0;
            moves_seen <= 0; moves_started <= 0; sets_seen <= 0; sets_done <= 0;
        end else begin
            if (header_in) begin
                if (opcode_known(arriving_opcode)) words_left <= operand_words(fifo_dout);
                else framing_lost <= 1;
                if (is_move) moves_seen <= moves_seen + 1;
                if (arriving_opcode == OPCODE_SET) sets_seen <= sets_seen + 1;
                if (choose_command && !picked && (is_move || arriving_opcode == OPCODE_SET || arriving_opcode == OPCODE_DWELL)) begin
                    picked <= 1;
                    moves_before_dwell <= moves_seen;
                    sets_before_dwell <= sets_seen;
                    picked_opcode <= arriving_opcode;
                    picked_header <= fifo_dout;
                    picked_number <= is_move ? moves_seen : sets_seen;
                    picked_words <= 0;
                end
            end else if (word_in && words_left != 0) begin
                words_left <= words_left - 1;
                if (picked && !picked_whole) begin
                    case (picked_words)
                        0: picked_0 <= fifo_dout;
                        1: picked_1 <= fifo_dout;
                        2: picked_2 <= fifo_dout;
                        default: picked_3 <= fifo_dout;
                    endcase
                    picked_words <= picked_words + 1;
                    picked_whole <= words_left == 1;
                end
            end
            if (picked_whole && dwell_elapsed != 32'hffffffff) dwell_elapsed <= dwell_elapsed + 1;
            if (dda_start) moves_started <= moves_started + 1;
            if (set_strobe) sets_done <= sets_done + 1;
        end
    end
    // a LINE's axes: LINE.AXES, 0 standing for X and Y (a two-axis card runs no other)
    wire [LINE_AXES_WIDTH-1:0] line_axes = picked_header[LINE_AXES_LSB +: LINE_AXES_WIDTH];
    wire line_has_x = line_axes == 0 || line_axes[0], line_has_y = line_axes == 0 || line_axes[1];
    // (a picked DWELL counts SETs: only a picked move is compared with a start)
    wire picked_starts = picked && (picked_opcode == OPCODE_LINE || picked_opcode == OPCODE_ARC) && dda_start
                         && moves_started == picked_number;
    wire picked_sets = picked && picked_opcode == OPCODE_SET && set_strobe && sets_done == picked_number;
    always @(posedge clock) if (reset_n) begin
        if (dda_start) begin cmd_start_for_a_move: assert(moves_started < moves_seen); end
        if (set_strobe) begin cmd_set_for_a_set: assert(sets_done < sets_seen); end
        if (picked_starts) begin
            cmd_move_as_written: assert(picked_whole && dda_line == (picked_opcode == OPCODE_LINE)
                && dda_blend == picked_header[LINE_BLEND_LSB]   // BLEND: one field of LINE and ARC
                && (picked_opcode == OPCODE_LINE
                    // LINE.AXES (docs/axes.md): X's displacement first, an axis not in the mask 0
                    ? dda_xs == 0 && dda_ys == 0 && dda_xe == (line_has_x ? picked_0[COORD_WIDTH-1:0] : 0)
                      && dda_ye == (!line_has_y ? 0 : line_has_x ? picked_1[COORD_WIDTH-1:0]
                                                                 : picked_0[COORD_WIDTH-1:0])
                    : dda_ccw == picked_header[ARC_CCW_LSB]
                      && dda_variant == picked_header[ARC_VARIANT_LSB +: ARC_VARIANT_WIDTH]
                      && dda_lambda_shift == picked_header[ARC_LAMBDA_LSB +: ARC_LAMBDA_WIDTH]
                      && dda_acc_bits == picked_header[ARC_ACC_BITS_LSB +: ARC_ACC_BITS_WIDTH]
                      && dda_xs == picked_0[COORD_WIDTH-1:0] && dda_ys == picked_1[COORD_WIDTH-1:0]
                      && dda_xe == picked_2[COORD_WIDTH-1:0] && dda_ye == picked_3[COORD_WIDTH-1:0]));
        end
        // DWELL n: nothing after it executes within n clocks of its operand
        if (picked && picked_opcode == OPCODE_DWELL && ((dda_start && moves_started >= moves_before_dwell)
                                                || (set_strobe && sets_done >= sets_before_dwell))) begin
            cmd_dwell_waits: assert(picked_whole && dwell_elapsed >= picked_0);
        end
        if (picked_sets) begin
            cmd_set_as_written: assert(picked_whole && set_index == picked_header[SET_INDEX_LSB +: SET_INDEX_WIDTH] && set_value == picked_0);
        end
    end
`ifdef COMMANDS_WITHOUT_CLEAR
    // execution resumes after CLEAR_ERROR with the command after the bad one:
    // the counts above assume no COMMAND write (soft reset, clear error)
    always @(*) assume(!(l_we && !l_space && l_offset == REG_COMMAND));
`endif
    // ------------------------------------------------------------ pulse outputs
    // STEP high for at least STEP_WIDTH clocks and low for at least STEP_SPACE;
    // DIR stable DIR_SETUP clocks before a STEP leading edge and DIR_HOLD
    // clocks after its trailing edge (docs/registers.md), judged with the
    // settings in force when the interval began (a bus write to a timing
    // register in the interval leaves it unjudged; a SET does not)
    // every STEP pulse on a pin answers a step request: of the interpolator
    // (steps_step) or of the direct pulse generator (PULSE, PULSE_COUNT_*)
    genvar axis;
    generate for (axis = 0; axis < AXES; axis = axis + 1) begin : axes
        pulse_axis_rules timing (.clock(clock), .reset_n(reset_n), .step(pins_step[axis]), .dir(pins_dir[axis]),
            .width(model_step_width), .space(model_step_space), .setup(model_dir_setup), .hold(model_dir_hold),
            .settings_written(timing_written));
        pulse_requests requests (.clock(clock), .reset_n(reset_n),
            .request(steps_step[axis] || direct_request[axis]), .step(pins_step[axis]));
    end endgenerate
    // POS_X counts the STEP pulses that left the X pin, +1 where DIR (without
    // DIR_POLARITY) is high, -1 where low, at the edge the pin rises;
    // COMMAND.CLEAR_POSITION zeroes it (docs/registers.md, rtl/regs/pulse_out.py)
    reg p_pins_step_x = 0, cleared_position = 0, clear_position_due = 0;
    reg [1:0] p_polarity = 0;
    reg [31:0] position_x = 0, position_x_read = 0;
    wire step_x_rose = pins_step[0] && !p_pins_step_x && !cleared_position;
    wire [31:0] position_x_now = position_x + (step_x_rose ? ((pins_dir[0] ^ p_polarity[0]) ? 32'd1 : 32'hffffffff) : 32'd0);
    always @(posedge clock) begin
        p_pins_step_x <= pins_step[0];
        p_polarity <= model_dir_polarity;
        clear_position_due <= reset_n && stage_write && stage_addr == REG_COMMAND
                              && stage_data[COMMAND_CLEAR_POSITION_LSB] && stage_mask[COMMAND_CLEAR_POSITION_LSB];
        cleared_position <= !reset_n || clear_position_due;
        position_x <= (!reset_n || clear_position_due) ? 32'd0 : position_x_now;
        position_x_read <= position_x_now;
    end
    always @(posedge clock) if (reset_n && read_now && l_offset == REG_POS_X) begin
        pulse_position_x: assert(l_rdata == position_x_read);
    end
`ifdef POSITION_WITHOUT_HOMING
    // HOME zeroes the homed axis's position where its filtered switch
    // releases (docs/machine.md), which this model does not follow: no HOME
    // (0x7C) here; sim/card/test_homing.py checks the zeroing
    always @(*) assume(!(l_we && !l_space && l_offset == REG_HOME));
`endif
`ifdef DIRECT_COUNTS
    // direct mode (docs/registers.md): a PULSE_COUNT write of a signed n
    // gives no more than |n| pulses of its axis (pulse_rules.sv), on every
    // axis (at any of its register's offsets), judged from a write
    // taken with CONTROL.MODE = 1 and all bytes enabled, until MODE is
    // cleared, a COMMAND write (SOFT_RESET drops the pulses) or the next
    // write.  With MACHINE_RUNNING nothing halts the card and no HOME takes
    // the pulses.
    genvar counted;
    generate for (counted = 0; counted < AXES; counted = counted + 1) begin : direct_counts
        direct_count_rules rules (.clock(clock), .reset_n(reset_n),
            .drop(!model_control[CONTROL_MODE_LSB] || (stage_write && stage_addr == REG_COMMAND)),
            .count_write(stage_write && stage_addr == axis_pulse_count(counted)), .judge(stage_mask == 32'hFFFFFFFF),
            .count(stage_data), .request(direct_request[counted]));
    end endgenerate
`endif
`ifdef PULSE_PACED
    // every step request leaves on its pin: while one waits, a STEP edge
    // follows within one step period of the timing in force (DIR hold, DIR
    // set-up, STEP high and low) and a few clocks of the queue.  The
    // interpolator steps only after an `advance` (the feed rate, given only
    // while the queue has room: rtl/dda_arc.py), the timing stays as reset
    // (no SET of STEP_WIDTH, DIR_SETUP, DIR_HOLD, STEP_SPACE), nothing drops the queue
    // (no COMMAND write)
    always @(*) begin
        if (!p_advance) assume(steps_step == 0);
        assume(!(set_strobe && (set_index == SET_STEP_WIDTH || set_index == SET_DIR_SETUP || set_index == SET_DIR_HOLD
                                || set_index == SET_STEP_SPACE)));
        assume(!(l_we && !l_space && l_offset == REG_COMMAND));
    end
    wire [9:0] step_period = model_step_width + model_step_space + model_dir_setup + model_dir_hold
                             + `PULSE_QUEUE_CLOCKS;
    genvar paced;
    generate for (paced = 0; paced < AXES; paced = paced + 1) begin : progress
        pulse_progress rule (.clock(clock), .reset_n(reset_n), .request(steps_step[paced] || direct_request[paced]),
            .step(pins_step[paced]), .period(step_period));
    end endgenerate
`endif
`ifdef PULSE_TIMING_BY_SET
    // the host sets the pulse timing between moves (SET, which waits until the
    // outputs are idle) and the DIR polarity before: no bus write of
    // STEP_WIDTH, DIR_SETUP, DIR_HOLD, DIR_POLARITY, STEP_SPACE
    always @(*) assume(!(l_we && !l_space && (l_offset == REG_STEP_WIDTH || l_offset == REG_DIR_SETUP
                                               || l_offset == REG_DIR_HOLD || l_offset == REG_DIR_POLARITY
                                               || l_offset == REG_STEP_SPACE)));
`endif
    // a SET of a timing register waits until the outputs are quiet and never
    // changes a pulse under way (docs/instructions.md): it leaves nothing
    // unjudged, each interval keeps the setting in force when it began
    wire timing_written = stage_write && (stage_addr == REG_STEP_WIDTH || stage_addr == REG_DIR_SETUP
                                          || stage_addr == REG_DIR_HOLD || stage_addr == REG_STEP_SPACE);
`ifndef STEP_MODES_FREE
    // the pins' rules here are those of step/dir mode, STEP_MODE's reset: no
    // bus write of STEP_MODE (the other modes: sim/card/test_card_units.py)
    always @(*) assume(!(l_we && !l_space && l_offset == REG_STEP_MODE));
`endif
`ifdef REGS_FIFO_INVARIANTS
`include "regs_fifo_invariants.vh"
`endif
endmodule
