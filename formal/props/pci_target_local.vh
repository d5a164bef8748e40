// The local side of pci_target_harness.sv (included there, in its scope):
// each write data phase reaches the back end once, in order, with its
// offset, byte enables and data (a chosen-one shadow), nothing
// acknowledged waits for the back end, and read data reach AD unchanged in
// the phase that asked for them.  It reads the harness's bus tracking
// (pci_rules outputs), its models and the back end's lines.

    // ------------------------------------------------------------ local side: writes
    // Each write data phase of an I/O or memory access reaches the back end
    // once, in order, with its offset, byte enables and data.  The first data
    // phase of a write goes to the back end before TRDY# (at most one ahead);
    // later ones are posted (at most POSTED_MAX acknowledged and not yet taken).
    // I/O and BAR2 (txn_regs) reach the registers, space 0, at BAR0's offset
    wire [LOCAL_WIDTH-3:0] io_dword = txn_address[IO_BITS-1:2];
    wire [LOCAL_WIDTH-3:0] mem_dword = txn_address[MEM_BITS-1:2] + txn_transfers;
    wire [LOCAL_WIDTH-3:0] phase_dword = txn_regs ? io_dword : mem_dword;
    wire bus_write = our_transfer && txn_write && !txn_config;
    wire local_write = l_we && l_ready;
    wire [LOCAL_WIDTH+36:0] bus_word = {!txn_regs, phase_dword, 2'b00, ~m_cbe_n, ad};
    wire [LOCAL_WIDTH+36:0] local_word = {l_space, l_addr, l_be, l_wdata};

    reg signed [3:0] pending = 0;   // bus write phases not taken yet (-1: one taken ahead)
    reg [LOCAL_WIDTH+36:0] ahead_word = 0;
    reg tracking = 0;
    reg [2:0] tracked_position = 0;
    reg [LOCAL_WIDTH+36:0] tracked_word = 0;
    reg [4:0] oldest_wait = 0;      // clocks the oldest acknowledged dword has waited

    reg signed [3:0] pending_after_take;
    reg tracking_next, match_now, start_tracking;
    reg [2:0] position_next;
    reg [LOCAL_WIDTH+36:0] match_expected, match_seen;
    always @(*) begin
        pending_after_take = pending;
        tracking_next = tracking;
        position_next = tracked_position;
        match_now = 0;
        start_tracking = 0;
        match_expected = tracked_word;
        match_seen = local_word;
        if (local_write) begin
            pending_after_take = pending - 1;
            if (pending > 0 && tracking) begin
                if (tracked_position == 0) begin
                    match_now = 1;
                    tracking_next = 0;
                end else
                    position_next = tracked_position - 1;
            end
        end
        if (bus_write && choose_write && !tracking_next && !match_now) begin
            if (pending_after_take < 0) begin
                match_now = 1;
                match_expected = bus_word;
                match_seen = (local_write && pending == 0) ? local_word : ahead_word;
            end else begin
                tracking_next = 1;
                start_tracking = 1;
                position_next = pending_after_take[2:0];
            end
        end
    end
    always @(posedge clock) begin
        if (!reset_n) begin
            pending <= 0;
            tracking <= 0;
            oldest_wait <= 0;
        end else begin
            pending <= pending_after_take + bus_write;
            tracking <= tracking_next;
            tracked_position <= position_next;
            if (start_tracking)
                tracked_word <= bus_word;
            if (local_write && pending <= 0)
                ahead_word <= local_word;
            if (pending_after_take + bus_write <= 0 || local_write)
                oldest_wait <= 0;
            else if (oldest_wait != 5'h1f)
                oldest_wait <= oldest_wait + 1;
        end
    end
    always @(posedge clock) if (reset_n) begin
        if (match_now) begin write_reaches_back_end_as_on_bus: assert(match_seen == match_expected); end
        write_taken_at_most_one_ahead: assert(pending >= -1);
        write_posted_at_most: assert(pending <= POSTED_MAX);
        if (!data_edge) begin write_not_taken_for_retried_phase: assert(pending >= 0); end
        // nothing acknowledged is dropped: it reaches the back end in time
        acknowledged_write_drains: assert(oldest_wait < DRAIN_LIMIT);
`ifdef LOCAL_ROOM
        // the write credit: every dword acknowledged and not yet taken is
        // one the back end promised to take
        acknowledged_within_credit: assert(pending <= $signed({2'b00, promised}));
`endif
    end

    // ------------------------------------------------------------ local side: reads
    reg [31:0] watched_data = 0;
    reg watched_valid = 0;
    reg [15:0] local_reads = 0;      // back-end reads taken in this transaction
    wire local_read = l_re && l_ready;
    wire bus_read = our_transfer && !txn_write && !txn_config;
    wire [LOCAL_WIDTH-3:0] read_dword = txn_regs ? io_dword
                                        : txn_address[MEM_BITS-1:2] + local_reads;
    always @(posedge clock) begin
        if (!reset_n || address_edge) begin
            watched_valid <= 0;
            local_reads <= 0;
        end else begin
            if (local_read) begin
                local_reads <= local_reads + 1;
                if (l_space == watch_space && l_addr[LOCAL_WIDTH-1:2] == watch_dword) begin
                    watched_valid <= 1;
                    watched_data <= l_rdata;
                end
            end
        end
    end
    always @(posedge clock) if (reset_n) begin
        if (local_read) begin
            read_only_in_read_transaction: assert(data_edge && txn_hit && !txn_write && !txn_config);
            read_of_the_next_dword: assert(l_space == !txn_regs && l_addr == {read_dword, 2'b00});
            read_ahead_at_most_two: assert(local_reads <= txn_transfers + (txn_regs ? 0 : 1));
            // docs/pci.md: reads of BAR1 fetch whole dwords
            if (l_space) begin read_whole_dwords: assert(l_be == 4'hF); end
        end
        if (bus_read && !txn_regs == watch_space && phase_dword == watch_dword) begin
            read_data_reach_ad: assert(watched_valid && ad == watched_data);
        end
    end

