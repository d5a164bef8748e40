// split_core: a small PCI target with split ports and one output enable
// per bit, as cores written for FPGAs with per-bit I/O registers have them
// (32 on AD, 4 on C/BE#, which a target never enables).  Configuration
// space (IDs, Command, one memory BAR), four dwords of RAM behind the BAR,
// one data phase per transaction (STOP# with TRDY#), and a write strobe to
// a back end (wr_stb, wr_word, wr_data) for every memory dword written.
// Variants, by define: LATE_RELEASE keeps AD[15:0] enabled one clock after
// the end of a read, when AD[31:16] is released (a line driven only in
// part); AD_OE_BITS gives the AD enable another width.
`ifndef AD_OE_BITS
`define AD_OE_BITS 32
`endif

module split_core #(
    parameter ADDR_BITS = 4                          // BAR: 2^ADDR_BITS bytes, 4 dwords
) (
    input  wire        clk,
    input  wire        rst_n,
    input  wire [31:0] ad_in,
    output reg  [31:0] ad_out,
    output reg  [`AD_OE_BITS-1:0] ad_oe,
    input  wire [3:0]  cbe_in,
    output wire [3:0]  cbe_out,
    output wire [3:0]  cbe_oe,
    input  wire        par_in,
    output reg         par_out,
    output reg         par_oe,
    input  wire        frame_n, irdy_n, idsel,
    output reg         trdy_n, devsel_n, stop_n,
    output reg         ctl_oe,
    output reg         wr_stb,
    output reg  [1:0]  wr_word,
    output reg  [31:0] wr_data
);
    localparam IDLE = 3'd0, DECODE = 3'd1, DATA = 3'd2, BACKOFF = 3'd3, ENDING = 3'd4;
    localparam MEM_READ = 4'h6, MEM_WRITE = 4'h7, CFG_READ = 4'hA, CFG_WRITE = 4'hB;

    reg [2:0] state;
    reg [31:0] address;
    reg [3:0] command;
    reg config_hit, frame_before, mem_enable;
    reg [31:ADDR_BITS] bar;
    reg [31:0] ram [0:3];
    wire [1:0] word = address[3:2];
    wire memory_hit = mem_enable && address[31:ADDR_BITS] == bar
                      && (command == MEM_READ || command == MEM_WRITE);
    wire [31:0] data_in = {cbe_in[3] ? 8'h00 : ad_in[31:24], cbe_in[2] ? 8'h00 : ad_in[23:16],
                           cbe_in[1] ? 8'h00 : ad_in[15:8], cbe_in[0] ? 8'h00 : ad_in[7:0]};
`ifdef LATE_RELEASE
    wire [`AD_OE_BITS-1:0] released = {{(`AD_OE_BITS-16){1'b0}}, ad_oe[15:0]};
`else
    wire [`AD_OE_BITS-1:0] released = 0;       // AD's enables at the end of a transaction
`endif
    assign cbe_out = 4'hF;
    assign cbe_oe = 4'h0;                            // a target only reads C/BE#

    always @(posedge clk or negedge rst_n)
        if (!rst_n) begin
            state <= IDLE; frame_before <= 1'b1; mem_enable <= 1'b0; bar <= 0;
            address <= 0; command <= 0; config_hit <= 1'b0;
            ad_out <= 0; ad_oe <= 0; par_out <= 1'b0; par_oe <= 1'b0;
            trdy_n <= 1'b1; devsel_n <= 1'b1; stop_n <= 1'b1; ctl_oe <= 1'b0;
            wr_stb <= 1'b0; wr_word <= 0; wr_data <= 0;
        end else begin
            frame_before <= frame_n;
            par_out <= ^{ad_out, cbe_in};
            par_oe <= |ad_oe;
            wr_stb <= 1'b0;
            case (state)
                IDLE: if (frame_before && !frame_n) begin
                    address <= ad_in;
                    command <= cbe_in;
                    config_hit <= idsel && ad_in[1:0] == 2'b00 && (cbe_in == CFG_READ || cbe_in == CFG_WRITE);
                    state <= DECODE;
                end
                DECODE: if (config_hit || memory_hit) begin
                    ctl_oe <= 1'b1; devsel_n <= 1'b0; trdy_n <= 1'b0; stop_n <= 1'b0;
                    if (!command[0]) begin
                        ad_out <= !config_hit ? ram[word] : address[7:2] == 6'h00 ? 32'h5107_1234
                                : address[7:2] == 6'h01 ? {30'h0, mem_enable, 1'b0}
                                : address[7:2] == 6'h04 ? {bar, {ADDR_BITS{1'b0}}} : 32'h0;
                        ad_oe <= {`AD_OE_BITS{1'b1}};
                    end
                    state <= DATA;
                end else
                    state <= IDLE;
                DATA: if (!irdy_n) begin
                    if (command == CFG_WRITE && config_hit && address[7:2] == 6'h01 && !cbe_in[0])
                        mem_enable <= ad_in[1];
                    if (command == CFG_WRITE && config_hit && address[7:2] == 6'h04)
                        bar <= ad_in[31:ADDR_BITS];
                    if (command == MEM_WRITE && !config_hit) begin
                        ram[word] <= data_in;
                        wr_stb <= 1'b1; wr_word <= word; wr_data <= data_in;
                    end
                    trdy_n <= 1'b1;
                    if (frame_n) begin
                        devsel_n <= 1'b1; stop_n <= 1'b1;
                        ad_oe <= released;
                        state <= ENDING;
                    end else
                        state <= BACKOFF;
                end
                BACKOFF: if (frame_n && !irdy_n) begin
                    devsel_n <= 1'b1; stop_n <= 1'b1; ad_oe <= released;
                    state <= ENDING;
                end
                ENDING: begin
                    ctl_oe <= 1'b0; ad_oe <= 0;
                    state <= IDLE;
                end
                default: state <= IDLE;
            endcase
        end
endmodule
