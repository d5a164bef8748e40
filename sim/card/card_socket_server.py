"""The card server's side of one client: the simulated card's requests on a Unix socket.

``CardServer(session, clock_hz, ...)`` answers one client's requests on a
Verilator ``CardSession`` (``serve``), runs the card on its own once the
client has gone (``finish``) and makes the record the test compares
(``record``); ``python -m sim.card.card_server`` (``sim/card/card_server.py``:
the command line, its refusals and the log) runs it.

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
import struct

from models import registers as regmap
from models.card_socket import ADVANCE, ANSWER_WORDS, FIFO, MAX_BURST, READ, REQUEST_WORDS, WRITE
from sim.card.card_session import AccessError

REQUEST = struct.Struct("<" + "I" * REQUEST_WORDS)
ANSWER = struct.Struct("<" + "I" * ANSWER_WORDS)
PPM_ONE = 1_000_000
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
            for name in ("ENC_COUNT", "ENC_STATUS"):
                self.final[name] = [self.session.read(regmap.axis_offset(name, axis)) for axis in range(self.pins.axes)]

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
