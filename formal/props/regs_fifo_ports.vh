// The ports of gen/regs_fifo.v that regs_fifo_harness.sv and
// machine_harness.sv both connect (included inside the unit's instance; the
// wires are declared by regs_fifo_env.vh): the LocalBus, the DDA port, and
// the registers of the unit both harnesses make ports with yosys `expose`
// (the FIFO's pop and flush, the SET command's write port, the guard's
// stop).  The per-axis ports (step requests, STEP/DIR pins, the machine
// inputs: E-STOP, each axis's limits and home switch, and each axis's
// direct-pulse request) follow in regs_fifo_axes.vh, generated for the
// build's axes by formal/axes_props.py.
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
        .fifo_pop(fifo_pop), .fifo_flush(fifo_flush),
        .set_strobe(set_strobe), .set_index(set_index), .set_value(set_value), .guard_stopped(guard_stopped)
`include "regs_fifo_axes.vh"
