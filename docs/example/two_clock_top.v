`timescale 1ns/1ps
// two_clock_top: split_core with a back end in a clock domain of its own,
// as a core with a Wishbone side has one.  The back end's clock comes from
// this wrapper (a clock generator with # delays: 25 MHz, asynchronous to the
// PCI clock); every dword written over PCI crosses to it by a toggle and a
// two-flop synchroniser.  Two outputs for the bench to watch: the last dword
// the back end took (wb_mailbox) and its clocks since reset (wb_ticks).
module two_clock_top (
    input  wire        clk,
    input  wire        rst_n,
    input  wire [31:0] ad_in,
    output wire [31:0] ad_out,
    output wire [31:0] ad_oe,
    input  wire [3:0]  cbe_in,
    input  wire        par_in,
    output wire        par_out,
    output wire        par_oe,
    input  wire        frame_n, irdy_n, idsel,
    output wire        trdy_n, devsel_n, stop_n, ctl_oe,
    output reg  [31:0] wb_mailbox,
    output reg  [15:0] wb_ticks
);
    localparam WB_HALF_PERIOD = 20;           // ns: 25 MHz
    reg wb_clk = 1'b0;
    always #WB_HALF_PERIOD wb_clk = !wb_clk;

    wire wr_stb;
    wire [1:0] wr_word;
    wire [31:0] wr_data;
    wire [3:0] cbe_out, cbe_oe;
    split_core core (
        .clk(clk), .rst_n(rst_n), .ad_in(ad_in), .ad_out(ad_out), .ad_oe(ad_oe),
        .cbe_in(cbe_in), .cbe_out(cbe_out), .cbe_oe(cbe_oe), .par_in(par_in), .par_out(par_out),
        .par_oe(par_oe), .frame_n(frame_n), .irdy_n(irdy_n), .idsel(idsel), .trdy_n(trdy_n),
        .devsel_n(devsel_n), .stop_n(stop_n), .ctl_oe(ctl_oe), .wr_stb(wr_stb), .wr_word(wr_word),
        .wr_data(wr_data)
    );

    reg toggle;                               // PCI side: the dword held, a toggle per write
    reg [31:0] held;
    always @(posedge clk or negedge rst_n)
        if (!rst_n) begin
            toggle <= 1'b0; held <= 0;
        end else if (wr_stb) begin
            toggle <= !toggle; held <= wr_data;
        end

    reg [2:0] sync;                           // back end: the toggle synchronised, then its edge
    always @(posedge wb_clk or negedge rst_n)
        if (!rst_n) begin
            sync <= 0; wb_mailbox <= 0; wb_ticks <= 0;
        end else begin
            sync <= {sync[1:0], toggle};
            wb_ticks <= wb_ticks + 1'b1;
            if (sync[2] != sync[1]) wb_mailbox <= held;
        end
endmodule
