// Helper invariants of rtl/regs_fifo.py and rtl/regs/sync_fifo.py that let
// k-induction close; included into regs_fifo_harness when
// REGS_FIFO_INVARIANTS is defined.  They tie the FIFO's own count and flags
// and the register write and read stages (made ports by yosys `expose`) to the models
// of the harness; they are asserted, so they are proved too, and they name
// today's registers.
    always @(posedge clock) if (reset_n) begin
        inv_fifo_count_model: assert(sync_fifo0_count == level);
`ifdef LOCAL_ROOM
        // free places as a thermometer: bit i while more than i are free
        inv_fifo_flags: assert(sync_fifo0_is_empty == (sync_fifo0_count == 0)
                               && sync_fifo0_free[0] == (sync_fifo0_count < DEPTH)
                               && sync_fifo0_free[1] == (sync_fifo0_count < DEPTH - 1)
                               && sync_fifo0_free[2] == (sync_fifo0_count < DEPTH - 2)
                               && sync_fifo0_free_beyond == (sync_fifo0_count < DEPTH - 3));
        // the writes still promised have their places
        inv_promise_has_places: assert(promised <= DEPTH - sync_fifo0_count);
`else
        inv_fifo_flags: assert(sync_fifo0_is_empty == (sync_fifo0_count == 0)
                               && sync_fifo0_is_full == (sync_fifo0_count == DEPTH));
`endif
        inv_write_stage: assert(io_written == stage_write);
        inv_read_stage: assert(read_waited == read_asked);
    end
