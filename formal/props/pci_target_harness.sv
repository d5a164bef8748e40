// The PCI target (gen/pci_slave.v or a netlist with its ports) on a formal
// bus: a free initiator that keeps PCI's initiator rules, other targets whose
// TRDY#/DEVSEL#/STOP# are free outside this target's transactions, and a free
// back end that keeps the LocalBus rules.  Checked here, besides pci_rules
// (target side) and local_bus_rules (requester side):
//   * configuration space (PCI 2.3 6.1, 6.2; docs/pci.md): a model of the
//     header, written by the configuration writes seen on the bus, says what
//     each configuration read returns and which addresses are decoded;
//   * target abort only for the causes docs/pci.md gives (3.2.2 byte enables
//     of an I/O access, 3.7.3 address parity error);
//   * the local side carries exactly the PCI transaction (pci_target_local.vh,
//     included): each write data phase reaches the back end once, in order,
//     with its offset, byte enables and data (a chosen-one shadow); read data
//     reach AD unchanged in the phase that asked for them; no local read
//     outside a read of this target;
//   * BAR2, the registers' memory alias (docs/pci.md): decoded and sized as
//     the configuration model says, its accesses reach the back end as the
//     I/O access at the same offset does (space 0, the bus's byte enables),
//     one data phase per transaction;
//   * register accesses (I/O, BAR2) are not retried when the registers answer;
//   * every dword acknowledged on the bus reaches the back end.
// The bus lines, the unit's PCI pins and the bus model (configuration,
// decode, the transaction) are the card harness's too: pci_bus_lines.vh,
// pci_pins.vh, pci_bus_model.vh, with pci_table.vh from models/pci.py.
`default_nettype none

module pci_target_harness #(
    parameter IO_BITS = 6,
    parameter MEM_BITS = 12,
    parameter REG_BITS = 4,        // BAR2's bits when larger than BAR0's (pci_bus_model.vh)
    parameter LOCAL_WIDTH = 12,
    parameter [31:0] ID_WORD = 32'hDDA01234,
    parameter [31:0] CLASS_WORD = 32'h08800001,
    parameter [31:0] SUBSYSTEM_WORD = 32'h00011234,
    parameter POSTED_MAX = 3,      // dwords the target may hold acknowledged
    parameter DRAIN_LIMIT = 8      // clocks an acknowledged dword may wait
) (
    input wire clock,
    input wire reset_n,
    // the initiator
    input wire [31:0] m_ad, input wire [3:0] m_cbe_n, input wire m_par,
    input wire m_frame_n, input wire m_irdy_n, input wire m_idsel,
    // other targets
    input wire o_trdy_n, input wire o_devsel_n, input wire o_stop_n,
    // the back end
    input wire [31:0] l_rdata, input wire l_ready, input wire l_retry,
    input wire l_room,     // the back end's write credit (with LOCAL_ROOM)
    input wire irq,
    // free choice of the write shadow: follow the write data phase at this edge
    input wire choose_write
);
    // the read shadow watches one dword of the back end, chosen freely
    (* anyconst *) reg [LOCAL_WIDTH-3:0] watch_dword;
    (* anyconst *) reg watch_space;

    // ------------------------------------------------------------ the target
`include "pci_table.vh"
`include "pci_bus_lines.vh"
    wire l_space, l_we, l_re, l_write;
    wire [LOCAL_WIDTH-1:0] l_addr;
    wire [3:0] l_be;
    wire [31:0] l_wdata;

    pci_slave dut (
`include "pci_pins.vh"
        , .irq(irq),
        .local_space(l_space), .local_addr(l_addr), .local_be(l_be), .local_wdata(l_wdata),
        .local_we(l_we), .local_re(l_re), .local_write(l_write), .local_rdata(l_rdata),
        .local_ready(l_ready), .local_retry(l_retry)
`ifdef LOCAL_ROOM
        , .local_room(l_room)
`endif
`ifdef PCI_SLAVE_INVARIANTS
        , .state(i_state), .trdy_q(i_trdy_q), .stop_q(i_stop_q), .devsel_q(i_devsel_q),
        .wait_count(i_wait_count), .initial_wait_over(i_initial_wait_over),
        .subsequent_wait_over(i_subsequent_wait_over), .first_phase(i_first_phase),
        .is_read(i_is_read), .is_config(i_is_config), .space_mem(i_space_mem),
        .io_enable(i_io_enable), .mem_enable(i_mem_enable), .parity_response(i_parity_response),
        .serr_enable(i_serr_enable), .interrupt_disable(i_interrupt_disable), .bar0(i_bar0),
        .bar1(i_bar1), .bar2(i_bar2), .config_write_q(i_config_write_q), .phase_addr(i_phase_addr),
        .at_last(i_at_last), .before_last(i_before_last), .h_valid(i_h_valid), .s_valid(i_s_valid),
        .wq_valid(i_wq_valid), .b_valid(i_b_valid), .fetching(i_fetching),
        .first_pending(i_first_pending), .req_addr_stale(i_req_addr_stale), .single(i_single),
        .frame_q(i_frame_q), .pci_config0_signaled_target_abort(i_signaled_target_abort),
        .pci_config0_signaled_system_error(i_signaled_system_error),
        .pci_config0_detected_parity_error(i_detected_parity_error), .parity_error_q(i_parity_error_q),
        .pci_config0_interrupt_line(i_interrupt_line), .h_data(i_h_data), .spare_data(i_spare_data),
        .ad_q(i_ad_q), .h_be(i_h_be), .s_be(i_s_be), .cbe_q(i_cbe_q), .req_addr(i_req_addr), .ad_out_q(i_ad_out_q)
`endif
        );

`include "harness_reset.vh"
`include "pci_bus_model.vh"

    local_bus_rules #(.CHECK_REQUESTER(1), .ADDR_WIDTH(LOCAL_WIDTH)) back_end (
        .clock(clock), .reset_n(reset_n), .space(l_space), .addr(l_addr), .be(l_be),
        .wdata(l_wdata), .we(l_we), .re(l_re), .write(l_write), .ready(l_ready), .retry(l_retry),
        .room(l_room), .promised(promised));
    wire [2:0] promised;

    // other targets answer only transactions that are not this target's
    always @(*) if (!data_edge || txn_hit) assume(o_trdy_n && o_devsel_n && o_stop_n);

    // the header as the model says a read returns it
    reg [31:0] expected_config;
    always @(*) begin
        case (config_dword)
            CONFIG_ID: expected_config = ID_WORD;
            CONFIG_COMMAND: expected_config = {detected_parity_error, signaled_system_error, 2'b00,
                                     signaled_target_abort, 2'b01, 5'b00000, irq, 3'b000,
                                     5'b00000, interrupt_disable, 1'b0, serr_enable, 1'b0,
                                     parity_response, 4'b0000, mem_enable, io_enable};
            CONFIG_CLASS: expected_config = CLASS_WORD;
            CONFIG_BAR0: expected_config = {16'h0000, bar0 & IO_WRITABLE} | 32'h1;
            CONFIG_BAR1: expected_config = bar1 & MEM_WRITABLE;
            CONFIG_BAR2: expected_config = bar2 & ALIAS_WRITABLE;
            CONFIG_SUBSYSTEM: expected_config = SUBSYSTEM_WORD;
            CONFIG_INTERRUPT: expected_config = {16'h0000, 8'h01, interrupt_line};
            default: expected_config = 32'h0;
        endcase
    end
    // Status bits set during this very transaction may or may not show yet;
    // Interrupt Status follows irq, which may change at any clock.
    reg p_irq = 0, pp_irq = 0, p_judged = 0;
    always @(posedge clock) begin
        p_irq <= irq;
        pp_irq <= p_irq;
        p_judged <= judged;
    end
    reg irq_moved = 0;       // irq changed since the address edge
    always @(posedge clock) irq_moved <= !address_edge && (irq_moved || irq != p_irq);
    wire [31:0] unsettled = (status_event ? 32'hC8000000 : 32'h0)
                            | ((irq_moved || irq != p_irq || p_irq != pp_irq) ? 32'h00080000 : 32'h0);

    always @(posedge clock) if (reset_n) begin
        // 6.1, 6.2: every configuration read returns the header the model holds
        // (read-only bits never change, read/write bits read back what was
        // written, write-one-to-clear bits clear, a BAR reads back its size mask)
        if (our_transfer && txn_config && !txn_write) begin
            config_read_as_written: assert((ad & ~unsettled) == (expected_config & ~unsettled));
        end
        // INTA# (2.2.6, 6.2.2 Interrupt Disable): open drain, asserted while irq
        // and not Interrupt Disable (checked once both have settled)
        if (irq_settled && p_interrupt_disable == interrupt_disable && pp_interrupt_disable == interrupt_disable) begin
            inta_follows_irq: assert((t_inta_oe && !t_inta_n) == (irq && !interrupt_disable));
        end
        if (t_inta_oe) begin inta_open_drain: assert(!t_inta_n); end
    end
    reg p_interrupt_disable = 0, pp_interrupt_disable = 0;
    always @(posedge clock) begin
        p_interrupt_disable <= interrupt_disable;
        pp_interrupt_disable <= p_interrupt_disable;
    end
    wire irq_settled = p_irq == irq && pp_irq == irq && p_judged;

    // ------------------------------------------------------------ target abort causes
    // 3.2.2: an I/O access enabling a byte below the one AD[1:0] addresses;
    // 3.7.3: an address parity error when Parity Error Response is set.
    reg [1:0] io_byte = 0;
    reg abort_due = 0;
    always @(posedge clock) begin
        if (address_edge) io_byte <= ad[1:0];
        if (!reset_n || address_edge)
            abort_due <= 0;
        else if (data_edge && clk_now == 1 && txn_hit) begin
            if (txn_io && ((io_byte == 2'd1 && !m_cbe_n[0]) || (io_byte == 2'd2 && m_cbe_n[1:0] != 2'b11)
                           || (io_byte == 2'd3 && m_cbe_n[2:0] != 3'b111)))
                abort_due <= 1;
            if (parity_wrong_now && parity_response)
                abort_due <= 1;
        end
    end
    always @(posedge clock) if (reset_n) begin
        if (target_abort) begin target_abort_only_when_due: assert(abort_due); end
        if (data_edge && txn_hit && clk_now >= 3 && abort_due) begin
            target_abort_when_due: assert(!(!t_trdy_n && t_trdy_oe));
        end
        if (last_completion && txn_hit && abort_due) begin
            target_abort_ends_when_due: assert(target_abort);
        end
    end

`include "pci_target_local.vh"

    // ------------------------------------------------------------ BAR2
    // docs/pci.md: one data phase per BAR2 transaction (disconnect with data)
    always @(posedge clock) if (reset_n) begin
        if (our_transfer && txn_alias) begin t_alias_one_phase: assert(txn_transfers == 0); end
        cover_alias_read: cover(our_transfer && txn_alias && !txn_write);
        // a burst's first data phase with STOP#: disconnect with data
        cover_alias_write_burst_disconnected: cover(our_transfer && txn_alias && txn_write && !m_frame_n && !stop_n);
    end

    // ------------------------------------------------------------ I/O never waits behind the FIFO
    // When the registers answer every request (ready within two clocks, never
    // retry), an I/O or BAR2 access is not retried: it completes with data.
    reg regs_slow = 0, io_waited = 0;
    always @(posedge clock) begin
        if (!reset_n || address_edge) begin
            regs_slow <= 0;
            io_waited <= 0;
        end else begin
            io_waited <= (l_we || l_re) && !l_space && !l_ready;
            if ((l_we || l_re) && !l_space && (l_retry || (!l_ready && io_waited)))
                regs_slow <= 1;
        end
    end
    always @(posedge clock) if (reset_n) begin
        if (data_edge && txn_hit && txn_regs && !regs_slow && txn_transfers == 0 && !abort_due) begin
            io_not_retried_when_registers_answer: assert(!(t_stop_oe && !t_stop_n && (t_trdy_n || !t_trdy_oe)));
        end
    end
`ifdef PCI_SLAVE_INVARIANTS
`include "pci_slave_invariants.vh"
`endif
endmodule
