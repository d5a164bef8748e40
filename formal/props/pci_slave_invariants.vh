// Helper invariants of rtl/pci_slave.py that let k-induction close; included
// into pci_target_harness when PCI_SLAVE_INVARIANTS is defined.
//
// The bus rules (pci_rules.sv) only see the pins.  Induction starts from any
// state whose last k steps keep every assertion; without these it may start
// in a state the target never reaches (say Read_Hold with TRDY# asserted, or
// Command register bits other than the ones the bus wrote) and report a
// failure that no run from reset can show.  These tie the target's own
// registers (made ports by yosys `expose`, so the generated file is read
// unchanged) to the transaction the bus rules track and to the configuration
// model.  They are asserted, so they are proved as well; they name the
// registers of today's pci_slave and change with it.  State codes are the
// enum's: S_IDLE 0, S_CON_HOLD 1, S_IO_HOLD 2, S_MEM_HOLD 3, S_READ_HOLD 4,
// S_CONFIGURING 5, S_RWING 6, S_BACKOFF 7, S_ENDING 8.
    wire [3:0] i_state, i_wait_count;
    wire i_trdy_q, i_stop_q, i_devsel_q, i_initial_wait_over, i_subsequent_wait_over;
    wire i_first_phase, i_is_read, i_is_config, i_space_mem;
    wire i_io_enable, i_mem_enable, i_parity_response, i_serr_enable, i_interrupt_disable;
    wire i_config_write_q;
    wire [15:0] i_bar0;
    wire [31:0] i_bar1, i_bar2;
    wire [7:0] i_interrupt_line;
    wire [31:0] i_h_data, i_spare_data, i_ad_q;
    wire [3:0] i_h_be, i_s_be, i_cbe_q;
    wire [LOCAL_WIDTH-3:0] i_req_addr;
    wire [31:0] i_ad_out_q;
    wire [LOCAL_WIDTH-3:0] i_read_start = txn_regs ? io_dword : txn_address[MEM_BITS-1:2];
    wire [LOCAL_WIDTH-3:0] i_phase_addr;
    wire i_at_last, i_before_last;
    wire i_single, i_frame_q;
    wire i_signaled_target_abort, i_signaled_system_error, i_detected_parity_error, i_parity_error_q;
    wire i_h_valid, i_s_valid, i_wq_valid, i_b_valid, i_fetching, i_first_pending, i_req_addr_stale;
    localparam [LOCAL_WIDTH-3:0] MEM_LAST = (1 << (MEM_BITS - 2)) - 1;
    wire [LOCAL_WIDTH-3:0] i_config_dword = txn_address[7:2];

    wire i_hold = i_state >= 4'd1 && i_state <= 4'd4;
    wire i_in_phase = i_state == 4'd5 || i_state == 4'd6;
    wire i_claimed = i_state != 4'd0 && i_state != 4'd8;

    always @(posedge clock) if (reset_n) begin
        inv_state_code: assert(i_state <= 4'd8);
        inv_drive_follows_state: assert(t_devsel_oe == (i_state != 4'd0));
        inv_ad_drive_follows_state: assert(t_ad_oe == (i_claimed && i_is_read));
        if (i_state == 4'd0) begin inv_idle_quiet: assert(i_trdy_q && i_stop_q && i_devsel_q); end
        if (i_hold) begin inv_hold_waits: assert(i_trdy_q && i_stop_q && !i_devsel_q); end
        if (i_in_phase) begin inv_phase_claimed: assert(!i_devsel_q); end
        if (i_state == 4'd7) begin inv_backoff_stops: assert(!i_stop_q && i_trdy_q); end
        if (i_state == 4'd8) begin inv_ending_quiet: assert(i_trdy_q && i_stop_q && i_devsel_q && !data_edge); end
        if (i_claimed) begin
            inv_claimed_in_transaction: assert(data_edge && txn_hit && clk_now >= 2);
            inv_direction: assert(i_is_read == !txn_write);
            inv_kind: assert(i_is_config == txn_config && i_space_mem == (!txn_config && !txn_regs));
            inv_first_phase: assert(i_first_phase == (txn_transfers == 0));
            inv_claimed_command: assert(txn_config || txn_io || memory_command(txn_command));
            inv_burst_inside_bar: assert(txn_config || txn_regs ? txn_transfers <= 1
                                         : {1'b0, txn_address[MEM_BITS-1:2]} + txn_transfers <= MEM_LAST + 1);
            inv_phase_address: assert(i_phase_addr == (txn_config ? i_config_dword : phase_dword));
        end
        if (data_edge) begin inv_bus_claim: assert(target_claimed == (i_claimed && clk_now >= 3)); end
        if (i_state == 4'd0 && data_edge && txn_hit) begin inv_claim_pending: assert(clk_now == 1); end
        if (i_state == 4'd1 || i_state == 4'd5) begin inv_config_states: assert(i_is_config); end
        inv_initial_limit: assert(i_initial_wait_over == (i_wait_count == 4'd11));
        inv_subsequent_limit: assert(i_subsequent_wait_over == (i_wait_count == 4'd5));
        inv_wait_bound: assert(i_wait_count <= 4'd11);
        if (i_claimed && i_first_phase && i_trdy_q && i_stop_q) begin
            inv_first_wait: assert(i_wait_count == clk_now - 2);
        end
        // the configuration model holds what the target holds, but in the
        // clock after a configuration write, which the target takes one later
        if (!i_config_write_q) begin
            inv_command_model: assert(i_io_enable == io_enable && i_mem_enable == mem_enable
                                      && i_parity_response == parity_response
                                      && i_serr_enable == serr_enable
                                      && i_interrupt_disable == interrupt_disable);
            inv_bar_model: assert((i_bar0 & IO_WRITABLE) == (bar0 & IO_WRITABLE)
                                  && (i_bar1 & MEM_WRITABLE) == (bar1 & MEM_WRITABLE)
                                  && (i_bar2 & ALIAS_WRITABLE) == (bar2 & ALIAS_WRITABLE)
                                  && i_interrupt_line == interrupt_line);
        end
        // a single-phase access (or the last dword of BAR1) asserts TRDY# without
        // STOP# only once FRAME# has gone
        if (i_claimed && (i_single || i_at_last) && !i_trdy_q && i_stop_q) begin
            inv_single_phase_last: assert(i_frame_q && m_frame_n);
        end
        if (i_claimed) begin inv_single_kind: assert(i_single == (txn_config || txn_regs || txn_address[1:0] != 2'b00)); end
        // read-ahead and the posting queue
        if (i_fetching) begin inv_fetch_in_read: assert(i_is_read && !i_is_config); end
        if (i_fetching && !i_space_mem) begin inv_io_fetches_once: assert(i_first_pending); end
        if (i_state == 4'd6) begin inv_burst_after_first: assert(!i_first_pending && !i_req_addr_stale); end
        if (i_b_valid) begin inv_skid_in_read: assert(i_is_read && (i_state == 4'd3 || i_state == 4'd4 || i_state == 4'd6)); end
        if (i_s_valid) begin inv_second_after_head: assert(i_h_valid); end
        if (i_wq_valid) begin inv_posted_phase: assert(write_phase_before); end
        // the write shadow of the harness against the posting queue: the head
        // (h), the second entry (s), the input register (ad_q); a first-phase
        // write is taken by the back end one clock before its data phase
        inv_pending_posted: assert(pending == {2'b00, i_h_valid} + {2'b00, i_s_valid} + {2'b00, i_wq_valid}
                                              - {2'b00, i_first_write_ahead});
        if (i_first_write_ahead) begin
            inv_ahead_word: assert(ahead_word == {i_space_mem, i_req_addr - 1'b1, 2'b00, ~i_cbe_q, i_ad_q});
        end
        if ((i_h_valid || i_wq_valid || i_first_write_ahead) && !i_req_addr_stale) begin
            inv_posted_addresses: assert(i_req_addr + i_h_valid + i_s_valid + i_wq_valid
                                         == i_phase_addr + i_first_write_ahead);
        end
        if (tracking) begin
            inv_tracked_in_queue: assert(tracked_position < pending);
            inv_tracked_word: assert(tracked_word == i_queue_word);
        end
        // read-ahead against the read shadow: the AD register holds the current
        // phase's dword while TRDY# is asserted, B the next one
        if (i_claimed && i_is_read && i_is_config) begin inv_config_reads_local_none: assert(local_reads == 0); end
        if (i_claimed && i_is_read && !i_is_config && !i_req_addr_stale && !i_first_pending) begin
            inv_read_address: assert(i_req_addr == i_read_start + local_reads[LOCAL_WIDTH-3:0]);
        end
        if (i_claimed && i_is_read && !i_is_config && i_first_pending) begin inv_read_none_yet: assert(local_reads == 0); end
        if (i_state == 4'd6 && i_is_read && !i_is_config) begin
            inv_read_fetched: assert(local_reads == txn_transfers + !i_trdy_q + i_b_valid);
            if (i_b_valid) begin inv_skid_behind_ad: assert(!i_trdy_q); end
            if (!i_trdy_q && watch_space == !txn_regs && watch_dword == phase_dword) begin
                inv_ad_holds_watched: assert(watched_valid && i_ad_out_q == watched_data);
            end
            if (i_b_valid && watch_space == !txn_regs && watch_dword == phase_dword + 1'b1) begin
                inv_skid_holds_watched: assert(watched_valid && i_spare_data == watched_data);
            end
        end
        if (watched_valid && data_edge) begin
            inv_watched_fetched: assert(txn_hit && !txn_write && !txn_config && watch_space == !txn_regs
                                        && {6'b0, watch_dword - i_read_start} < local_reads);
        end
        inv_last_flags: assert(i_at_last == (i_phase_addr == MEM_LAST)
                               && i_before_last == (i_phase_addr == MEM_LAST - 1));
        // status bits: the target sets Signaled Target Abort one clock before
        // the bus shows it, Detected Parity Error one clock after the bus did
        if (!i_config_write_q) begin
            inv_status_model: assert((i_signaled_system_error == signaled_system_error)
                                     && (i_signaled_target_abort == signaled_target_abort
                                         || (i_signaled_target_abort && target_abort))
                                     && (i_detected_parity_error == detected_parity_error
                                         || (detected_parity_error && i_parity_error_q)));
        end
        inv_config_write_follows_phase: assert(i_config_write_q == (write_phase_before && config_phase_before));
    end
    wire i_first_write_ahead = i_state == 4'd6 && i_first_phase && !i_is_read && !i_is_config;
    // the queue entry the tracked position names, as the back end would see it
    reg [LOCAL_WIDTH+36:0] i_queue_word;
    always @(*) begin
        case ({i_h_valid, i_s_valid, tracked_position[1:0]})
            4'b1000, 4'b1100: i_queue_word = {1'b1, i_req_addr, 2'b00, i_h_be, i_h_data};
            4'b1101: i_queue_word = {1'b1, i_req_addr + 1'b1, 2'b00, i_s_be, i_spare_data};
            4'b1001: i_queue_word = {1'b1, i_req_addr + 1'b1, 2'b00, ~i_cbe_q, i_ad_q};
            4'b1110: i_queue_word = {1'b1, i_req_addr + 2'd2, 2'b00, ~i_cbe_q, i_ad_q};
            default: i_queue_word = {1'b1, i_req_addr, 2'b00, ~i_cbe_q, i_ad_q};
        endcase
    end
    reg config_phase_before = 0;
    always @(posedge clock) config_phase_before <= txn_config;
