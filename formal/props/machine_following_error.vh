// The machine guard's FOLLOWING_ERROR stop (docs/machine.md, docs/encoders.md),
// included into machine_harness.sv with FERROR_GUARD on a build with encoders
// (group machine_following_error): the units' error, limit and strobes come
// from ferror_axes.vh, FERROR_LIMIT's models from ferror_models.vh, the
// history (p_stopped, p_active, stop_rose, steps_quiet) from the harness.
    // ------------------------------------------------------------ following error (a build with encoders)
    // docs/encoders.md, docs/machine.md: an axis's following-error stop flag
    // rises at the edge after a clock whose |ENC_FERROR| is beyond its
    // FERROR_LIMIT (not 0) without an align, and stays until a CLEAR_STOP
    // without a new cause; the guard latches the stop at the edge after a
    // flag (only an E-stop comes first) with REASON FOLLOWING_ERROR and AXIS
    // the lowest flagged axis; DRIVE_ENABLE is low from the clock after the
    // latch, once no STEP pulse is under way (as ms_stopped_drive_low).  The error,
    // limit and strobes are the per-axis units' own (ferror_axes.vh), the
    // limit also the table's FERROR_LIMIT model (ferror_models.vh).
    wire [32*AXES-1:0] ferror_error, ferror_limit;
    wire [AXES-1:0] ferror_align, ferror_clear, ferror_flags;
    wire [2:0] guard_axis;
`include "ferror_models.vh"
    wire [AXES-1:0] ferror_cause;   // beyond the limit (not 0), no align in the clock
    genvar lagging;
    generate for (lagging = 0; lagging < AXES; lagging = lagging + 1) begin : ferror
        wire [31:0] error = ferror_error[32*lagging +: 32], limit = ferror_limit[32*lagging +: 32];
        wire [31:0] magnitude = error[31] ? -error : error;   // |-2**31| = 2**31 fits unsigned
        assign ferror_cause[lagging] = limit != 0 && magnitude > limit && !ferror_align[lagging];
    end endgenerate
    function [2:0] lowest_axis(input [AXES-1:0] flags);
        integer k;
        begin
            lowest_axis = 0;
            for (k = AXES - 1; k >= 0; k = k - 1) if (flags[k]) lowest_axis = k;
        end
    endfunction
    reg [AXES-1:0] flags_model = 0, p_flags = 0;
    always @(posedge clock) begin
        flags_model <= reset_n ? ferror_cause | (flags_model & ~ferror_clear) : 0;
        p_flags <= ferror_flags;
    end
    always @(posedge clock) if (judged) begin
        // the limit the check uses is FERROR_LIMIT as written (the register table's model)
        fg_limit_as_written: assert(ferror_limit == ferror_limit_model);
        // the flags: never within the limit, always beyond it, held until cleared
        fg_flags_as_errors: assert(ferror_flags == flags_model);
        // the guard latches a flag at the next edge, REASON FOLLOWING_ERROR, AXIS the lowest flagged
        if (p_flags != 0 && !p_stopped && !p_active[0]) begin
            fg_stops_on_a_flag: assert(guard_stopped && machine_guard0_guard_reason == REASON_FOLLOWING_ERROR
                                       && guard_axis == lowest_axis(p_flags));
        end
        // and never without one
        if (stop_rose && machine_guard0_guard_reason == REASON_FOLLOWING_ERROR) begin
            fg_stop_only_on_a_flag: assert(p_flags != 0 && guard_axis == lowest_axis(p_flags));
        end
        // the drives off from the clock after the latch, once no STEP pulse is under way
        if (p_stopped && machine_guard0_guard_reason == REASON_FOLLOWING_ERROR && steps_quiet) begin
            fg_drive_low: assert(!pins_drive_enable);
        end
        fg_cover_stop: cover(stop_rose && machine_guard0_guard_reason == REASON_FOLLOWING_ERROR && guard_axis != 0);
    end
