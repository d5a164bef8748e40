// The DDA interpolator (rtl/dda_arc.py, a narrow build: W-bit coordinates)
// with every command input free, and position counters kept from its STEP
// and DIR outputs (docs/dda.md, rtl/interfaces/ DdaPort).
//
// Environment (assumed): RST# in the first clock only; `start` only while
// the interpolator is idle (`ready` and not `busy`: one move at a time, no
// chained set-up); with DDA_LINES only lines, with DDA_ARCS only arcs; with
// DDA_FULL_SPEED `advance` always high (an iteration every two clocks),
// otherwise `advance` is free.  A move's legality is the set-up's own rule:
// a move it refuses raises `error`; the rules below say what a refused move
// must never do, and which refusals are due.
module dda_harness #(parameter W = 6) (
    input clock,
    input start, line, ccw, blend, advance,
    input [1:0] variant,
    input [4:0] lambda_shift, acc_bits,
    input signed [W-1:0] xs, ys, xe, ye
);
    localparam P = W + 3;              // position counters: the move stays within +-2**(W-1) + 1
    reg init = 1;
    always @(posedge clock) init <= 0;
    wire reset = !init;                // RST#: active low, the first clock

    wire busy, done, error, ready, step_x, step_y, dir_x, dir_y;
    wire [1:0] quadrant;
    wire [W+2:0] stop_left;

    dda_arc dut(.clock(clock), .reset(reset), .cmd_start(start), .cmd_line(line), .cmd_variant(variant),
                .cmd_lambda_shift(lambda_shift), .cmd_acc_bits(acc_bits), .cmd_ccw(ccw),
                .cmd_blend(blend), .cmd_xs(xs), .cmd_ys(ys), .cmd_xe(xe), .cmd_ye(ye),
                .cmd_advance(advance), .cmd_busy(busy), .cmd_done(done), .cmd_error(error),
                .cmd_quadrant(quadrant), .cmd_ready(ready), .cmd_stop_left(stop_left),
                .steps_step_x(step_x), .steps_step_y(step_y), .steps_dir_x(dir_x), .steps_dir_y(dir_y));

    always @* begin
        if (init) assume(!start);
        if (start) assume(ready && !busy);
`ifdef DDA_LINES
        if (start) assume(line);
`endif
`ifdef DDA_ARCS
        if (start) assume(!line);
`endif
`ifdef DDA_FULL_SPEED
        assume(advance);
`endif
    end

    // ---- the move the harness follows: the one of the last start ----
    reg running = 0;                   // a move taken and not yet ended (done or error)
    reg is_line = 0;
    reg signed [P-1:0] pos_x = 0, pos_y = 0, end_x = 0, end_y = 0;
    reg signed [P-1:0] start_x = 0, start_y = 0;
    reg [P-1:0] count_x = 0, count_y = 0;   // steps of the move so far
    reg [15:0] clocks = 0;             // clocks since the start edge (saturating)

    wire signed [P-1:0] delta_x = step_x ? (dir_x ? 1 : -1) : 0;
    wire signed [P-1:0] delta_y = step_y ? (dir_y ? 1 : -1) : 0;
    // the position after this clock's steps (done comes with the last step)
    wire signed [P-1:0] now_x = pos_x + delta_x;
    wire signed [P-1:0] now_y = pos_y + delta_y;

    always @(posedge clock) begin
        if (init) begin
            running <= 0;
        end else if (start) begin
            running <= 1;
            is_line <= line;
            pos_x <= line ? 0 : xs;
            pos_y <= line ? 0 : ys;
            start_x <= line ? 0 : xs;
            start_y <= line ? 0 : ys;
            end_x <= xe;
            end_y <= ye;
            count_x <= 0;
            count_y <= 0;
            clocks <= 0;
        end else begin
            pos_x <= now_x;
            pos_y <= now_y;
            count_x <= count_x + step_x;
            count_y <= count_y + step_y;
            if (clocks != 16'hffff) clocks <= clocks + 1;
            if (done || error) running <= 0;
        end
    end

    // magnitudes and the set-up's tolerance, for the rules below
    wire [P-1:0] mag_dx = end_x < 0 ? -end_x : end_x;
    wire [P-1:0] mag_dy = end_y < 0 ? -end_y : end_y;
    wire [P-1:0] mag_sx = start_x < 0 ? -start_x : start_x;
    wire [P-1:0] mag_sy = start_y < 0 ? -start_y : start_y;
    wire [P-1:0] m = mag_sx > mag_sy ? mag_sx : mag_sy;
    wire signed [2*P:0] start_square = start_x * start_x + start_y * start_y;
    wire signed [2*P:0] end_square = end_x * end_x + end_y * end_y;
    wire signed [2*P:0] difference = end_square - start_square;
    wire signed [2*P:0] two_m = 2 * m;
    // the end within one step of the start radius: -(2m - 1) <= difference <= 2m + 1 (docs/dda.md)
    wire within_one_step = difference >= 1 - two_m && difference <= two_m + 1;
    wire [P-1:0] line_major = mag_dx > mag_dy ? mag_dx : mag_dy;

    always @(posedge clock) if (!init) begin
        // STEP only in a move that was started and has not ended (`busy` falls with the
        // last step and done)
        dda_step_only_in_a_move: assert(!(step_x || step_y) || running);
        dda_busy_in_a_move: assert(!running || busy || done || error || clocks == 0);
        dda_done_only_in_a_move: assert(!done || running);
        // an iteration takes the clock of its advance and the next (docs/dda.md): a step
        // leaves in the clock after an advance, never on one axis in two clocks running
        dda_step_after_advance: assert(!(step_x || step_y) || $past(advance));
        dda_one_step_per_iteration_x: assert(!(step_x && $past(step_x)));
        dda_one_step_per_iteration_y: assert(!(step_y && $past(step_y)));
        // a move ends exactly on its end point: (DX, DY) from where it began for a line,
        // (XE, YE) for an arc
        dda_ends_at_end_point: assert(!(done && running) || (now_x == end_x && now_y == end_y));
        // a refused move never steps (and is refused before any step)
        dda_refused_move_never_steps: assert(!(error && running) || (count_x == 0 && count_y == 0));
        dda_error_xor_done: assert(!(error && done));
        // the set-up's rule: an arc whose end is not within one step of the start radius,
        // or with a point at the centre, is refused (it ends with error, not done)
        dda_arc_off_circle_refused: assert(!(done && running && !is_line)
                                          || (within_one_step && start_square != 0 && end_square != 0));
        // a line steps each axis towards its end, at most |DX| and |DY| times: never past
        // its end counters
        if (running && is_line) begin
            dda_line_x_towards_end: assert(!step_x || (dir_x == !end_x[P-1] && count_x < mag_dx));
            dda_line_y_towards_end: assert(!step_y || (dir_y == !end_y[P-1] && count_y < mag_dy));
        end
`ifdef DDA_FULL_SPEED
        // always finishes: a line of length L (the larger of |DX|, |DY|) has ended by its two
        // set-up clocks, the hand-over clock and L iterations of two clocks
        dda_line_finishes: assert(!(running && is_line) || clocks <= 2 + 1 + 2 * line_major);
`endif
    end
endmodule
