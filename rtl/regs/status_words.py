"""The card's status registers: STATUS, INT_STATUS's events and INTA#, MARK_TAG,
MACHINE_STATUS, STOP_REASON, INPUT_RAW, INPUT_ACTIVE, POS_X and POS_Y."""
from myhdl import Signal, always_comb, always_seq, block, intbv

from models import registers as regmap
from rtl.interfaces import ERROR_BITS

INT_BITS = len(regmap.register("INT_STATUS").fields)


def _bit(name, field_name):
    return regmap.register(name).field(field_name).lsb


@block
def status_words(clock, reset, words, guard, conditioning, mark):
    """What the status registers read, from what the card's units report.

    Ports (``rtl/interfaces/``): ``words`` (``StatusWords``: the sources in,
    the register words and ``irq`` out); ``guard`` (``MachineGuard``: its
    latch, stop event, reason, limits and drive enable); ``conditioning``
    (``InputConditioning``: the raw and filtered inputs, ``changed``);
    ``mark`` (``MarkPort``: a reached MARK's tag).  No parameters: every
    field's place and width comes from ``models/registers.py``.

    STATUS.DONE is set the clock after ``busy`` falls and cleared while
    ``busy``; ``int_set`` raises an INT_STATUS bit for one clock per event
    (DONE as ``busy`` falls, LOW_WATER as the level drops below LOW_WATER,
    ERROR as the error code leaves 0, MARK, CLAMPED, STOPPED, INPUT, HOMED,
    INDEX, PROBE with their one-clock sources); the register word sets the bit at the next
    edge, and ``irq`` follows INT_STATUS & INT_ENABLE:
        clock        _/~\\_/~\\_/~\\_/~\\_/~\\_
        busy         ~~~~~~~\\_____________
        STATUS.DONE  _________/~~~~~~~~~~~
        int_set.DONE _______/~~~\\_________
        INT_STATUS   _________/~~~~~~~~~~~     DONE (written 1 clears it)
        irq          _________/~~~~~~~~~~~     INT_ENABLE.DONE = 1
    MACHINE_STATUS (the first ``XY_INPUTS`` inputs: ESTOP, X's and Y's), STOP_REASON,
    INPUT_RAW, INPUT_ACTIVE (every input of the card), MARK_TAG (the tag of the last MARK, taken
    with ``mark.strobe``), POS_X and POS_Y follow their sources.
    """
    busy_before, done_flag, low_before, error_before = (Signal(bool(0)) for _ in range(4))
    busy_bit, done_bit = _bit("STATUS", "BUSY"), _bit("STATUS", "DONE")
    quadrant_lsb, error_lsb = _bit("STATUS", "QUADRANT"), _bit("STATUS", "ERROR")
    empty_bit, full_bit = _bit("STATUS", "FIFO_EMPTY"), _bit("STATUS", "FIFO_FULL")
    level_lsb, stopped_bit = _bit("STATUS", "FIFO_LEVEL"), _bit("STATUS", "STOPPED")
    int_done, int_low, int_error = (_bit("INT_STATUS", f) for f in ("DONE", "LOW_WATER", "ERROR"))
    int_mark, int_clamp, int_stopped = (_bit("INT_STATUS", f) for f in ("MARK", "CLAMPED", "STOPPED"))
    int_input, int_homed = _bit("INT_STATUS", "INPUT"), _bit("INT_STATUS", "HOMED")
    int_index, int_probe = _bit("INT_STATUS", "INDEX"), _bit("INT_STATUS", "PROBE")
    raw_lsb, active_lsb = _bit("MACHINE_STATUS", "RAW"), _bit("MACHINE_STATUS", "ACTIVE")
    machine_stopped, machine_drive = _bit("MACHINE_STATUS", "STOPPED"), _bit("MACHINE_STATUS", "DRIVE_ENABLE")
    held_bit, stopping_bit = _bit("MACHINE_STATUS", "HELD"), _bit("MACHINE_STATUS", "STOPPING")
    reason_lsb, limits_lsb, axis_lsb = (_bit("STOP_REASON", f) for f in ("REASON", "LIMITS", "AXIS"))
    inputs, reason_bits, limit_bits = regmap.XY_INPUTS, len(guard.reason), len(guard.limits)
    axis_bits = len(guard.axis)
    status_bits, machine_bits, reason_word = len(words.status), len(words.machine_status), len(words.stop_reason)
    position_x, position_y = words.position_x, words.position_y

    @always_seq(clock.posedge, reset=reset)
    def remember():
        busy_before.next = words.busy
        if words.busy:
            done_flag.next = 0
        elif busy_before:
            done_flag.next = 1
        error_before.next = words.error_code != 0
        low_before.next = words.fifo_level < words.low_water
        if mark.strobe:
            words.mark_tag.next = mark.tag

    @always_comb
    def assemble_status():
        word = intbv(0)[status_bits:]
        word[busy_bit] = words.busy
        word[done_bit] = done_flag
        word[quadrant_lsb + 2:quadrant_lsb] = words.quadrant
        word[error_lsb + ERROR_BITS:error_lsb] = words.error_code
        word[empty_bit] = words.fifo_empty
        word[full_bit] = words.fifo_full
        word[stopped_bit] = guard.stopped
        word[status_bits:level_lsb] = words.fifo_level
        words.status.next = word

    @always_comb
    def detect_events():
        word = intbv(0)[INT_BITS:]
        word[int_done] = busy_before and not words.busy
        word[int_low] = words.fifo_level < words.low_water and not low_before
        word[int_error] = words.error_code != 0 and not error_before
        word[int_mark] = mark.strobe
        word[int_clamp] = words.clamped
        word[int_stopped] = guard.stop_event
        word[int_input] = conditioning.changed
        word[int_homed] = words.home_ended
        word[int_index] = words.index_fired
        word[int_probe] = words.probe_fired
        words.int_set.next = word

    @always_comb
    def request():
        words.irq.next = (words.int_status & words.int_enable) != 0

    @always_comb
    def assemble_machine():
        word = intbv(0)[machine_bits:]
        word[raw_lsb + inputs:raw_lsb] = conditioning.raw[inputs:]
        word[active_lsb + inputs:active_lsb] = conditioning.active[inputs:]
        word[machine_stopped] = guard.stopped
        word[machine_drive] = guard.drive_enable
        word[held_bit] = guard.held
        word[stopping_bit] = guard.stopping
        words.machine_status.next = word
        why = intbv(0)[reason_word:]
        why[reason_lsb + reason_bits:reason_lsb] = guard.reason
        why[limits_lsb + limit_bits:limits_lsb] = guard.limits
        why[axis_lsb + axis_bits:axis_lsb] = guard.axis
        words.stop_reason.next = why
        words.input_raw.next = conditioning.raw
        words.input_active.next = conditioning.active

    @always_comb
    def show_positions():
        words.pos_x.next = position_x[32:]
        words.pos_y.next = position_y[32:]

    return [remember, assemble_status, detect_events, request, assemble_machine, show_positions]

