// The card's probe latch (rtl/encoder/probe.py, the default build's two
// axes, converted alone into the work folder) with every input free; the
// statements of docs/encoders.md (docs/formal.md lists them):
//   prb_*  the probe fires exactly at an armed rise of the filtered probe,
//          disarms then, latches every axis's count and step position as
//          they were before that edge, and never twice between two arms.
// The filtered level and the sample before it are made ports by yosys
// `expose`.  Environment: RST# in the first clock.
`default_nettype none

module probe_harness (
    input wire clock,
    input wire reset_n,
    input wire pin, input wire invert, input wire arm, input wire [3:0] filter,
    input wire [31:0] count_x, input wire [31:0] pos_x, input wire [31:0] count_y, input wire [31:0] pos_y
);
`include "harness_reset.vh"
    wire armed, fired, level, seen;
    wire [31:0] latched_count_x, latched_pos_x, latched_count_y, latched_pos_y;

    probe dut(.clock(clock), .reset(reset_n), .port_pin(pin), .port_invert(invert), .port_arm(arm),
              .port_filter(filter), .port_armed(armed), .port_fired(fired),
              .port_count_x(count_x), .port_pos_x(pos_x), .port_latched_count_x(latched_count_x),
              .port_latched_pos_x(latched_pos_x), .port_count_y(count_y), .port_pos_y(pos_y),
              .port_latched_count_y(latched_count_y), .port_latched_pos_y(latched_pos_y),
              .level(level), .seen(seen));

    reg p_armed = 0, p_arm = 0, p_level = 0, p_seen = 0;
    reg [31:0] p_count_x = 0, p_pos_x = 0, p_count_y = 0, p_pos_y = 0;
    always @(posedge clock) begin
        p_armed <= armed; p_arm <= arm; p_level <= level; p_seen <= seen;
        p_count_x <= count_x; p_pos_x <= pos_x; p_count_y <= count_y; p_pos_y <= pos_y;
    end
    wire fire_now = (armed || arm) && level && !seen;   // this edge latches
    wire p_armed_rise = (p_armed || p_arm) && p_level && !p_seen;

    reg [1:0] fires_since_arm = 0;   // latches since the last arm (the arm's own edge included)
    always @(posedge clock) begin
        if (!reset_n) fires_since_arm <= 0;
        else if (arm) fires_since_arm <= fire_now ? 2'd1 : 2'd0;
        else if (fire_now && fires_since_arm != 2'd3) fires_since_arm <= fires_since_arm + 2'd1;
    end

    always @(*) begin
        if (judged) begin
            prb_fires_at_an_armed_rise: assert(fired == p_armed_rise);
            prb_disarms_as_it_fires: assert(armed == ((p_armed || p_arm) && !p_armed_rise));
            if (fired) begin
                prb_latches_every_axis_before: assert(latched_count_x == p_count_x && latched_pos_x == p_pos_x
                                                      && latched_count_y == p_count_y && latched_pos_y == p_pos_y);
            end
        end
        if (reset_n) begin
            prb_once_per_arm: assert(fires_since_arm <= 2'd1);
            prb_inv_fired_means_disarmed: assert(fires_since_arm == 2'd0 || !armed);
        end
    end
endmodule
