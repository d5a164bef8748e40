// The ports of gen/regs_fifo.v that regs_fifo_harness.sv and
// machine_harness.sv both connect (included inside the unit's instance; the
// wires are declared by regs_fifo_env.vh): the LocalBus, the DDA port, the
// step requests and the pins, the machine inputs (machine_in: E-STOP, the
// four limits, the two home switches), and the registers of the unit both
// harnesses make ports with yosys `expose` (the FIFO's pop and flush, the
// SET command's write port, the direct pulse requests, the guard's stop).
        .clock(clock), .reset(reset_n), .irq(irq), .core_clear(core_clear),
        .local_space(l_space), .local_addr(l_addr), .local_be(l_be), .local_wdata(l_wdata),
        .local_we(l_we), .local_re(l_re), .local_write(l_write), .local_rdata(l_rdata),
        .local_ready(l_ready), .local_retry(l_retry),
`ifdef LOCAL_ROOM
        .local_room(l_room),
`endif
        .dda_start(dda_start), .dda_line(dda_line), .dda_variant(dda_variant),
        .dda_lambda_shift(dda_lambda_shift), .dda_acc_bits(dda_acc_bits), .dda_ccw(dda_ccw),
        .dda_blend(dda_blend), .dda_xs(dda_xs), .dda_ys(dda_ys), .dda_xe(dda_xe), .dda_ye(dda_ye),
        .dda_advance(dda_advance), .dda_busy(dda_busy), .dda_done(dda_done), .dda_error(dda_error),
        .dda_quadrant(dda_quadrant), .dda_ready(dda_ready), .dda_stop_left(dda_stop_left),
        .steps_step_x(steps_step_x), .steps_step_y(steps_step_y), .steps_dir_x(steps_dir_x),
        .steps_dir_y(steps_dir_y), .pins_step_x(pins_step_x), .pins_dir_x(pins_dir_x),
        .pins_step_y(pins_step_y), .pins_dir_y(pins_dir_y), .pins_estop(machine_in[0]),
        .pins_limit_pos_x(machine_in[1]), .pins_limit_neg_x(machine_in[2]), .pins_limit_pos_y(machine_in[3]),
        .pins_limit_neg_y(machine_in[4]), .pins_home_x(machine_in[5]), .pins_home_y(machine_in[6]),
        .fifo_pop(fifo_pop), .fifo_flush(fifo_flush),
        .set_strobe(set_strobe), .set_index(set_index), .set_value(set_value),
        .direct_request_x(direct_request_x), .direct_request_y(direct_request_y), .guard_stopped(guard_stopped)
