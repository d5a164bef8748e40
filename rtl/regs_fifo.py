"""Function registers, data FIFO, instruction register and pulse outputs of the card."""
from myhdl import ConcatSignal, Signal, always_comb, always_seq, block, concat, intbv

from models import registers as regmap
from models.axes import AXIS_NAMES
from models.dda_build import variants_choice
from models.parameters import COORD_WIDTH, Build
from rtl.interfaces import (AliasBlock, AxesCommand, AxisBlock, AxisPulses, DdaPort, DirectPulseCommand, EncoderRegisters, FeedPort,
                            FifoRead, Homing,
                            InputConditioning, LocalBus, MachineGuard, MarkPort, MotorPins, PulseCommand, PulseControl,
                            RampSettings, ReadChain, RegisterBus, RegisterWord, SequencerControl, SetPort, StatusWords,
                            StepPositions, StepRequest, card_reset)
from rtl.machine.homing import homing
from rtl.machine.input_filter import input_filter
from rtl.machine.machine_guard import machine_guard
from rtl.regs.alias_block import alias_block
from rtl.regs.axis_block import axis_block
from rtl.regs.axis_request import axis_request
from rtl.regs.direct_pulse import direct_pulse
from rtl.regs.encoder_block import encoder_block, realign_on
from rtl.regs.feed_rate import feed_rate
from rtl.regs.pulse_out import pulse_out
from rtl.regs.pulse_source import pulse_source
from rtl.regs.reg_word import reg_word, zero_extend
from rtl.regs.sequencer import sequencer
from rtl.regs.status_words import status_words
from rtl.regs.sync_fifo import sync_fifo


def _bit(name, field_name):
    return regmap.register(name).field(field_name).lsb


# ``build``: the card's ``Build`` (``models/parameters.py``); the parameters the
# docstring names are its fields, its coord_width and variants those of ``dda``
# (the docstring is gen/regs_fifo.v's header).
@block
def regs_fifo(clock, reset, local, dda, axes_cmd, steps, pins, irq, core_clear, *, build=Build()):
    """The card behind the PCI target: everything of the paper's figure 1 but the DDA.

    Ports: ``local`` (the target's back end; space 0 = the registers of
    ``models/registers.py``: BAR0's at their offsets, beyond them BAR2's
    per-axis blocks, X's and Y's answered by BAR0's register words
    (``reg_word``'s ``aliases``); space 1 = the FIFO: every data phase with a byte
    enabled pushes one word; ``local.room`` is high while the FIFO has
    three free places, the promise the target needs before it acknowledges
    a posted dword, and a write to a full FIFO answers ``retry``, so the
    target retries or disconnects and no word is lost); ``dda`` (drives the
    interpolator's command, reads its status); ``axes_cmd`` (the plane and
    a LINE's displacements for the N-axis interpolator, ``AxesCommand``);
    ``steps`` (the interpolator's step requests, every axis); ``pins`` (STEP/DIR and DRIVE_ENABLE out, the machine
    inputs in: ``input_filter`` and ``machine_guard`` watch them, and a
    stop resets and holds the sequencer, the direct pulses and the pulse
    outputs and resets the DDA; the FIFO keeps its words until
    COMMAND.CLEAR_STOP empties it, docs/machine.md); ``irq`` (level, to
    INTA#: INT_STATUS & INT_ENABLE, from ``status_words``, which also
    assembles STATUS, MACHINE_STATUS, STOP_REASON, MARK_TAG and POS_X/Y;
    ``axis_block`` holds the positions a POS_X read captures); every axis
    has its direct pulses (``pulse_source``, ``direct_pulse``);
    ``core_clear`` (one registered clock on
    COMMAND.SOFT_RESET or a stop: the top resets the DDA with it).
    Parameters (``models/parameters.py``): ``fifo_depth`` (words, a power of
    two; 512 words of 32 bits are four iCE40 4-Kbit block RAMs);
    ``clock_hz`` and ``device`` only set capability registers (CLOCK_HZ,
    BUILD; FIFO_SIZE, BUILD.COORD_WIDTH and BUILD.DDA_VARIANTS come from
    ``fifo_depth``, ``dda.coord_width`` and ``dda.variants``: the
    sequencer refuses an ARC that names a variant the DDA lacks).

    Local bus: I/O and FIFO writes complete in the clock they are requested,
    a full FIFO answers retry; an I/O write reaches the registers one clock
    later, and a request in that clock waits one clock (PCI never asks that
    soon); an I/O read waits one clock: the registers' read chain ends in a
    register (``read_word``), so the PCI target's AD register is fed from a
    flip-flop, and a read's side effect (POS_X captures the other axes' POS) happens once, at
    the edge that takes the word; ``room`` is the FIFO's own flag (three
    places free or more):
        clock    _/~\\_/~\\_/~\\_/~\\_
        we       _/~~~~~~~~~~~\\___
        space    _/~~~~~~~~~~~\\___     memory BAR
        ready    _/~~~~~~~\\_______
        retry    _________/~~~\\___     FIFO full
        room     ~~~~~\\___________     three places free at first

        re       _/~~~~~~~\\_______     I/O BAR
        ready    _____/~~~\\_______     read_word taken at the first edge
    """
    if (dda.coord_width, variants_choice(dda.variants)) != (build.coord_width, build.variants):
        raise ValueError(f"regs_fifo: dda is a {dda.coord_width}-bit DdaPort of the variants "
                         f"{variants_choice(dda.variants)}, the build says {build.coord_width} and {build.variants}")
    if (pins.axes, steps.axes, axes_cmd.axes, pins.encoders) != (build.axes,) * 3 + (build.encoders,):
        raise ValueError(f"regs_fifo: pins, steps and axes_cmd of {pins.axes}, {steps.axes} and {axes_cmd.axes} axes, "
                         f"pins with encoders {pins.encoders}; the build says {build.axes} and {build.encoders}")
    fifo_depth, axes = build.fifo_depth, build.axes
    # BAR0's registers of the build (the input registers with the bits of its inputs: ``built_register``),
    # then those only the per-axis blocks have (models/registers.py)
    specs = (tuple(regmap.built_register(r, axes) for r in regmap.bar0_registers(build.as_dict()))
             + regmap.axis_registers(axes, build.as_dict()))
    io_write, io_read, push = (Signal(bool(0)) for _ in range(3))
    # a register read: the word is taken at the edge after the request, answered ready in the next clock
    read_waited, read_word = Signal(bool(0)), Signal(intbv(0)[32:])
    byte_mask = Signal(intbv(0)[32:])
    # an I/O write reaches the registers one clock after the bus transfer (see write_stage)
    io_written = Signal(bool(0))
    written_addr = Signal(intbv(0)[len(local.addr):])
    written_data = Signal(intbv(0)[32:])
    # the byte enables as a mask, as far as a register merges bytes with its own (the RW registers)
    merged_width = max(spec.width for spec in specs if spec.access == "RW")
    written_mask = Signal(intbv(0)[merged_width:])
    fifo_dout = Signal(intbv(0)[32:])
    fifo_pop, fifo_empty, fifo_full = Signal(bool(0)), Signal(bool(1)), Signal(bool(0))
    fifo_level = Signal(intbv(0, min=0, max=fifo_depth + 1))
    level_bits = regmap.register("STATUS").field("FIFO_LEVEL").width
    level_wide = Signal(intbv(0)[level_bits:])

    # RO registers read the hardware, the capability registers the build
    words = {r.name: RegisterWord(r, regmap.build_word(r, build.as_dict()) if r.access == "RO" else 0) for r in specs}
    values = {name: word.value for name, word in words.items()}
    hw = {name: word.hw for name, word in words.items()}
    strobes = {name: word.strobe for name, word in words.items()}
    chain = [ReadChain() for _ in range(len(specs) + 1)]
    register_bus = RegisterBus(len(local.addr), merged_width, addr=local.addr, write_addr=written_addr,
                               write=io_written, byte_mask=written_mask, wdata=written_data)
    # X's and Y's per-axis blocks in BAR2: their BAR0 registers answer there too, each block tested once
    blocks = {}
    aliases = {}
    for bar2, bar0 in regmap.axis_aliases().items():
        base = bar2 - (bar2 - regmap.AXIS_BLOCK_BASE) % regmap.AXIS_STRIDE
        aliases[bar0] = dict(alias=blocks.setdefault(base, AliasBlock(base, regmap.AXIS_STRIDE)),
                             alias_offset=bar2 - base)

    set_port, mark = SetPort(), MarkPort()
    # named at this level, as the formal harness (formal/props) and the waves know them
    set_strobe, set_index, set_value = set_port.strobe, set_port.index, set_port.value
    sequencer_clear = Signal(bool(0))
    seq_control = SequencerControl(clear=sequencer_clear)
    enable, clear_error, error_code = seq_control.enable, seq_control.clear_error, seq_control.error_code
    seq_busy, motion_run, discard_on_clear = seq_control.busy, seq_control.motion_run, seq_control.discard_on_clear
    clear_position, direct_mode = Signal(bool(0)), Signal(bool(0))
    pulses = PulseCommand(axes)
    pulse_busy, outputs_busy, seq_load = pulses.busy, pulses.outputs_busy, pulses.load
    # every axis's step requests: the interpolator's ``steps`` and the direct pulses of every axis
    requests, granted = AxisPulses(axes), AxisPulses(axes)
    requested = ConcatSignal(*reversed([requests.step(axis) for axis in range(axes)]))
    halt, pulse_clear, clear_stop, releasing = (Signal(bool(0)) for _ in range(4))
    home_idle, direct_clear = Signal(bool(0)), Signal(bool(0))
    home_zero = Signal(intbv(0)[axes:])
    step_mode = values["STEP_MODE"]   # named at this level, as the formal harnesses know it
    outputs = PulseControl(axes, clear=pulse_clear, clear_position=clear_position, zero=home_zero,
                           width=values["STEP_WIDTH"], space=values["STEP_SPACE"], mode=step_mode,
                           setup=values["DIR_SETUP"], hold=values["DIR_HOLD"],
                           **{f"polarity_{name.lower()}": values["DIR_POLARITY"](axis)
                              for axis, name in enumerate(AXIS_NAMES[:axes])})
    out_ready, out_active = outputs.ready, outputs.active
    position = StepPositions(axes)
    axis_names = AXIS_NAMES[:axes]
    direct = [DirectPulseCommand(clear=direct_clear, remaining=hw[f"PULSE_COUNT_{name}"]) for name in axis_names]
    settled, direct_ready = Signal(bool(0)), Signal(bool(1))   # guard.held; direct pulses wait while stopping
    direct_out = [StepRequest(ready=direct_ready) for _ in axis_names]
    direct_busy = ConcatSignal(*reversed([d.busy for d in direct]))
    direct_running = ConcatSignal(*reversed([d.running for d in direct]))
    direct_asked = ConcatSignal(*reversed([d.asked for d in direct]))
    direct_request, direct_dir = [o.step for o in direct_out], [o.dir for o in direct_out]
    axis_regs = AxisBlock(axes, len(local.addr), addr=local.addr, read=io_read, positions=position,
                          pos_words=[hw[f"POS_{name}"] for name in axis_names[2:]])
    feed = FeedPort(dda.coord_width, run=motion_run, stop_left=dda.stop_left)
    tick, hold = feed.tick, feed.hold
    fifo_flush, soft_reset_taken = Signal(bool(0)), Signal(bool(0))
    requested_before, out_active_before = Signal(bool(0)), Signal(bool(0))
    any_busy, busy_but_loads = Signal(bool(0)), Signal(bool(0))
    pos_y_snapshot = axis_regs.held.y

    drive_bit, hold_bit = _bit("MACHINE_CONTROL", "DRIVE_ENABLE"), _bit("MACHINE_CONTROL", "HOLD")
    drive_cleared, drive_mask = hw["MACHINE_CONTROL"], regmap.register("MACHINE_CONTROL").field("DRIVE_ENABLE").mask
    watchdog_left = hw["WATCHDOG"]   # named here, as the formal harness knows it
    # on ECP5 the block RAM's 5.8 ns clock-to-output would start the sequencer's decisions on the word
    units = [sync_fifo(clock, reset, push, local.wdata, fifo_pop, fifo_dout, fifo_flush, fifo_level,
                       fifo_empty, fifo_full, local.room, depth=fifo_depth, output_register=build.device == "ecp5")]
    for i, spec in enumerate(specs):
        units.append(reg_word(clock, reset, bus=register_bus, set_port=set_port, word=words[spec.name],
                              chain_in=chain[i], chain_out=chain[i + 1], **aliases.get(spec.offset, {})))
    units += [alias_block(register_bus, block_hit) for block_hit in blocks.values()]
    units.append(sequencer(clock, reset, fifo=FifoRead(dout=fifo_dout, empty=fifo_empty, pop=fifo_pop),
                           control=seq_control, dda=dda, axes_cmd=axes_cmd, pulses=pulses, set_port=set_port, mark=mark,
                           set_indices=tuple(regmap.SET_TARGETS)))
    settings = RampSettings(target=values["FEED_RATE"], ramp_start=values["RAMP_START"],
                            ramp_step=values["RAMP_STEP"])
    units.append(feed_rate(clock, reset, settings=settings, feed=feed))
    for axis in range(axes):
        units.append(direct_pulse(clock, reset, command=direct[axis], out=direct_out[axis]))
    units.append(axis_block(clock, reset, axis_regs, axes=axes))
    units.append(pulse_out(clock, reset, request=granted, control=outputs, pins=pins, position=position))
    conditioning = InputConditioning(axes, pins=ConcatSignal(*reversed(pins.inputs())),
                                     polarity=values["INPUT_POLARITY"],
                                     samples=values["INPUT_FILTER"], tick=values["INPUT_TICK"])
    guard = MachineGuard(axes, active=conditioning.active, drive_request=values["MACHINE_CONTROL"](drive_bit),
                         clear_stop=clear_stop, held=settled, pulsing=outputs.pulsing,
                         watchdog_load=strobes["WATCHDOG"], watchdog_timeout=values["WATCHDOG"], halt=halt,
                         drive_enable=pins.drive_enable, watchdog_left=watchdog_left)
    # every axis's filtered home input, bit i axis i's
    home_inputs = ConcatSignal(*reversed([conditioning.active(regmap.home_input(axis)) for axis in range(axes)]))
    home = Homing(axes, start=strobes["HOME"], request=values["HOME"], seek_period=values["HOME_SEEK_PERIOD"],
                  release_period=values["HOME_RELEASE_PERIOD"], backoff=values["HOME_BACKOFF"],
                  search=values["HOME_SEARCH"], idle=home_idle, clear=core_clear, pulse_busy=pulse_busy,
                  outputs_active=out_active, zero=home_zero, taken=hw["HOME"], state=hw["HOME_STATUS"],
                  home=home_inputs)
    units += [input_filter(clock, reset, conditioning),
              machine_guard(clock, reset, guard, requests, granted, ferror_axes=axes if build.encoders else 0),
              homing(clock, reset, home)]
    index_fired, probe_fired = Signal(bool(0)), Signal(bool(0))
    if build.encoders:   # the encoder inputs (docs/encoders.md); their realignment follows the positions' setting
        encoders = EncoderRegisters(axes, {r.name: words[r.name] for r in specs if r.option == "encoders"},
                                    positions=position, clear_stop=clear_stop, index_fired=index_fired,
                                    probe_fired=probe_fired)
        units += [encoder_block(clock, reset, pins, encoders), realign_on(clear_position, home_zero, encoders.realign),
                  zero_extend(encoders.ferror, guard.ferror)]

    read_end, clamp_end = chain[-1].data, chain[-1].clamped
    control, command, command_strobe = values["CONTROL"], values["COMMAND"], strobes["COMMAND"]
    machine_control, ramp_step = values["MACHINE_CONTROL"], values["RAMP_STEP"]
    enable_bit, mode_bit = _bit("CONTROL", "ENABLE"), _bit("CONTROL", "MODE")
    reset_bit, clear_bit, zero_bit, release_bit = (_bit("COMMAND", f) for f in ("SOFT_RESET", "CLEAR_ERROR",
                                                                                "CLEAR_POSITION", "CLEAR_STOP"))
    estop = regmap.INPUT_NAMES.index("ESTOP")
    command_offset = regmap.offset("COMMAND")

    @always_comb
    def decode_bus():
        mask = intbv(0)[32:]
        if local.be[0]:
            mask[8:0] = 0xFF
        if local.be[1]:
            mask[16:8] = 0xFF
        if local.be[2]:
            mask[24:16] = 0xFF
        if local.be[3]:
            mask[32:24] = 0xFF
        byte_mask.next = mask
        # transfers happen only while answered ready: not in the clock after an I/O write
        io_write.next = local.we and not local.space and not io_written
        io_read.next = local.re and not local.space and not io_written and not read_waited
        push.next = local.we and local.space and not fifo_full and local.be != 0 and not io_written

    @always_comb
    def answer_bus():
        # from the request's direction, not from we/re: see LocalBus; a request in
        # the clock after an I/O write waits one clock, so it sees that write's effect
        local.ready.next = ((local.write or local.space or read_waited) and not io_written
                            and not (local.write and local.space and fifo_full))
        local.retry.next = local.write and local.space and fifo_full and not io_written
        # read data from a flip-flop (the target samples it only with re and
        # ready); the memory BAR reads zero
        if local.space:
            local.rdata.next = 0
        else:
            local.rdata.next = read_word

    @always_seq(clock.posedge, reset=reset)
    def read_stage():
        # the chain follows the address alone; re, the target's late request
        # logic, reaches only read_waited
        read_waited.next = io_read
        read_word.next = read_end

    @always_seq(clock.posedge, reset=reset)
    def write_stage():
        # registered, so the target's request logic does not reach the register
        # merge and clamp logic in the same clock
        io_written.next = io_write
        written_addr.next = local.addr
        # masked here, where the flip-flops' logic cells have room for it: the registers'
        # merges and range checks then read the bytes without their enables
        written_data.next = local.wdata & byte_mask
        written_mask.next = byte_mask[merged_width:]

    @always_comb
    def control_bits():
        enable.next = control[enable_bit] and not control[mode_bit] and not halt and not home.busy
        direct_mode.next = control[mode_bit]
        clear_error.next = command_strobe and command[clear_bit]
        clear_position.next = command_strobe and command[zero_bit]
        clear_stop.next = command_strobe and command[release_bit]
        releasing.next = command_strobe and command[release_bit] and guard.stopped and not conditioning.active[estop]
        # feed hold: the host's HOLD bit or the guard's decelerated stop, which latches
        # once the rate is zero and the last step has left the pins
        feed.pause.next = machine_control[hold_bit] or guard.stopping
        guard.ramp.next = ramp_step != 0
        settled.next = feed.held and not tick and not pulses.outputs_busy   # the last tick steps a clock later
        direct_ready.next = out_ready and not guard.stopping
        # no new STEP edge while the guard halts (a pulse already high ends normally)
        pulse_clear.next = core_clear or halt
        # held while stopped: the sequencer takes no word from the FIFO
        sequencer_clear.next = core_clear or guard.stopped
        # HOME starts only with nothing queued, moving or stopped; its cut clears the direct pulses.
        # Only a HOME write starts it, so no PULSE_COUNT write loads in that clock (one register
        # write a clock; a PULSE command's load comes with the sequencer busy): busy_but_loads
        # leaves the loads, and the halt behind them, out of this decision
        home_idle.next = not busy_but_loads and fifo_empty and not guard.stopped and not halt
        direct_clear.next = core_clear or home.cut
        # a stop clears MACHINE_CONTROL.DRIVE_ENABLE and holds it at 0: CLEAR_STOP does not re-energise
        drive_cleared.next = 0
        if guard.stopped:
            drive_cleared.next = drive_mask

    @always_seq(clock.posedge, reset=reset)
    def soft_reset():
        # a stop of the guard resets the DDA, the sequencer and the pulses as SOFT_RESET does;
        # only SOFT_RESET empties the FIFO with it (see fifo_emptying)
        soft_reset_taken.next = command_strobe and command[reset_bit]
        core_clear.next = (command_strobe and command[reset_bit]) or guard.stop_event

    @always_comb
    def fifo_emptying():
        # after BAD_OPCODE, CLEAR_ERROR empties the FIFO when the registers take it,
        # the clock after its bus write; a request in that clock waits (answer_bus),
        # so every word written before the clear is dropped, every later one kept.
        # SOFT_RESET empties it with core_clear, three clocks after the edge e
        # that takes its bus write (then the strobe, then core_clear): no word
        # arrives in between, as the target holds no posted dword when it starts
        # a register access, and the next transaction's address phase comes at
        # e + 2 at the earliest, its first dword two clocks later.  A CLEAR_STOP
        # that releases the stop empties it in the clock the guard takes it (the
        # strobe's, as SOFT_RESET's, no word arrives then): the stop may have cut
        # a command in two, and words written since are dropped with it; one the
        # guard refuses (the E-stop input active) changes nothing
        fifo_flush.next = soft_reset_taken or releasing or (
            io_written and written_addr == command_offset and discard_on_clear and written_data[clear_bit])

    level_pad = level_bits - len(fifo_level)

    @always_comb
    def widen_level():
        level_wide.next = concat(intbv(0)[level_pad:], fifo_level)

    @always_comb
    def copy_level():   # a FIFO of 2**15 words: the level fills the field
        level_wide.next = fifo_level

    direct_request_x, direct_request_y = direct_request[:2]
    direct_dir_x, direct_dir_y = direct_dir[:2]

    @always_seq(clock.posedge, reset=reset)
    def outputs_before():
        # registered, so the pulse queue's logic does not reach the sequencer's issue
        requested_before.next = requested != 0
        out_active_before.next = out_active

    @always_comb
    def pulse_activity():
        # the sequencer's and homing's: the loads as asked (a latched stop clears both)
        pulse_busy.next = direct_running != 0 or direct_asked != 0
        # a step request is not yet in the pulse queue in its own clock, nor seen
        # in out_active_before in the next: both clocks are covered by the requests
        outputs_busy.next = requested != 0 or requested_before or out_active_before
        hold.next = not out_ready
        dda.advance.next = tick and out_ready and motion_run
        busy_but_loads.next = seq_busy or direct_running != 0 or out_active or dda.busy or home.busy
        any_busy.next = busy_but_loads or direct_busy != 0

    @always_comb
    def merge_requests():
        requests.step_x.next = steps.step_x or direct_request_x
        requests.step_y.next = steps.step_y or direct_request_y
        requests.dir_x.next = steps.dir_x if steps.step_x else direct_dir_x
        requests.dir_y.next = steps.dir_y if steps.step_y else direct_dir_y

    units += [decode_bus, answer_bus, read_stage, write_stage, control_bits, soft_reset, fifo_emptying, outputs_before,
              pulse_activity, merge_requests, widen_level if level_pad else copy_level]
    index = regmap.register("HOME").field("AXIS_INDEX")
    home_axis = hw["HOME"](index.lsb + index.width, index.lsb)   # the homed axis, as HOME reads it
    for axis, name in enumerate(axis_names):
        units.append(pulse_source(direct_mode, strobes[f"PULSE_COUNT_{name}"], values[f"PULSE_COUNT_{name}"], halt,
                                  conditioning.active(estop), values[f"PULSE_PERIOD_{name}"], pulses, home, home_axis,
                                  direct[axis], axis=axis))
        if axis >= 2:   # X's and Y's: merge_requests
            units.append(axis_request(steps.step(axis), steps.dir(axis), direct_out[axis], requests.step(axis),
                                       requests.dir(axis)))
    status = StatusWords(axes, busy=any_busy, quadrant=dda.quadrant, error_code=error_code, fifo_empty=fifo_empty,
                         fifo_full=fifo_full, fifo_level=level_wide, clamped=clamp_end, home_ended=home.ended,
                         index_fired=index_fired, probe_fired=probe_fired,
                         low_water=values["LOW_WATER"], int_status=values["INT_STATUS"],
                         int_enable=values["INT_ENABLE"], position_x=position.x, position_y=pos_y_snapshot,
                         status=hw["STATUS"], int_set=hw["INT_STATUS"], mark_tag=hw["MARK_TAG"],
                         machine_status=hw["MACHINE_STATUS"], stop_reason=hw["STOP_REASON"], pos_x=hw["POS_X"],
                         pos_y=hw["POS_Y"], input_raw=hw["INPUT_RAW"], input_active=hw["INPUT_ACTIVE"], irq=irq)
    units.append(status_words(clock, reset, words=status, guard=guard, conditioning=conditioning, mark=mark))
    return units


def regs_fifo_ports(coord_width=Build.coord_width, variants=Build.variants, axes=Build.axes,
                    encoders=Build.encoders):
    """Fresh ports of ``regs_fifo`` for conversion and benches: ``dda`` of
    ``coord_width`` bits (the card's range: the feed rate needs 14 at least) and ``variants``,
    ``axes_cmd``, ``steps`` and ``pins`` of ``axes`` axes, with encoder pins with ``encoders``."""
    return dict(clock=Signal(bool(0)), reset=card_reset(), local=LocalBus(),
                dda=DdaPort(COORD_WIDTH.check(coord_width), variants),
                axes_cmd=AxesCommand(axes, COORD_WIDTH.check(coord_width)), steps=AxisPulses(axes),
                pins=MotorPins(axes, encoders),
                irq=Signal(bool(0)), core_clear=Signal(bool(0)))
