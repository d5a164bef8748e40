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
`default_nettype none

module pci_target_harness #(
    parameter IO_BITS = 6,
    parameter MEM_BITS = 12,
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
    wire [31:0] t_ad;
    wire t_ad_oe, t_par, t_par_oe, t_trdy_n, t_trdy_oe, t_devsel_n, t_devsel_oe;
    wire t_stop_n, t_stop_oe, t_perr_n, t_perr_oe, t_serr_n, t_serr_oe, t_inta_n, t_inta_oe;
    wire l_space, l_we, l_re, l_write;
    wire [LOCAL_WIDTH-1:0] l_addr;
    wire [3:0] l_be;
    wire [31:0] l_wdata;

    wire [31:0] ad = t_ad_oe ? t_ad : m_ad;
    wire par = t_par_oe ? t_par : m_par;
    wire trdy_n = (t_trdy_oe ? t_trdy_n : 1'b1) & o_trdy_n;
    wire devsel_n = (t_devsel_oe ? t_devsel_n : 1'b1) & o_devsel_n;
    wire stop_n = (t_stop_oe ? t_stop_n : 1'b1) & o_stop_n;
    wire perr_n = t_perr_oe ? t_perr_n : 1'b1;
    wire serr_n = t_serr_oe ? t_serr_n : 1'b1;

    pci_slave dut (
        .clock(clock), .reset(reset_n), .irq(irq),
        .pci_ad_in(ad), .pci_ad_out(t_ad), .pci_ad_oe(t_ad_oe), .pci_cbe_in(m_cbe_n),
        .pci_par_in(par), .pci_par_out(t_par), .pci_par_oe(t_par_oe),
        .pci_frame_in(m_frame_n), .pci_irdy_in(m_irdy_n), .pci_idsel_in(m_idsel),
        .pci_trdy_out(t_trdy_n), .pci_trdy_oe(t_trdy_oe), .pci_devsel_out(t_devsel_n),
        .pci_devsel_oe(t_devsel_oe), .pci_stop_out(t_stop_n), .pci_stop_oe(t_stop_oe),
        .pci_perr_out(t_perr_n), .pci_perr_oe(t_perr_oe), .pci_serr_out(t_serr_n),
        .pci_serr_oe(t_serr_oe), .pci_inta_out(t_inta_n), .pci_inta_oe(t_inta_oe),
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

    // ------------------------------------------------------------ reset
    reg started = 0;
    always @(posedge clock) started <= 1;
    always @(*) if (!started) assume(!reset_n);

    // ------------------------------------------------------------ configuration model
    localparam [15:0] IO_WRITABLE = 16'hFFFF << IO_BITS;
    localparam [31:0] MEM_WRITABLE = 32'hFFFFFFFF << MEM_BITS;
    // BAR2: BAR0's size in memory space, 16 bytes at least (6.2.5.1)
    localparam ALIAS_BITS = IO_BITS > 4 ? IO_BITS : 4;
    localparam [31:0] ALIAS_WRITABLE = 32'hFFFFFFFF << ALIAS_BITS;
    reg io_enable = 0, mem_enable = 0, parity_response = 0, serr_enable = 0, interrupt_disable = 0;
    reg [15:0] bar0 = 0;
    reg [31:0] bar1 = 0, bar2 = 0;
    reg [7:0] interrupt_line = 0;
    reg signaled_target_abort = 0, signaled_system_error = 0, detected_parity_error = 0;
    reg status_event = 0;    // a status bit was set in this transaction

    wire [3:0] command = m_cbe_n;
    wire cmd_config = command == 4'hA || command == 4'hB;
    wire cmd_io = command == 4'h2 || command == 4'h3;
    wire cmd_mem = command == 4'h6 || command == 4'h7 || command == 4'hC || command == 4'hE
                   || command == 4'hF;
    wire config_hit = m_idsel && ad[1:0] == 2'b00 && ad[10:8] == 3'b000 && cmd_config;
    wire io_hit = io_enable && cmd_io && ad[31:16] == 16'h0
                  && (ad[15:0] & IO_WRITABLE) == (bar0 & IO_WRITABLE);
    wire mem_hit = mem_enable && cmd_mem && (ad & MEM_WRITABLE) == (bar1 & MEM_WRITABLE);
    // docs/pci.md: BAR1 answers an address a host let BAR1 and BAR2 share
    wire alias_hit = mem_enable && cmd_mem && !mem_hit && (ad & ALIAS_WRITABLE) == (bar2 & ALIAS_WRITABLE);
    wire decoded = config_hit || io_hit || mem_hit || alias_hit;

    wire address_edge, data_edge, completion, transfer, last_completion, txn_hit;
    wire addr_parity_error, target_abort, target_claimed, par_wrong;
    wire [3:0] since_completion;
    wire [3:0] txn_command;
    wire [31:0] txn_address;
    wire [15:0] txn_transfers;
    wire [5:0] clk_now;

    pci_rules #(.CHECK_TARGET(1)) bus (
        .clock(clock), .reset_n(reset_n),
        .ad(ad), .cbe_n(m_cbe_n), .par(par), .frame_n(m_frame_n), .irdy_n(m_irdy_n),
        .trdy_n(trdy_n), .devsel_n(devsel_n), .stop_n(stop_n), .perr_n(perr_n), .serr_n(serr_n),
        .t_ad(t_ad), .t_ad_oe(t_ad_oe), .t_par(t_par), .t_par_oe(t_par_oe),
        .t_trdy_n(t_trdy_n), .t_trdy_oe(t_trdy_oe), .t_devsel_n(t_devsel_n),
        .t_devsel_oe(t_devsel_oe), .t_stop_n(t_stop_n), .t_stop_oe(t_stop_oe),
        .t_perr_n(t_perr_n), .t_perr_oe(t_perr_oe), .t_serr_n(t_serr_n), .t_serr_oe(t_serr_oe),
        .m_ad(m_ad), .m_cbe_n(m_cbe_n), .m_frame_n(m_frame_n), .m_irdy_n(m_irdy_n),
        .decoded(decoded), .parity_response(parity_response), .serr_enable(serr_enable),
        .address_edge(address_edge), .data_edge(data_edge), .completion(completion),
        .transfer(transfer), .last_completion(last_completion), .txn_hit(txn_hit),
        .txn_command(txn_command), .txn_address(txn_address), .txn_transfers(txn_transfers),
        .clk_now(clk_now), .addr_parity_error(addr_parity_error), .target_abort(target_abort),
        .target_claimed(target_claimed), .since_completion(since_completion),
        .par_wrong(par_wrong));

    local_bus_rules #(.CHECK_REQUESTER(1), .ADDR_WIDTH(LOCAL_WIDTH)) back_end (
        .clock(clock), .reset_n(reset_n), .space(l_space), .addr(l_addr), .be(l_be),
        .wdata(l_wdata), .we(l_we), .re(l_re), .write(l_write), .ready(l_ready), .retry(l_retry),
        .room(l_room), .promised(promised));
    wire [2:0] promised;

    // other targets answer only transactions that are not this target's
    always @(*) if (!data_edge || txn_hit) assume(o_trdy_n && o_devsel_n && o_stop_n);

    wire txn_config = txn_command[3:1] == 3'b101;
    wire txn_io = txn_command[3:1] == 3'b001;
    // a BAR2 transaction (taken at its address edge): the registers, as txn_io
    reg txn_alias = 0;
    always @(posedge clock) if (address_edge) txn_alias <= alias_hit;
    wire txn_regs = txn_io || txn_alias;
    wire txn_write = txn_command[0];
    wire our_transfer = transfer && txn_hit;
    wire [5:0] config_dword = txn_address[7:2] + txn_transfers[5:0];
    wire [3:0] be_n = m_cbe_n;

    // the model takes each configuration write at its data phase (6.2)
    always @(posedge clock) begin
        if (!reset_n) begin
            io_enable <= 0; mem_enable <= 0; parity_response <= 0; serr_enable <= 0;
            interrupt_disable <= 0; bar0 <= 0; bar1 <= 0; bar2 <= 0; interrupt_line <= 0;
            signaled_target_abort <= 0; signaled_system_error <= 0; detected_parity_error <= 0;
            status_event <= 0;
        end else begin
            if (address_edge)
                status_event <= 0;
            if (our_transfer && txn_config && txn_write) begin
                case (config_dword)
                    6'd1: begin
                        if (!be_n[0]) begin
                            io_enable <= ad[0]; mem_enable <= ad[1]; parity_response <= ad[6];
                        end
                        if (!be_n[1]) begin
                            serr_enable <= ad[8]; interrupt_disable <= ad[10];
                        end
                        if (!be_n[3]) begin
                            if (ad[27]) signaled_target_abort <= 0;
                            if (ad[30]) signaled_system_error <= 0;
                            if (ad[31]) detected_parity_error <= 0;
                        end
                    end
                    6'd4: begin
                        if (!be_n[0]) bar0[7:0] <= ad[7:0];
                        if (!be_n[1]) bar0[15:8] <= ad[15:8];
                    end
                    6'd5: begin
                        if (!be_n[0]) bar1[7:0] <= ad[7:0];
                        if (!be_n[1]) bar1[15:8] <= ad[15:8];
                        if (!be_n[2]) bar1[23:16] <= ad[23:16];
                        if (!be_n[3]) bar1[31:24] <= ad[31:24];
                    end
                    6'd6: begin
                        if (!be_n[0]) bar2[7:0] <= ad[7:0];
                        if (!be_n[1]) bar2[15:8] <= ad[15:8];
                        if (!be_n[2]) bar2[23:16] <= ad[23:16];
                        if (!be_n[3]) bar2[31:24] <= ad[31:24];
                    end
                    6'd15: if (!be_n[0]) interrupt_line <= ad[7:0];
                    default: ;
                endcase
            end
            // status bits the bus shows being earned (6.2.3)
            if (target_abort) begin
                signaled_target_abort <= 1; status_event <= 1;
            end
            if (!serr_n) begin
                signaled_system_error <= 1; status_event <= 1;
            end
            if (data_edge && clk_now == 1 && parity_wrong_now) begin
                detected_parity_error <= 1; status_event <= 1;
            end
            if (write_phase_before && parity_wrong_now) begin
                detected_parity_error <= 1; status_event <= 1;
            end
        end
    end

    // PAR at this edge against the AD and C/BE# of the edge before
    reg write_phase_before = 0;   // a write data phase to this target completed at the last edge
    always @(posedge clock) begin
        write_phase_before <= reset_n && our_transfer && txn_write;
    end
    wire parity_wrong_now = par_wrong;

    // the header as the model says a read returns it
    reg [31:0] expected_config;
    always @(*) begin
        case (config_dword)
            6'd0: expected_config = ID_WORD;
            6'd1: expected_config = {detected_parity_error, signaled_system_error, 2'b00,
                                     signaled_target_abort, 2'b01, 5'b00000, irq, 3'b000,
                                     5'b00000, interrupt_disable, 1'b0, serr_enable, 1'b0,
                                     parity_response, 4'b0000, mem_enable, io_enable};
            6'd2: expected_config = CLASS_WORD;
            6'd4: expected_config = {16'h0000, bar0 & IO_WRITABLE} | 32'h1;
            6'd5: expected_config = bar1 & MEM_WRITABLE;
            6'd6: expected_config = bar2 & ALIAS_WRITABLE;
            6'd11: expected_config = SUBSYSTEM_WORD;
            6'd15: expected_config = {16'h0000, 8'h01, interrupt_line};
            default: expected_config = 32'h0;
        endcase
    end
    // Status bits set during this very transaction may or may not show yet;
    // Interrupt Status follows irq, which may change at any clock.
    reg p_irq = 0, pp_irq = 0, p_valid = 0, pp_valid = 0;
    always @(posedge clock) begin
        p_irq <= irq;
        pp_irq <= p_irq;
        p_valid <= reset_n;
        pp_valid <= p_valid && reset_n;
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
    wire irq_settled = p_irq == irq && pp_irq == irq && pp_valid;

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
