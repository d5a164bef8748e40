// The machine side of the card's back end (gen/regs_fifo.v: input filter,
// machine guard, feed hold, homing) behind a free requester that keeps the
// LocalBus rules, a free interpolator and free machine inputs.  The
// properties are the statements of docs/machine.md (docs/formal.md lists
// them with their groups):
//   mr_*  the input filter's reaction, E-stop pin to STEP and DRIVE_ENABLE;
//   ms_*  E-stop, limits and the stop latch;   mw_*, mwl_*  the watchdog;
//   md_*  DRIVE_ENABLE: around every STEP pulse, and only a write re-energises;
//   fh_*  feed hold and the decelerated stop;
//   hm_*, hp_*  homing;   minv_*  helper invariants for k-induction.
// The guard's, the filter's, the feed rate's and the homing unit's own
// registers and ports (stopped, stopping, reason, held, the rate, the
// homing state, the zero, the step requests before and after the guard's
// gate) and a few of the FIFO's are made ports by yosys `expose`, so the
// generated file is read unchanged.  The register models (model_*) come
// from the register table (regs_table.vh); the environment and the unit's
// common ports are regs_fifo_harness.sv's (regs_fifo_env.vh,
// regs_fifo_ports.vh).  The per-axis signals are vectors over the build's
// AXES (0 X, 1 Y, 2 Z, ...) and the machine inputs INPUTS wide, wired by
// regs_fifo_axes.vh and machine_axes.vh, with each axis's limits and home
// switch among the inputs in axes_inputs.vh (formal/axes_props.py
// generates them for the build), so every property holds for every axis.
//
// Environment: INPUT_POLARITY, INPUT_FILTER and INPUT_TICK keep their reset
// values (0, 3 samples, 1 clock: the settings of the docs' reaction table);
// WATCHDOG is written whole (all byte enables).
`default_nettype none

module machine_harness #(
    parameter COORD_WIDTH = 24,
    parameter FILTER = 3,           // INPUT_FILTER as reset
    parameter AXES = 2,             // axes of the build (formal/axes_props.py)
    parameter INPUTS = 7            // its machine inputs: E-STOP, limits and home switches
) (
    input wire clock,
    input wire reset_n,
    input wire l_space, input wire [15:0] l_addr, input wire [3:0] l_be, input wire [31:0] l_wdata,
    input wire l_we, input wire l_re, input wire l_write,
    input wire dda_busy, input wire dda_done, input wire dda_error, input wire [1:0] dda_quadrant,
    input wire dda_ready, input wire [COORD_WIDTH+2:0] dda_stop_left,
    input wire [AXES-1:0] steps_step, input wire [AXES-1:0] steps_dir,
    input wire [INPUTS-1:0] machine_in
);
`include "regs_offsets.vh"
`include "regs_fifo_env.vh"
    wire pins_drive_enable;
    // exposed registers and ports of the units
    wire guard_stopping, settled;
    wire [INPUTS-1:0] conditioning_active;
    wire [STOP_REASON_REASON_WIDTH-1:0] machine_guard0_guard_reason;
    wire [2*AXES-1:0] machine_guard0_guard_limits;
    wire [15:0] feed_rate0_rate;
    wire [2:0] homing0_state;
    wire [2:0] homing0_axis;   // HOME.AXIS_INDEX as taken: 0 X, 1 Y, 2 Z, ...
    wire homing0_refused, homing0_not_found;
    wire [AXES-1:0] home_zero;
    // per axis: the step requests before the guard's gate (the interpolator's
    // or the direct pulses'), those it grants, the pulse outputs' pulses,
    // the direct pulses' loads (machine_axes.vh)
    wire [AXES-1:0] request_step, request_dir, granted_step, pulse, direct_pending;
    wire [15:0] ramp_step;
    wire feed_held;
    wire [9:0] sync_fifo0_count;
    wire sync_fifo0_is_empty, sync_fifo0_is_full, sync_fifo0_free_beyond, io_written;
    wire [2:0] sync_fifo0_free;
    wire [23:0] watchdog_left;
    wire [1:0] machine_control;
    wire [1:0] step_mode;

    regs_fifo dut (
`include "regs_fifo_ports.vh"
        , .pins_drive_enable(pins_drive_enable),
        .guard_stopping(guard_stopping), .settled(settled),
        .conditioning_active(conditioning_active), .machine_guard0_guard_reason(machine_guard0_guard_reason),
        .machine_guard0_guard_limits(machine_guard0_guard_limits), .feed_rate0_rate(feed_rate0_rate),
        .homing0_state(homing0_state), .homing0_axis(homing0_axis), .homing0_refused(homing0_refused),
        .homing0_not_found(homing0_not_found), .home_zero(home_zero),
        .ramp_step(ramp_step), .machine_control(machine_control), .step_mode(step_mode),
        .feed_held(feed_held), .sync_fifo0_count(sync_fifo0_count), .sync_fifo0_is_empty(sync_fifo0_is_empty),
`ifdef LOCAL_ROOM
        .sync_fifo0_free(sync_fifo0_free), .sync_fifo0_free_beyond(sync_fifo0_free_beyond),
`else
        .sync_fifo0_is_full(sync_fifo0_is_full),
`endif
        .io_written(io_written), .watchdog_left(watchdog_left)
`include "machine_axes.vh"
`ifdef FERROR_GUARD
`include "ferror_axes.vh"
`endif
        );
`include "axes_inputs.vh"

    // ------------------------------------------------------------ environment
    always @(*) begin
        // the inputs' conditioning as reset: the reaction times of docs/machine.md
        assume(!(l_we && !l_space && (l_offset == REG_INPUT_POLARITY || l_offset == REG_INPUT_FILTER || l_offset == REG_INPUT_TICK)));
        // the STEP pins' rules here are those of step/dir mode, STEP_MODE's reset
        assume(!(l_we && !l_space && l_offset == REG_STEP_MODE));
        if (l_we && !l_space && l_offset == REG_WATCHDOG) assume(l_be == 4'hF);
`ifdef WATCHDOG_SMALL
        if (l_we && !l_space && l_offset == REG_WATCHDOG) assume(l_wdata < `WATCHDOG_SMALL);
`endif
    end
    // the interpolator (regs_fifo_env.vh) steps only in the clock after an
    // `advance` (a feed tick)
    always @(*) if (!p_advance) assume(steps_step == 0);
`ifdef PATH_ONLY
    // the hold acts on the path only (direct pulses run on: docs/machine.md)
    always @(*) assume(direct_request == 0);
`endif

    // ------------------------------------------------------------ history
    reg p_stopped = 0, pp_stopped = 0, p_stopping = 0, p_held = 0, p_drive = 0;
    reg [AXES-1:0] p_step = 0;
    reg [INPUTS-1:0] p_active = 0;
    reg [15:0] p_ramp = 0, pp_ramp = 0;
    reg [1:0] p_control = 0;
    reg [STOP_REASON_REASON_WIDTH-1:0] p_reason = 0;
    always @(posedge clock) begin
        p_step <= pins_step;
        p_stopped <= guard_stopped; pp_stopped <= p_stopped; p_stopping <= guard_stopping; p_held <= settled;
        p_drive <= pins_drive_enable; p_active <= conditioning_active;
        p_ramp <= model_ramp_step; pp_ramp <= p_ramp; p_control <= model_machine_control;
        p_reason <= machine_guard0_guard_reason;
    end
    wire [AXES-1:0] rise = pins_step & ~p_step;   // STEP leading edges, per axis
    wire steps_quiet = pins_step == 0 && p_step == 0;   // no STEP pin high nor in the clock before
    wire stop_rose = guard_stopped && !p_stopped;

    // a MACHINE_CONTROL write of DRIVE_ENABLE = 1 taken by the register (the
    // clock after its stage) since the card was last stopped (md_*)
    reg rearmed = 0;
    always @(posedge clock) begin
        if (!reset_n || guard_stopped) rearmed <= 0;
        else if (stage_write && stage_addr == REG_MACHINE_CONTROL
                 && stage_data[MACHINE_CONTROL_DRIVE_ENABLE_LSB] && stage_mask[MACHINE_CONTROL_DRIVE_ENABLE_LSB]) rearmed <= 1;
    end

    // helper invariants (k-induction): the unit's RAMP_STEP and
    // MACHINE_CONTROL registers hold what the table's models say
    always @(posedge clock) if (reset_n) begin
        minv_registers: assert(ramp_step == model_ramp_step && machine_control == model_machine_control);
        // the FIFO's own count: the words pushed and not taken
        minv_fifo_level: assert(sync_fifo0_count == level && level <= 512 && io_written == stage_write);
`ifdef LOCAL_ROOM
        minv_fifo_flags: assert(sync_fifo0_is_empty == (sync_fifo0_count == 0)
                                && sync_fifo0_free[0] == (sync_fifo0_count < 512)
                                && sync_fifo0_free[1] == (sync_fifo0_count < 511)
                                && sync_fifo0_free[2] == (sync_fifo0_count < 510)
                                && sync_fifo0_free_beyond == (sync_fifo0_count < 509)
                                && promised <= 512 - sync_fifo0_count);
`else
        minv_fifo_flags: assert(sync_fifo0_is_empty == (sync_fifo0_count == 0)
                                && sync_fifo0_is_full == (sync_fifo0_count == 512));
`endif
        // the feed rate's own hold flag: held at rate 0
        minv_feed_held: assert(!feed_held || feed_rate0_rate == 0);
        // MACHINE_CONTROL.DRIVE_ENABLE is 1 only by a write since the last stop
        minv_drive_rearmed: assert(!machine_control[0] || rearmed);
        // STEP_MODE as reset (step/dir: no bus write of it here), so the
        // STEP pins carry the pulse outputs' own pulses
        minv_step_dir: assert(step_mode == model_step_mode && step_mode == 0
                              && pins_step == pulse);
    end

    // ------------------------------------------------------------ E-stop and the stop latch
    // each input: clocks its pin has been at its level (the filter's reaction)
    wire [4*INPUTS-1:0] same_for;        // per input, 4 bits: clocks at its level
    genvar i;
    generate for (i = 0; i < INPUTS; i = i + 1) begin : inputs
        input_reaction #(.FILTER(FILTER)) reaction (.clock(clock), .reset_n(reset_n), .judged(judged),
            .pin(machine_in[i]), .active(conditioning_active[i]), .same_for(same_for[4*i+3:4*i]));
    end endgenerate
    
    always @(posedge clock) if (judged) begin
        // "E-stop: no new STEP rise after INPUT_FILTER + 3 clocks, DRIVE_ENABLE
        // low at INPUT_FILTER + 3 clocks" from the clock the pin changes (the
        // pin's first clock at its level is clock 0, same_for 1)
        // (sim/card/test_machine_card.py: a rise at clock 6 is the last allowed)
        if (machine_in[0] && same_for[3:0] >= FILTER + 5) begin mr_estop_no_step: assert(rise == 0); end
        // (or, with a STEP pulse under way, the clock after its STEP fell: md_*)
        if (machine_in[0] && same_for[3:0] >= FILTER + 4 && steps_quiet)
        begin mr_estop_drive_low: assert(!pins_drive_enable); end
        // "the guard latches a stop at the edge after its cause: 1 ESTOP"
        if (p_active[0]) begin
            ms_estop_stops: assert(guard_stopped && (p_stopped || machine_guard0_guard_reason == REASON_ESTOP));
            // CLEAR_STOP refused while the E-stop input is active
            if (p_stopped) begin ms_estop_clear_refused: assert(machine_guard0_guard_reason == p_reason); end
        end
        // "No new STEP edge starts ... DRIVE_ENABLE falls at the edge the latch sets"
        // (a pulse the outputs started in the clock before the latch rises on
        // the pin, a register later, in the clock after it)
        if (p_stopped && pp_stopped) begin ms_stopped_no_step: assert(rise == 0); end
        // (a STEP pulse under way keeps it high to the clock after its fall: md_*)
        if (p_stopped && steps_quiet) begin
            ms_stopped_drive_low: assert(!pins_drive_enable);
        end
        if (guard_stopped) begin ms_stopped_has_reason: assert(machine_guard0_guard_reason != 0); end
        // "STOP_REASON reads the cause from the edge STOPPING rises" (WATCHDOG or LIMIT)
        if (guard_stopping) begin
            ms_stopping_has_reason: assert(!guard_stopped && (machine_guard0_guard_reason == REASON_WATCHDOG
                                                              || machine_guard0_guard_reason == REASON_LIMIT));
        end
    end

    // ------------------------------------------------------------ limits
    // a step request towards an active limit (without a ramp) is dropped
    // whole and latches the stop with reason LIMIT; requests away pass.
    // towards: per limit, in STOP_REASON.LIMITS's order (limit_bits, axes_inputs.vh)
    wire [AXES-1:0] towards_pos = request_step & request_dir & limit_pos_active;
    wire [AXES-1:0] towards_neg = request_step & ~request_dir & limit_neg_active;
    wire [2*AXES-1:0] towards = limit_bits;
    reg [2*AXES-1:0] p_towards = 0;
    reg p_halted = 0;
    always @(posedge clock) begin
        p_towards <= towards;
        p_halted <= guard_stopped || conditioning_active[0];
    end
    wire ramp_off = model_ramp_step == 0 && p_ramp == 0;
    always @(posedge clock) if (judged) begin
        if (towards != 0 && ramp_off) begin
            ms_limit_dropped: assert(granted_step == 0);
        end
        if (towards == 0 && !guard_stopped && !conditioning_active[0]) begin
            ms_away_passes: assert(granted_step == request_step);
        end
        if (p_towards != 0 && p_ramp == 0 && pp_ramp == 0 && !p_halted && !p_stopping) begin
            ms_limit_stops: assert(guard_stopped && (machine_guard0_guard_reason == REASON_WATCHDOG
                || (machine_guard0_guard_reason == REASON_LIMIT && machine_guard0_guard_limits == p_towards)));
        end
    end

    // ------------------------------------------------------------ watchdog
    // "Writing WATCHDOG loads the count ... stops TIMEOUT clocks after the
    // write reaches the register (within 3)": from the clock the bus write is
    // answered; the stop is judged when nothing else stopped the card since
    // (a write reaches the register up to 3 clocks after its bus clock, so
    // a stop may still come from the write before it: prev_*)
    reg wd_armed = 0, wd_quiet = 0, prev_armed = 0, wd_fired = 0;
    reg [23:0] wd_timeout = 0, prev_timeout = 0;
    reg [24:0] wd_elapsed = 0, prev_elapsed = 0;
    always @(posedge clock) begin
        if (!reset_n) begin
            wd_armed <= 0; wd_quiet <= 0; wd_elapsed <= 0; prev_armed <= 0;
        end else begin
            if (io_write_now && l_offset == REG_WATCHDOG) begin
                wd_armed <= l_wdata[23:0] != 0; wd_timeout <= l_wdata[23:0]; wd_elapsed <= 0;
                wd_quiet <= !guard_stopped && !guard_stopping; wd_fired <= 0;
                prev_armed <= wd_armed; prev_timeout <= wd_timeout; prev_elapsed <= wd_elapsed + 1;
            end else begin
                if (stop_rose && machine_guard0_guard_reason == REASON_WATCHDOG) wd_fired <= 1;
                if (!wd_elapsed[24]) wd_elapsed <= wd_elapsed + 1;
                if ((conditioning_active & STOPPING_INPUTS) != 0 || model_ramp_step != 0 || towards != 0
                    || (guard_stopped && machine_guard0_guard_reason != REASON_WATCHDOG))
                    wd_quiet <= 0;
            end
            if (!prev_elapsed[24]) prev_elapsed <= prev_elapsed + 1;
        end
    end
    always @(posedge clock) if (judged) begin
        // wd_elapsed is 0 in the clock after the bus write: T + 2 is the
        // write's clock + TIMEOUT + 3 (DRIVE_ENABLE: ms_stopped_drive_low)
        if (wd_armed && wd_quiet && wd_elapsed == wd_timeout + 2) begin
            mw_watchdog_stops: assert(wd_fired || (stop_rose && machine_guard0_guard_reason == REASON_WATCHDOG));
        end
        if (stop_rose && machine_guard0_guard_reason == REASON_WATCHDOG && !p_stopping) begin
            mw_watchdog_not_early: assert((wd_armed && wd_elapsed >= wd_timeout)
                                          || (wd_elapsed <= 3 && prev_armed && prev_elapsed >= prev_timeout));
        end
    end

    // ------------------------------------------------------------ feed hold, decelerated stop
    always @(posedge clock) if (judged) begin
        // "HELD is 1 once the rate is zero and the last step has left the pins"
        if (settled) begin fh_held_rate_zero: assert(feed_rate0_rate == 0 && pins_step == 0); end
        if (p_held) begin fh_held_no_step: assert(rise == 0); end
        // "With RAMP_STEP = 0 the rate is zero in the clock after the register takes HOLD"
        if (p_control[1] && p_ramp == 0 && pp_ramp == 0) begin fh_hold_at_once: assert(feed_rate0_rate == 0); end
        // "the guard sets STOPPING ... the stop latches at the edge after HELD rises"
        if (stop_rose && machine_guard0_guard_reason != REASON_ESTOP && p_ramp != 0 && pp_ramp != 0) begin
            fh_stopping_precedes: assert(p_stopping && p_held);
        end
        // "DRIVE_ENABLE stays high until the latch" (the host asking for it, no E-stop)
        if (guard_stopping && !guard_stopped && p_control[0] && !p_active[0]) begin
            fh_drive_while_stopping: assert(pins_drive_enable);
        end
        // the latch after a decelerated stop: the last step has left the pins
        if (stop_rose && p_stopping && machine_guard0_guard_reason != REASON_ESTOP) begin
            fh_stop_after_last_step: assert(steps_quiet);
        end
    end

    // ------------------------------------------------------------ DRIVE_ENABLE around every counted STEP
    // "every STEP the card counts (POS counts the rises) rises and ends its
    // high time while DRIVE_ENABLE is high": DRIVE_ENABLE never falls while a
    // STEP pin is high or in the clock after its fall (with ms_stopped_no_step:
    // once stopped, only the pulse started before the latch rises, inside
    // DRIVE_ENABLE if it was high before).  "After a stop, DRIVE_ENABLE rises
    // only after a new MACHINE_CONTROL write of DRIVE_ENABLE = 1" (rearmed).
    always @(posedge clock) if (judged) begin
        if (p_drive && !pins_drive_enable) begin
            md_drive_holds_pulse: assert(steps_quiet);
        end
        if (pins_drive_enable && !p_drive) begin md_drive_needs_write: assert(rearmed && !guard_stopped); end
    end

    // ------------------------------------------------------------ WATCHDOG writes
    // "a write loads the count with the value written (0 turns the watchdog
    // off) ... clamped to the largest timeout": the write reaches the register
    // the clock after its stage, the guard's count the clock after that
    reg [31:0] wd_stage_value = 0, wd_loaded_value = 0;
    reg wd_stage = 0, wd_loaded = 0;
    always @(posedge clock) begin
        wd_stage <= reset_n && stage_write && stage_addr == REG_WATCHDOG;
        wd_stage_value <= stage_data;
        wd_loaded <= reset_n && wd_stage;
        wd_loaded_value <= wd_stage_value;
    end
    always @(posedge clock) if (judged && wd_loaded) begin
        mwl_write_loads_clamped: assert(watchdog_left == (wd_loaded_value > 32'hFFFFFF ? 24'hFFFFFF
                                                                                   : wd_loaded_value[23:0]));
        if (wd_loaded_value != 0) begin mwl_only_zero_turns_off: assert(watchdog_left != 0); end
    end

`ifdef FERROR_GUARD
`include "machine_following_error.vh"
`endif

    // ------------------------------------------------------------ homing
    localparam HOME_IDLE = 3'd0, HOME_RELEASE = 3'd4;
    // the HOME write reaches the register (its strobe) the clock after its stage
    reg home_strobe = 0;
    always @(posedge clock) home_strobe <= reset_n && stage_write && stage_addr == REG_HOME;
    reg p_home_strobe = 0, zeroed = 0, p_not_found = 0, p_not_idle = 0;
    reg [2:0] p_home_state = 0;
    // (level, regs_fifo_env.vh: FIFO words the sequencer has not taken, a command queued)
    always @(posedge clock) begin
        p_home_strobe <= home_strobe; p_home_state <= homing0_state; p_not_found <= homing0_not_found;
        p_not_idle <= guard_stopped || conditioning_active[0] || homing0_state != HOME_IDLE || level != 0
                      || pins_step != 0;
        if (!reset_n || (homing0_state == HOME_IDLE && home_strobe)) zeroed <= 0;
        else if (home_zero != 0) zeroed <= 1;
    end
    always @(posedge clock) if (judged) begin
        // "In the clock the sequencer sees it [the filtered input inactive] it
        // stops the steps and zeroes that axis's position" (release only)
        if (home_zero != 0) begin
            hm_zero_at_release: assert(homing0_state == HOME_RELEASE && homing0_axis < AXES
                && home_zero == (1 << homing0_axis) && !home_active[homing0_axis]);
        end
        // "NOT_FOUND ... the position is not zeroed"
        if (homing0_not_found && !p_not_found) begin hm_not_found_not_zeroed: assert(!zeroed); end
        // "3. Back-off ... then DONE": after the zero only the back-off follows
        if (zeroed && homing0_state != HOME_IDLE) begin hm_back_off_after_zero: assert(homing0_state >= 3'd5); end
        // "REFUSED: HOME written while the card was not idle, stopped, E-stop, homing"
        if (p_home_strobe && p_not_idle) begin
            hm_refused: assert(homing0_refused && (p_home_state != HOME_IDLE || homing0_state == HOME_IDLE));
        end
        // homing steps only the chosen axis: no direct pulse nor STEP rise on any other
        if (homing0_state != HOME_IDLE) begin
            hm_chosen_axis: assert(((direct_request | direct_pending) & ~(1 << homing0_axis)) == 0);
            // on the pins (bounded: the pulse outputs' queue has no helper invariant)
            hp_chosen_axis_pins: assert((rise & ~(1 << homing0_axis)) == 0);
        end
    end
endmodule

// One machine input (INPUT_TICK 1, INPUT_POLARITY 0): "a pin that changes
// in the clock before edge e is ACTIVE after edge e + INPUT_FILTER + 1",
// so ACTIVE equals a level the pin has kept for FILTER + 3 clocks; and "a
// new level counts once INPUT_FILTER samples in a row saw it": ACTIVE takes
// a level only when the pin had it in the FILTER clocks that reached the
// filter's samples (the synchroniser's two clocks and the filter's register
// before them).
module input_reaction #(parameter FILTER = 3) (
    input wire clock, input wire reset_n, input wire judged, input wire pin, input wire active,
    output wire [3:0] same_for
);
    reg p_pin = 0, p_active = 0;
    reg [3:0] same_before = 0;                  // same_for of the last clock
    reg [FILTER+2:0] history = 0;               // history[k-1]: the pin k clocks ago
    assign same_for = pin != p_pin ? 4'd1 : (same_before == 4'hF ? same_before : same_before + 1);
    always @(posedge clock) begin
        p_pin <= pin; p_active <= active;
        history <= {history[FILTER+1:0], pin};
        same_before <= reset_n ? same_for : 4'd0;
    end
    wire [FILTER-1:0] sampled = history[FILTER+1:2];  // the pin 3 .. FILTER + 2 clocks ago
    always @(posedge clock) if (judged) begin
        if (same_for >= FILTER + 3) begin mr_filter_follows: assert(active == pin); end
        if (active != p_active) begin mr_filter_not_early: assert(sampled == {FILTER{active}}); end
    end
endmodule
