// scratch_target: a small PCI target written to show how to bench a
// Verilog target with the project's host and monitor (docs/verification.md).
// Configuration space (IDs, Command, one memory BAR), WORDS dwords of
// scratch RAM behind the BAR, medium DEVSEL#, one data phase per
// transaction (a burst is disconnected with its first datum, STOP# with
// TRDY#).  The first attempt of every read of an odd dword is retried, as a
// target does whose data are not ready yet; with `X_ON_RETRY defined it
// drives X on AD while it retries (a defect the X/Z detector reports).
// Tri-state ports, as on a real card.  Auteur: pièce d'exemple (Latin-1).
`include "scratch_defs.vh"

module scratch_target #(
    parameter WORDS = 16,
    parameter ADDR_BITS = 6,         // BAR size 2^ADDR_BITS bytes = 4 * WORDS
    parameter AD_BITS = 32           // no 64-bit extension
) (
    input  wire        clk,
    input  wire        rst_n,
    inout  wire [AD_BITS-1:0] ad,
    input  wire [3:0]  cbe_n,
    inout  wire        par,
    input  wire        frame_n,
    input  wire        irdy_n,
    input  wire        idsel,
    inout  wire        trdy_n,
    inout  wire        devsel_n,
    inout  wire        stop_n
);
    localparam IDLE = 3'd0, DECODE = 3'd1, DATA = 3'd2, BACKOFF = 3'd3, ENDING = 3'd4;
    localparam CFG_READ = 4'hA, CFG_WRITE = 4'hB, MEM_READ = 4'h6, MEM_WRITE = 4'h7;

    reg [2:0] state;
    reg [31:0] address;
    reg [3:0] command;
    reg config_hit;
    reg frame_before;
    reg [31:0] ad_q;
    reg ad_oe, par_q, par_oe, ctl_oe, trdy_q, devsel_q, stop_q;
    reg mem_enable;
    reg [31:ADDR_BITS] bar;
    reg [31:0] ram [0:WORDS-1];
    reg [WORDS-1:0] asked;            // odd dwords whose first read was retried

    assign ad = ad_oe ? ad_q : 32'bz;
    assign par = par_oe ? par_q : 1'bz;
    assign trdy_n = ctl_oe ? trdy_q : 1'bz;
    assign devsel_n = ctl_oe ? devsel_q : 1'bz;
    assign stop_n = ctl_oe ? stop_q : 1'bz;

    wire [ADDR_BITS-3:0] word = address[ADDR_BITS-1:2];
    wire memory_hit = mem_enable && address[31:ADDR_BITS] == bar
                      && (command == MEM_READ || command == MEM_WRITE);
    wire write = command[0];

    function [31:0] config_word(input [5:0] register);
        case (register)
            6'h00: config_word = {`SCRATCH_DEVICE, `SCRATCH_VENDOR};
            6'h01: config_word = {16'h0200, 14'b0, mem_enable, 1'b0};  // medium DEVSEL#
            6'h02: config_word = {`SCRATCH_CLASS, 8'h01};
            6'h04: config_word = {bar, {ADDR_BITS{1'b0}}};             // 32-bit memory BAR
            default: config_word = 32'h0;
        endcase
    endfunction

    function [31:0] merge(input [31:0] old, input [31:0] value, input [3:0] be_n);
        merge = {be_n[3] ? old[31:24] : value[31:24], be_n[2] ? old[23:16] : value[23:16],
                 be_n[1] ? old[15:8] : value[15:8], be_n[0] ? old[7:0] : value[7:0]};
    endfunction

    always @(posedge clk or negedge rst_n) begin
        if (!rst_n) begin
            state <= IDLE;
            ad_oe <= 1'b0; par_oe <= 1'b0; ctl_oe <= 1'b0;
            trdy_q <= 1'b1; devsel_q <= 1'b1; stop_q <= 1'b1;
            mem_enable <= 1'b0; bar <= 0; asked <= 0;
            frame_before <= 1'b1; address <= 0; command <= 0; config_hit <= 1'b0;
            ad_q <= 0; par_q <= 1'b0;
        end else begin
            frame_before <= frame_n;
            par_q <= ^{ad_q, cbe_n};          // PAR of the AD this target drove, a clock later
            par_oe <= ad_oe;
            case (state)
                IDLE: if (frame_before && !frame_n) begin
                    address <= ad;
                    command <= cbe_n;
                    config_hit <= idsel && ad[1:0] == 2'b00 && (cbe_n == CFG_READ || cbe_n == CFG_WRITE);
                    state <= DECODE;
                end
                DECODE: if (config_hit || memory_hit) begin
                    ctl_oe <= 1'b1;
                    devsel_q <= 1'b0;
                    if (!write && !config_hit && word[0] && !asked[word]) begin
                        asked[word] <= 1'b1;     // retry: the data are "not ready"
                        stop_q <= 1'b0;
`ifdef X_ON_RETRY
                        ad_q <= 32'bx;
                        ad_oe <= 1'b1;
`endif
                        state <= BACKOFF;
                    end else begin
                        trdy_q <= 1'b0;
                        stop_q <= 1'b0;          // one data phase: disconnect with data
                        if (!write) begin
                            ad_q <= config_hit ? config_word(address[7:2]) : ram[word];
                            ad_oe <= 1'b1;
                            if (!config_hit) asked[word] <= 1'b0;
                        end
                        state <= DATA;
                    end
                end else
                    state <= IDLE;
                DATA: if (!irdy_n) begin         // the data phase completes
                    if (write && config_hit && address[7:2] == 6'h01 && !cbe_n[0])
                        mem_enable <= ad[1];
                    if (write && config_hit && address[7:2] == 6'h04)
                        bar <= merge({bar, {ADDR_BITS{1'b0}}}, ad, cbe_n) >> ADDR_BITS;
                    if (write && !config_hit)
                        ram[word] <= merge(ram[word], ad, cbe_n);
                    trdy_q <= 1'b1;
                    if (frame_n) begin
                        devsel_q <= 1'b1; stop_q <= 1'b1; ad_oe <= 1'b0;
                        state <= ENDING;
                    end else
                        state <= BACKOFF;
                end
                BACKOFF: if (frame_n && !irdy_n) begin
                    devsel_q <= 1'b1; stop_q <= 1'b1; ad_oe <= 1'b0;
                    state <= ENDING;
                end
                ENDING: begin
                    ctl_oe <= 1'b0;
                    state <= IDLE;
                end
                default: state <= IDLE;
            endcase
        end
    end
endmodule
