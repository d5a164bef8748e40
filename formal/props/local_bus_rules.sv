// The card's back-end bus between the PCI target and the registers/FIFO
// (`LocalBus`, rtl/interfaces/; docs/pci.md "The local bus as the target
// uses it"), as immediate assertions for `read -formal`.
//
// CHECK_REQUESTER = 1: the requester's rules (the PCI target) are asserted,
// the responder's (the back end) assumed; 0: the reverse, for a back end
// under test behind a free requester.
//
// With LOCAL_ROOM defined (a LocalBus with the write credit `room`), the
// back end's promise is a responder rule too: while `room` is high, the
// next ROOM_PLACES writes to space 1 are answered ready, never retry; a
// promise is used up only by the writes taken.
`default_nettype none

module local_bus_rules #(
    parameter CHECK_REQUESTER = 1,
    parameter ADDR_WIDTH = 12,
    parameter ROOM_PLACES = 3      // writes a high `room` promises (LocalBus.ROOM_PLACES)
) (
    input wire clock,
    input wire reset_n,
    input wire space,
    input wire [ADDR_WIDTH-1:0] addr,
    input wire [3:0] be,
    input wire [31:0] wdata,
    input wire we,
    input wire re,
    input wire write,
    input wire ready,
    input wire retry,
    input wire room,
    output wire [2:0] promised      // writes still promised (with LOCAL_ROOM)
);
`define LB_REQ(label, cond) if (CHECK_REQUESTER) begin label: assert(cond); end else begin label: assume(cond); end
`define LB_RSP(label, cond) if (CHECK_REQUESTER) begin label: assume(cond); end else begin label: assert(cond); end

    reg p_valid = 0;
    reg p_waiting = 0;       // a request waited for an answer at the last edge
    reg p_we = 0, p_re = 0, p_space = 0;
    reg [ADDR_WIDTH-1:0] p_addr = 0;
    reg [3:0] p_be = 0;
    reg [31:0] p_wdata = 0;
    reg [2:0] since_register_write = 3'd7;   // edges since a register (space 0) write was taken

    always @(posedge clock) begin
        p_valid <= reset_n;
        p_waiting <= reset_n && (we || re) && !ready && !retry;
        p_we <= we;
        p_re <= re;
        p_space <= space;
        p_addr <= addr;
        p_be <= be;
        p_wdata <= wdata;
        if (!reset_n)
            since_register_write <= 3'd7;
        else if (we && ready && !space)
            since_register_write <= 3'd1;
        else if (since_register_write != 3'd7)
            since_register_write <= since_register_write + 1;
    end

    always @(posedge clock) if (reset_n) begin
        // one request at a time, its direction announced by `write`
        `LB_REQ(lb_one_request, !(we && re))
        if (we || re) begin `LB_REQ(lb_write_gives_direction, write == we) end
        // byte offsets of whole dwords
        if (we || re) begin `LB_REQ(lb_dword_aligned, addr[1:0] == 2'b00) end
        // a request is held until answered (it may be withdrawn, not changed)
        if (p_waiting && (we || re)) begin
            `LB_REQ(lb_request_held, we == p_we && re == p_re && space == p_space && addr == p_addr
                                     && be == p_be && (!we || wdata == p_wdata))
        end
        // a register write takes effect over the next clocks (COMMAND.SOFT_RESET
        // empties the FIFO two clocks after it): no FIFO write is taken in the
        // three clocks after one (the PCI target needs more for a new transaction)
        if (since_register_write <= 3) begin `LB_REQ(lb_fifo_write_after_register_write_settles, !(we && space)) end
        // an answer is ready or retry, never both
        `LB_RSP(lb_one_answer, !(ready && retry))
        // a FIFO write waits at most one clock for its answer (the card's
        // back end answers at once, but in the clock after a register write)
        if (p_waiting && p_we && p_space && we && space) begin `LB_RSP(lb_fifo_write_answered, ready || retry) end
`ifdef LOCAL_ROOM
        // the write credit: a promised FIFO write is not refused, and waits
        // at most one clock; room falls only when the back end takes a write
        if (we && space && promise_open) begin `LB_RSP(lb_promise_kept, !retry) end
        if (p_valid && p_room && !room) begin `LB_RSP(lb_room_falls_by_writes, p_took) end
`endif
    end
`ifdef LOCAL_ROOM
    // writes still promised: ROOM_PLACES while room is high (counting the
    // write taken in that clock), then one fewer for each write taken
    reg [2:0] promised_left = 0;
    reg p_room = 0, p_took = 0;
    localparam [2:0] PLACES = ROOM_PLACES;
    wire [2:0] promised_now = room ? PLACES : promised_left;
    wire promise_open = promised_now != 0;
    wire took = we && space && ready;
    always @(posedge clock) begin
        p_room <= room;
        p_took <= took;
        if (!reset_n)
            promised_left <= 0;
        else
            promised_left <= promised_now - (took && promise_open);
    end
    assign promised = promised_left;
`else
    assign promised = 3'd0;
`endif
    always @(posedge clock) if (!reset_n) begin
        `LB_REQ(lb_quiet_in_reset, !we && !re)
    end
`undef LB_REQ
`undef LB_RSP
endmodule
