// Reset of a harness (included by pci_target_harness.sv, card_harness.sv,
// regs_fifo_harness.sv and machine_harness.sv): RST# asserted in the first
// clock, free after it; `judged` from the second clock out of reset on, when
// the registers that hold the last clock's values (p_*) hold a clock of the
// unit out of reset.
    reg started = 0;
    always @(posedge clock) started <= 1;
    always @(*) if (!started) assume(!reset_n);
    reg past_reset = 0;         // the last clock was out of reset
    always @(posedge clock) past_reset <= reset_n;
    wire judged = reset_n && past_reset;
