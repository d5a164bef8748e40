// One axis's following-error check (rtl/encoder/following_error.py,
// converted alone into the work folder) with every input free; the
// statements of docs/encoders.md (docs/formal.md lists them):
//   fe_*  the stop never rises while |ENC_FERROR| <= FERROR_LIMIT (or the
//         limit is 0), always rises at the edge after one where it is
//         beyond, stays until cleared; an align reads 0; with the step
//         position still, ENC_FERROR follows the count one edge later (so
//         a count that crosses the limit stops 2 edges later).
// Environment: RST# in the first clock; the count, the position's two low
// bits (POS moves by one step at most a clock), scale, limit and strobes
// are free.
`default_nettype none

module following_error_harness (
    input wire clock,
    input wire reset_n,
    input wire [31:0] count, input wire zeroing, input wire [1:0] pos_low, input wire [31:0] scale,
    input wire [31:0] limit, input wire align, input wire clear_stop
);
`include "harness_reset.vh"
    wire [31:0] error;
    wire stop;

    following_error dut(.clock(clock), .reset(reset_n), .check_count(count), .check_zeroing(zeroing),
                        .check_pos_low(pos_low), .check_scale(scale), .check_limit(limit), .check_align(align),
                        .check_clear_stop(clear_stop), .check_error(error), .check_stop(stop));

    // |error| read signed (|-2**31| = 2**31 fits 32 bits unsigned) beyond a limit that is not 0
    wire [31:0] magnitude = error[31] ? -error : error;
    wire beyond = limit != 0 && magnitude > limit;

    reg p_beyond = 0, p_align = 0, pp_align = 0, p_zeroing = 0, pp_zeroing = 0, p_stop = 0, p_clear = 0;
    reg [31:0] p_error = 0, p_count = 0, pp_count = 0;
    reg [1:0] p_pos = 0, pp_pos = 0;
    reg pp_judged = 0;
    always @(posedge clock) begin
        p_beyond <= beyond; p_align <= align; pp_align <= p_align; p_zeroing <= zeroing; pp_zeroing <= p_zeroing;
        p_stop <= stop; p_clear <= clear_stop; p_error <= error;
        p_count <= count; pp_count <= p_count; p_pos <= pos_low; pp_pos <= p_pos;
        pp_judged <= judged;
    end
    wire cause = p_beyond && !p_align;   // beyond the limit at the last edge, and no align in that clock

    always @(*) begin
        if (judged) begin
            fe_never_within_the_limit: assert(!(stop && !p_stop) || cause);
            fe_always_beyond_it: assert(!cause || stop);
            fe_held_until_cleared: assert(!(p_stop && !p_clear) || stop);
            fe_cleared_without_a_cause: assert(!(p_stop && p_clear && !cause) || !stop);
            if (p_align) begin fe_align_reads_zero: assert(error == 0); end
        end
        // both counts and the still position of the last two clocks, no align nor index zero in them
        if (judged && pp_judged && p_pos == pp_pos && !p_align && !pp_align && !pp_zeroing) begin
            fe_error_follows_the_count: assert(error - p_error == p_count - pp_count);
        end
    end
endmodule
