"""The PCI side: the bus as the cores see it, the pads, the target's back-end
bus and the bundles between the target's units."""
from myhdl import Signal, TristateSignal, intbv, modbv

from rtl.interfaces.bundle import adopt


class PciBus:
    """The target's view of a 32-bit PCI bus.

    ``*_in`` is what the target samples from the line, ``*_out`` what it would
    drive and ``*_oe`` whether it drives.  SERR# and INTA# are open-drain: the
    target drives them low (``*_oe`` high, ``*_out`` low) or not at all.
    """

    def __init__(self):
        self.ad_in = Signal(intbv(0)[32:])
        self.ad_out = Signal(intbv(0)[32:])
        self.ad_oe = Signal(bool(0))
        self.cbe_in = Signal(intbv(0xF)[4:])
        self.par_in = Signal(bool(0))
        self.par_out = Signal(bool(0))
        self.par_oe = Signal(bool(0))
        self.frame_in = Signal(bool(1))
        self.irdy_in = Signal(bool(1))
        self.idsel_in = Signal(bool(0))
        self.trdy_out = Signal(bool(1))
        self.trdy_oe = Signal(bool(0))
        self.devsel_out = Signal(bool(1))
        self.devsel_oe = Signal(bool(0))
        self.stop_out = Signal(bool(1))
        self.stop_oe = Signal(bool(0))
        self.perr_out = Signal(bool(1))
        self.perr_oe = Signal(bool(0))
        self.serr_out = Signal(bool(1))
        self.serr_oe = Signal(bool(0))
        self.inta_out = Signal(bool(1))
        self.inta_oe = Signal(bool(0))


class LocalBus:
    """The PCI target's back-end bus (one per card, both BARs).

    A request (``we`` or ``re``) with ``space``, ``addr``, ``be`` and, for a
    write, ``wdata`` is held until the clock edge at which the back end answers
    ``ready`` (the transfer happens at that edge; ``rdata`` is valid while
    ``ready`` is high) or ``retry`` (nothing happens: the back end cannot serve
    the request now and the target terminates with retry or disconnect).

    ``space`` 0 is the function registers (BAR0, I/O, and its alias BAR2,
    memory: the back end cannot tell them apart), 1 the memory BAR1 (data
    FIFO window).  ``addr`` is the byte offset inside the BAR, dword aligned.
    ``be`` are active-high byte enables.  ``write`` gives the direction of a
    request (1: ``we``) from the target's flip-flops, ahead of ``we``/``re``:
    a back end answers from it, ``space`` and its own state, so that the
    target's request logic and its reaction to the answer do not form one
    combinational loop through the back end.

    ``room`` (from the back end's flip-flops) is the back end's promise for
    space 1: while it is high, the next ``ROOM_PLACES`` writes to space 1
    will be answered ``ready``, not ``retry`` (possibly after wait clocks),
    whatever else happens.  A promise is never taken back: only the writes
    the back end takes use it up (``room`` may fall then), and a back end
    answers ``retry`` to a space-1 write only when no promise is open.  The
    target acknowledges a posted memory-write data phase on the bus only
    while ``room`` is high: the dwords it may still hold and the one it
    acknowledges are never more than ``ROOM_PLACES``.

        clock    _/~\\_/~\\_/~\\_/~\\_
        we       __/~~~~~~~~~~~\\___
        addr     --<  A0 >< A1 >---
        ready    ________/~~~~~\\___     A0 waits one clock, A1 none
        room     ~~~~~~~~~~~~~\\____     space 1 with four places at first: two left
    """

    ROOM_PLACES = 3   # writes a high ``room`` promises: what the target may have in flight

    def __init__(self, addr_width=16):
        self.addr_width = addr_width
        self.space = Signal(bool(0))
        self.addr = Signal(intbv(0)[addr_width:])
        self.be = Signal(intbv(0)[4:])
        self.wdata = Signal(intbv(0)[32:])
        self.we = Signal(bool(0))
        self.re = Signal(bool(0))
        self.write = Signal(bool(0))
        self.rdata = Signal(intbv(0)[32:])
        self.ready = Signal(bool(0))
        self.retry = Signal(bool(0))
        self.room = Signal(bool(0))


class PciPins:
    """The card's PCI pins, as the top level's ports (bus polarity).

    Every line is a ``TristateSignal``, as on the bus: an agent drives it or
    leaves it (the bench's bus model resolves the drivers and the pull-ups),
    and every pin can be the ``PACKAGE_PIN`` of an iCE40 I/O cell.  The
    target drives AD, PAR, TRDY#, DEVSEL#, STOP#, PERR#, SERR# and INTA#;
    it only reads C/BE#, FRAME#, IRDY# and IDSEL.  Only ``rtl/pci/pci_pads.py``
    joins these to a ``PciBus``.
    """

    def __init__(self):
        self.ad = TristateSignal(intbv(0)[32:])
        self.cbe = TristateSignal(intbv(0xF)[4:])
        self.par = TristateSignal(bool(0))
        self.frame = TristateSignal(bool(1))
        self.irdy = TristateSignal(bool(1))
        self.idsel = TristateSignal(bool(0))
        self.trdy = TristateSignal(bool(1))
        self.devsel = TristateSignal(bool(1))
        self.stop = TristateSignal(bool(1))
        self.perr = TristateSignal(bool(1))
        self.serr = TristateSignal(bool(1))
        self.inta = TristateSignal(bool(1))


class TargetControlNext:
    """Next state and control lines of the PCI target (``rtl/pci_slave.py``)
    for one case of the FRAME# and IRDY# pins; ``idle`` is the state enum's
    idle item.  The target computes one bundle per case from registers only,
    and the pins choose among them."""

    FIELDS = ("state", "trdy", "stop", "devsel", "drive", "ad_oe")

    def __init__(self, idle):
        self.state = Signal(idle)
        self.trdy = Signal(bool(1))
        self.stop = Signal(bool(1))
        self.devsel = Signal(bool(1))
        self.drive = Signal(bool(0))
        self.ad_oe = Signal(bool(0))


class ConfigSpace:
    """The PCI target's configuration header (``rtl/pci/pci_config.py``) and the
    transaction logic around it (``rtl/pci_slave.py``).

    To the header: ``write`` (a configuration write data phase completed at
    the last edge), ``index`` (its dword, 0..63), ``data`` and ``cbe_n`` (AD
    and C/BE# of that phase, bus polarity), the Status events
    ``target_abort`` (the target signals one now), ``system_error`` (SERR#
    driven) and ``parity_error`` (a parity error was detected at the last
    edge), and ``irq`` (Status.Interrupt Status).  From it: the Command bits
    the target obeys, the BARs as written (``bar0`` 16 bits of PC I/O space,
    ``bar1`` and ``bar2`` 32; the bits below a BAR's size stay 0), and ``rdata``, the dword ``index`` names as a configuration
    read returns it."""

    def __init__(self):
        self.write = Signal(bool(0))
        self.index = Signal(intbv(0)[6:])
        self.data = Signal(intbv(0)[32:])
        self.cbe_n = Signal(intbv(0xF)[4:])
        self.target_abort = Signal(bool(0))
        self.system_error = Signal(bool(0))
        self.parity_error = Signal(bool(0))
        self.irq = Signal(bool(0))
        self.io_enable = Signal(bool(0))
        self.mem_enable = Signal(bool(0))
        self.parity_response = Signal(bool(0))
        self.serr_enable = Signal(bool(0))
        self.interrupt_disable = Signal(bool(0))
        self.bar0 = Signal(intbv(0)[16:])
        self.bar1 = Signal(intbv(0)[32:])
        self.bar2 = Signal(intbv(0)[32:])
        self.rdata = Signal(intbv(0)[32:])


class TargetState:
    """What the PCI target's next-state logic (``rtl/pci/pci_control.py``) reads:
    the target's registers and its back end's answer, all settled before the
    FRAME# and IRDY# pins arrive.  ``state`` is the state enum (``idle`` its
    idle item); the target wires in the signals it has (``given``).

    Transaction: ``state``, ``single`` (one data phase only), ``at_last`` /
    ``before_last`` (the data phase is at / one before BAR1's last dword),
    ``is_read``, ``is_config``, ``first_phase``, ``fetching`` (reads: more
    dwords may be requested), ``timeout`` (the latency budget is spent),
    ``fatal`` (target abort now).  Its lines as driven: ``trdy_q``,
    ``stop_q``, ``devsel_q``, ``drive`` (DEVSEL#, TRDY#, STOP# driven),
    ``ad_oe``.  Claim: ``claim``, ``claim_config``, ``claim_io``,
    ``read_command`` (C/BE#[0] low in the address phase).  Data: ``b_valid``
    (the skid register holds a dword), ``burst_got`` (read data arrive in a
    burst), ``buffered`` (posted dwords held after this edge), ``room`` (the
    back end's write credit), ``hold_got``, ``hold_accepted``, ``hold_retry``
    (the first request answered read data, write taken, retry)."""

    BOOLS = ("single", "at_last", "before_last", "is_read", "is_config", "first_phase", "fetching",
             "timeout", "fatal", "trdy_q", "stop_q", "devsel_q", "drive", "ad_oe", "claim",
             "claim_config", "claim_io", "read_command", "b_valid", "burst_got", "room", "hold_got",
             "hold_accepted", "hold_retry")

    def __init__(self, idle, **given):
        adopt(self, given, state=Signal(idle), buffered=Signal(intbv(0, min=0, max=4)),
               **{name: Signal(bool(0)) for name in self.BOOLS})


class TargetDecode:
    """The PCI target's address decoder (``rtl/pci/pci_decode.py``); ``idle`` is
    the state enum's idle item, ``width`` the bits of a dword offset, and the
    target wires in the signals it has.

    From the target: ``ad``, ``cbe``, ``idsel`` (the input registers, bus
    polarity), ``io_enable``, ``mem_enable``, ``bar0``, ``bar1``, ``bar2`` (the
    configuration header), ``state``, ``address_phase`` (the input register
    holds an address).  To it: ``claim`` (an address phase this target
    claims), ``claim_config``, ``claim_io``, ``claim_alias`` (which space it
    hits: configuration, BAR0, BAR2; none of them is BAR1),
    ``read_command`` (C/BE#[0] low) and ``start_addr`` (the dword offset the
    address names in its space)."""

    def __init__(self, idle, width, **given):
        self.idle = idle
        adopt(self, given, ad=Signal(intbv(0)[32:]), cbe=Signal(intbv(0xF)[4:]), idsel=Signal(bool(0)),
               io_enable=Signal(bool(0)), mem_enable=Signal(bool(0)), bar0=Signal(intbv(0)[16:]),
               bar1=Signal(intbv(0)[32:]), bar2=Signal(intbv(0)[32:]), state=Signal(idle),
               address_phase=Signal(bool(0)), claim=Signal(bool(0)), claim_config=Signal(bool(0)),
               claim_io=Signal(bool(0)), claim_alias=Signal(bool(0)),
               read_command=Signal(bool(0)), start_addr=Signal(modbv(0)[width:]))


class TargetParity:
    """The PCI target's parity (``rtl/pci/pci_parity.py``).

    From the target's registers: ``ad``, ``cbe`` (the input registers, bus
    polarity), ``frame_q`` / ``frame_qq`` (FRAME# one and two edges back),
    ``serr_enable``, ``parity_response`` (Command bits), ``write_done`` (the
    input register holds a completed write data phase), ``perr_q`` (PERR# as
    driven), ``ad_out`` and ``ad_out_parity_q`` (the AD output register and
    the parity it had one clock before).  To them: ``address_phase`` (the
    input register holds an address), ``ad_out_parity``, ``par_out`` (PAR as
    driven), and the next values the PAR pin decides: ``perr_next``,
    ``perr_oe_next``, ``serr_oe_next``, ``address_fault_next`` (address
    parity error, Parity Error Response set), ``parity_error_next`` (Status:
    a parity error was detected)."""

    def __init__(self, **given):
        adopt(self, given, ad=Signal(intbv(0)[32:]), cbe=Signal(intbv(0xF)[4:]),
               frame_q=Signal(bool(1)), frame_qq=Signal(bool(1)), serr_enable=Signal(bool(0)),
               parity_response=Signal(bool(0)), write_done=Signal(bool(0)), perr_q=Signal(bool(1)),
               ad_out=Signal(intbv(0)[32:]), ad_out_parity_q=Signal(bool(0)),
               address_phase=Signal(bool(0)), ad_out_parity=Signal(bool(0)), par_out=Signal(bool(0)),
               perr_next=Signal(bool(1)), perr_oe_next=Signal(bool(0)), serr_oe_next=Signal(bool(0)),
               address_fault_next=Signal(bool(0)), parity_error_next=Signal(bool(0)))


class TargetBuffers:
    """The PCI target's data buffers (``rtl/pci/pci_buffers.py``); ``idle`` is
    the state enum's idle item, the target wires in the signals it has.

    From the target: ``ad``, ``cbe`` (input registers, bus polarity),
    ``state``, ``is_read``, ``trdy_q``, ``first_phase``, ``space_mem``, ``got``
    (read data arrive at this edge), ``accepted`` (the back end takes a
    write at this edge), the back end's ``re``, ``ready``, ``rdata``, and the
    next values the IRDY# pin decides: ``b_valid_next``, ``wq_valid_next``,
    ``write_done_next``, ``config_write_next``.  The buffers' registers:
    ``b_valid`` (the skid register holds a dword), ``wq_valid`` (``ad``
    holds a posted dword), ``h_valid``/``h_data``/``h_be`` (head entry),
    ``s_valid``/``spare_data``/``s_be`` (second entry; ``spare_data`` is also
    the skid register), ``write_done_q``, ``config_write_q`` (``ad`` holds
    the data of a completed write / configuration write phase).  To the
    target: ``b_kept``, ``posting`` (conditions for the IRDY# pin's LUTs) and
    ``buffered`` (posted dwords held after this edge)."""

    def __init__(self, idle, **given):
        bools = ("is_read", "trdy_q", "first_phase", "space_mem", "got", "accepted", "re", "ready",
                 "b_valid_next", "wq_valid_next", "write_done_next", "config_write_next", "b_valid",
                 "wq_valid", "h_valid", "s_valid", "write_done_q", "config_write_q", "b_kept", "posting")
        adopt(self, given, ad=Signal(intbv(0)[32:]), cbe=Signal(intbv(0xF)[4:]), state=Signal(idle),
               rdata=Signal(intbv(0)[32:]), h_data=Signal(intbv(0)[32:]), spare_data=Signal(intbv(0)[32:]),
               h_be=Signal(intbv(0)[4:]), s_be=Signal(intbv(0)[4:]), buffered=Signal(intbv(0, min=0, max=4)),
               **{name: Signal(bool(0)) for name in bools})


class TargetRequests:
    """The PCI target's request logic (``rtl/pci/pci_requests.py``); ``idle`` is
    the state enum's idle item, ``width`` the bits of a dword address; the
    target wires in the signals it has.

    From the target's registers: ``req_addr`` (dword of the next request),
    ``state``, ``address_fault``, ``io_byte`` (AD[1:0] of an I/O access),
    ``cbe``, ``ad`` (input registers), ``first_pending``, ``is_config``,
    ``req_addr_stale``, ``is_read``, ``fetching``, ``b_valid``, ``trdy_q``,
    ``frame_q``, ``irdy_q``, ``h_valid``, ``wq_valid``, ``space_mem``,
    ``h_data``, ``h_be`` (as in ``TargetState`` and ``TargetBuffers``).  To
    the target: ``fatal`` (target abort now), ``first_ready``,
    ``fetch_more`` (the request's conditions without the state),
    ``draining`` (posted data wait for the back end), ``got``, ``accepted``,
    and the answers ``hold_got``, ``hold_accepted``, ``hold_retry``,
    ``burst_got``."""

    def __init__(self, idle, width, **given):
        bools = ("address_fault", "first_pending", "is_config", "req_addr_stale", "is_read", "fetching",
                 "b_valid", "trdy_q", "frame_q", "irdy_q", "h_valid", "wq_valid", "space_mem", "fatal",
                 "first_ready", "fetch_more", "draining", "got", "accepted", "hold_got", "hold_accepted",
                 "hold_retry", "burst_got")
        adopt(self, given, req_addr=Signal(intbv(0)[width:]), state=Signal(idle),
               io_byte=Signal(intbv(0)[2:]), cbe=Signal(intbv(0xF)[4:]), ad=Signal(intbv(0)[32:]),
               h_data=Signal(intbv(0)[32:]), h_be=Signal(intbv(0)[4:]),
               **{name: Signal(bool(0)) for name in bools})


class TargetTransaction:
    """The PCI target's transaction registers (``rtl/pci/pci_transaction.py``);
    ``idle`` is the state enum's idle item, ``width`` the bits of a dword
    address; the target wires in the signals it has.

    From the target: ``state_next``, ``first_phase_next``,
    ``address_fault_next`` (next values the pins chose), ``phase_step`` (the
    claim, or a completed phase of a memory burst), ``claim``,
    ``claim_config``, ``claim_io``, ``claim_alias``, ``start_addr``,
    ``address_phase``, ``ad``, ``cbe`` (input registers), ``trdy_q``,
    ``stop_q``, ``got``, ``accepted``, ``draining`` (``TargetRequests``).  Its
    registers: ``state``, ``first_phase``, ``address_fault``, ``phase_addr``,
    ``at_last``, ``before_last`` (``phase_addr`` is the last / the last but
    one dword of BAR1), ``is_read``, ``is_config``, ``space_mem``,
    ``single``, ``first_pending``, ``fetching``, ``io_byte``, ``req_addr``,
    ``req_addr_stale``, ``wait_count``, ``initial_wait_over``,
    ``subsequent_wait_over``; and ``waiting`` (a data phase waits for this
    target), ``timeout`` (the latency rule ends it)."""

    def __init__(self, idle, width, **given):
        bools = ("first_phase_next", "address_fault_next", "phase_step", "claim", "claim_config", "claim_io",
                 "claim_alias", "address_phase", "trdy_q", "stop_q", "got", "accepted", "draining",
                 "first_phase", "address_fault", "at_last", "before_last", "is_read", "is_config", "space_mem",
                 "single", "first_pending", "fetching", "req_addr_stale", "initial_wait_over",
                 "subsequent_wait_over", "waiting", "timeout")
        adopt(self, given, state_next=Signal(idle), state=Signal(idle), start_addr=Signal(modbv(0)[width:]),
               ad=Signal(intbv(0)[32:]), cbe=Signal(intbv(0xF)[4:]), phase_addr=Signal(modbv(0)[width:]),
               req_addr=Signal(modbv(0)[width:]), io_byte=Signal(intbv(0)[2:]),
               wait_count=Signal(intbv(0, min=0, max=16)), **{name: Signal(bool(0)) for name in bools})


class TargetBoundary:
    """The PCI target's flip-flops at the bus (``rtl/pci/pci_boundary.py``);
    the target wires in the signals it has.

    Input registers (the bus at the last edge): ``ad``, ``cbe``, ``idsel``
    (the pads' own with ``io_registers``), ``frame_q``, ``frame_qq`` (two
    edges back), ``irdy_q``.  Output registers and their next values:
    ``trdy_q``/``trdy_next``, ``stop_q``/``stop_next``,
    ``devsel_q``/``devsel_next``, ``drive_next`` (TRDY#, STOP#, DEVSEL#
    driven), ``ad_oe_next``, ``ad_out`` (the AD register;
    ``read_source`` the dword it takes unless the master has yet to take the
    one on the bus), ``ad_parity_q``/``ad_out_parity``, ``perr_q``/
    ``perr_next``, ``perr_oe_next``, ``serr_oe_next``, ``parity_error_q``/
    ``parity_error_next``; ``irq`` and ``interrupt_disable`` (INTA#)."""

    def __init__(self, **given):
        words = ("ad", "ad_out", "read_source")
        ones = ("frame_q", "frame_qq", "irdy_q", "trdy_q", "trdy_next", "stop_q", "stop_next", "devsel_q",
                "devsel_next", "perr_q", "perr_next")
        zeros = ("idsel", "drive_next", "ad_oe_next", "ad_parity_q", "ad_out_parity", "perr_oe_next",
                 "serr_oe_next", "parity_error_q", "parity_error_next", "irq", "interrupt_disable")
        adopt(self, given, cbe=Signal(intbv(0xF)[4:]), **{name: Signal(intbv(0)[32:]) for name in words},
               **{name: Signal(bool(1)) for name in ones}, **{name: Signal(bool(0)) for name in zeros})
