"""The encoder registers: every axis's encoder and following error, the card's
time stamp and probe, wired to their register words (docs/encoders.md)."""
from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, intbv, modbv

from models import registers as regmap
from models.parameters import AXES
from rtl.encoder.encoder import encoder
from rtl.encoder.following_error import following_error
from rtl.encoder.probe import probe
from rtl.encoder.timestamp import timestamp
from rtl.interfaces import (EncoderPins, EncoderPort, EncoderRegisters, FollowingErrorPort, MotorPins, ProbePort,
                            RegisterWord, Timestamp, axis_suffixes, card_reset, named)


def _field(name, field_name):
    """A field of BAR0's ``name`` (PROBE_CONTROL) or of the block register ``name``."""
    return (regmap.register(name) if name == "PROBE_CONTROL" else regmap.axis_spec(name)).field(field_name)


def _span(name, field_name):
    item = _field(name, field_name)
    return item.lsb + item.width, item.lsb


@block
def encoder_block(clock, reset, pins, regs):
    """A build's encoder inputs (``encoders`` 1) behind their registers.

    Ports: ``pins`` (``MotorPins`` with encoder pins and ``probe``),
    ``regs`` (``EncoderRegisters``).  Each axis is an ``_axis_encoder``
    (``axis_x``, ...: its ``encoder`` and ``following_error``); the card has
    one ``timestamp`` (TIMESTAMP, and ENC_TIME's source) and one ``probe``
    (PROBE_CONTROL; it latches every axis's ENC_COUNT and POS into PROBE_ENC
    and PROBE_POS).  ``regs.ferror`` bit i is axis i's following-error stop
    flag (the machine guard's FOLLOWING_ERROR cause); ``index_fired`` is
    any axis's index latch, ``probe_fired`` the probe's, one clock each.

    Writes act at the edge after the register took them (their strobe):
        clock         _/~\\_/~\\_/~\\_
        ENC_CONTROL   _/~~~\\_______     bus write, INDEX_ARM 1
        strobe        _____/~~~\\___
        armed         _________/~~~~     INDEX_ARM reads 1
    """
    axes = regs.axes
    stamp = Timestamp()
    probe_port = ProbePort(axes)
    fired = [Signal(bool(0)) for _ in range(axes)]
    stops = [Signal(bool(0)) for _ in range(axes)]
    units = [named("timestamp", timestamp(clock, reset, stamp))]
    for axis, suffix in enumerate(axis_suffixes(axes)):
        setattr(probe_port, f"count_{suffix}", Signal(modbv(0)[32:]))   # the axis's ENC_COUNT
        units.append(named(f"axis_{suffix}", _axis_encoder(
            clock, reset, pins, regs, stamp.coming, probe_port, fired[axis], stops[axis], axis=axis)))
    units.append(named("probe", probe(clock, reset, probe_port)))
    control = regs.word("PROBE_CONTROL")
    arm_bit, invert_bit = _field("PROBE_CONTROL", "ARM").lsb, _field("PROBE_CONTROL", "INVERT").lsb
    filter_top, filter_lsb = _span("PROBE_CONTROL", "FILTER")
    timestamp_hw = regs.word("TIMESTAMP").hw
    any_fired = ConcatSignal(*reversed(fired)) if axes > 1 else fired[0]
    stop_flags = ConcatSignal(*reversed(stops)) if axes > 1 else stops[0]

    @always_comb
    def probe_registers():
        probe_port.pin.next = pins.probe
        probe_port.invert.next = control.value[invert_bit]
        probe_port.filter.next = control.value[filter_top:filter_lsb]
        probe_port.arm.next = control.strobe and control.value[arm_bit]
        control.hw.next = control.value
        control.hw.next[arm_bit] = probe_port.armed
        timestamp_hw.next = stamp.value
        regs.probe_fired.next = probe_port.fired
        regs.index_fired.next = any_fired != 0
        regs.ferror.next = stop_flags

    return units, probe_registers


@block
def _axis_encoder(clock, reset, pins, regs, coming, probe_port, fired, stop, *, axis):
    """Axis ``axis``'s encoder, following error and block registers."""
    port = EncoderPort(coming=coming, count=probe_port.signals("count", axis))
    check = FollowingErrorPort(count=port.count, zeroing=port.zeroing, stop=stop)
    pin_set = EncoderPins(a=pins.encoder(axis, "enc_a"), b=pins.encoder(axis, "enc_b"),
                          index=pins.encoder(axis, "enc_index"))
    control, status, scale = (regs.word(name, axis) for name in ("ENC_CONTROL", "ENC_STATUS", "ENC_SCALE"))
    count_hw, latch_hw, time_hw = (regs.word(name, axis).hw for name in ("ENC_COUNT", "ENC_INDEX_LATCH", "ENC_TIME"))
    ferror_hw, limit = regs.word("ENC_FERROR", axis).hw, regs.word("FERROR_LIMIT", axis).value
    probe_enc_hw, probe_pos_hw = regs.word("PROBE_ENC", axis).hw, regs.word("PROBE_POS", axis).hw
    position, pos_word = regs.positions.of(axis), probe_port.signals("pos", axis)
    latched_count, latched_pos = probe_port.signals("latched_count", axis), probe_port.signals("latched_pos", axis)
    mode_bit, zero_bit = _field("ENC_CONTROL", "MODE").lsb, _field("ENC_CONTROL", "INDEX_ZERO").lsb
    arm_bit, quad_bit = _field("ENC_CONTROL", "INDEX_ARM").lsb, _field("ENC_STATUS", "QUAD_ERROR").lsb
    direction_bit, quad_mask = _field("ENC_STATUS", "DIRECTION").lsb, _field("ENC_STATUS", "QUAD_ERROR").mask
    polarity_top, polarity_lsb = _span("ENC_CONTROL", "POLARITY")
    filter_top, filter_lsb = _span("ENC_CONTROL", "FILTER")
    errors_top, errors_lsb = _span("ENC_STATUS", "ERROR_COUNT")
    realigned = Signal(bool(0))

    @always_seq(clock.posedge, reset=reset)
    def realign():
        # the position was set at the last edge: re-align in the first clock that shows the new one
        realigned.next = regs.realign[axis]

    @always_comb
    def settings():
        port.mode.next = control.value[mode_bit]
        port.index_zero.next = control.value[zero_bit]
        port.polarity.next = control.value[polarity_top:polarity_lsb]
        port.filter.next = control.value[filter_top:filter_lsb]
        port.arm.next = control.strobe and control.value[arm_bit]
        port.clear_error.next = status.strobe and (status.value & quad_mask) != 0
        check.pos_low.next = position[len(check.pos_low):]
        check.scale.next = scale.value
        check.limit.next = limit
        check.align.next = scale.strobe or realigned
        check.clear_stop.next = regs.clear_stop
        pos_word.next = position[32:]
        fired.next = port.fired

    @always_comb
    def words():
        control.hw.next = control.value
        control.hw.next[arm_bit] = port.armed
        flags = intbv(0)[len(status.hw):]
        flags[quad_bit] = port.quad_error
        flags[direction_bit] = port.direction
        flags[errors_top:errors_lsb] = port.error_count
        status.hw.next = flags
        count_hw.next = port.count
        latch_hw.next = port.latch
        time_hw.next = port.time
        scale.hw.next = scale.value
        ferror_hw.next = check.error
        probe_enc_hw.next = latched_count
        probe_pos_hw.next = latched_pos

    return (named("encoder", encoder(clock, reset, pin_set, port)),
            named("following_error", following_error(clock, reset, check)), realign, settings, words)


@block
def realign_on(clear_position, zero, realign):
    """An axis's position is set (CLEAR_POSITION: every axis; homing's ``zero``: its bit) at the coming edge."""

    @always_comb
    def setting():
        if clear_position:
            realign.next = (1 << len(realign)) - 1
        else:
            realign.next = zero

    return setting


def encoder_block_ports(axes=AXES.default):
    """Fresh ports of ``encoder_block`` for benches: ``axes`` axes, a word per encoder register."""
    specs = [r for r in regmap.ENCODER_REGISTERS] + [
        r for r in regmap.axis_registers(axes, {"encoders": 1}) if r.option]
    words = {r.name: RegisterWord(r) for r in specs}
    return dict(clock=Signal(bool(0)), reset=card_reset(), pins=MotorPins(axes, encoders=1),
                regs=EncoderRegisters(axes, words))
