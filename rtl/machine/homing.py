"""Homing: seek the home switch, step off it slowly, zero the position where it releases."""
from myhdl import Signal, always_comb, always_seq, block, concat, enum, intbv, modbv

from models import registers as regmap
from models.parameters import AXES
from rtl.interfaces import Homing, card_reset

PHASE_IDLE, PHASE_SEEK, PHASE_RELEASE, PHASE_BACKOFF = (regmap.HOME_PHASES.index(name)
                                                        for name in ("IDLE", "SEEK", "RELEASE", "BACKOFF"))


@block
def homing(clock, reset, port):
    """One HOME at a time, on one axis, through that axis's direct pulses.

    Ports (``rtl/interfaces/``): ``port`` (``Homing``).  A ``start`` while
    ``idle`` homes the axis ``request`` names (AXIS_INDEX, 0 X .. 5 C, or
    when it is 0 AXIS, 0 X or 1 Y; NEGATIVE: the switch is towards negative
    positions); one the card lacks (``port.axes``) is REFUSED:

    1. SEEK: ``load`` HOME_SEARCH steps towards the switch at
       ``seek_period``; when the filtered switch is active, ``cut`` them.
    2. RELEASE: ``load`` HOME_SEARCH steps the other way at
       ``release_period``; when the switch is inactive again, ``retarget``
       the generator to HOME_BACKOFF steps and ``zero`` the axis's position
       in the same clock: the position counts the steps whose STEP rises
       from the next edge on.
    3. BACKOFF: the generator goes on with those steps at the period's count
       under way, so the first back-off step comes ``release_period`` after
       the last release step (none when 0); then wait until the pulse
       outputs are empty: DONE.

    If the generator runs out of steps and the outputs are empty before the
    switch trips (SEEK) or releases (RELEASE): NOT_FOUND, and the position is
    not zeroed.  A ``start`` while not ``idle`` (or while homing) is REFUSED
    and changes nothing else, also in the clock of a ``clear``.  ``clear``
    (a stop, SOFT_RESET) ends homing at once with neither DONE nor
    NOT_FOUND.  ``ended`` marks every end.  ``taken`` is what HOME reads
    (AXIS, NEGATIVE), ``state`` what HOME_STATUS reads: BUSY (also in the
    clock of ``start``: a read right after the HOME write never sees the
    HOME before it), DONE, NOT_FOUND, REFUSED, PHASE.  ``busy``, ``load``
    and ``count`` leave flip-flops, ``retarget`` one LUT after them (the
    filtered switch), so that the direct pulses' selection and the
    generator's 24-bit count start from registers.

    Switch trips in SEEK, releases in RELEASE (``count``: the next load's
    or retarget's, registered):
        clock     _/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_/~\\_
        home      _/~~~~~~~~~~~~~~~~~~~~~\\_________
        state     =SEEK==X=TURN=X=RELEASE===X=BACKOFF===
        cut       _/~~~\\___________________________
        load      _____/~~~\\_______________________
        count     =search====X=backoff=============
        retarget  _____________________/~~~\\_______
        zero      _____________________/~~~\\_______
    """
    state_t = enum("IDLE", "SEEK_LOAD", "SEEK", "TURN", "RELEASE", "BACKOFF", "SETTLE")
    state, following = Signal(state_t.IDLE), Signal(state_t.IDLE)   # following: the state after this clock
    # What the direct pulses take from the state, each in a flip-flop of its
    # own (loaded from ``following``, so in step with ``state``): the
    # source's selection and the generator's decision then start from a
    # register instead of a decoded state.
    releasing = Signal(bool(0))   # state == RELEASE
    home_spec = regmap.register("HOME")
    index_field = home_spec.field("AXIS_INDEX")
    axes = port.axes
    if len(port.home) != axes or len(port.zero) != axes:
        raise ValueError(f"homing: home and zero of {len(port.home)}, {len(port.zero)} bits for {axes} axes")
    axis, asked = (Signal(intbv(0)[index_field.width:]) for _ in range(2))
    negative, valid = Signal(bool(0)), Signal(bool(0))
    slot_bits = max(1, (axes - 1).bit_length())
    slot = Signal(intbv(0)[slot_bits:])   # the homed axis as an index of ``home`` and ``zero``, as wide as they ask
    done, not_found, refused = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    switch, positive, seeking, seek_next = (Signal(bool(0)) for _ in range(4))
    opened, gave_up, finished = (Signal(bool(0)) for _ in range(3))   # opened: the switch released in RELEASE
    # The count of the next load or retarget, |distance| or its two's
    # complement (one adder, ~magnitude + 1), and the period are registered:
    # the direct-pulse generator's own adders then start from flip-flops.
    count_bits = len(port.count)
    magnitude, operand, addend = (Signal(intbv(0)[count_bits:]) for _ in range(3))
    signed_count = Signal(modbv(0)[count_bits:])
    backoff_pad, search_pad = count_bits - len(port.backoff), count_bits - len(port.search)
    phase = Signal(intbv(0)[2:])
    axis_bit, negative_bit = (home_spec.field(name).lsb for name in ("AXIS", "NEGATIVE"))
    index_lsb, index_msb = index_field.lsb, index_field.lsb + index_field.width
    busy_bit, done_bit, not_found_bit, refused_bit, phase_lsb = (
        regmap.register("HOME_STATUS").field(name).lsb for name in ("BUSY", "DONE", "NOT_FOUND", "REFUSED", "PHASE"))

    @always_comb
    def ask():
        # AXIS_INDEX names the axis; 0 leaves it to AXIS (X or Y), as a two-axis host writes HOME
        if port.request[index_msb:index_lsb] != 0:
            asked.next = port.request[index_msb:index_lsb]
            valid.next = port.request[index_msb:index_lsb] < axes
        else:
            asked.next = concat(intbv(0)[index_field.width - 1:], port.request[axis_bit])
            valid.next = True   # X or Y: every card has them

    @always_comb
    def index():
        slot.next = axis[slot_bits:]

    @always_comb
    def select():
        switch.next = 0
        if axis < axes:
            switch.next = port.home[slot]
        seeking.next = state == state_t.SEEK_LOAD or state == state_t.SEEK
        seek_next.next = state == state_t.IDLE or state == state_t.SEEK_LOAD or (state == state_t.SEEK and not switch)
        # the load after IDLE is the seek's, after SEEK the release's; the retarget in RELEASE the back-off's
        if state == state_t.TURN or state == state_t.RELEASE:
            magnitude.next = concat(intbv(0)[backoff_pad:], port.backoff)
        else:
            magnitude.next = concat(intbv(0)[search_pad:], port.search)

    @always_comb
    def command():
        # the seek goes towards the switch, the release and the back-off away from it
        if state == state_t.IDLE:
            positive.next = not port.request[negative_bit]
        else:
            positive.next = negative

    @always_comb
    def sign():
        if positive:
            operand.next = magnitude
            addend.next = 0
        else:
            operand.next = ~magnitude
            addend.next = 1

    @always_comb
    def negate():
        signed_count.next = operand + addend

    @always_seq(clock.posedge, reset=reset)
    def next_load():
        port.count.next = signed_count.signed()
        if seek_next:
            port.period.next = port.seek_period
        else:
            port.period.next = port.release_period

    @always_comb
    def edges():
        drained = not port.pulse_busy and not port.outputs_active
        released = releasing and not switch
        opened.next = released
        gave_up.next = drained and ((state == state_t.SEEK and not switch) or (state == state_t.RELEASE and switch))
        finished.next = state == state_t.SETTLE and not port.outputs_active
        port.cut.next = state == state_t.SEEK and switch
        port.retarget.next = released
        zero = intbv(0)[axes:]
        if released and axis < axes:
            zero[slot] = 1
        port.zero.next = zero

    @always_comb
    def phases():
        if state == state_t.IDLE:
            phase.next = PHASE_IDLE
        elif seeking:
            phase.next = PHASE_SEEK
        elif state == state_t.TURN or state == state_t.RELEASE:
            phase.next = PHASE_RELEASE
        else:
            phase.next = PHASE_BACKOFF

    @always_comb
    def show():
        taken = intbv(0)[len(port.taken):]
        taken[axis_bit] = axis[0]
        taken[negative_bit] = negative
        taken[index_msb:index_lsb] = axis
        port.taken.next = taken
        word = intbv(0)[len(port.state):]
        # a read in the clock the HOME write is taken shows it busy already
        word[busy_bit] = state != state_t.IDLE or port.start
        word[done_bit] = done
        word[not_found_bit] = not_found
        word[refused_bit] = refused
        word[phase_lsb + 2:phase_lsb] = phase
        port.state.next = word

    @always_seq(clock.posedge, reset=reset)
    def outcome():
        port.ended.next = 0
        if port.clear:
            if port.start:
                # a HOME in the clock a stop (or SOFT_RESET) clears the card:
                # the card is not idle, so it is refused, and says so
                done.next = 0
                not_found.next = 0
                refused.next = 1
                port.ended.next = 1
        elif state == state_t.IDLE:
            if port.start:
                axis.next = asked
                negative.next = port.request[negative_bit]
                done.next = 0
                not_found.next = 0
                refused.next = not port.idle or not valid
                port.ended.next = not port.idle or not valid
        else:
            if port.start:
                refused.next = 1
                port.ended.next = 1
            if gave_up:
                not_found.next = 1
                port.ended.next = 1
            elif finished:
                done.next = 1
                port.ended.next = 1

    @always_comb
    def transition():
        following.next = state
        if port.clear or gave_up or finished:
            following.next = state_t.IDLE
        elif state == state_t.IDLE:
            if port.start and port.idle and valid:
                following.next = state_t.SEEK_LOAD
        elif state == state_t.SEEK_LOAD:
            following.next = state_t.SEEK
        elif state == state_t.SEEK:
            if switch:
                following.next = state_t.TURN
        elif state == state_t.TURN:
            following.next = state_t.RELEASE
        elif state == state_t.RELEASE:
            if opened:
                if port.backoff != 0:
                    following.next = state_t.BACKOFF
                else:
                    following.next = state_t.SETTLE
        elif state == state_t.BACKOFF:
            if not port.pulse_busy:
                following.next = state_t.SETTLE

    @always_seq(clock.posedge, reset=reset)
    def sequence():
        state.next = following
        port.busy.next = following != state_t.IDLE
        port.load.next = following == state_t.SEEK_LOAD or following == state_t.TURN
        releasing.next = following == state_t.RELEASE

    return ask, index, select, command, sign, negate, next_load, edges, phases, show, outcome, transition, sequence


def homing_ports(axes=AXES.default):
    """Fresh ports of ``homing`` for conversion and benches, of a card of ``axes`` axes."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), port=Homing(axes))
