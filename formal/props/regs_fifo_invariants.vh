// Helper invariants of rtl/regs_fifo.py and rtl/sync_fifo.py that let
// k-induction close; included into regs_fifo_harness when
// REGS_FIFO_INVARIANTS is defined.  They tie the FIFO's own count and flags
// and the register write stage (made ports by yosys `expose`) to the models
// of the harness; they are asserted, so they are proved too, and they name
// today's registers.
    always @(posedge clock) if (reset_n) begin
        inv_fifo_count_model: assert(sync_fifo0_count == level);
        inv_fifo_flags: assert(sync_fifo0_is_empty == (sync_fifo0_count == 0)
                               && sync_fifo0_is_full == (sync_fifo0_count == DEPTH));
        inv_write_stage: assert(io_written == stage_write);
    end
