"""The PCI target's data buffers: posted write data and the read skid register.

Writes (memory space) are posted: the dword of a completed data phase waits
in the input register (``wq_valid``), then in the head (h) and second (s)
entries until the back end takes it (``accepted``); the target acknowledges
a phase only while these hold at most two dwords and the back end promises
room (``rtl/pci/pci_control.py``), so nothing acknowledged is dropped.  Reads:
the AD output register is fed by a one-dword skid register B, which keeps a
dword read ahead while the master waits; B and s share one register, as
reads and writes never use it at once.

Where a posted dword goes at an edge (the oldest always leaves first)::

    ad_q (wq_valid) --> h (h_valid) --> back end, when ``accepted``
            \\--------> s (s_valid) --/   (s moves to h when h leaves)
"""
from myhdl import always_comb, always_seq, block, instances, intbv

from rtl.pci.pci_control import t_state


@block
def pci_buffers(clock, reset, buffers):
    """Ports: ``clock``, ``reset``; ``buffers`` a ``TargetBuffers``."""
    ad, cbe, state, is_read, trdy_q = buffers.ad, buffers.cbe, buffers.state, buffers.is_read, buffers.trdy_q
    first_phase, space_mem, got, accepted = (buffers.first_phase, buffers.space_mem, buffers.got,
                                             buffers.accepted)
    re, ready, rdata = buffers.re, buffers.ready, buffers.rdata
    b_valid, wq_valid, h_valid, s_valid = buffers.b_valid, buffers.wq_valid, buffers.h_valid, buffers.s_valid
    h_data, spare_data, h_be, s_be = buffers.h_data, buffers.spare_data, buffers.h_be, buffers.s_be
    write_done_q, config_write_q = buffers.write_done_q, buffers.config_write_q
    b_kept, posting, buffered = buffers.b_kept, buffers.posting, buffers.buffered
    b_valid_next, wq_valid_next = buffers.b_valid_next, buffers.wq_valid_next
    write_done_next, config_write_next = buffers.write_done_next, buffers.config_write_next

    @always_seq(clock.posedge, reset=reset)
    def read_buffer():
        b_valid.next = b_valid_next

    @always_comb
    def read_buffer_hold():
        # B keeps a dword if the AD register holds (IRDY# pin: ``b_valid_next``)
        in_read = is_read and (state == t_state.S_MEM_HOLD or state == t_state.S_IO_HOLD
                               or state == t_state.S_READ_HOLD or state == t_state.S_RWING)
        b_kept.next = in_read and (b_valid or got) and not trdy_q

    @always_comb
    def write_posting():
        # a completed phase now (IRDY# pin: ``wq_valid_next``) is posted
        posting.next = not trdy_q and not is_read and not first_phase and space_mem

    @always_seq(clock.posedge, reset=reset)
    def write_buffer():
        write_done_q.next = write_done_next
        config_write_q.next = config_write_next
        wq_valid.next = wq_valid_next
        if h_valid:
            if accepted:
                if s_valid:
                    h_data.next = spare_data
                    h_be.next = s_be
                    s_valid.next = wq_valid
                    if wq_valid:
                        spare_data.next = ad
                        s_be.next = ~cbe
                elif wq_valid:
                    h_data.next = ad
                    h_be.next = ~cbe
                else:
                    h_valid.next = False
            elif wq_valid:
                s_valid.next = True
                spare_data.next = ad
                s_be.next = ~cbe
        elif wq_valid and not accepted:
            h_valid.next = True
            h_data.next = ad
            h_be.next = ~cbe
        if re and ready:
            # B takes every dword read; it counts only if the AD register
            # is holding (b_valid), which keeps IRDY# out of this path
            spare_data.next = rdata

    @always_comb
    def posted_count():
        # Posted dwords held after this edge (head and second entry), as the
        # state machine reads it in Configuring and Rwing: there the only
        # write request drains posted data, so a held dword goes when the
        # back end answers ready (``accepted``, without the request logic).
        held = intbv(0, min=0, max=4)
        if h_valid:
            held[:] = 1
            if s_valid:
                held[:] = 2
            if ready:
                held[:] = held - 1
            if wq_valid:
                held[:] = held + 1
        elif wq_valid and not ready:
            held[:] = 1
        buffered.next = held

    return instances()
