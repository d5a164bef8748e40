// One axis's encoder unit (rtl/encoder/encoder.py, converted alone into the
// work folder) with free pins and controls; the statements of
// docs/encoders.md (docs/formal.md lists them with their groups):
//   enc_count_*  no count without a legal transition: the count moves by
//                the Gray-code step of the filtered (A, B) between two
//                samples, +1 or -1, and by nothing else (an illegal
//                sample sets the error flag instead; step/dir counts A's rises);
//   enc_pins_*   from the pins: legal transitions at any spacing the filter
//                passes (ENC_FILTER + 1 clocks or more between edges) are
//                all counted, each 3 + ENC_FILTER edges after the pin's;
//   idx_*        the index latches once per arm: at an armed rise of the
//                filtered index, the count before it; never twice.
// The filtered levels and the decoder's and the index latch's samples are
// made ports by yosys `expose`, so the converted file is read unchanged.
//
// Environment: RST# in the first clock; with ENCODER_PINS the pins make only
// legal transitions (one input at a time, 00 in reset), at least ENC_FILTER
// + 1 clocks apart, ENC_FILTER constant and at most PINS_FILTER_MAX,
// ENC_POLARITY 0, quadrature mode and no INDEX_ZERO; otherwise all is free.
`default_nettype none

module encoder_harness #(
    parameter PINS_FILTER_MAX = 3,
    parameter ERROR_MAX = 0           // the error counter's saturation (set from models/encoder_model.py)
) (
    input wire clock,
    input wire reset_n,
    input wire pin_a, input wire pin_b, input wire pin_index,
    input wire [3:0] filter,
    input wire [2:0] polarity,
    input wire mode, input wire index_zero, input wire arm, input wire clear_error,
    input wire [31:0] coming
);
`include "harness_reset.vh"
    wire [31:0] count, time_, latch;
    wire [7:0] error_count;
    wire direction, quad_error, armed, fired, zeroing;
    // exposed: the filtered levels and the samples before them
    wire conditioner_a_level, conditioner_b_level, conditioner_index_level;
    wire decoder_seen_a, decoder_seen_b, index_latch_seen;

    encoder dut(.clock(clock), .reset(reset_n), .pins_a(pin_a), .pins_b(pin_b), .pins_index(pin_index),
                .port_filter(filter), .port_polarity(polarity), .port_mode(mode), .port_index_zero(index_zero),
                .port_arm(arm), .port_clear_error(clear_error), .port_coming(coming), .port_count(count),
                .port_direction(direction), .port_quad_error(quad_error), .port_error_count(error_count),
                .port_time(time_), .port_armed(armed), .port_latch(latch), .port_fired(fired),
                .port_zeroing(zeroing),
                .conditioner_a_level(conditioner_a_level), .conditioner_b_level(conditioner_b_level),
                .conditioner_index_level(conditioner_index_level), .decoder_seen_a(decoder_seen_a),
                .decoder_seen_b(decoder_seen_b), .index_latch_seen(index_latch_seen));

    // ---- the last clock, as the properties judge it ----
    reg [31:0] p_count = 0;
    reg [7:0] p_error_count = 0;
    reg p_a = 0, p_b = 0, p_seen_a = 0, p_seen_b = 0, p_mode = 0, p_zeroing = 0, p_clear = 0, p_quad = 0;
    reg p_armed = 0, p_arm = 0, p_index = 0, p_seen_index = 0;
    always @(posedge clock) begin
        p_count <= count; p_error_count <= error_count; p_quad <= quad_error;
        p_a <= conditioner_a_level; p_b <= conditioner_b_level;
        p_seen_a <= decoder_seen_a; p_seen_b <= decoder_seen_b;
        p_mode <= mode; p_zeroing <= zeroing; p_clear <= clear_error;
        p_armed <= armed; p_arm <= arm; p_index <= conditioner_index_level; p_seen_index <= index_latch_seen;
    end

    // The Gray-code phase of (A, B), forwards 00 -> 10 -> 11 -> 01: phase = {B, A ^ B};
    // a step of +1 or -1 (mod 4) is legal, 2 is illegal.
    wire [1:0] phase_before = {p_seen_b, p_seen_a ^ p_seen_b};
    wire [1:0] phase_after = {p_b, p_a ^ p_b};
    wire [1:0] phase_step = phase_after - phase_before;
    wire step_dir_rise = p_a && !p_seen_a;
    wire [31:0] expected_move = p_mode ? (step_dir_rise ? (p_b ? 32'd1 : -32'd1) : 32'd0)
                                       : (phase_step == 2'd1 ? 32'd1 : phase_step == 2'd3 ? -32'd1 : 32'd0);
    wire illegal = !p_mode && phase_step == 2'd2;

    always @(*) begin
        if (judged) begin
            enc_count_only_legal_moves: assert(count == (p_zeroing ? 32'd0 : p_count) + expected_move);
            enc_count_illegal_flagged: assert(quad_error == (illegal || (p_quad && !p_clear)));
            if (illegal) begin
                enc_count_errors_counted: assert(error_count == (p_clear ? 8'd1 :
                                                  p_error_count == ERROR_MAX ? ERROR_MAX : p_error_count + 8'd1));
            end else begin
                enc_count_no_error_counted: assert(error_count == (p_clear ? 8'd0 : p_error_count));
            end
        end
    end

    // ---- the index: once per arm ----
    wire armed_fire = (armed || arm) && conditioner_index_level && !index_latch_seen;   // this edge latches
    reg [1:0] fires_since_arm = 0;   // index latches since the last arm (the arm's own edge included)
    always @(posedge clock) begin
        if (!reset_n) fires_since_arm <= 0;
        else if (arm) fires_since_arm <= armed_fire ? 2'd1 : 2'd0;
        else if (armed_fire && fires_since_arm != 2'd3) fires_since_arm <= fires_since_arm + 2'd1;
    end
    wire p_armed_rise = (p_armed || p_arm) && p_index && !p_seen_index;

    always @(*) begin
        if (judged) begin
            idx_fires_at_an_armed_rise: assert(fired == p_armed_rise);
            idx_disarms_as_it_fires: assert(armed == ((p_armed || p_arm) && !p_armed_rise));
            if (fired) begin idx_latches_the_count_before: assert(latch == p_count); end
            idx_zeroes_only_as_it_fires: assert(!zeroing || armed_fire);
        end
        if (reset_n) begin
            idx_once_per_arm: assert(fires_since_arm <= 2'd1);
            idx_inv_fired_means_disarmed: assert(fires_since_arm == 2'd0 || !armed);
        end
    end

`ifdef ENCODER_PINS
    // ---- from the pins: every legal transition counted, at every spacing the filter passes ----
    reg [3:0] held_filter = 0;
    reg pa_pin = 0, pb_pin = 0;      // the pins at the last edge
    reg [4:0] since = 5'd31;         // edges since the last pin change (saturating)
    reg [31:0] position = 0;         // the legal transitions so far, +1 forwards
    always @(posedge clock) begin
        held_filter <= filter;
        pa_pin <= pin_a; pb_pin <= pin_b;
        since <= (pin_a != pa_pin || pin_b != pb_pin) ? 5'd1 : (since == 5'd31 ? since : since + 5'd1);
        position <= reset_n ? position + pin_move : 32'd0;   // the pins are 00 in reset: the unit's reset state
    end
    wire [1:0] pin_step = {pin_b, pin_a ^ pin_b} - {pb_pin, pa_pin ^ pb_pin};
    wire [31:0] pin_move = pin_step == 2'd1 ? 32'd1 : pin_step == 2'd3 ? -32'd1 : 32'd0;
    always @(*) begin
        assume(filter <= PINS_FILTER_MAX && polarity == 0 && !mode && !index_zero);
        if (started) assume(filter == held_filter);
        if (!reset_n) assume(!pin_a && !pin_b);
        if (pin_a != pa_pin || pin_b != pb_pin) begin
            assume(!(pin_a != pa_pin && pin_b != pb_pin));   // one input at a time: legal
            assume(since >= filter + 5'd1);                  // no closer than the filter passes
        end
    end

    // the position after each of the last 3 + PINS_FILTER_MAX edges: history[k] is k edges old
    localparam DEPTH = 4 + PINS_FILTER_MAX;
    reg [31:0] history [1:DEPTH-1];
    integer k;
    initial for (k = 1; k < DEPTH; k = k + 1) history[k] = 0;
    always @(posedge clock) begin
        history[1] <= reset_n ? position : 32'd0;
        for (k = 2; k < DEPTH; k = k + 1) history[k] <= reset_n ? history[k - 1] : 32'd0;
    end

    always @(*) begin
        if (reset_n) begin
            enc_pins_every_legal_edge_counted: assert(count == history[filter + 3]);
            enc_pins_no_error: assert(!quad_error);
        end
    end
`endif
endmodule
