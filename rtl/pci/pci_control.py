"""The PCI target's next state and control lines, chosen by FRAME# and IRDY#.

The target's state machine (the paper's section 3; states in code spelling,
``docs/pci.md``) must register its next state and TRDY#, STOP#, DEVSEL# and
their drivers in the clock in which FRAME# and IRDY# arrive, with 7 ns of
set-up: no time for logic after the pins.  So the next values are computed
from registers for each case of the pins that can occur in a transaction
(a Shannon expansion on the two pins), and the pins only choose among them,
one LUT per bit (``rtl/pci/pin_pick.py``).
"""
from myhdl import Signal, always_comb, block, enum, instances

from rtl.interfaces import TargetControlNext
from rtl.pci.pin_pick import pin_coding, pin_pick

t_state = enum("S_IDLE", "S_CON_HOLD", "S_IO_HOLD", "S_MEM_HOLD", "S_READ_HOLD",
               "S_CONFIGURING", "S_RWING", "S_BACKOFF", "S_ENDING")


def state_triples(bit):
    """(F, I, B) of one bit of the state code: the pins change the state only
    when a data phase can end (Rwing, Configuring -> Ending or Backoff) and
    in Backoff (-> Ending)."""
    code = {item: int(getattr(t_state, item)._val, 2) >> bit & 1
            for item in ("S_RWING", "S_CONFIGURING", "S_BACKOFF", "S_ENDING")}
    ending, backoff = code["S_ENDING"], code["S_BACKOFF"]
    triples = {(0, 0, 0), (1, 1, 1), (backoff, ending, backoff)}
    for phase in (code["S_RWING"], code["S_CONFIGURING"]):
        triples |= {(phase, ending, phase), (phase, ending, backoff)}
    return triples


# (F, I, B) of the control lines (1 = deasserted); see ``control_case``:
# TRDY# ends high after the last phase, stays low while the master waits,
# and goes high or stays low after a completed phase; STOP# likewise, but
# it stays low while the master waits on a disconnect; DEVSEL# and the AD
# drive only change at the last phase (FRAME# deasserted); the drivers of
# DEVSEL#, TRDY#, STOP# only idle and ending, whatever the pins.
CONTROL_TRIPLES = dict(
    trdy={(0, 0, 0), (1, 1, 1), (0, 1, 0), (0, 1, 1)},
    stop={(0, 0, 0), (1, 1, 1), (0, 1, 0), (1, 1, 0)},
    devsel={(0, 0, 0), (1, 1, 1), (0, 1, 0)},
    drive={(0, 0, 0), (1, 1, 1)},
    ad_oe={(0, 0, 0), (1, 1, 1), (1, 0, 1)})


@block
def pci_control(frame_pin, irdy_pin, target, chosen, *, device):
    """Ports: ``frame_pin``, ``irdy_pin`` FRAME# and IRDY# as they arrive
    (bus polarity); ``target`` a ``TargetState`` (registers and the back
    end's answer); ``chosen`` a ``TargetControlNext``: the values the
    target's registers take at this edge.

    Parameters: ``device``, how the choosing LUTs are written
    (``rtl/pci/pin_lut.py``).

        edge      k
        target    --< settled from registers >--
        pins      FRAME#, IRDY# sampled at k choose
        chosen    --< next values for k >--
    """

    @block
    def control_case(irdy_asserted, frame_asserted, out):
        """Next values of the state and the target's control lines, should
        IRDY# and FRAME# be as given at this edge (``irdy_asserted``,
        ``frame_asserted``: Python bools).  Combinational, from registers and
        the back end's answer only; ``pin_pick`` chooses one for the registers.
        One process says what the next data phase can do (``outlook``), one
        drives the state, one TRDY# and STOP#, one DEVSEL# and the drivers.

            edge      k           k+1
            pins      IRDY#, FRAME# sampled at k choose
            out       --<next values for k>--
        """
        last_data = Signal(bool(0))        # the next data phase is the last one
        ready_for_phase = Signal(bool(0))  # the next data phase can carry data
        exhausted = Signal(bool(0))        # reads: no data will come any more

        @always_comb
        def outlook():
            done = irdy_asserted and not target.trdy_q      # a data phase completes
            if done:
                last_data.next = target.single or target.before_last
            else:
                last_data.next = target.single or target.at_last
            # The write credit: TRDY# for a posted phase needs a place
            # here and the back end's promise (``room``) to take
            # its next three writes.  This target asserts it only while
            # it holds at most two posted dwords (one when a phase
            # completes at the same edge), so at most three acknowledged
            # dwords ever wait for the back end, all promised; only its
            # own writes use the promise.  Without it the phase waits,
            # and the latency rules end the burst.
            buffer_room = target.buffered <= 1
            if done and not target.first_phase:
                buffer_room = target.buffered == 0
            if target.is_read:
                ready_for_phase.next = target.b_valid or target.burst_got
                exhausted.next = not target.b_valid and not target.burst_got and not target.fetching
            else:
                ready_for_phase.next = target.is_config or (buffer_room and target.room)
                exhausted.next = False

        @always_comb
        def next_state():
            done = irdy_asserted and not target.trdy_q
            hold = not irdy_asserted and not target.trdy_q  # TRDY# waits for the master
            out.state.next = target.state
            if target.state == t_state.S_IDLE:
                if target.claim:
                    if target.claim_config:
                        out.state.next = t_state.S_CON_HOLD
                    elif target.claim_io:
                        out.state.next = t_state.S_IO_HOLD
                    else:
                        out.state.next = t_state.S_MEM_HOLD
            elif (target.state == t_state.S_CON_HOLD or target.state == t_state.S_IO_HOLD
                  or target.state == t_state.S_MEM_HOLD or target.state == t_state.S_READ_HOLD):
                if target.fatal:
                    out.state.next = t_state.S_BACKOFF
                elif target.state == t_state.S_CON_HOLD:
                    out.state.next = t_state.S_CONFIGURING
                elif target.hold_got or target.hold_accepted:
                    out.state.next = t_state.S_RWING
                elif target.hold_retry or target.timeout:
                    out.state.next = t_state.S_BACKOFF
                elif target.is_read:
                    out.state.next = t_state.S_READ_HOLD
            elif target.state == t_state.S_CONFIGURING or target.state == t_state.S_RWING:
                if hold:
                    pass
                elif done and (not frame_asserted or not target.stop_q):
                    if frame_asserted:
                        out.state.next = t_state.S_BACKOFF
                    else:
                        out.state.next = t_state.S_ENDING
                elif ready_for_phase:
                    pass
                elif exhausted or target.timeout:
                    out.state.next = t_state.S_BACKOFF
            elif target.state == t_state.S_BACKOFF:
                if not frame_asserted:
                    out.state.next = t_state.S_ENDING
            else:
                out.state.next = t_state.S_IDLE

        @always_comb
        def next_trdy_stop():
            done = irdy_asserted and not target.trdy_q
            hold = not irdy_asserted and not target.trdy_q
            trdy = bool(target.trdy_q)
            stop = bool(target.stop_q)
            if (target.state == t_state.S_CON_HOLD or target.state == t_state.S_IO_HOLD
                    or target.state == t_state.S_MEM_HOLD or target.state == t_state.S_READ_HOLD):
                if target.fatal:
                    stop = False
                elif target.state == t_state.S_CON_HOLD:
                    trdy = False
                    stop = not frame_asserted
                elif target.hold_got or target.hold_accepted:
                    trdy = False
                    stop = not (last_data and frame_asserted)
                elif target.hold_retry or target.timeout:
                    stop = False
            elif target.state == t_state.S_CONFIGURING or target.state == t_state.S_RWING:
                if hold:
                    pass
                elif done and (not frame_asserted or not target.stop_q):
                    trdy = True
                    if not frame_asserted:
                        stop = True
                elif ready_for_phase:
                    trdy = False
                    stop = not (last_data and frame_asserted)
                elif exhausted or target.timeout:
                    trdy = True
                    stop = False
                else:
                    trdy = True
            elif target.state == t_state.S_BACKOFF:
                if not frame_asserted:
                    trdy = True
                    stop = True
            out.trdy.next = trdy
            out.stop.next = stop

        @always_comb
        def next_devsel_drive():
            # DEVSEL# and the drivers change only at the claim, a target
            # abort, the end of Ending, and the last data phase or FRAME#
            # gone in Backoff
            done = irdy_asserted and not target.trdy_q
            devsel = bool(target.devsel_q)
            drive = bool(target.drive)
            ad_oe = bool(target.ad_oe)
            if target.state == t_state.S_IDLE:
                # TRDY# and STOP# stay as they are: deasserted, as Ending
                # left them; so the address decode stays out of their logic
                drive = False
                ad_oe = False
                if target.claim:
                    drive = True
                    devsel = False
                    ad_oe = bool(target.read_command)
            elif target.state == t_state.S_ENDING:
                drive = False
            elif (target.state == t_state.S_CON_HOLD or target.state == t_state.S_IO_HOLD
                  or target.state == t_state.S_MEM_HOLD or target.state == t_state.S_READ_HOLD):
                if target.fatal:
                    devsel = True
            elif not frame_asserted and (target.state == t_state.S_BACKOFF or done):
                # Configuring and Rwing after their last phase, Backoff once FRAME# is gone
                devsel = True
                ad_oe = False
            out.devsel.next = devsel
            out.drive.next = drive
            out.ad_oe.next = ad_oe

        return outlook, next_state, next_trdy_stop, next_devsel_drive

    if_frame, if_irdy, if_both = (TargetControlNext(t_state.S_IDLE) for _ in range(3))
    control_cases = [control_case(False, True, if_frame), control_case(True, False, if_irdy),
                     control_case(True, True, if_both)]
    picks = [pin_pick(frame_pin, irdy_pin, if_frame.state, if_irdy.state, if_both.state,
                      chosen.state, [pin_coding(state_triples(bit)) for bit in range(len(target.state))],
                      device=device)]
    picks += [pin_pick(frame_pin, irdy_pin, getattr(if_frame, field), getattr(if_irdy, field),
                       getattr(if_both, field), picked, [pin_coding(CONTROL_TRIPLES[field])], device=device)
              for field, picked in (("trdy", chosen.trdy), ("stop", chosen.stop),
                                    ("devsel", chosen.devsel), ("drive", chosen.drive),
                                    ("ad_oe", chosen.ad_oe))]

    return instances()
