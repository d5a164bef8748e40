"""The simulated card served on a Unix socket, for the LinuxCNC driver's tests.

``python -m sim.card.card_server --socket PATH --log FILE [--clock-hz N] [--axes N] [--encoders]
[--free-run CLOCKS] [--ppm N] [--machine FILE [--estop CLOCK ...] [--stall AXIS@CLOCK ...]]
[--encoder-walk CUE ...] [--encoder-pulses CUE ...] [--encoder-glitch CUE ...] [--index CUE ...]
[--probe CUE ...]``
opens ``CardSession("verilator", clock_hz=N, axes=N, encoders=...)`` (a card built to report N in
CLOCK_HZ, of N axes, with encoder inputs with ``--encoders``), listens on PATH, serves one client
and, when the client goes,
writes FILE: the card clock of every ADVANCE, register write and FIFO burst,
the STEP/DIR pin rises (``rises``: clock, X and Y stepped, their DIR pins;
``axis_rises``: clock, every axis's step position after it, from the raw
DIR pins), the changes of the DRIVE_ENABLE pin and the card's
final state (STATUS, MACHINE_STATUS, STOP_REASON, POS_X, POS_Y read after
the end).

``--ppm N`` runs the card's clock N ppm fast (negative: slow) against the
ADVANCEs, as a real card's crystal differs from the PC's timer: each ADVANCE
of a clocks runs a (1 + N / 1e6) clocks, the fractions carried.

``--fail KIND@N`` makes the card or the server fail after the N-th ADVANCE,
for the driver's fault tests: ``unplug`` (the card left the bus: every READ
answers all-ones, as a master abort does, WRITE and FIFO are lost; card
time still runs), ``freeze`` (the card's clock stops: ADVANCE answers but
runs nothing, so the FIFO no longer drains), ``stall`` (the server stops
answering but keeps the socket open, until the client goes) or ``hang-up``
(the server closes the socket, as when it dies).  ``lost`` records the
requests an unplugged card did not take: (clock, op).  ``requests`` in the record counts the requests
of each period: those since the ADVANCE before, this one included.

``--machine FILE`` puts the simulated machine of FILE (a
``models.sim_machine.MachineConfig`` as JSON: home and limit switches, E-stop
wiring, drives, motors with encoders; docs/machine.md) on the card's inputs,
run in the compiled clock loop (its ``motors`` drive the encoder inputs: they
need ``--encoders``); ``--estop CLOCK`` (repeatable) toggles its E-stop at that
card clock (pressed at the first, released at the second, ...) and
``--stall AXIS@CLOCK`` (repeatable; AXIS X or Y) stalls that axis's motor from
that card clock on, each inside an ADVANCE if one spans it.  The log then has
``machine``: the machine's positions, the steps it lost (DRIVE_ENABLE low, or
a stalled motor), its input pins, the motors' encoder counts (None without a
motor).

``--encoder-walk AXIS@CLOCK:COUNTS`` (repeatable) walks that axis's encoder
A/B by COUNTS counts from that card clock on, one legal step every
``encoder_pins.WALK_SPACING`` clocks; ``--encoder-pulses AXIS@CLOCK:COUNTS``
gives it abs(COUNTS) step/dir pulses instead (B the direction from CLOCK on,
1 up and 0 down, then A low and high WALK_SPACING clocks each per pulse: what
the card's step/dir mode, hostmot2's counter mode, counts);
``--encoder-glitch AXIS@CLOCK`` changes its A and B in the same clock (a
quadrature error); walks, pulses and glitches are taken in the order of their
clocks.  ``--index AXIS@CLOCK:WIDTH`` pulses its index high for WIDTH clocks,
``--probe CLOCK:WIDTH`` the card's probe input (``sim/card/encoder_pins.py``;
all need ``--encoders``).  The log's ``final`` then has ``ENC_COUNT`` and
``ENC_STATUS``: every axis's.

A real card goes on without its PC: with ``--free-run CLOCKS`` the server,
once the client has gone (socket closed, however it died), runs the card on
its own for CLOCKS more clocks before it reads the final state, so a test
sees what the card's watchdog does when the driver stops advancing it.
DRIVE_ENABLE is sampled at the end of every request (a change inside an
ADVANCE is recorded at its end) and at every clock of the free run while it
is high, so its fall there is recorded at its clock (numbered as the rises).

The server's side of the socket, its protocol and the record it keeps are
``sim/card/card_socket_server.py``'s ``CardServer``.
"""
import argparse
import json
import os
import socket
import sys

from models.parameters import AXES, CLOCK_HZ, ParameterError
from models.sim_machine import MOTOR_AXES, MachineConfig
from sim.card.card_session import CardSession
from sim.card.card_socket_server import FAILURES, CardServer
from sim.card.encoder_pins import EncoderPins, parse_cue, parse_glitch, parse_probe

MAX_FREE_RUN = 1 << 30  # clocks
MAX_PPM = 100_000


def _stall(parser, text, machine):
    """``--stall AXIS@CLOCK`` as (card clock, axis index); refused unless the machine has that motor."""
    name, _, clock = text.partition("@")
    if not clock.isdigit() or name.upper() not in MOTOR_AXES:
        parser.error(f"--stall must be AXIS@CLOCK with AXIS one of {', '.join(MOTOR_AXES)}, not {text}")
    if machine is None or name.upper() not in machine.motors:
        parser.error(f"--stall {text}: --machine has no motor on {name.upper()}")
    return int(clock), MOTOR_AXES.index(name.upper())


def parse_arguments(argv=None):
    """The command line as (args, failure, machine, stalls, pins), every bad value refused (exit 2)
    before anything is built or written: ``failure`` (kind, after how many ADVANCEs) or None,
    ``machine`` a MachineConfig or None, ``stalls`` [(card clock, axis)], ``pins`` an EncoderPins or None."""
    parser = argparse.ArgumentParser(prog="python -m sim.card.card_server", description=__doc__.splitlines()[0])
    parser.add_argument("--socket", required=True, help="Unix socket to listen on (must not exist)")
    parser.add_argument("--log", required=True, help="JSON file written when the client has gone")
    parser.add_argument("--clock-hz", type=int, default=CLOCK_HZ.default,
                        help=f"clock the simulated card reports in CLOCK_HZ (default {CLOCK_HZ.default})")
    parser.add_argument("--axes", type=int, default=AXES.default,
                        help=f"axes the simulated card is built with (BUILD.AXES; {AXES.bounds()}; "
                             f"default {AXES.default})")
    parser.add_argument("--encoders", action="store_true",
                        help="the card is built with encoder inputs (BUILD.ENCODERS; docs/encoders.md)")
    parser.add_argument("--free-run", type=int, default=0, metavar="CLOCKS",
                        help="clocks the card runs on its own after the client has gone (default 0)")
    parser.add_argument("--ppm", type=int, default=0,
                        help="the card's clock this many ppm fast (negative: slow) against the ADVANCEs "
                             "(a real card's crystal against the PC's timer; default 0)")
    parser.add_argument("--fail", metavar="KIND@N",
                        help=f"fail after the N-th ADVANCE: {', '.join(FAILURES)} (see above; default: never)")
    parser.add_argument("--machine", help="a simulated machine on the card's inputs, from this JSON file "
                                          "(models.sim_machine.MachineConfig)")
    parser.add_argument("--estop", type=int, action="append", default=[], metavar="CLOCK",
                        help="toggle the simulated machine's E-stop at this card clock (repeatable; needs --machine)")
    parser.add_argument("--stall", action="append", default=[], metavar="AXIS@CLOCK",
                        help="stall the simulated machine's motor of AXIS (X, Y, ... of the card) from this card "
                             "clock on (repeatable; needs a motor on AXIS in --machine)")
    parser.add_argument("--encoder-walk", action="append", default=[], metavar="AXIS@CLOCK:COUNTS",
                        help="walk that axis's encoder by COUNTS counts from that card clock on (repeatable; "
                             "needs --encoders)")
    parser.add_argument("--encoder-pulses", action="append", default=[], metavar="AXIS@CLOCK:COUNTS",
                        help="give that axis's encoder abs(COUNTS) step/dir pulses from that card clock on: B the "
                             "direction (1 up), A low then high each pulse (repeatable; needs --encoders)")
    parser.add_argument("--encoder-glitch", action="append", default=[], metavar="AXIS@CLOCK",
                        help="change that axis's encoder A and B in the same card clock: a quadrature error "
                             "(repeatable; needs --encoders)")
    parser.add_argument("--index", action="append", default=[], metavar="AXIS@CLOCK:WIDTH",
                        help="pulse that axis's index input high for WIDTH clocks (repeatable; needs --encoders)")
    parser.add_argument("--probe", action="append", default=[], metavar="CLOCK:WIDTH",
                        help="pulse the card's probe input high for WIDTH clocks (repeatable; needs --encoders)")
    args = parser.parse_args(argv)
    failure = None
    if args.fail is not None:
        kind, _, after = args.fail.partition("@")
        if kind not in FAILURES or not after.isdigit():
            parser.error(f"--fail must be KIND@N with KIND one of {', '.join(FAILURES)}, not {args.fail}")
        failure = (kind, int(after))
    machine = None
    if args.machine:
        try:
            with open(args.machine) as config:
                machine = MachineConfig.from_json(config.read())
        except (OSError, ValueError) as error:
            parser.error(f"--machine {args.machine}: {error}")
    if args.estop and machine is None:
        parser.error("--estop needs --machine: the E-stop is the simulated machine's")
    if any(clock < 0 for clock in args.estop):
        parser.error("--estop clocks are card clocks since the server opened the card, not negative")
    if machine is not None and machine.motors and not args.encoders:
        parser.error("--machine: its motors drive encoder inputs: add --encoders (a card built with them)")
    stalls = [_stall(parser, text, machine) for text in args.stall]
    if not 1 <= args.clock_hz <= 0xFFFFFFFF:
        parser.error(f"--clock-hz must be 1..{0xFFFFFFFF}, not {args.clock_hz}")
    try:
        AXES.check(args.axes)
    except ParameterError as error:
        parser.error(f"--axes {error.problem}")
    if machine is not None:
        try:
            machine.check_axes(args.axes)
        except ValueError as error:
            parser.error(f"--machine {args.machine}: {error}")
    if not 0 <= args.free_run <= MAX_FREE_RUN:
        parser.error(f"--free-run must be 0..{MAX_FREE_RUN} clocks, not {args.free_run}")
    if not -MAX_PPM <= args.ppm <= MAX_PPM:
        parser.error(f"--ppm must be {-MAX_PPM}..{MAX_PPM}, not {args.ppm}")
    pins = None
    cued = args.encoder_walk or args.encoder_pulses or args.encoder_glitch or args.index or args.probe
    cue_options = "--encoder-walk, --encoder-pulses, --encoder-glitch, --index and --probe"
    if cued and not args.encoders:
        parser.error(f"{cue_options} need --encoders: a card without encoders has no such pins")
    if cued and machine is not None and machine.motors:
        parser.error(f"{cue_options} drive the encoder pins the --machine's motors drive: give one or the other")
    if cued:
        pins = EncoderPins(args.axes)
        try:
            pins.cue(walks=[parse_cue(cue, args.axes) for cue in args.encoder_walk],
                     pulses=[parse_cue(cue, args.axes) for cue in args.encoder_pulses],
                     glitches=[parse_glitch(cue, args.axes) for cue in args.encoder_glitch])
            for cue in args.index:
                pins.pulse(*parse_cue(cue, args.axes))
            for cue in args.probe:
                pins.probe(*parse_probe(cue))
        except ValueError as error:
            parser.error(str(error))
    if os.path.exists(args.socket):
        parser.error(f"{args.socket} exists: remove it or choose another path")
    return args, failure, machine, stalls, pins


def main(argv=None):
    args, failure, machine, stalls, pins = parse_arguments(argv)
    session = CardSession("verilator", clock_hz=args.clock_hz, machine=machine, axes=args.axes,
                          encoders=int(args.encoders))
    try:
        server = CardServer(session, args.clock_hz, args.ppm, failure, args.estop, stalls, pins)
        listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        listener.bind(args.socket)
        os.chmod(args.socket, 0o666)  # the driver runs as LinuxCNC's (ordinary) user
        listener.listen(1)
        print(f"card server listening on {args.socket}", flush=True)
        connection, _ = listener.accept()
        try:
            server.serve(connection)
        finally:
            connection.close()
            listener.close()
            os.unlink(args.socket)
        try:
            server.finish(args.free_run)
        finally:
            with open(args.log, "w") as log:
                json.dump(server.record(), log)
    finally:
        session.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
