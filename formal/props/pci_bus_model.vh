// The configuration a target decodes with and the transaction on the bus,
// shared by pci_target_harness.sv (where the target's decode and header are
// proved against this model) and card_harness.sv (where the whole card is
// judged through it); included after the unit, with pci_table.vh
// (generated from models/pci.py) and pci_bus_lines.vh before it.
//   * the model of the header's registers (6.2.2 Command, 6.2.3 Status, 6.2.5
//     BARs, Interrupt Line), written by the configuration writes seen on the
//     bus, and the status bits the bus shows being earned;
//   * the decode: configuration (IDSEL, AD[1:0] = 00, function 0), I/O
//     inside BAR0, memory inside BAR1, BAR2 (BAR0's registers in memory
//     space, BAR1 first where a host let them overlap: docs/pci.md);
//   * pci_rules (CHECK_TARGET = 1) tracking the transaction, and its kind
//     (txn_config, txn_io, txn_alias, txn_regs, txn_write) and position
//     (config_dword).
    // ------------------------------------------------------------ configuration model
    localparam [15:0] IO_WRITABLE = 16'hFFFF << IO_BITS;
    localparam [31:0] MEM_WRITABLE = 32'hFFFFFFFF << MEM_BITS;
    // BAR2: BAR0's size in memory space, 16 bytes at least (6.2.5.1), or
    // REG_BITS where that is larger (the card's per-axis register blocks:
    // rtl/pci/pci_slave_build.py alias_bar_bits)
    localparam ALIAS_BITS = REG_BITS > IO_BITS && REG_BITS > 4 ? REG_BITS : (IO_BITS > 4 ? IO_BITS : 4);
    localparam [31:0] ALIAS_WRITABLE = 32'hFFFFFFFF << ALIAS_BITS;
    reg io_enable = 0, mem_enable = 0, parity_response = 0, serr_enable = 0, interrupt_disable = 0;
    reg [15:0] bar0 = 0;
    reg [31:0] bar1 = 0, bar2 = 0;
    reg [7:0] interrupt_line = 0;
    reg signaled_target_abort = 0, signaled_system_error = 0, detected_parity_error = 0;
    reg status_event = 0;    // a status bit was set in this transaction

    wire [3:0] command = m_cbe_n;
    wire config_hit = m_idsel && ad[1:0] == 2'b00 && ad[10:8] == 3'b000 && config_command(command);
    wire io_hit = io_enable && io_command(command) && ad[31:16] == 16'h0
                  && (ad[15:0] & IO_WRITABLE) == (bar0 & IO_WRITABLE);
    wire mem_hit = mem_enable && memory_command(command) && (ad & MEM_WRITABLE) == (bar1 & MEM_WRITABLE);
    // docs/pci.md: BAR1 answers an address a host let BAR1 and BAR2 share
    wire alias_hit = mem_enable && memory_command(command) && !mem_hit
                     && (ad & ALIAS_WRITABLE) == (bar2 & ALIAS_WRITABLE);
    wire decoded = config_hit || io_hit || mem_hit || alias_hit;

    // ------------------------------------------------------------ the transaction
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

    wire txn_config = config_command(txn_command);
    wire txn_io = io_command(txn_command);
    // a BAR2 transaction (taken at its address edge): the registers, as txn_io
    reg txn_alias = 0;
    always @(posedge clock) if (address_edge) txn_alias <= alias_hit;
    wire txn_regs = txn_io || txn_alias;    // the function registers, through BAR0 or BAR2
    wire txn_write = txn_command[0];
    wire our_transfer = transfer && txn_hit;
    wire [5:0] config_dword = txn_address[7:2] + txn_transfers[5:0];

    // PAR at this edge against the AD and C/BE# of the edge before
    reg write_phase_before = 0;   // a write data phase to this target completed at the last edge
    always @(posedge clock) write_phase_before <= reset_n && our_transfer && txn_write;
    wire parity_wrong_now = par_wrong;

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
                    CONFIG_COMMAND: begin
                        if (!m_cbe_n[0]) begin
                            io_enable <= ad[COMMAND_IO]; mem_enable <= ad[COMMAND_MEMORY];
                            parity_response <= ad[COMMAND_PARITY_RESPONSE];
                        end
                        if (!m_cbe_n[1]) begin
                            serr_enable <= ad[COMMAND_SERR_ENABLE];
                            interrupt_disable <= ad[COMMAND_INTERRUPT_DISABLE];
                        end
                        // Status: write one to clear (6.2.3)
                        if (!m_cbe_n[3]) begin
                            if (ad[27]) signaled_target_abort <= 0;
                            if (ad[30]) signaled_system_error <= 0;
                            if (ad[31]) detected_parity_error <= 0;
                        end
                    end
                    CONFIG_BAR0: begin
                        if (!m_cbe_n[0]) bar0[7:0] <= ad[7:0];
                        if (!m_cbe_n[1]) bar0[15:8] <= ad[15:8];
                    end
                    CONFIG_BAR1: begin
                        if (!m_cbe_n[0]) bar1[7:0] <= ad[7:0];
                        if (!m_cbe_n[1]) bar1[15:8] <= ad[15:8];
                        if (!m_cbe_n[2]) bar1[23:16] <= ad[23:16];
                        if (!m_cbe_n[3]) bar1[31:24] <= ad[31:24];
                    end
                    CONFIG_BAR2: begin
                        if (!m_cbe_n[0]) bar2[7:0] <= ad[7:0];
                        if (!m_cbe_n[1]) bar2[15:8] <= ad[15:8];
                        if (!m_cbe_n[2]) bar2[23:16] <= ad[23:16];
                        if (!m_cbe_n[3]) bar2[31:24] <= ad[31:24];
                    end
                    CONFIG_INTERRUPT: if (!m_cbe_n[0]) interrupt_line <= ad[7:0];
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
