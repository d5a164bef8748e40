"""The streamer: a planned job of any length through the card's FIFO.

``stream(card, plan)`` queues the plan's commands as the FIFO makes room:
it fills the FIFO, sleeps until the LOW_WATER interrupt (the level fell
below ``low_water`` words: half the FIFO by default) and fills it again, so
a blended run never finds the FIFO empty at a segment boundary (the card
would stop it at speed).  A command is never split between two bursts.
MARKs (the planner puts them at stops) are read back as they are reached
(tag and position); inside a blended run progress is the words the card has
consumed.  After the last word it waits for DONE.

``progress(consumed, total)`` is called after every refill; ``should_stop()``
is asked at least every ``slice_seconds`` of card time: when it says yes,
``Stopped`` is raised with the queue still running (the caller stops the
card: ``Card.stop``).  Card errors come back as ``CardError`` naming the
program line whose command the card refused.
"""
from dataclasses import dataclass, field

from models import registers as regmap
from models.commands import command_words

SLICE_SECONDS = 0.02  # card time between two looks at should_stop while waiting


class Stopped(Exception):
    """``should_stop`` asked the streamer to stop."""


@dataclass
class StreamResult:
    words: int = 0
    commands: int = 0
    bursts: int = 0
    interrupts: int = 0
    marks: list = field(default_factory=list)   # (tag, position) as each MARK was reached
    position: tuple = (0, 0)
    seconds: float = 0.0                        # card time from the first word to DONE


def command_list(plan):
    """[(words, name)] of the plan's commands; the name says where the command came from."""
    commands = []
    for entry in plan.entries:
        kind = type(entry.command).__name__.replace("Command", "").upper()
        commands.append((command_words(entry.command), f"{entry.where or 'the job'}: {kind}"))
    return commands


def stream(card, plan, low_water=None, progress=None, should_stop=None, slice_seconds=SLICE_SECONDS):
    """Run ``plan`` (a ``host.planner.Plan``) on ``card``; a ``StreamResult``."""
    transport = card.transport
    depth = card.identity.fifo_words
    low_water = depth // 2 if low_water is None else low_water
    if not 0 < low_water < depth:
        raise ValueError(f"the low-water mark must be 1..{depth - 1} words, not {low_water}")
    should_stop = should_stop or (lambda: False)
    commands = command_list(plan)
    total = sum(len(words) for words, _ in commands)
    result = StreamResult(commands=len(commands))
    card.start(interrupts=("LOW_WATER", "MARK", "ERROR", "DONE"), low_water=low_water)
    start = transport.now()
    index = 0
    while True:
        status = card.status()
        card.check(status)
        room = depth - regmap.field_value("STATUS", "FIFO_LEVEL", status)
        burst, taken = [], []
        while index < len(commands) and len(burst) + len(commands[index][0]) <= room:
            words, name = commands[index]
            burst += words
            taken.append((len(words), name))
            index += 1
        if burst:
            card.queue(burst, taken)
            result.words += len(burst)
            result.bursts += 1
        if progress:
            progress(card.consumed(), total)
        if index == len(commands):
            card.write("INT_ENABLE", regmap.field_of("INT_ENABLE", MARK=1, ERROR=1, DONE=1))
        pending = _wait(card, result, should_stop, slice_seconds)
        if index == len(commands) and _finished(card, pending):
            break
    result.position = card.position()
    result.seconds = transport.now() - start
    if progress:
        progress(total, total)
    return result


def _wait(card, result, should_stop, slice_seconds):
    """Until INTA# (or a slice of card time): acknowledge and handle what it says; INT_STATUS."""
    while True:
        if should_stop():
            raise Stopped()
        if card.transport.wait_interrupt(slice_seconds):
            break
        status = card.status()
        # a stopped card keeps BUSY while its FIFO holds words: the caller's check raises MachineStopped
        if not regmap.field_value("STATUS", "BUSY", status) or regmap.field_value("STATUS", "STOPPED", status):
            break
    pending = card.read("INT_STATUS")
    if pending:
        card.write("INT_STATUS", pending)
        result.interrupts += 1
    if regmap.field_value("INT_STATUS", "ERROR", pending):
        card.check()
    if regmap.field_value("INT_STATUS", "MARK", pending):
        result.marks.append((card.last_mark(), card.position()))
    return pending


def _finished(card, pending):
    status = card.status()
    card.check(status)
    return not regmap.field_value("STATUS", "BUSY", status) and regmap.field_value("STATUS", "FIFO_EMPTY", status)
