// body_ports_top: split_core behind ports in the older style, named in the
// header and declared in the body, with one output enable per line.  The
// functions and the task have inputs of their own (e, v, en_all's, mixed's),
// which are not ports; comments and attributes mention ports that are not
// there either: input fake_in; output fake_out;
// With INNER_WIDTH_BUG defined the write strobe's word is wired 1 bit wide
// (Icarus warns about it).
module body_ports_top (clk, rst_n, ad_in, ad_out, ad_en, cbe_in, par_in, par_out, par_en,
                       frame_n, irdy_n, idsel, trdy_n, devsel_n, stop_n, ctl_en);
    parameter WIDTH = 32;
    (* keep = "true" *) input clk;
    input wire rst_n;                 /* input rst; (not a port) */
    input wire [WIDTH-1:0] ad_in;
    output [WIDTH-1:0] ad_out;
    output ad_en;
    input [3:0] cbe_in;
    input par_in, frame_n, irdy_n, idsel;
    output wire par_out, par_en;
    output trdy_n, devsel_n, stop_n, ctl_en;

    wire [WIDTH-1:0] ad_drive, ad_oe;
    wire [3:0] cbe_out, cbe_oe;
    wire wr_stb;
`ifdef INNER_WIDTH_BUG
    wire wr_word;
`else
    wire [1:0] wr_word;
`endif
    wire [31:0] wr_data;

    function en_all(input [WIDTH-1:0] e);   // the line is enabled when every bit is
        en_all = &e;
    endfunction

    function [WIDTH-1:0] mixed;              // the older style of function inputs
        input [WIDTH-1:0] v;
        input [WIDTH-1:0] e;
        mixed = v & e;
    endfunction

    task expect_whole;                        // a task with an input: not a port either
        input [WIDTH-1:0] e;
        if (e != 0 && ~e != 0) $display("%m: AD enabled in part: %h", e);
    endtask

    always @(posedge clk) expect_whole(ad_oe);
    assign ad_out = mixed(ad_drive, ad_oe);
    assign ad_en = en_all(ad_oe);

    split_core core (
        .clk(clk), .rst_n(rst_n), .ad_in(ad_in), .ad_out(ad_drive), .ad_oe(ad_oe),
        .cbe_in(cbe_in), .cbe_out(cbe_out), .cbe_oe(cbe_oe), .par_in(par_in), .par_out(par_out),
        .par_oe(par_en), .frame_n(frame_n), .irdy_n(irdy_n), .idsel(idsel), .trdy_n(trdy_n),
        .devsel_n(devsel_n), .stop_n(stop_n), .ctl_oe(ctl_en), .wr_stb(wr_stb), .wr_word(wr_word),
        .wr_data(wr_data)
    );
endmodule
