// Smoke test of the generated card (gen/card.v): reset, then one PCI
// configuration read of dword 0 (Device ID, Vendor ID), as a PCI master does it.
// Run through FuseSoC (pci_dda_card.core, target sim); tests/fpgaflow/test_fusesoc.py.
//
// clock    _/~\_/~\_/~\_/~\_/~\_/~\_
// FRAME#   ~~\___/~~~~~~~~~~~~~~~~~~    address phase: AD = 0, C/BE# = 1010, IDSEL
// IRDY#    ~~~~~~\___________/~~~~~~    the master waits for TRDY#
// DEVSEL#  ~~~~~~~~~~~\______/~~~~~~    the card claims the access ...
// TRDY#    ~~~~~~~~~~~~~~~\__/~~~~~~    ... and shows the ID dword on AD
//
// EXPECTED_ID is the dword the PCI spec puts there: {Device ID, Vendor ID}, by
// default those of `python -m rtl.top --help` (0xDDA0, 0x1234).  The bench
// stops with $fatal (non-zero exit) on a wrong dword, a retry, a disconnect,
// no answer, PERR#, SERR# or INTA# asserted, or a STEP/DIR pin that moves.
`timescale 1ns/1ps
`default_nettype none

module card_config_read_tb;
parameter [31:0] EXPECTED_ID = 32'hDDA01234;
localparam [3:0] CONFIG_READ = 4'b1010;
localparam integer MAX_WAIT = 16;  // clocks from the address phase; DEVSEL# is due within 5

reg clock = 1'b0;
reg reset = 1'b0;  // RST#, asserted
initial forever #15 clock = ~clock;  // 33 MHz

// master side: lines set 1 ns after an edge, as a driver's clock-to-output
reg [31:0] host_ad = 32'h0;
reg host_ad_oe = 1'b0;
reg [3:0] host_cbe = 4'hF;
reg host_frame = 1'b1;
reg host_irdy = 1'b1;
reg host_idsel = 1'b0;
reg host_par = 1'b0;
reg host_par_oe = 1'b0;

wire [31:0] card_ad_out;
wire card_ad_oe, card_par_out, card_par_oe;
wire card_trdy_out, card_trdy_oe, card_devsel_out, card_devsel_oe, card_stop_out, card_stop_oe;
wire card_perr_out, card_perr_oe, card_serr_out, card_serr_oe, card_inta_out, card_inta_oe;
wire step_x, dir_x, step_y, dir_y, drive_enable;

// the bus: whoever enables a line drives it; TRDY#, DEVSEL#, STOP# are pulled up
wire [31:0] ad = card_ad_oe ? card_ad_out : host_ad_oe ? host_ad : 32'h0;
wire par = card_par_oe ? card_par_out : host_par_oe ? host_par : 1'b0;
wire trdy = card_trdy_oe ? card_trdy_out : 1'b1;
wire devsel = card_devsel_oe ? card_devsel_out : 1'b1;
wire stop = card_stop_oe ? card_stop_out : 1'b1;

card dut (
    .clock(clock), .reset(reset),
    .pci_ad_in(ad), .pci_ad_out(card_ad_out), .pci_ad_oe(card_ad_oe),
    .pci_cbe_in(host_cbe), .pci_par_in(par), .pci_par_out(card_par_out), .pci_par_oe(card_par_oe),
    .pci_frame_in(host_frame), .pci_irdy_in(host_irdy), .pci_idsel_in(host_idsel),
    .pci_trdy_out(card_trdy_out), .pci_trdy_oe(card_trdy_oe),
    .pci_devsel_out(card_devsel_out), .pci_devsel_oe(card_devsel_oe),
    .pci_stop_out(card_stop_out), .pci_stop_oe(card_stop_oe),
    .pci_perr_out(card_perr_out), .pci_perr_oe(card_perr_oe),
    .pci_serr_out(card_serr_out), .pci_serr_oe(card_serr_oe),
    .pci_inta_out(card_inta_out), .pci_inta_oe(card_inta_oe),
    .pins_step_x(step_x), .pins_dir_x(dir_x), .pins_step_y(step_y), .pins_dir_y(dir_y), .pins_drive_enable(drive_enable),
    .pins_estop(1'b0), .pins_limit_pos_x(1'b0), .pins_limit_neg_x(1'b0), .pins_limit_pos_y(1'b0),
    .pins_limit_neg_y(1'b0), .pins_home_x(1'b0), .pins_home_y(1'b0)
);

// PAR covers AD and C/BE# of the clock before: the master drives it the clock after it drove AD
always @(posedge clock) begin
    host_par <= #1 ^{host_ad, host_cbe};
    host_par_oe <= #1 host_ad_oe;
end

// an access with good parity and no motion command: the error, interrupt and motor pins stay quiet
wire perr = card_perr_oe ? card_perr_out : 1'b1;
wire serr = card_serr_oe ? card_serr_out : 1'b1;
wire inta = card_inta_oe ? card_inta_out : 1'b1;
reg [3:0] motor_idle;
reg watching = 1'b0;  // from the address phase on
always @(posedge clock) begin
    if (watching && (!perr || !serr || !inta))
        $fatal(1, "FAIL: PERR# %b, SERR# %b, INTA# %b", perr, serr, inta);
    if (watching && {step_x, dir_x, step_y, dir_y} !== motor_idle)
        $fatal(1, "FAIL: STEP/DIR moved from %b to %b", motor_idle, {step_x, dir_x, step_y, dir_y});
    if (watching && drive_enable !== 1'b0)
        $fatal(1, "FAIL: DRIVE_ENABLE %b without a MACHINE_CONTROL write", drive_enable);
end

integer waited;
reg claimed;
reg [31:0] data;

initial begin
    repeat (4) @(posedge clock);
    #1 reset = 1'b1;
    repeat (4) @(posedge clock);
    #1 begin  // address phase
        motor_idle = {step_x, dir_x, step_y, dir_y};
        watching = 1'b1;
        host_frame = 1'b0;
        host_ad = 32'h0;  // type 0, register 0
        host_ad_oe = 1'b1;
        host_cbe = CONFIG_READ;
        host_idsel = 1'b1;
    end
    @(posedge clock);
    #1 begin  // the only data phase: turnaround on AD, all bytes enabled
        host_frame = 1'b1;
        host_irdy = 1'b0;
        host_ad_oe = 1'b0;
        host_cbe = 4'h0;
        host_idsel = 1'b0;
    end
    claimed = 1'b0;
    waited = 0;
    data = 32'hx;
    while (data === 32'hx) begin
        @(posedge clock);
        waited = waited + 1;
        claimed = claimed | ~devsel;
        if (!stop)
            $fatal(1, "FAIL: STOP# asserted (retry or disconnect) after %0d clocks", waited);
        if (!trdy)
            data = ad;
        else if (waited == MAX_WAIT)
            $fatal(1, "FAIL: no TRDY# within %0d clocks (DEVSEL# %s)", MAX_WAIT, claimed ? "asserted" : "never asserted");
    end
    #1 host_irdy = 1'b1;
    repeat (2) @(posedge clock);
    if (!claimed)
        $fatal(1, "FAIL: data without DEVSEL#");
    if (!trdy || !devsel)
        $fatal(1, "FAIL: TRDY#/DEVSEL# still asserted after the transaction");
    if (data !== EXPECTED_ID)
        $fatal(1, "FAIL: configuration dword 0 is %h, expected %h", data, EXPECTED_ID);
    $display("PASS: configuration dword 0 = %h after %0d clocks", data, waited);
    $finish;
end

endmodule

`default_nettype wire
