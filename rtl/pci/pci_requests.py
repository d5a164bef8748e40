"""The PCI target's requests to its back end (``LocalBus``) and the answers.

A request is made from flip-flops only, in one process, so that the back
end never sees a half-updated address or data: the first request of a
transaction once posted data have drained (held until answered), read
prefetches in a burst, and posted write data (head entry first).  The
answers are decoded here as the state machine reads them
(``rtl/pci/pci_control.py``), so that no test of the state lies between the
back end's registers and the target's::

    edge       k     k+1   k+2
    re/we    __/~~~~~~~~~~~\\___     held until answered
    ready    ________/~~~~~\\___
    got      ________/~~~~~\\___     read data taken at k+2
"""
from myhdl import always_comb, block, concat, instances, intbv

from rtl.pci.pci_control import t_state


@block
def pci_requests(requests, local):
    """Ports: ``requests`` a ``TargetRequests`` (the target's registers in,
    the decoded answers out); ``local`` the target's ``LocalBus``.  The PCI
    rule applied here: an I/O access that enables a byte below the one
    AD[1:0] addresses is answered with target abort (``fatal``), and so is an
    address with a parity error when Parity Error Response is set."""
    req_addr, state, address_fault, io_byte = (requests.req_addr, requests.state, requests.address_fault,
                                               requests.io_byte)
    cbe_q, ad_q, first_pending, is_config = requests.cbe, requests.ad, requests.first_pending, requests.is_config
    req_addr_stale, is_read, fetching, b_valid = (requests.req_addr_stale, requests.is_read, requests.fetching,
                                                  requests.b_valid)
    trdy_q, frame_q, irdy_q = requests.trdy_q, requests.frame_q, requests.irdy_q
    h_valid, wq_valid, space_mem = requests.h_valid, requests.wq_valid, requests.space_mem
    h_data, h_be, fatal = requests.h_data, requests.h_be, requests.fatal
    first_ready, fetch_more, draining = requests.first_ready, requests.fetch_more, requests.draining
    got, accepted, burst_got = requests.got, requests.accepted, requests.burst_got
    hold_got, hold_accepted, hold_retry = requests.hold_got, requests.hold_accepted, requests.hold_retry

    @always_comb
    def local_request():
        # From flip-flops only, in one process, so that a request never shows
        # a half-updated address or data.
        drain = h_valid or wq_valid
        hold_state = (state == t_state.S_CON_HOLD or state == t_state.S_IO_HOLD
                      or state == t_state.S_MEM_HOLD or state == t_state.S_READ_HOLD)
        # PCI: an I/O access that enables a byte below the one AD[1:0]
        # addresses is fatal, and so is a corrupt address.
        bad = False
        if address_fault:
            bad = True
        elif state == t_state.S_IO_HOLD:
            if io_byte == 1:
                bad = not cbe_q[0]
            elif io_byte == 2:
                bad = not (cbe_q[0] and cbe_q[1])
            elif io_byte == 3:
                bad = not (cbe_q[0] and cbe_q[1] and cbe_q[2])
        fatal.next = hold_state and bad
        first_open = (first_pending and hold_state and not is_config and not drain
                      and not req_addr_stale)
        first = first_open and not bad
        prefetch = (state == t_state.S_RWING and is_read and fetching and not b_valid
                    and (trdy_q or not frame_q))
        local.re.next = (first and is_read) or prefetch
        local.we.next = drain or (first and not is_read and not irdy_q)
        first_ready.next = first_pending and not is_config and not drain and not req_addr_stale
        fetch_more.next = is_read and fetching and not b_valid and (trdy_q or not frame_q)
        local.space.next = drain or space_mem
        local.write.next = drain or not is_read
        if h_valid:
            local.wdata.next = h_data
            local.be.next = h_be
        elif is_read and space_mem and not drain:
            local.wdata.next = ad_q
            local.be.next = 0xF
        else:
            local.wdata.next = ad_q
            local.be.next = ~cbe_q
        local.addr.next = concat(req_addr, intbv(0)[2:])

    @always_comb
    def local_answer():
        draining.next = h_valid or wq_valid
        got.next = (local.re and local.ready) or (state == t_state.S_CON_HOLD and is_read)
        accepted.next = local.we and local.ready
        # The answers as the state machine reads them: each takes what the
        # state already says about the request, so that no state test lies
        # between the registers and the answer.  In I/O_Hold, Mem_Hold and
        # Read_Hold the request is the first one, once posted data has
        # drained; the abort check is left out, as ``fatal`` decides first
        # there (which keeps C/BE# of the first data phase off the path).
        # In Configuring and Rwing the request is a prefetch, or posted data
        # (see write_path).
        hold_got.next = first_ready and is_read and local.ready
        hold_accepted.next = first_ready and not is_read and not irdy_q and local.ready
        hold_retry.next = first_ready and (is_read or not irdy_q) and local.retry
        burst_got.next = fetch_more and local.ready

    return instances()
