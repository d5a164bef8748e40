"""The PCI target's transaction registers: the state, the data phase's
address and what the address phase said (``rtl/pci_slave.py``).

Everything here is a flip-flop loaded from the next values the pins chose
(``rtl/pci/pci_control.py``, ``pin_lut``) or from flip-flops through logic:
the address phase's kind is taken at every address phase in Idle, claimed
or not, so the BAR compares reach only the state and the bus lines; the
latency counter keeps its limits registered, so no compare lies before the
timeout::

    edge        A     A+1    A+2
    claim     __/~~~~~\\_____         from the address phase sampled at A
    state       IDLE  *_HOLD ...      taken at A+1
    phase_addr  ====X start_addr      (a memory burst counts it on)
    is_read, is_config, space_mem, single, io_byte: taken at A+1
"""
from myhdl import always_comb, always_seq, block

from rtl.pci.pci_control import t_state
from rtl.pci.pci_slave_build import INITIAL_WAIT_LIMIT, SUBSEQUENT_WAIT_LIMIT, last_dword


@block
def pci_transaction(clock, reset, transaction, local, *, mem_bits):
    """Ports: ``transaction`` a ``TargetTransaction`` (the target's next
    values and input registers in, these registers out); ``local`` the
    target's ``LocalBus`` (its requests and answers count the request
    address on).  Parameter: ``mem_bits`` (BAR1 is 2**mem_bits bytes: a
    burst ends at its last dword).

        clock     _/~\\_/~\\_/~\\_/~\\_/~\\_
        waiting   __/~~~~~~~~~~~~~~~~~~~~     TRDY# and STOP# not asserted
        wait_count  0 X 1 X 2 X ... X n       n = INITIAL_WAIT_LIMIT: timeout
    """
    tx = transaction
    mem_last = last_dword(mem_bits)   # last dword of BAR1

    @always_comb
    def latency():
        target_waits = (tx.trdy_q and tx.stop_q and tx.state != t_state.S_IDLE
                        and tx.state != t_state.S_BACKOFF and tx.state != t_state.S_ENDING)
        tx.waiting.next = target_waits
        tx.timeout.next = target_waits and (
            (tx.first_phase and tx.initial_wait_over) or (not tx.first_phase and tx.subsequent_wait_over))

    @always_seq(clock.posedge, reset=reset)
    def phase_registers():
        tx.state.next = tx.state_next
        tx.first_phase.next = tx.first_phase_next
        tx.address_fault.next = tx.address_fault_next
        if tx.phase_step:   # the claim, or a completed phase of a memory burst
            if tx.claim:
                tx.phase_addr.next = tx.start_addr
                tx.at_last.next = tx.start_addr == mem_last
                tx.before_last.next = tx.start_addr == mem_last - 1
            else:
                tx.phase_addr.next = tx.phase_addr + 1
                tx.at_last.next = tx.before_last
                tx.before_last.next = tx.phase_addr == mem_last - 2

    @always_seq(clock.posedge, reset=reset)
    def transaction_kind():
        # taken at every address phase in Idle, claimed or not (Idle reads none
        # of it): the BAR compares reach only the state and the bus lines
        if tx.state == t_state.S_IDLE and tx.address_phase:
            tx.is_read.next = not tx.cbe[0]
            tx.is_config.next = tx.claim_config
            # BAR2 reaches the registers (space 0) as BAR0 does, one dword a
            # transaction: a burst is disconnected after its first data phase
            tx.space_mem.next = not tx.claim_config and not tx.claim_io and not tx.claim_alias
            tx.single.next = tx.claim_config or tx.claim_io or tx.claim_alias or tx.ad[0] or tx.ad[1]
            tx.first_pending.next = True
            tx.fetching.next = not tx.cbe[0] and not tx.claim_config
            tx.io_byte.next = tx.ad[2:0]
        else:
            if tx.got or tx.accepted:
                tx.first_pending.next = tx.first_pending and tx.draining
            if local.re and local.ready and (tx.single or tx.req_addr == mem_last):
                tx.fetching.next = False
            if local.re and local.retry and not tx.first_pending:
                tx.fetching.next = False

    @always_seq(clock.posedge, reset=reset)
    def request_address():
        if tx.claim:
            tx.req_addr_stale.next = tx.draining
        # loaded at an address phase in Idle, claimed or not, with no posted
        # data left: a claim finds it loaded, the BAR compare not before it
        if (local.re or local.we) and local.ready:
            tx.req_addr.next = tx.req_addr + 1
        elif tx.state == t_state.S_IDLE and tx.address_phase and not tx.draining:
            tx.req_addr.next = tx.start_addr
            tx.req_addr_stale.next = False
        elif tx.req_addr_stale and not tx.draining:
            tx.req_addr.next = tx.phase_addr
            tx.req_addr_stale.next = False

    @always_seq(clock.posedge, reset=reset)
    def latency_count():
        # Idle (the only state with a claim) never waits
        if not tx.waiting:
            tx.wait_count.next = 0
            tx.initial_wait_over.next = False
            tx.subsequent_wait_over.next = False
        elif not tx.timeout:
            tx.wait_count.next = tx.wait_count + 1
            tx.initial_wait_over.next = tx.wait_count == INITIAL_WAIT_LIMIT - 1
            tx.subsequent_wait_over.next = tx.wait_count == SUBSEQUENT_WAIT_LIMIT - 1

    return latency, phase_registers, transaction_kind, request_address, latency_count
