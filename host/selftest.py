"""``python -m host selftest``: checks any card can run on itself, on any transport.

* register walk: every RW register takes walking ones and zeros within its
  range (the register table's widths, minima and maxima), an out-of-range
  value is clamped and flags INT_STATUS.CLAMPED, and the reset values come
  back afterwards (soft reset does not reset registers, so the walk restores
  what it found);
* FIFO loop: with execution held, MARK words fill the FIFO to the level
  FIFO_SIZE says, STATUS.FIFO_FULL shows, soft reset empties it;
* a short move: LINE, ARC back through a full circle, LINE home; the
  position must come back to where it started, and in between read what
  the golden model says.

Each check gives (name, None) or (name, what went wrong).
"""
from models import instructions as isa
from models import registers as regmap
from models.dda_model import ArcCommand, LineCommand

WALK = ("LOW_WATER", "FEED_RATE", "RAMP_START", "RAMP_STEP", "STEP_WIDTH", "DIR_SETUP", "DIR_HOLD",
        "DIR_POLARITY", "PULSE_PERIOD_X", "PULSE_PERIOD_Y")
MOVES = (LineCommand(120, -45), ArcCommand(-30, 40, -30, 40, ccw=True, variant=3), LineCommand(-120, 45))


def selftest(card):
    """Yield (check name, None or a problem)."""
    card.stop()
    yield "register walk", _register_walk(card)
    yield "FIFO loop", _fifo_loop(card)
    yield "short move", _short_move(card)


def _values(reg):
    low = reg.minimum if reg.minimum is not None else 0
    high = reg.maximum if reg.maximum is not None else (1 << reg.width) - 1
    walk = {1 << bit for bit in range(reg.width)} | {high & ~(1 << bit) for bit in range(reg.width)}
    return low, high, sorted(v for v in walk if low <= v <= high) + [low, high]


def _register_walk(card):
    transport = card.transport
    for name in WALK:
        reg = regmap.register(name)
        saved = transport.read(reg.offset)
        low, high, values = _values(reg)
        for value in values:
            transport.write(reg.offset, value)
            back = transport.read(reg.offset)
            if back != value:
                return f"{name}: wrote {value:#x}, read {back:#x}"
        if reg.maximum is not None and reg.maximum < (1 << reg.width) - 1:
            transport.write(regmap.offset("INT_STATUS"), regmap.field_of("INT_STATUS", CLAMPED=1))
            transport.write(reg.offset, reg.maximum + 1)
            back = transport.read(reg.offset)
            flagged = regmap.field_value("INT_STATUS", "CLAMPED", transport.read(regmap.offset("INT_STATUS")))
            if back != reg.maximum or not flagged:
                return f"{name}: {reg.maximum + 1} read back {back} (clamped to {reg.maximum}?), CLAMPED {flagged}"
        transport.write(reg.offset, saved)
        if transport.read(reg.offset) != saved:
            return f"{name}: the value found, {saved:#x}, did not come back"
    transport.write(regmap.offset("INT_STATUS"), regmap.field_of("INT_STATUS", CLAMPED=1))
    return None


def _fifo_loop(card):
    depth = card.identity.fifo_words
    card.write("CONTROL", 0)
    words = [w for tag in range(depth + 1) for w in isa.encode("MARK", TAG=tag)]
    # one command goes into the instruction register, ``depth`` into the FIFO
    card.queue(words, [(1, f"MARK {tag}") for tag in range(depth + 1)])
    status = card.status()
    level = regmap.field_value("STATUS", "FIFO_LEVEL", status)
    full = regmap.field_value("STATUS", "FIFO_FULL", status)
    card.stop()
    after = regmap.field_value("STATUS", "FIFO_LEVEL", card.status())
    if level != depth or not full or after != 0:
        return f"{depth + 1} MARKs queued: FIFO level {level} (expected {depth}), FULL {full}, after reset {after}"
    return None


def _short_move(card):
    card.configure()
    card.write("COMMAND", regmap.field_of("COMMAND", CLEAR_POSITION=1))
    card.start(interrupts=("ERROR", "DONE"))
    start = card.position()
    first, circle, back = MOVES
    card.line(first.dx, first.dy)
    card.wait_done(timeout=1.0)
    there = card.position()
    card.arc(centre=(-circle.xs, -circle.ys), end=(0, 0), ccw=True)
    card.line(back.dx, back.dy)
    card.wait_done(timeout=1.0)
    home = card.position()
    expected_there = (start[0] + first.dx, start[1] + first.dy)
    if there != expected_there or home != start:
        return f"position after the first LINE {there} (expected {expected_there}), at the end {home} " \
               f"(expected {start})"
    return None
