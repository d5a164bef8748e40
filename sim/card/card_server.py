"""The simulated card served on a Unix socket, for the LinuxCNC driver's tests.

``python -m sim.card.card_server --socket PATH --log FILE [--clock-hz N] [--axes N] [--encoders]
[--free-run CLOCKS] [--ppm N] [--machine FILE [--estop CLOCK ...] [--stall AXIS@CLOCK ...]]
[--encoder-walk CUE ...] [--index CUE ...] [--probe CUE ...]``
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
``encoder_pins.WALK_SPACING`` clocks; ``--index AXIS@CLOCK:WIDTH`` pulses its
index high for WIDTH clocks, ``--probe CLOCK:WIDTH`` the card's probe input
(``sim/card/encoder_pins.py``; all need ``--encoders``).  The log then has ``encoder_final``: every axis's ENC_COUNT.

A real card goes on without its PC: with ``--free-run CLOCKS`` the server,
once the client has gone (socket closed, however it died), runs the card on
its own for CLOCKS more clocks before it reads the final state, so a test
sees what the card's watchdog does when the driver stops advancing it.
DRIVE_ENABLE is sampled at the end of every request (a change inside an
ADVANCE is recorded at its end) and at every clock of the free run while it
is high, so its fall there is recorded at its clock (numbered as the rises).

The protocol is lock-step: simulated time moves only inside requests, and
the driver asks for one servo period of card clocks (ADVANCE) in each of its
periods, so card time and servo time agree whatever the wall clock does.
Every request is three little-endian 32-bit words, ``op, a, b``; FIFO is
followed by ``a`` data words.  Every answer is two words, ``status, value``
(status 0: done; else ``value`` is the length of a UTF-8 message that follows).

    op 1 READ    a = register offset       value = the register
    op 2 WRITE   a = register offset, b = value
                 (offsets: BAR0's, and beyond BAR0 BAR2's per-axis blocks;
                 models/card_socket.py)
    op 3 FIFO    a = word count, words     (one burst into BAR1)
    op 4 ADVANCE a = card clocks           value = card clocks since the server opened
                                           the card, low 32 bits: the card runs until
                                           they equal the sum of all ADVANCEs (the bus
                                           accesses of the period count in it)
"""
import argparse
import json
import os
import socket
import struct
import sys

from models import registers as regmap
from models.card_socket import ADVANCE, ANSWER_WORDS, FIFO, MAX_BURST, READ, REQUEST_WORDS, WRITE
from models.parameters import AXES, CLOCK_HZ, ParameterError
from models.sim_machine import MOTOR_AXES, MachineConfig
from sim.card.card_session import AccessError, CardSession
from sim.card.encoder_pins import EncoderPins, parse_cue, parse_probe

WORD = struct.Struct("<I")
REQUEST = struct.Struct("<" + "I" * REQUEST_WORDS)
ANSWER = struct.Struct("<" + "I" * ANSWER_WORDS)
MAX_FREE_RUN = 1 << 30  # clocks
PPM_ONE = 1_000_000
MAX_PPM = 100_000
DRIVE_PIN = "pins_drive_enable"  # the card's DRIVE_ENABLE output, as MyHDL names the top's port
FINAL_REGISTERS = ("STATUS", "MACHINE_STATUS", "STOP_REASON", "POS_X", "POS_Y")
FAILURES = ("unplug", "freeze", "stall", "hang-up")
ALL_ONES = 0xFFFFFFFF  # what a read of a card gone from the bus returns (master abort)


class ProtocolError(RuntimeError):
    """A request the server cannot take."""


def receive(connection, size):
    """Exactly ``size`` bytes, or None when the client closed the socket first."""
    chunks = bytearray()
    while len(chunks) < size:
        chunk = connection.recv(size - len(chunks))
        if not chunk:
            return None
        chunks += chunk
    return bytes(chunks)


class CardServer:
    """One client's requests on ``session`` (a Verilator ``CardSession`` built for ``clock_hz``).
    Clocks are card clocks since the server opened the card: ``advances``
    (clock before, clock after), ``fifo`` (clock, words), ``writes`` (clock
    at the end of the access, offset, value), ``drive``
    (clock, DRIVE_ENABLE level) at every change, ``free_run`` and ``final``
    once ``finish`` has run."""

    def __init__(self, session, clock_hz, ppm=0, failure=None, estop=(), stalls=(), pins=None):
        self.session, self.clock_hz = session, clock_hz
        # (card clock, axis): the E-stop toggles at its clocks (pressed first, axis None), a motor stalls
        self.events = sorted([(clock, None) for clock in estop] + list(stalls), key=lambda e: (e[0], e[1] or 0))
        self.pins = pins  # an EncoderPins: the encoder pins' cues, or None
        if pins is not None:
            # a cue due while a bus access runs the card clock by clock is taken at its clock too,
            # not held back to the next ADVANCE (two edges of a walk would then meet in one clock)
            edge = session.bench.clock_edge

            def clock_edge(in_reset=False):
                for _, name, level in pins.due(self.now()):
                    session.set_input(name, level)
                edge(in_reset)
            session.bench.clock_edge = clock_edge
        self.pressed = False
        self.ppm, self.ppm_fraction = ppm, 0
        self.failure = failure  # (kind, after how many ADVANCEs) or None
        self.requests = []
        self.lost = []
        self._since_advance = 0
        self.model = session.bench.model
        self.start = session.clocks
        self.advances = []
        self.fifo = []
        self.writes = []
        self.drive = []
        self.free_run = None
        self.final = None
        self.deadline = 0  # card clocks the ADVANCEs so far add up to

    def now(self):
        return self.session.clocks - self.start

    def _sample_drive(self):
        level = int(self.model[DRIVE_PIN])
        if not self.drive or self.drive[-1][1] != level:
            self.drive.append((self.now(), level))
        return level

    def failing(self, kind):
        return self.failure is not None and self.failure[0] == kind and len(self.advances) >= self.failure[1]

    def handle(self, op, a, b, payload):
        session = self.session
        self._since_advance += 1
        if op == ADVANCE:
            self.requests.append(self._since_advance)
            self._since_advance = 0
        if self.failing("unplug") and op in (READ, WRITE, FIFO):
            if op != READ:
                self.lost.append((self.now(), op))
            return ALL_ONES if op == READ else 0
        if self.failing("freeze") and op == ADVANCE:
            self.advances.append((self.now(), self.now()))
            return self.now() & 0xFFFFFFFF
        if op == READ:
            return session.read(a)
        if op == WRITE:
            session.write(a, b)
            self.writes.append((self.now(), a, b))
            return 0
        if op == FIFO:
            self.fifo.append((self.now(), payload))
            session.fifo_write(payload)
            return 0
        if op == ADVANCE:
            # The period's bus accesses took card clocks too: run to the period's end, not a more.
            # A card clock ppm fast runs a(1 + ppm / 1e6) clocks, the fraction carried.
            scaled = a * (PPM_ONE + self.ppm) + self.ppm_fraction
            self.deadline += scaled // PPM_ONE
            self.ppm_fraction = scaled % PPM_ONE
            before = session.clocks - self.start
            self._run_to(self.deadline)
            after = session.clocks - self.start
            self.advances.append((before, after))
            return after & 0xFFFFFFFF
        raise ProtocolError(f"unknown request {op}")

    def _cues(self, deadline):
        """(clock, what to do then) of the E-stop toggles, the motors' stalls and the encoder pin changes
        up to ``deadline``, in order."""
        cues = []
        while self.events and self.events[0][0] <= deadline:
            at, axis = self.events.pop(0)
            cues.append((at, self._toggle_estop if axis is None else lambda axis=axis: self.session.machine.stall(axis)))
        for at, name, level in self.pins.due(deadline) if self.pins else ():
            cues.append((at, lambda name=name, level=level: self.session.set_input(name, level)))
        return sorted(cues, key=lambda cue: cue[0])

    def _toggle_estop(self):
        self.pressed = not self.pressed
        self.session.machine.press_estop(self.pressed)

    def _run_to(self, deadline):
        """Run the card to clock ``deadline``, toggling the machine's E-stop, stalling its motors and
        changing the encoder pins at their clocks on the way."""
        for at, act in self._cues(deadline):
            if at > self.now():
                self.session.wait(at - self.now())
            act()
        if deadline > self.now():
            self.session.wait(deadline - self.now())

    def serve(self, connection):
        """Answer requests until the client closes the socket (or dies: a reset or broken pipe)."""
        self._sample_drive()
        try:
            self._serve(connection)
        except (ConnectionResetError, BrokenPipeError):
            pass

    def _serve(self, connection):
        while True:
            if self.failing("hang-up"):
                return
            if self.failing("stall"):
                while receive(connection, 1) is not None:  # no answer any more; wait for the client to go
                    pass
                return
            header = receive(connection, REQUEST.size)
            if header is None:
                return
            op, a, b = REQUEST.unpack(header)
            payload = []
            if op == FIFO:
                if a > MAX_BURST:
                    raise ProtocolError(f"a FIFO burst of {a} words is more than {MAX_BURST}")
                data = receive(connection, 4 * a)
                if data is None:
                    return
                payload = list(struct.unpack(f"<{a}I", data))
            try:
                value = self.handle(op, a, b, payload)
            except (AccessError, ValueError, ProtocolError) as error:
                self._sample_drive()
                message = str(error).encode()
                connection.sendall(ANSWER.pack(1, len(message)) + message)
                continue
            self._sample_drive()
            connection.sendall(ANSWER.pack(0, value))

    def finish(self, free_run=0):
        """The client has gone: run the card on its own for ``free_run`` clocks
        (clock by clock while DRIVE_ENABLE is high, then the rest at once), then
        read its final state over the bus."""
        self.free_run = dict(start=self.now(), clocks=free_run)
        ran = 0
        while ran < free_run and self._sample_drive():
            self.session.wait(1)
            ran += 1
        self._sample_drive()
        if ran < free_run:
            self.session.wait(free_run - ran)
        self._sample_drive()
        self.free_run["end"] = self.now()
        self.final = {name: self.session.read(regmap.offset(name)) for name in FINAL_REGISTERS}
        if self.pins is not None:
            self.final["ENC_COUNT"] = [self.session.read(regmap.axis_offset("ENC_COUNT", axis))
                                       for axis in range(self.pins.axes)]

    def record(self):
        """What the test compares: clocks are card clocks since the server opened the card."""
        rises = [(int(r[0]) - self.start, *map(int, r[1:])) for r in self.session.log.rises]
        axes = self.session.target.axes
        axis_rises = [(int(clock) - self.start, point) for clock, point in self.session.log.axis_rises(axes)]
        record = dict(clock_hz=self.clock_hz, advances=self.advances, requests=self.requests, lost=self.lost,
                      rises=rises, axis_rises=axis_rises, fifo=self.fifo, writes=self.writes, drive=self.drive, free_run=self.free_run,
                      final=self.final)
        if self.session.machine is not None:
            state = self.session.machine.state()
            record["machine"] = dict(positions=state.positions, lost=state.lost, inputs=state.inputs,
                                     estop=state.estop, counts=state.counts)
        return record


def _stall(parser, text, machine):
    """``--stall AXIS@CLOCK`` as (card clock, axis index); refused unless the machine has that motor."""
    name, _, clock = text.partition("@")
    if not clock.isdigit() or name.upper() not in MOTOR_AXES:
        parser.error(f"--stall must be AXIS@CLOCK with AXIS one of {', '.join(MOTOR_AXES)}, not {text}")
    if machine is None or name.upper() not in machine.motors:
        parser.error(f"--stall {text}: --machine has no motor on {name.upper()}")
    return int(clock), MOTOR_AXES.index(name.upper())


def main(argv=None):
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
                        help="stall the simulated machine's motor of AXIS (X, Y) from this card clock on "
                             "(repeatable; needs a motor on AXIS in --machine)")
    parser.add_argument("--encoder-walk", action="append", default=[], metavar="AXIS@CLOCK:COUNTS",
                        help="walk that axis's encoder by COUNTS counts from that card clock on (repeatable; "
                             "needs --encoders)")
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
    if not 0 <= args.free_run <= MAX_FREE_RUN:
        parser.error(f"--free-run must be 0..{MAX_FREE_RUN} clocks, not {args.free_run}")
    if not -MAX_PPM <= args.ppm <= MAX_PPM:
        parser.error(f"--ppm must be {-MAX_PPM}..{MAX_PPM}, not {args.ppm}")
    pins = None
    cued = args.encoder_walk or args.index or args.probe
    if cued and not args.encoders:
        parser.error("--encoder-walk, --index and --probe need --encoders: a card without encoders has no such pins")
    if cued and machine is not None and machine.motors:
        parser.error("--encoder-walk, --index and --probe drive the encoder pins the --machine's motors drive: "
                     "give one or the other")
    if cued:
        pins = EncoderPins(args.axes)
        try:
            for axis, clock, counts in sorted((parse_cue(cue, args.axes) for cue in args.encoder_walk),
                                              key=lambda cue: cue[1]):
                pins.walk(axis, clock, counts)
            for cue in args.index:
                pins.pulse(*parse_cue(cue, args.axes))
            for cue in args.probe:
                pins.probe(*parse_probe(cue))
        except ValueError as error:
            parser.error(str(error))
    if os.path.exists(args.socket):
        parser.error(f"{args.socket} exists: remove it or choose another path")
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
