"""Where one axis's direct pulses come from: the host's PULSE_COUNT, the PULSE
command or the homing sequencer."""
from myhdl import Signal, always_comb, block, intbv

from rtl.interfaces import DirectPulseCommand, Homing, PulseCommand


@block
def pulse_source(direct_mode, count_strobe, count_value, halt, estop, pulse_period, pulses, home, home_axis,
                 command, *, axis):
    """Direct pulses come from PULSE_COUNT in direct mode, from PULSE commands
    otherwise; none start while the guard halts.  While homing, the homing
    sequencer drives those of the axis it homes and the others wait.

    Ports: ``direct_mode`` (CONTROL.MODE), ``count_strobe`` and
    ``count_value`` (the axis's PULSE_COUNT write), ``halt`` (the guard's)
    and ``estop`` (the E-stop input, one of halt's two causes),
    ``pulse_period`` (the axis's PULSE_PERIOD), ``pulses``
    (``PulseCommand``: the axis takes ``count(axis)`` on a ``load`` with
    its ``mask`` bit set), ``home`` (``Homing``) and ``home_axis``
    (HOME.AXIS as taken); ``command`` (``DirectPulseCommand``: ``load``,
    ``asked``, ``count``, ``period`` and ``retarget`` out).  ``asked`` is
    ``load`` with the E-stop in place of the whole halt: the sequencer and
    homing take their busy from it, and a latched stop clears both itself,
    so the stop's path through the load stays out of their decisions.
    Parameter: ``axis`` (0 X).  All combinational:

        clock         _/~\\_/~\\_
        count_strobe  _/~~~\\___     direct mode
        command.load  _/~~~\\___     count = PULSE_COUNT's value
    """
    seq_count = pulses.count(axis)
    homeable = axis < 1 << len(home_axis)   # HOME.AXIS can name this axis

    @always_comb
    def choose_source():
        command.period.next = pulse_period
        command.retarget.next = home.busy and home.retarget and home_axis == axis
        if home.busy:
            command.load.next = home.load and home_axis == axis
            command.asked.next = home.load and home_axis == axis
            command.count.next = home.count
            command.period.next = home.period
        elif direct_mode:
            command.load.next = count_strobe and not halt
            command.asked.next = count_strobe and not estop
            command.count.next = count_value.signed()
        else:
            command.load.next = pulses.load and pulses.mask[axis]
            command.asked.next = pulses.load and pulses.mask[axis]
            command.count.next = seq_count

    @always_comb
    def choose_unhomed_source():
        # HOME.AXIS cannot name this axis: homing only holds it
        command.period.next = pulse_period
        command.retarget.next = False
        command.count.next = seq_count
        if home.busy:
            command.load.next = False
            command.asked.next = False
        elif direct_mode:
            command.load.next = count_strobe and not halt
            command.asked.next = count_strobe and not estop
            command.count.next = count_value.signed()
        else:
            command.load.next = pulses.load and pulses.mask[axis]
            command.asked.next = pulses.load and pulses.mask[axis]

    return choose_source if homeable else choose_unhomed_source


def pulse_source_ports(axis=0):
    """Fresh ports of ``pulse_source`` for conversion and benches."""
    period = DirectPulseCommand().period
    return dict(direct_mode=Signal(bool(0)), count_strobe=Signal(bool(0)),
                count_value=Signal(intbv(0)[len(DirectPulseCommand().remaining):]), halt=Signal(bool(0)),
                estop=Signal(bool(0)), pulse_period=Signal(intbv(int(period))[len(period):]),
                pulses=PulseCommand(max(2, axis + 1)),
                home=Homing(), home_axis=Signal(intbv(0)[1:]), command=DirectPulseCommand(), axis=axis)
