// Conventional PCI 2.3 (32 bits) as seen from one target and its initiator:
// the bus rules as immediate assertions that yosys reads with `read -formal`.
//
// CHECK_TARGET = 1: the target's rules are asserted and the initiator's are
// assumed (a target under test, a free initiator); CHECK_TARGET = 0: the
// reverse, so the same file checks an initiator against a free target.
//
// Every signal is the value sampled at a rising CLK edge (levels: an
// active-low line reads 0 when asserted).  The resolved lines (ad ... serr_n)
// are what every agent samples; t_* are the observed target's own drivers,
// m_* the initiator's.  Edges are counted from the address edge A (the edge
// that samples FRAME# first asserted): clk_now = 1 at A + 1.
//
// Each rule's label begins with its area; the comment names the clause of the
// PCI Local Bus Specification 2.3 (section numbers; "App. C" for the protocol
// rules of Appendix C) and the rule of sim/pci/checker.py it matches (rN).
//
// Not covered: fast back-to-back transactions (an idle clock is assumed
// between transactions, as the project's benches do), 64-bit extensions,
// LOCK#, dual address cycles, special cycles.
`default_nettype none

module pci_rules #(
    parameter CHECK_TARGET = 1
) (
    input wire clock,
    input wire reset_n,
    // resolved bus
    input wire [31:0] ad, input wire [3:0] cbe_n, input wire par,
    input wire frame_n, input wire irdy_n, input wire trdy_n, input wire devsel_n,
    input wire stop_n, input wire perr_n, input wire serr_n,
    // the observed target's drivers
    input wire [31:0] t_ad, input wire t_ad_oe, input wire t_par, input wire t_par_oe,
    input wire t_trdy_n, input wire t_trdy_oe, input wire t_devsel_n, input wire t_devsel_oe,
    input wire t_stop_n, input wire t_stop_oe, input wire t_perr_n, input wire t_perr_oe,
    input wire t_serr_n, input wire t_serr_oe,
    // the initiator's drivers
    input wire [31:0] m_ad, input wire [3:0] m_cbe_n, input wire m_frame_n, input wire m_irdy_n,
    // from a model of the target's configuration space: the address phase
    // sampled at this edge is for the target; Command register bits
    input wire decoded, input wire parity_response, input wire serr_enable,
    // the transaction as tracked here, for the harness
    output wire address_edge,      // this edge samples an address phase
    output wire data_edge,         // this edge lies in the data part of a transaction
    output wire completion,        // a data phase completes at this edge
    output wire transfer,          // data move at this edge (IRDY#, TRDY#, DEVSEL#)
    output wire last_completion,   // the last data phase completes at this edge
    output reg  txn_hit,           // the transaction's address was for the target
    output reg  [3:0] txn_command, // C/BE# of its address phase
    output reg  [31:0] txn_address,
    output reg  [15:0] txn_transfers, // data moved before this edge (saturates)
    output wire [5:0] clk_now,     // edges since the address edge (saturates at 63)
    output reg  addr_parity_error, // PAR at A + 1 did not cover the address phase
    output wire target_abort,      // the target signals target abort at this edge
    output wire target_claimed,    // the target's DEVSEL# was sampled before this edge
    output wire [3:0] since_completion, // edges from the last completion (or address) to the last edge
    output wire par_wrong          // PAR at this edge does not cover the AD and C/BE# of the last
);
`define PCI_T(label, cond) if (CHECK_TARGET) begin label: assert(cond); end else begin label: assume(cond); end
`define PCI_M(label, cond) if (CHECK_TARGET) begin label: assume(cond); end else begin label: assert(cond); end

    // even parity over AD[31:0] and C/BE#[3:0]: XOR of all 36 bits, folded
    // in halves (any order gives the same value; a balanced fold keeps the
    // solver's work small)
    function parity36(input [31:0] a, input [3:0] c);
        reg [15:0] f16;
        reg [7:0] f8;
        reg [3:0] f4;
        reg [1:0] f2;
        begin
            f16 = a[31:16] ^ a[15:0];
            f8 = f16[15:8] ^ f16[7:0];
            f4 = f8[7:4] ^ f8[3:0];
            f2 = f4[3:2] ^ f4[1:0];
            parity36 = f2[1] ^ f2[0] ^ c[3] ^ c[2] ^ c[1] ^ c[0];
        end
    endfunction

    wire frame = !frame_n, irdy = !irdy_n, trdy = !trdy_n, devsel = !devsel_n, stop = !stop_n;
    wire t_trdy = t_trdy_oe && !t_trdy_n;
    wire t_devsel = t_devsel_oe && !t_devsel_n;
    wire t_stop = t_stop_oe && !t_stop_n;
    wire t_perr = t_perr_oe && !t_perr_n;
    wire t_serr = t_serr_oe && !t_serr_n;
    wire m_frame = !m_frame_n, m_irdy = !m_irdy_n;

    // ---- the previous edge
    reg p_valid = 0;         // an edge out of reset before this one
    reg p_frame = 0, p_irdy = 0, p_trdy = 0, p_stop = 0;
    reg p_t_trdy = 0, p_t_stop = 0, p_t_devsel = 0, p_t_perr = 0;
    reg p_t_trdy_oe = 0, p_t_stop_oe = 0, p_t_devsel_oe = 0, p_t_perr_oe = 0, p_t_ad_oe = 0;
    reg p_t_trdy_n = 1, p_t_stop_n = 1, p_t_devsel_n = 1, p_t_perr_n = 1;
    reg [31:0] p_ad = 0, p_m_ad = 0;
    reg [3:0] p_cbe_n = 0, p_m_cbe_n = 0;
    reg p_data = 0, p_completion = 0, p_last = 0, p_transfer_write = 0, p_address = 0;
    reg p_parity_response = 0, p_serr_enable = 0;

    // ---- transaction tracking (state after the previous edge)
    reg in_txn = 0;          // the next edge is a data edge
    reg [5:0] edges = 0;     // edges since the address edge, at the previous edge
    reg [3:0] since = 0;     // edges since the last completion (or the address edge)
    reg devsel_seen = 0;     // DEVSEL# (any target) sampled in this transaction
    reg t_devsel_seen = 0;   // the target's DEVSEL# sampled in this transaction
    reg any_completed = 0;   // a data phase of this transaction completed
    reg t_no_data_stop = 0;  // the target asserted STOP# without TRDY# in this transaction
    reg hit_ended = 0;       // the last edge ended a transaction of the target
    reg perr_due = 0, serr_due = 0;   // PERR#/SERR# due at this edge

    wire address = frame && !p_frame && !in_txn;
    wire data = in_txn;
    wire [5:0] clk = (edges == 6'h3f) ? edges : edges + 1;
    wire devsel_now = devsel_seen || devsel;
    wire master_abort = data && !devsel_now && clk >= 4;
    wire complete_now = data && irdy && (trdy || stop || master_abort);
    wire last = complete_now && !frame;
    wire [4:0] since_now = since + 1;
    wire write = txn_command[0];
    wire parity_ok = parity36(p_ad, p_cbe_n) == par;

    assign address_edge = address;
    assign data_edge = data;
    assign completion = complete_now;
    assign transfer = data && irdy && trdy && devsel;
    assign last_completion = last;
    assign clk_now = clk;
    assign target_abort = data && t_stop && !t_devsel;
    assign target_claimed = t_devsel_seen;
    assign since_completion = since;
    assign par_wrong = !parity_ok;

    always @(posedge clock) begin
        if (!reset_n) begin
            p_valid <= 0;
            in_txn <= 0;
            hit_ended <= 0;
            perr_due <= 0;
            serr_due <= 0;
            txn_hit <= 0;
            addr_parity_error <= 0;
        end else begin
            p_valid <= 1;
            hit_ended <= last && txn_hit;
            if (address) begin
                in_txn <= 1;
                edges <= 0;
                since <= 0;
                devsel_seen <= 0;
                t_devsel_seen <= 0;
                any_completed <= 0;
                t_no_data_stop <= 0;
                txn_hit <= decoded;
                txn_command <= cbe_n;
                txn_address <= ad;
                txn_transfers <= 0;
                addr_parity_error <= 0;
            end else if (data) begin
                edges <= clk;
                since <= complete_now ? 4'd0 : (since == 4'hf ? since : since + 1);
                devsel_seen <= devsel_now;
                t_devsel_seen <= t_devsel_seen || t_devsel;
                any_completed <= any_completed || complete_now;
                t_no_data_stop <= t_no_data_stop || (t_stop && !t_trdy);
                if (transfer && txn_transfers != 16'hffff)
                    txn_transfers <= txn_transfers + 1;
                if (last)
                    in_txn <= 0;
                if (p_address)
                    addr_parity_error <= !parity_ok;
            end
            // PERR#: two edges after a write data phase to the target whose PAR
            // (one edge later) is wrong; SERR#: two edges after a bad address
            perr_due <= p_transfer_write && !parity_ok && p_parity_response;
            serr_due <= p_address && !parity_ok && p_serr_enable && p_parity_response;
        end
        p_frame <= frame && reset_n;
        p_irdy <= irdy && reset_n;
        p_trdy <= trdy;
        p_stop <= stop;
        p_t_trdy <= t_trdy;
        p_t_stop <= t_stop;
        p_t_devsel <= t_devsel;
        p_t_perr <= t_perr;
        p_t_trdy_oe <= t_trdy_oe;
        p_t_stop_oe <= t_stop_oe;
        p_t_devsel_oe <= t_devsel_oe;
        p_t_perr_oe <= t_perr_oe;
        p_t_ad_oe <= t_ad_oe;
        p_t_trdy_n <= t_trdy_n;
        p_t_stop_n <= t_stop_n;
        p_t_devsel_n <= t_devsel_n;
        p_t_perr_n <= t_perr_n;
        p_ad <= ad;
        p_m_ad <= m_ad;
        p_cbe_n <= cbe_n;
        p_m_cbe_n <= m_cbe_n;
        p_data <= data && reset_n;
        p_completion <= complete_now;
        p_last <= last && reset_n;
        p_transfer_write <= transfer && txn_hit && write && reset_n;
        p_address <= address && reset_n;
        p_parity_response <= parity_response;
        p_serr_enable <= serr_enable;
    end

    // ================================================================ initiator
    always @(posedge clock) if (reset_n) begin
        // 2.2.1 RST#; the bus is idle in the first clock after reset
        if (!p_valid) begin `PCI_M(m_idle_after_reset, !m_frame && !m_irdy) end
        // 3.4.1 / App. C (bus idle): a transaction starts from an idle bus (r4;
        // no fast back-to-back)
        if (address) begin `PCI_M(m_frame_from_idle, !p_irdy) end
        // App. C: FRAME# is not asserted again within a transaction
        if (data && !p_frame) begin `PCI_M(m_frame_not_reasserted, !m_frame) end
        // App. C: IRDY# only in a transaction, first asserted with FRAME# (r5)
        if (m_irdy) begin `PCI_M(m_irdy_in_transaction, data && (p_irdy || p_frame)) end
        // 3.3.3.1 / App. C: FRAME# is deasserted only with IRDY# asserted (r6)
        if (p_frame && !m_frame && p_valid) begin `PCI_M(m_frame_ends_with_irdy, m_irdy) end
        // 3.3.1 / App. C: once IRDY# is asserted, IRDY# and FRAME# hold until
        // the data phase completes (r7, r8)
        if (p_data && p_irdy && !p_completion) begin
            `PCI_M(m_irdy_held, m_irdy)
            `PCI_M(m_frame_held, m_frame == p_frame)
        end
        // App. C: IRDY# deasserted the clock after the last data phase
        if (p_last) begin `PCI_M(m_irdy_released, !m_irdy && !m_frame) end
        // 3.3.2: write data held while the target waits (r1)
        if (data && p_data && write && p_irdy && !p_completion) begin
            `PCI_M(m_write_data_held, m_ad == p_m_ad)
        end
        // 3.2.2, 3.3.1: C/BE# valid and held through each data phase (r3)
        if (data && p_data && !p_completion) begin `PCI_M(m_cbe_held, m_cbe_n == p_m_cbe_n) end
        // 3.3.3.1 master abort: no DEVSEL# by clock 5, the initiator ends
        if (data && !devsel_now && clk >= 5) begin `PCI_M(m_master_abort_ends, !m_frame) end
        // 3.3.3.2.2 / App. C: after STOP#, FRAME# goes as soon as IRDY# can be asserted
        if (p_data && p_stop && p_frame && p_irdy) begin `PCI_M(m_stop_ends_frame, !m_frame) end
        if (p_data && p_stop && p_frame && !p_irdy) begin `PCI_M(m_stop_ends_frame_with_irdy, !(m_irdy && m_frame)) end
        // 3.5.2: IRDY# within 8 clocks of the address phase or the last completion (r15)
        if (data && since_now >= 8) begin `PCI_M(m_irdy_latency, m_irdy) end
    end
    always @(posedge clock) if (!reset_n) begin
        // 2.2.1 RST#: every agent floats its outputs (r18)
        `PCI_M(m_released_in_reset, !m_frame && !m_irdy)
    end

    // ================================================================ target
    always @(posedge clock) if (reset_n) begin
        // 3.6.1: the target claims exactly the transactions decoded for it, with
        // DEVSEL# sampled asserted at A + 2 (medium, as Status[10:9] says)
        if (data && txn_hit && clk == 2) begin `PCI_T(t_claims_decoded, t_devsel) end
        // 3.6.1, App. C: DEVSEL#, TRDY#, STOP# only in a transaction decoded for
        // this target (r12)
        if (t_devsel || t_trdy || t_stop) begin `PCI_T(t_signals_only_when_decoded, data && txn_hit) end
        // App. C: TRDY#/STOP# only with DEVSEL# or after it (target abort) (r12)
        if (t_trdy) begin `PCI_T(t_trdy_with_devsel, t_devsel) end
        if (t_stop && !t_devsel) begin `PCI_T(t_abort_after_devsel, t_devsel_seen && !t_trdy) end
        // 3.6.1: DEVSEL# held until the last data phase, except for target abort (r13)
        if (data && p_t_devsel && !t_devsel) begin `PCI_T(t_devsel_held, t_stop && !t_trdy) end
        // 3.3.3.2.1 / App. C: once TRDY# or STOP# is asserted, DEVSEL#, TRDY#, STOP#
        // do not change until the data phase completes (r11)
        if (data && p_data && !p_irdy && (p_t_trdy || p_t_stop)) begin
            `PCI_T(t_trdy_held, t_trdy == p_t_trdy)
            `PCI_T(t_stop_held_in_phase, t_stop == p_t_stop)
            `PCI_T(t_devsel_held_in_phase, t_devsel == p_t_devsel)
        end
        // 3.3.3.2.1 / App. C: STOP# held while FRAME# is asserted (r9), released once
        // FRAME# is deasserted (r10)
        if (data && p_data && p_t_stop && p_frame) begin `PCI_T(t_stop_held_until_frame, t_stop) end
        if (p_data && p_t_stop && !p_frame) begin `PCI_T(t_stop_released, !t_stop) end
        // 3.3.3.2.1: after STOP# without TRDY# (retry, disconnect without data,
        // target abort) no data moves in the transaction
        if (data && t_no_data_stop) begin `PCI_T(t_no_trdy_after_stop_without_data, !t_trdy) end
        // App. C: TRDY#, STOP#, DEVSEL# deasserted the clock after the last data
        // phase (r13), driven high one clock before they float (r17)
        if (!data) begin `PCI_T(t_deasserted_after_end, !t_trdy && !t_stop && !t_devsel) end
        if (t_trdy_oe || t_stop_oe || t_devsel_oe) begin `PCI_T(t_drives_only_when_claimed, (data && txn_hit) || hit_ended) end
        if (p_t_trdy_oe && !t_trdy_oe) begin `PCI_T(t_trdy_high_before_float, p_t_trdy_n) end
        if (p_t_stop_oe && !t_stop_oe) begin `PCI_T(t_stop_high_before_float, p_t_stop_n) end
        if (p_t_devsel_oe && !t_devsel_oe) begin `PCI_T(t_devsel_high_before_float, p_t_devsel_n) end
        if (p_t_perr_oe && !t_perr_oe) begin `PCI_T(t_perr_high_before_float, p_t_perr_n) end
        // 3.2.4, 3.3.1: AD driven only in a read of this target, from the clock
        // after the turnaround clock, released after the last data phase (r16)
        if (t_ad_oe) begin `PCI_T(t_ad_only_in_read, data && txn_hit && !write && clk >= 2) end
        // 3.3.1 / App. C: TRDY# on a read only with data on AD
        if (data && !write && t_trdy) begin `PCI_T(t_read_data_driven, t_ad_oe) end
        // 3.3.1: read data held while the initiator waits (r2)
        if (data && p_data && !write && p_t_trdy && !p_irdy) begin `PCI_T(t_read_data_held, t_ad == p_ad) end
        // 3.7.1 / 3.2.4: PAR driven one clock after AD, even parity over the AD and
        // C/BE# of the clock before (r14)
        `PCI_T(tp_par_follows_ad, t_par_oe == p_t_ad_oe)
        if (t_par_oe) begin `PCI_T(tp_par_even, t_par == parity36(p_ad, p_cbe_n)) end
        // 3.7.4.1: PERR# two edges after a write data phase with bad parity when
        // Parity Error Response is set, for one clock, then high one clock (r14)
        `PCI_T(tp_perr_when_due, t_perr == perr_due)
        if (t_perr_oe) begin `PCI_T(tp_perr_driven_briefly, t_perr || p_t_perr) end
        // 3.7.4.2: SERR# (open drain) two edges after an address parity error when
        // SERR# Enable and Parity Error Response are set, for one clock (r14)
        `PCI_T(tp_serr_when_due, t_serr == serr_due)
        if (t_serr_oe) begin `PCI_T(tp_serr_open_drain, !t_serr_n) end
        // 3.5.1.1: the first data phase ends (TRDY# or STOP#) within 16 clocks (r15)
        if (data && t_devsel_seen && !any_completed && clk >= 16) begin `PCI_T(t_initial_latency, t_trdy || t_stop) end
        // 3.5.1.2: later data phases within 8 clocks of the last completion (r15)
        if (data && t_devsel_seen && any_completed && since_now >= 8) begin `PCI_T(t_subsequent_latency, t_trdy || t_stop) end
    end
    always @(posedge clock) if (!reset_n) begin
        // 2.2.1 RST#: every output floats during reset (r18)
        `PCI_T(t_released_in_reset, !t_ad_oe && !t_par_oe && !t_trdy_oe && !t_devsel_oe
                                    && !t_stop_oe && !t_perr_oe && !t_serr_oe)
    end

    // ================================================================ covers
    wire cmd_io = txn_command[3:1] == 3'b001;
    wire cmd_mem = txn_command == 4'h6 || txn_command == 4'h7 || txn_command[3:2] == 2'b11;
    wire cmd_config = txn_command[3:1] == 3'b101;
    always @(posedge clock) if (reset_n) begin
        cover_config_read: cover(transfer && txn_hit && cmd_config && !write);
        cover_config_write: cover(transfer && txn_hit && cmd_config && write);
        cover_io_read: cover(transfer && txn_hit && cmd_io && !write);
        cover_io_write: cover(transfer && txn_hit && cmd_io && write);
        cover_memory_read_burst: cover(transfer && txn_hit && cmd_mem && !write && txn_transfers >= 2);
        cover_memory_write_burst: cover(transfer && txn_hit && cmd_mem && write && txn_transfers >= 2);
        cover_retry: cover(last && txn_hit && t_stop && !t_trdy && t_devsel && txn_transfers == 0);
        cover_disconnect: cover(last && txn_hit && t_stop && txn_transfers != 0);
        cover_target_abort: cover(data && t_stop && !t_devsel);
        cover_master_abort: cover(last && master_abort);
        cover_data_parity_error: cover(t_perr);
        cover_address_parity_error: cover(t_serr);
    end
`undef PCI_T
`undef PCI_M
endmodule
