// The environment of gen/regs_fifo.v that regs_fifo_harness.sv and
// machine_harness.sv share (included before the unit's instance, whose
// common ports are regs_fifo_ports.vh):
//   * the unit's outputs and the registers both harnesses expose, the
//     per-axis ones as vectors over the build's AXES (a harness parameter);
//   * RST# in the first clock (harness_reset.vh);
//   * a free requester kept to the LocalBus rules (local_bus_rules.sv,
//     CHECK_REQUESTER = 0: the back end's answers asserted, `lb_*`);
//   * the register write of the last clock (`stage_*`: a register takes a
//     bus write one clock after the transfer, rtl/regs_fifo.py) and the
//     register models generated from the table (regs_table.vh); an access
//     is judged by the BAR0 offset of the register it reaches (`l_offset`,
//     `stage_addr`: X's and Y's block registers in BAR2 are BAR0's,
//     `bar0_offset` of regs_offsets.vh);
//   * the FIFO level: words the bus pushed (a memory-space write answered
//     ready with a byte enabled) and the sequencer has not taken;
//   * a free interpolator on the DDA port, busy only from a start until its
//     reset (core_clear resets it in the next clock), stepping only while
//     busy (rtl/dda_arc.py); `p_advance`: an `advance` (a feed tick) in the
//     last clock, for the harnesses that step only after one.
    wire [31:0] l_rdata;
    wire l_ready, l_retry, l_room, irq, core_clear;
    wire dda_start, dda_line, dda_ccw, dda_blend, dda_advance;
    wire [1:0] dda_variant;
    wire [4:0] dda_lambda_shift, dda_acc_bits;
    wire [COORD_WIDTH-1:0] dda_xs, dda_ys, dda_xe, dda_ye;
    wire [AXES-1:0] pins_step, pins_dir;    // per axis: 0 X, 1 Y, 2 Z, ...
    // exposed registers of the unit
    wire fifo_pop, fifo_flush, set_strobe, guard_stopped;
    wire [AXES-1:0] direct_request;
    // a build with encoders: every axis's encoder pins and the probe, free (regs_fifo_axes.vh)
    (* anyseq *) wire [AXES-1:0] enc_a, enc_b, enc_index;
    (* anyseq *) wire probe;
    wire [3:0] set_index;
    wire [31:0] set_value;

`include "harness_reset.vh"

    local_bus_rules #(.CHECK_REQUESTER(0), .ADDR_WIDTH(16)) bus (
        .clock(clock), .reset_n(reset_n), .space(l_space), .addr(l_addr), .be(l_be),
        .wdata(l_wdata), .we(l_we), .re(l_re), .write(l_write), .ready(l_ready), .retry(l_retry),
        .room(l_room), .promised(promised));
    wire [2:0] promised;
`ifndef LOCAL_ROOM
    assign l_room = 1'b0;
`endif

    // ------------------------------------------------------------ register access
    wire [15:0] l_offset = bar0_offset(l_addr);
    wire read_now = l_re && l_ready && !l_space;
    wire io_write_now = l_we && l_ready && !l_space;
    reg stage_write = 0;
    reg [15:0] stage_addr = 0;
    reg [31:0] stage_data = 0, stage_mask = 0;
    always @(posedge clock) begin
        stage_write <= reset_n && io_write_now;
        stage_addr <= l_offset;
        stage_data <= l_wdata;
        stage_mask <= {{8{l_be[3]}}, {8{l_be[2]}}, {8{l_be[1]}}, {8{l_be[0]}}};
    end
`include "regs_table.vh"

    // ------------------------------------------------------------ the FIFO level
    wire push = l_we && l_ready && l_space && l_be != 4'h0;
    reg [10:0] level = 0;       // words the bus pushed and the sequencer has not taken
    wire pop = fifo_pop && level != 0;
    always @(posedge clock) level <= (!reset_n || fifo_flush) ? 11'd0 : level + push - pop;

    // ------------------------------------------------------------ the interpolator
    reg dda_started = 0, p_advance = 0;
    always @(posedge clock) begin
        p_advance <= dda_advance;
        if (!reset_n || core_clear) dda_started <= 0;
        else if (dda_start) dda_started <= 1;
    end
    always @(*) begin
        if (!dda_started) assume(!dda_busy);
        if (!dda_busy) assume(steps_step == 0);
    end
