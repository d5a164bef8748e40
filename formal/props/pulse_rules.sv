// The pulse outputs' rules, one axis per instance, for the card's harness
// (regs_fifo_harness.sv): STEP high for at least STEP_WIDTH clocks and low
// for at least STEP_SPACE (step/dir mode),
// DIR set-up and hold around a STEP pulse (pulse_axis_rules; docs/registers.md),
// no STEP pulse without a step request (pulse_requests), and every request on
// its pin within one step period (pulse_progress, used with PULSE_PACED);
// in direct mode, no more pulses than a count written (direct_count_rules).
`default_nettype none

module pulse_axis_rules (
    input wire clock, input wire reset_n, input wire step, input wire dir,
    input wire [7:0] width, input wire [7:0] space, input wire [7:0] setup, input wire [7:0] hold,
    input wire settings_written
);
    reg p_step = 0, p_dir = 0, judged = 0, setup_judged = 0, hold_judged = 0;
    reg [8:0] high = 0, low = 9'h1ff, dir_age = 9'h1ff, since_fall = 9'h1ff;
    reg [7:0] width_then = 1, space_then = 1, setup_then = 1, hold_then = 1;
    always @(posedge clock) begin
        p_step <= step;
        p_dir <= dir;
        if (!reset_n) begin
            high <= 0; low <= 9'h1ff; dir_age <= 9'h1ff; since_fall <= 9'h1ff; judged <= 0;
        end else begin
            high <= step ? (high == 9'h1ff ? high : high + 1) : 0;
            low <= step ? 0 : (low == 9'h1ff ? low : low + 1);
            dir_age <= (dir != p_dir) ? 1 : (dir_age == 9'h1ff ? dir_age : dir_age + 1);
            since_fall <= (p_step && !step) ? 1 : (since_fall == 9'h1ff ? since_fall : since_fall + 1);
            if (step != p_step) begin
                width_then <= width;
                space_then <= space;
                judged <= !settings_written;
            end else if (settings_written)
                judged <= 0;
            // DIR set-up is timed from the DIR change, hold from the trailing edge
            if (dir != p_dir) begin
                setup_then <= setup;
                setup_judged <= !settings_written;
            end else if (settings_written)
                setup_judged <= 0;
            if (p_step && !step) begin
                hold_then <= hold;
                hold_judged <= !settings_written;
            end else if (settings_written)
                hold_judged <= 0;
        end
    end
    always @(posedge clock) if (reset_n && judged && !settings_written) begin
        if (p_step && !step) begin pulse_high_width: assert(high >= width_then); end
        if (!p_step && step && low != 9'h1ff) begin pulse_low_width: assert(low >= space_then); end
        if (!p_step && step) begin pulse_dir_setup: assert(dir == p_dir && (!setup_judged || dir_age >= setup_then)); end
        if (dir != p_dir && since_fall != 9'h1ff) begin pulse_dir_hold: assert(!p_step && (!hold_judged || since_fall >= hold_then)); end
    end
endmodule


module pulse_requests (
    input wire clock, input wire reset_n, input wire request, input wire step
);
    reg p_step = 0;
    reg [7:0] requested = 0, emitted = 0;
    always @(posedge clock) begin
        p_step <= step;
        if (!reset_n) begin
            requested <= 0; emitted <= 0;
        end else begin
            if (request && requested != 8'hff) requested <= requested + 1;
            if (step && !p_step && emitted != 8'hff) emitted <= emitted + 1;
        end
    end
    always @(posedge clock) if (reset_n && requested != 8'hff) begin
        pulse_only_when_requested: assert(emitted <= requested);
    end
endmodule

module pulse_progress (
    input wire clock, input wire reset_n, input wire request, input wire step, input wire [9:0] period
);
    reg p_step = 0;
    reg [7:0] waiting = 0;      // requests not yet on the pin
    reg [9:0] quiet = 0;        // clocks without a leading edge while some wait
    wire rose = step && !p_step;
    always @(posedge clock) begin
        p_step <= step;
        if (!reset_n) begin
            waiting <= 0; quiet <= 0;
        end else begin
            waiting <= waiting + request - (rose && waiting != 0);
            quiet <= (rose || waiting == 0) ? 0 : quiet + 1;
        end
    end
    always @(posedge clock) if (reset_n) begin
        pulse_request_leaves: assert(quiet <= period);
    end
endmodule

// A count written (``count_write``, the signed ``count``, judged when
// ``judge``) allows at most |count| requests, clamped to 24 signed bits, until
// ``drop`` or the next write; one more is allowed, as a request in the clock
// of the write may still be the previous count's.
module direct_count_rules (
    input wire clock, input wire reset_n, input wire drop, input wire count_write, input wire judge,
    input wire [31:0] count, input wire request
);
    wire signed [31:0] count_signed = count;
    wire [24:0] count_size = count_signed < -32'sd8388608 ? 25'd8388608
                           : count_signed > 32'sd8388607 ? 25'd8388607
                           : count_signed < 0 ? -count_signed[24:0] : count_signed[24:0];
    reg judged = 0;
    reg [25:0] left = 0;
    always @(posedge clock) begin
        if (!reset_n || drop)
            judged <= 0;
        else if (count_write) begin
            judged <= judge;
            left <= count_size + 1;
        end else if (request && left != 0)
            left <= left - 1;
    end
    always @(posedge clock) if (reset_n && judged && !count_write) begin
        if (request) begin direct_count_not_exceeded: assert(left != 0); end
    end
endmodule
