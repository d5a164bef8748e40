"""PCI 2.3 target (32-bit, 33 MHz) built on the state machine of the paper's section 3.

The paper's states keep their names in code spelling: ``S_IDLE`` (Idle),
``S_CON_HOLD`` (Con_Hold), ``S_IO_HOLD`` (I/O_Hold), ``S_MEM_HOLD``
(Mem_Hold), ``S_READ_HOLD`` (Read_Hold), ``S_CONFIGURING`` (Configuring),
``S_RWING`` (Rwing), ``S_ENDING`` (Ending); one state is added,
``S_BACKOFF``: STOP# asserted, waiting for FRAME# to go (retry, disconnect,
target abort).  ``docs/pci.md`` maps them and explains the timing.

Its units (``rtl/pci/``): ``pci_boundary`` (the input and output registers
at the bus), ``pci_decode`` (the claim), ``pci_control`` (the state
machine's next values), ``pci_transaction`` (the state and the transaction's
registers), ``pci_requests`` (the back-end requests), ``pci_buffers`` (read
and posted write data), ``pci_parity``, ``pci_config`` (the configuration
header); this block names their signals and wires them.

Timing architecture: AD, C/BE# and IDSEL are sampled into an input register
before any logic, and every PCI output and output enable but PAR comes
from a flip-flop.  Three inputs also reach a register through logic,
because PCI leaves no clock for a register in between: FRAME# and IRDY#
(ending a burst, advancing read data; the state machine's next values are
computed for each case of the two pins, which only choose among them) and
PAR (PERR# and SERR# two clocks after the phase they cover); each passes
one LUT on the way (``pin_pick``, ``pin_lut``).  PAR on reads covers the
AD and C/BE# of the clock before: it is the XOR of the AD register's
registered parity and the C/BE# input register, one LUT level after
flip-flops on the way out, where PCI's 11 ns leave room (the 7 ns of
set-up do not).  The registered address makes DEVSEL# timing MEDIUM.
"""
from myhdl import Signal, always_comb, block, instances, intbv, modbv

from models.parameters import Build
from rtl.interfaces import (ConfigSpace, LocalBus, PciBus, TargetBoundary, TargetBuffers, TargetControlNext, TargetDecode,
                            TargetParity, TargetRequests, TargetState, TargetTransaction, card_reset)
from rtl.pci.pci_boundary import pci_boundary
from rtl.pci.pci_buffers import pci_buffers
from rtl.pci.pci_config import pci_config
from rtl.pci.pci_control import pci_control, t_state
from rtl.pci.pci_decode import pci_decode
from rtl.pci.pci_parity import pci_parity
from rtl.pci.pci_requests import pci_requests
from rtl.pci.pci_slave_build import check_io_registers, local_addr_width
from rtl.pci.pci_transaction import pci_transaction
from rtl.pci.pin_lut import pin_lut


def pci_slave_ports(io_bar_bits=Build.io_bar_bits, mem_bar_bits=Build.mem_bar_bits, reg_bar_bits=Build.reg_bar_bits):
    """Fresh ports of ``pci_slave`` for BARs of these sizes (conversion and
    benches): ``local`` has ``local_addr_width`` address bits."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), pci=PciBus(),
                local=LocalBus(local_addr_width(io_bar_bits, mem_bar_bits, reg_bar_bits)), irq=Signal(bool(0)))


# ``build``: a ``Build`` (``models/parameters.py``); the parameters the docstring
# names, but io_registers, are its fields (the docstring is gen/pci_slave.v's header).
@block
def pci_slave(clock, reset, pci, local, irq, *, build=Build(), io_registers=False):
    """The PCI target.

    Ports: ``clock`` PCI CLK; ``reset`` RST# (``card_reset()``); ``pci`` a
    ``PciBus``; ``local`` a ``LocalBus`` of ``local_addr_width()`` address
    bits (space 0: the registers, through BAR0, I/O, or BAR2, memory, which
    holds them at BAR0's offsets and may be larger; space 1: BAR1, memory); ``irq`` level interrupt
    request, drives INTA# unless Command.Interrupt Disable is set.

    Parameters: vendor_id, device_id, revision_id, class_code (24 bits),
    subsystem_vendor_id, subsystem_id; io_bar_bits (BAR0 is 2**io_bar_bits
    bytes), reg_bar_bits (BAR2 is 2**reg_bar_bits bytes, BAR0's size at
    least: BAR0's registers at their offsets, the rest reaching the back end
    too; a BAR0 under 16 bytes repeats in BAR2's 16), mem_bar_bits (BAR1 is
    2**mem_bar_bits bytes); device (how the
    one-LUT paths from FRAME#, IRDY# and PAR are written: ``rtl/pci/pin_lut.py``);
    defaults and ranges in ``models/parameters.py``;
    io_registers (False: the core's own flip-flops sample AD and IDSEL and
    drive AD, PAR, TRDY#, DEVSEL#, STOP#, PERR#; True: the I/O cells of
    ``rtl.pci.pci_pads`` hold those registers, so ``pci.ad_in``/``idsel_in``
    arrive registered and those ``*_out`` carry the value for after the next
    edge; bus timing is the same).

    Memory read burst, zero wait states (edge A samples the address; DEVSEL#
    is medium: sampled asserted at A+2)::

        edge        A     +1    +2    +3    +4    +5
        FRAME#  ~~\\_______________________/~~~~~~~~~
        IRDY#   ~~~~~~\\_________________________/~~~
        AD      --<adr>-----<D0  ><D1  ><D2  >------   driven from A+1
        DEVSEL# ~~~~~~~~~~\\_____________________/~~~
        TRDY#   ~~~~~~~~~~~~~~~~\\_______________/~~~   data sampled at A+3..A+5
        state     IDLE  MEM_HOLD RWING ...      ENDING

    Memory write burst into a back end with four free places: D0 goes to
    the back end from the input register before its TRDY# (``we`` at A+2; a
    refusal would be a Retry); D1, D2, D3 are posted, each acknowledged only
    while ``local.room`` promises the next three writes; then it does not:
    TRDY# waits and the latency rule ends the burst (STOP# sampled at A+13,
    Disconnect without data)::

        edge           A  +1  +2  +3  +4  +5  +6  +7
        FRAME#  ~~~~\\_______________________________ ...
        IRDY#   ~~~~~~~~\\___________________________ ...
        DEVSEL# ~~~~~~~~~~~~\\_______________________ ...
        TRDY#   ~~~~~~~~~~~~~~~~\\_______________/~~~ ...   D0 +3, D1 +4, D2 +5, D3 +6
        we      ____________/~~~\\_______/~~~~~~~~~~~ ...   D0, then D1, D2, D3 drain
        room    ~~~~~~~~~~~~~~~~~~~~~~~~~~~~\\_______ ...
    """
    io_registers = check_io_registers(io_registers)
    io_bits, mem_bits, reg_bits, device = build.io_bar_bits, build.mem_bar_bits, build.reg_bar_bits, build.device
    width = local_addr_width(io_bits, mem_bits, reg_bits) - 2   # dword address counters
    if len(local.addr) != width + 2:
        raise ValueError(f"pci_slave: local.addr must have {width + 2} bits, has {len(local.addr)}")

    # --- input register: the bus as sampled at the last edge ---
    ad_q = pci.ad_in if io_registers else Signal(intbv(0)[32:])
    idsel_q = pci.idsel_in if io_registers else Signal(bool(0))
    cbe_q = pci.cbe_in if io_registers else Signal(intbv(0xF)[4:])
    frame_q = Signal(bool(1))
    frame_qq = Signal(bool(1))
    irdy_q = Signal(bool(1))

    # --- bus outputs: next value and register (the pads may hold the latter) ---
    # next values: for each case of the pins (``rtl/pci/pci_control.py``), chosen by them
    chosen = TargetControlNext(t_state.S_IDLE)
    state_next, trdy_next, stop_next = chosen.state, chosen.trdy, chosen.stop
    devsel_next, drive_next, ad_oe_next = chosen.devsel, chosen.drive, chosen.ad_oe
    trdy_q, stop_q, devsel_q = Signal(bool(1)), Signal(bool(1)), Signal(bool(1))
    ad_out_q = Signal(intbv(0)[32:])
    ad_parity_q = Signal(bool(0))     # parity of the AD driven in the clock before
    perr_q = Signal(bool(1))

    # --- transaction state ---
    state = Signal(t_state.S_IDLE)
    is_read = Signal(bool(0))
    is_config = Signal(bool(0))
    space_mem = Signal(bool(0))
    single = Signal(bool(0))          # one data phase only: config, I/O, non-linear order
    first_phase = Signal(bool(0))     # no data phase completed yet
    first_pending = Signal(bool(0))   # first back-end request not answered yet
    fetching = Signal(bool(0))        # reads: more dwords may be requested
    address_fault = Signal(bool(0))   # address parity error, Parity Error Response set
    wait_count = Signal(intbv(0, min=0, max=16))
    # wait_count at its limits, registered with it (no compare before the timeout)
    initial_wait_over, subsequent_wait_over = Signal(bool(0)), Signal(bool(0))
    phase_addr = Signal(modbv(0)[width:])   # dword of the current data phase
    req_addr = Signal(modbv(0)[width:])     # dword of the next back-end request
    req_addr_stale = Signal(bool(0))  # req_addr still serves posted data of the last write
    io_byte = Signal(intbv(0)[2:])          # AD[1:0] of an I/O access

    # --- read data: the AD register, fed by a one-dword skid register B;
    # --- posted write data: ad_q, then the head (h) and second (s) entries.
    # B and s share one register: reads and writes never use it at once.
    # (``rtl/pci/pci_buffers.py``)
    b_valid = Signal(bool(0))
    wq_valid = Signal(bool(0))        # ad_q holds a posted dword
    h_valid, s_valid = Signal(bool(0)), Signal(bool(0))
    h_data, spare_data = Signal(intbv(0)[32:]), Signal(intbv(0)[32:])
    h_be, s_be = Signal(intbv(0)[4:]), Signal(intbv(0)[4:])
    write_done_q = Signal(bool(0))    # ad_q holds data of a completed write phase

    # --- configuration header (``rtl/pci/pci_config.py``), its lines named here ---
    config = ConfigSpace()
    config_write_q = config.write
    io_enable, mem_enable = config.io_enable, config.mem_enable
    parity_response, serr_enable = config.parity_response, config.serr_enable
    interrupt_disable, bar0, bar1, bar2 = config.interrupt_disable, config.bar0, config.bar1, config.bar2
    fatal = config.target_abort       # target abort now
    parity_error_q = config.parity_error  # a parity error was detected at the last edge

    # --- combinational ---
    # parity (``rtl/pci/pci_parity.py``): PAR out, and the next values the PAR pin decides
    parity = TargetParity(ad=ad_q, cbe=cbe_q, frame_q=frame_q, frame_qq=frame_qq, serr_enable=serr_enable,
                          parity_response=parity_response, write_done=write_done_q, perr_q=perr_q,
                          ad_out=ad_out_q, ad_out_parity_q=ad_parity_q, par_out=pci.par_out)
    address_phase, ad_out_parity = parity.address_phase, parity.ad_out_parity
    perr_next, perr_oe_next, serr_oe_next = parity.perr_next, parity.perr_oe_next, parity.serr_oe_next
    address_fault_next, parity_error_next = parity.address_fault_next, parity.parity_error_next
    claim = Signal(bool(0))
    claim_config, claim_io, claim_alias = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    read_command = Signal(bool(0))    # C/BE#[0] low in the address phase
    # next values of registers that a data phase (IRDY# pin) changes
    first_phase_next, phase_step = Signal(bool(0)), Signal(bool(0))
    write_done_next, config_write_next = Signal(bool(0)), Signal(bool(0))
    posting, wq_valid_next = Signal(bool(0)), Signal(bool(0))
    b_kept, b_valid_next = Signal(bool(0)), Signal(bool(0))
    start_addr = Signal(modbv(0)[width:])  # dword offset the address phase names
    got = Signal(bool(0))             # read data arrives at this edge
    accepted = Signal(bool(0))        # the back end takes a write at this edge
    # the request's conditions without the state, and the answers to them
    # as the state machine reads them in its hold and in its burst states
    # (see local_answer)
    first_ready, fetch_more = Signal(bool(0)), Signal(bool(0))
    hold_got, hold_accepted, hold_retry = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    burst_got = Signal(bool(0))
    draining = Signal(bool(0))        # posted data waits for the back end
    buffered_next = Signal(intbv(0, min=0, max=4))
    read_source = Signal(intbv(0)[32:])
    waiting = Signal(bool(0))         # a data phase waits for this target
    timeout = Signal(bool(0))
    # phase_addr is the last / the last but one dword of BAR1: registered
    # with phase_addr, so the state machine sees no address compare
    at_last, before_last = Signal(bool(0)), Signal(bool(0))

    # ------------------------------------------------------------ bus boundary
    boundary = TargetBoundary(
        ad=ad_q, cbe=cbe_q, idsel=idsel_q, frame_q=frame_q, frame_qq=frame_qq, irdy_q=irdy_q, trdy_q=trdy_q,
        trdy_next=trdy_next, stop_q=stop_q, stop_next=stop_next, devsel_q=devsel_q, devsel_next=devsel_next,
        drive_next=drive_next, ad_oe_next=ad_oe_next, ad_out=ad_out_q, read_source=read_source,
        ad_parity_q=ad_parity_q, ad_out_parity=ad_out_parity, perr_q=perr_q, perr_next=perr_next,
        perr_oe_next=perr_oe_next, serr_oe_next=serr_oe_next, parity_error_q=parity_error_q,
        parity_error_next=parity_error_next, irq=irq, interrupt_disable=interrupt_disable)
    boundary_unit = pci_boundary(clock, reset, pci, boundary, device=device, io_registers=io_registers)

    parity_unit = pci_parity(pci.par_in, parity, device=device)

    # ------------------------------------------------------------ decoding
    decoder = TargetDecode(t_state.S_IDLE, width, ad=ad_q, cbe=cbe_q, idsel=idsel_q, io_enable=io_enable,
                           mem_enable=mem_enable, bar0=bar0, bar1=bar1, bar2=bar2, state=state,
                           address_phase=address_phase, claim=claim, claim_config=claim_config,
                           claim_io=claim_io, claim_alias=claim_alias, read_command=read_command,
                           start_addr=start_addr)
    decode_unit = pci_decode(decoder, io_bits=io_bits, mem_bits=mem_bits, reg_bits=reg_bits)

    # A data phase completes when the IRDY# pin and TRDY# (trdy_q) are both
    # low; each register it changes has its next value in one LUT after the pin.
    phase_luts = [
        pin_lut(first_phase_next, lambda irdy, trdy, claimed, first: int(
            claimed or (first and not (not irdy and not trdy))),
            pci.irdy_in, trdy_q, claim, first_phase, device=device),
        pin_lut(phase_step, lambda irdy, trdy, claimed, mem: int(
            claimed or (not irdy and not trdy and mem)),
            pci.irdy_in, trdy_q, claim, space_mem, device=device),
        pin_lut(write_done_next, lambda irdy, trdy, read: int(not irdy and not trdy and not read),
                pci.irdy_in, trdy_q, is_read, device=device),
        pin_lut(config_write_next, lambda irdy, trdy, read, config: int(
            not irdy and not trdy and not read and config),
            pci.irdy_in, trdy_q, is_read, is_config, device=device),
        pin_lut(wq_valid_next, lambda irdy, posted: int(not irdy and posted), pci.irdy_in, posting,
                device=device),
        pin_lut(b_valid_next, lambda irdy, kept: int(irdy and kept), pci.irdy_in, b_kept, device=device)]

    # ------------------------------------------------------------ back end
    requests = TargetRequests(
        t_state.S_IDLE, width, req_addr=req_addr, state=state, address_fault=address_fault, io_byte=io_byte,
        cbe=cbe_q, ad=ad_q, first_pending=first_pending, is_config=is_config,
        req_addr_stale=req_addr_stale, is_read=is_read, fetching=fetching, b_valid=b_valid,
        trdy_q=trdy_q, frame_q=frame_q, irdy_q=irdy_q, h_valid=h_valid, wq_valid=wq_valid,
        space_mem=space_mem, h_data=h_data, h_be=h_be, fatal=fatal, first_ready=first_ready,
        fetch_more=fetch_more, draining=draining, got=got, accepted=accepted, hold_got=hold_got,
        hold_accepted=hold_accepted, hold_retry=hold_retry, burst_got=burst_got)
    request_unit = pci_requests(requests, local)

    @always_comb
    def read_path():
        if b_valid:
            read_source.next = spare_data
        elif is_config:
            read_source.next = config.rdata
        else:
            read_source.next = local.rdata

    # ------------------------------------------------------------ state machine
    target = TargetState(
        t_state.S_IDLE, state=state, single=single, at_last=at_last, before_last=before_last,
        is_read=is_read, is_config=is_config, first_phase=first_phase, fetching=fetching,
        timeout=timeout, fatal=fatal, trdy_q=trdy_q, stop_q=stop_q, devsel_q=devsel_q,
        drive=pci.devsel_oe, ad_oe=pci.ad_oe, claim=claim, claim_config=claim_config,
        claim_io=claim_io, read_command=read_command, b_valid=b_valid, burst_got=burst_got,
        buffered=buffered_next, room=local.room, hold_got=hold_got, hold_accepted=hold_accepted,
        hold_retry=hold_retry)
    next_state = pci_control(pci.frame_in, pci.irdy_in, target, chosen, device=device)

    transaction = TargetTransaction(
        t_state.S_IDLE, width, state_next=state_next, first_phase_next=first_phase_next,
        address_fault_next=address_fault_next, phase_step=phase_step, claim=claim, claim_config=claim_config,
        claim_io=claim_io, claim_alias=claim_alias, start_addr=start_addr, address_phase=address_phase, ad=ad_q,
        cbe=cbe_q, trdy_q=trdy_q, stop_q=stop_q, got=got, accepted=accepted, draining=draining, state=state,
        first_phase=first_phase, address_fault=address_fault, phase_addr=phase_addr, at_last=at_last,
        before_last=before_last, is_read=is_read, is_config=is_config, space_mem=space_mem, single=single,
        first_pending=first_pending, fetching=fetching, io_byte=io_byte, req_addr=req_addr,
        req_addr_stale=req_addr_stale, wait_count=wait_count, initial_wait_over=initial_wait_over,
        subsequent_wait_over=subsequent_wait_over, waiting=waiting, timeout=timeout)
    transaction_unit = pci_transaction(clock, reset, transaction, local, mem_bits=mem_bits)

    # ------------------------------------------------------------ data buffers
    buffers = TargetBuffers(
        t_state.S_IDLE, ad=ad_q, cbe=cbe_q, state=state, is_read=is_read, trdy_q=trdy_q,
        first_phase=first_phase, space_mem=space_mem, got=got, accepted=accepted, re=local.re,
        ready=local.ready, rdata=local.rdata, b_valid_next=b_valid_next, wq_valid_next=wq_valid_next,
        write_done_next=write_done_next, config_write_next=config_write_next, b_valid=b_valid,
        wq_valid=wq_valid, h_valid=h_valid, s_valid=s_valid, h_data=h_data, spare_data=spare_data,
        h_be=h_be, s_be=s_be, write_done_q=write_done_q, config_write_q=config_write_q, b_kept=b_kept,
        posting=posting, buffered=buffered_next)
    buffer_unit = pci_buffers(clock, reset, buffers)

    # ------------------------------------------------------------ configuration space
    header = pci_config(clock, reset, config, build=build)

    @always_comb
    def config_lines():
        config.index.next = phase_addr[6:0]
        config.data.next = ad_q
        config.cbe_n.next = cbe_q
        config.system_error.next = pci.serr_oe
        config.irq.next = irq

    return instances()
