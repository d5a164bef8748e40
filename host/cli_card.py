"""``python -m host run / info / selftest``: the commands that talk to a card.

``--card`` names it: ``verilator``, ``myhdl`` or ``icarus`` (the simulated
card; ``--sim KIND`` says the same), ``pci`` (the one real card in this
machine) or ``pci:DDDD:BB:DD.F`` (that one).  ``run --encoders`` runs the
simulated card (Verilator or MyHDL) built with encoders, its simulated
machine's motors (those of ``--machine``, else one on every axis of the card
as ``Motor()`` has them) turning its steps into encoder counts, and reports
the path the encoders measured beside the pins' on every axis
(``host/encoder_path.py``) and whether the counts ended on the steps times
the counts per step.  Every option is checked before the card is opened or
anything is written.
"""
import argparse
import dataclasses
import importlib.util
import signal
import sys
import time
from pathlib import Path

from host import encoders, gcode, svg
from host.card import Card
from host.machine_io import MachineStopped
from host.check import check
from host.geometry import dimension
from host.planner import plan
from host.run_report import encoders_report, pin_rises, pins_report
from host.selftest import selftest
from host.stream import Stopped, stream
from host.errors import ProgramError
from host.transports import SIM_KINDS, open_transport
from models.parameters import AXES
from models.sim_machine import MOTOR_AXES, MachineConfig, Motor

STOP_EXIT = 130  # the shell's code for a job ended by SIGINT
ENCODER_KINDS = ("verilator", "myhdl")   # the simulated cards whose machine records the encoder pins


def add_commands(commands, positive, scales, count, axis_count):
    """The ``run``, ``info`` and ``selftest`` sub-commands on ``commands`` (argparse sub-parsers)."""
    def card_options(sub):
        sub.add_argument("--card", default="verilator",
                         help=f"{', '.join(SIM_KINDS)} (simulated), pci or pci:DDDD:BB:DD.F (default verilator)")
        sub.add_argument("--sim", choices=SIM_KINDS, help="the simulated card of this kind (same as --card KIND)")
        sub.add_argument("--machine", help="simulated card: a simulated machine on its inputs, from this JSON file "
                                           "(switches, E-stop, drives; docs/machine.md)")

    run = commands.add_parser("run", help="run FILE on a card, streaming it through the FIFO")
    run.add_argument("file", help="G-code program, or an .svg drawing")
    card_options(run)
    run.add_argument("--axes", type=axis_count,
                     help="the card's axes: a simulated card of this build (python -m rtl.top --axes N; default "
                          "2); a real card must report it in BUILD.AXES (default: what the card reports)")
    run.add_argument("--steps-per-mm", type=scales, default=(200.0,), metavar="X[,Y,...]",
                     help="steps per mm of each axis (per degree for A, B, C): one value for all, or one per "
                          "axis of the card (default 200)")
    run.add_argument("--rapid", type=positive, default=3000.0, help="rapid feed, mm/min (default 3000)")
    run.add_argument("--acceleration", type=positive, default=500.0, help="mm/s^2 (default 500)")
    run.add_argument("--start-feed", type=positive, default=60.0,
                     help="mm/min a move starts and stops with (default 60)")
    run.add_argument("--feed", type=positive, default=1200.0, help="SVG: feed of the drawn moves, mm/min")
    run.add_argument("--tolerance", type=positive, default=0.01, help="SVG: curves as arcs within this many mm")
    run.add_argument("--feed-override", type=positive, default=100.0, metavar="PERCENT",
                     help="scale every feed, rapid included (default 100)")
    run.add_argument("--mark-interval", type=count, default=256, help="words between MARKs (default 256)")
    run.add_argument("--step-width-ns", type=positive, default=1000.0, help="STEP high time (default 1000)")
    run.add_argument("--dir-setup-ns", type=positive, default=1000.0, help="DIR set-up time (default 1000)")
    run.add_argument("--dir-hold-ns", type=positive, default=1000.0, help="DIR hold time (default 1000)")
    run.add_argument("--low-water", type=count, help="refill when the FIFO falls below this (default: half)")
    run.add_argument("--preview", help="simulated card: draw the pins' path over the drawing into this PNG "
                                       "(with --encoders, the measured path too)")
    run.add_argument("--encoders", action="store_true",
                     help="--card verilator or myhdl built with encoders, the simulated machine's motors "
                          "(--machine's, else the default one on every axis) on them: report the path the "
                          "encoders measured")
    run.add_argument("--ferror-limit", type=_limit, metavar="COUNTS",
                     help="with --encoders: FERROR_LIMIT of each motor's axis, counts (default 0: no stop)")
    for name, text in (("info", "identify the card and print what it reports"),
                       ("selftest", "register walk, FIFO loop and a short move checked on position")):
        card_options(commands.add_parser(name, help=text))


def _limit(text):
    try:
        value = int(text)
    except ValueError:
        value = -1
    if not 0 <= value <= 0xFFFFFFFF:
        raise argparse.ArgumentTypeError(f"{text!r}: FERROR_LIMIT is a count, 0 .. {0xFFFFFFFF}")
    return value


def encoder_options(options, spec, opening, refuse):
    """``--encoders``: the transport opens the card with encoders and the machine with motors (checked
    before the card is opened); the machine's motors, or None without ``--encoders``."""
    machine = opening.get("machine")
    if not options.encoders:
        if options.ferror_limit is not None:
            refuse("--ferror-limit needs --encoders")
        return None
    if spec not in ENCODER_KINDS:
        refuse(f"--encoders runs on --card {' or '.join(ENCODER_KINDS)}: its simulated machine records the "
               "encoder pins")
    machine = machine or MachineConfig()
    if not machine.motors:
        axes = options.axes or AXES.default
        machine = dataclasses.replace(machine, motors={name: Motor() for name in MOTOR_AXES[:axes]})
    opening.update(machine=machine, encoders=1)
    return machine.motors


def card_spec(options, refuse):
    spec = options.sim or options.card
    if spec not in SIM_KINDS and spec != "pci" and not spec.startswith("pci:"):
        refuse(f"--card {spec}: use one of {', '.join(SIM_KINDS)}, pci or pci:DDDD:BB:DD.F")
    return spec


def transport_options(options, spec, refuse):
    """The transport's options: ``machine`` from ``--machine`` (checked before the card is opened)."""
    if not options.machine:
        return {}
    if spec not in SIM_KINDS:
        refuse("--machine needs a simulated card: a real card has a real machine")
    path = Path(options.machine)
    if not path.is_file():
        refuse(f"--machine {path}: no such file")
    try:
        config = MachineConfig.from_json(path.read_text())
    except ValueError as error:
        refuse(f"--machine {path}: {error}")
    if config.motors and not getattr(options, "encoders", False):
        refuse(f"--machine {path}: its motors need --encoders (python -m host run: a card built with encoder "
               "inputs)")
    axes = getattr(options, "axes", None) or AXES.default
    try:
        config.check_axes(axes)
    except ValueError as error:
        refuse(f"--machine {path}: {error}")
    return {"machine": config}


def run_command(options, refuse, per_axis):
    """``run``; the exit code."""
    spec = card_spec(options, refuse)
    path = Path(options.file)
    if not path.is_file():
        refuse(f"{path}: no such file")
    if options.preview:
        if spec not in SIM_KINDS:
            refuse("--preview needs a simulated card: the path is rebuilt from its pins")
        if not Path(options.preview).parent.is_dir():
            refuse(f"{options.preview}: its folder does not exist")
        if importlib.util.find_spec("matplotlib") is None:
            refuse("--preview needs matplotlib: pip install -e '.[plot]'")
    if path.suffix.lower() == ".svg":
        drawing = svg.parse(str(path), options.tolerance, options.feed, path.name)
    else:
        drawing = gcode.parse(path.read_text(), path.name)
    scale = options.feed_override / 100
    drawing = [dataclasses.replace(item, feed=item.feed * scale) if getattr(item, "feed", None) else item
               for item in drawing]
    wall = time.monotonic()
    opening = transport_options(options, spec, refuse)
    motors = encoder_options(options, spec, opening, refuse)
    if options.axes is not None and spec in SIM_KINDS:
        opening["axes"] = options.axes
    with open_transport(spec, **opening) as transport:
        card = Card(transport)
        axes = card.identity.axes
        if options.axes is not None and options.axes != axes:
            raise ValueError(f"--axes {options.axes}: the card reports {axes} axes (BUILD.AXES)")
        if path.suffix.lower() != ".svg" and dimension(drawing) > axes:
            gcode.parse(path.read_text(), path.name, axes)  # refuses the first line that needs more axes
        machine = card.configure(steps_per_mm=per_axis(options.steps_per_mm, axes, _raise),
                                 step_width_ns=options.step_width_ns,
                                 dir_setup_ns=options.dir_setup_ns, dir_hold_ns=options.dir_hold_ns,
                                 rapid=options.rapid * scale, acceleration=options.acceleration,
                                 start_feed=options.start_feed, mark_interval=options.mark_interval)
        for name, motor in (motors or {}).items():   # aligned here, before anything moved
            numerator, denominator = motor.ratio
            encoders.set_following_error(card, MOTOR_AXES.index(name), numerator / denominator,
                                         options.ferror_limit or 0)
        if motors:
            card.drive(True)   # the motors turn only with their drives enabled
        planned = plan(drawing, machine)
        model = check(planned)
        print(f"card:       {transport.name}, {card.identity.clock_hz} Hz, FIFO {card.identity.fifo_words} words")
        print(f"job:        {len(drawing)} segments, {len(planned.entries)} commands, "
              f"{len(planned.words())} words, {len(planned.runs)} runs")
        first_clock = transport.clocks
        first_rise = len(pin_rises(transport.pins, axes)) if transport.pins is not None else 0
        stop = _StopRequest()
        try:
            result = stream(card, planned, options.low_water, _progress_bar(), stop)
        except Stopped:
            position = card.stop()
            status = card.status()
            idle = not card.field("STATUS", "BUSY", status) and card.field("STATUS", "FIFO_EMPTY", status)
            sys.stderr.write("\n")
            print(f"stopped:    card stopped (soft reset; {'idle, FIFO empty' if idle else 'STILL BUSY'}) at "
                  f"{position} steps = ({', '.join(f'{v:.4f}' for v in machine.mm(position))}) mm")
            return STOP_EXIT
        except MachineStopped as error:   # E-stop, limit, watchdog or following error: what was measured
            print(f"stopped:    {error}; position {card.position()} steps")
            if motors:
                encoders_report(card, planned, model, transport, first_rise, motors, axes)
            return 1
        finally:
            stop.restore()
        print(f"streamed:   {result.words} words in {result.bursts} bursts, {result.interrupts} interrupts, "
              f"{len(result.marks)} MARKs read back")
        # POS_X, POS_Y: the other axes have no position register yet; a simulated card's pins tell them
        registers = "" if axes == 2 else " (POS_X, POS_Y)"
        print(f"position:   {result.position} steps{registers} (plan: {planned.end})")
        print(f"job time:   {model.job_seconds:.4f} s planned; {result.seconds:.4f} s of card time")
        ended = result.position == tuple(planned.end[:len(result.position)])
        if transport.clocks is not None:
            encoder_path = (encoders_report(card, planned, model, transport, first_rise, motors, axes)
                            if motors else None)
            pins_end = pins_report(planned, model, transport, first_rise, options.preview, card.timing["DIR_SETUP"],
                                    axes, encoder_path)
            if axes > 2:
                print(f"pins end:   {pins_end} steps (plan: {planned.end})")
                ended = ended and pins_end == tuple(planned.end)
            print(f"simulated:  {transport.clocks - first_clock} clocks, wall time {time.monotonic() - wall:.1f} s")
    return 0 if ended else 1


def _raise(message):
    raise ValueError(message)


class _StopRequest:
    """SIGINT sets a flag the streamer asks for (the card is stopped between two accesses)."""

    def __init__(self):
        self.requested = False
        self.previous = signal.signal(signal.SIGINT, self._handle)

    def _handle(self, *_):
        self.requested = True

    def __call__(self):
        return self.requested

    def restore(self):
        signal.signal(signal.SIGINT, self.previous)


def _progress_bar():
    if not sys.stderr.isatty():
        return None

    def show(done, total):
        filled = 40 * done // max(total, 1)
        sys.stderr.write(f"\r[{'#' * filled}{' ' * (40 - filled)}] {done}/{total} words")
        if done >= total:
            sys.stderr.write("\n")
        sys.stderr.flush()

    return show


def info_command(options, refuse):
    spec = card_spec(options, refuse)
    with open_transport(spec, **transport_options(options, spec, refuse)) as transport:
        card = Card(transport)
        ident = card.identity
        print(f"card:        {transport.name}")
        print(f"PCI IDs:     {ident.vendor_id:04x}:{ident.device_id:04x}")
        print(f"registers:   version {ident.version[0]}.{ident.version[1]}")
        print(f"clock:       {ident.clock_hz} Hz")
        print(f"FIFO:        {ident.fifo_words} words")
        print(f"coordinates: {ident.coord_width} bits; axes {ident.axes}; DDA variants {list(ident.variants)}; "
              f"device {ident.device}")
        print(f"status:      {card.status():#010x}; position {card.position()}; last MARK {card.last_mark()}")
        _machine_report(card)
        _encoder_report(card)
    return 0


def _encoder_report(card):
    """``info``'s encoders: per axis count, index latch, following error, quadrature errors."""
    if not card.identity.encoders:
        print("encoders:    none (BUILD.ENCODERS 0)")
        return
    for axis in range(card.identity.axes):
        reading = encoders.read_encoder(card, axis)
        print(f"encoder {names([axis])}:   count {reading.count}, index latch {reading.index_latch}"
              f"{' (armed)' if reading.index_armed else ''}, following error {reading.ferror}, "
              f"quadrature errors {reading.error_count}{' (flagged)' if reading.quad_error else ''}")


def _machine_report(card):
    """``info``'s machine side: inputs, the guard, DRIVE_ENABLE, the watchdog, homing."""
    side = card.machine_side()
    reason, limits = side["stop"]
    state = "STOPPED" if side["stopped"] else "STOPPING" if side["stopping"] else None
    which = f", {', '.join(limits)}" if limits else ""
    stop = f"{state} ({reason}{which})" if state else "running"
    pin, asked = side["drive_enable"]
    homing = side["homing"]
    outcome = next((name for name in ("DONE", "NOT_FOUND", "REFUSED") if homing[name]), "none")
    print(f"inputs:      active {', '.join(side['inputs']) or 'none'} (after INPUT_POLARITY and the filter); "
          f"pins high {', '.join(side['raw']) or 'none'}")
    print(f"guard:       {stop}")
    print(f"drives:      DRIVE_ENABLE pin {'high' if pin else 'low'}, MACHINE_CONTROL.DRIVE_ENABLE {int(asked)}; "
          f"hold {'on' if side['hold'][0] else 'off'}{' (held)' if side['hold'][1] else ''}")
    print(f"watchdog:    {side['watchdog']} clocks left" if side["watchdog"] else "watchdog:    off")
    print(f"homing:      {'busy, ' + homing['PHASE'] if homing['BUSY'] else 'idle'}; last HOME axis "
          f"{homing['AXIS']}: {outcome}")
    if card.machine is not None:
        state = card.machine.state()
        print(f"sim machine: positions {state.positions}, steps lost to a disabled drive {state.lost}, "
              f"E-stop {'pressed' if state.estop else 'released'}")


def selftest_command(options, refuse):
    spec = card_spec(options, refuse)
    with open_transport(spec, **transport_options(options, spec, refuse)) as transport:
        card = Card(transport)
        failures = 0
        for name, problem in selftest(card):
            print(f"{name:28} {'ok' if problem is None else 'FAILED: ' + problem}")
            failures += problem is not None
    print(f"selftest:    {'passed' if not failures else f'{failures} FAILED'}")
    return 1 if failures else 0
