"""``CardSession``: the card driven one call at a time gives the same pins,
clock for clock, on every back end as the golden model says."""
import pytest

from models import registers as regmap
from models.commands import command_words
from models.dda_model import ArcCommand, LineCommand
from sim.backends.verilator.model import Stop
from sim.card.card_bench import expected_path
from sim.card.card_e2e import KINDS, io_read, io_write, program
from sim.card.card_session import CardSession

MOVES = [LineCommand(7, -3), ArcCommand(5, 0, 0, 5, ccw=True, variant=3), LineCommand(-2, 9)]


def session_run(kind):
    """Program, burst, wait for INTA# one call at a time; (pins' edges, position, clocks, INTA# reason)."""
    session = CardSession(kind)
    try:
        bench, target = session.bench, session.target
        session.call(program(bench, target))
        words = [w for move in MOVES for w in command_words(move)]
        session.call(bench.host.mem_write(session.mem, words))
        _, reason = session.wait(20000, inta=True)
        x = session.call(io_read(bench, target, "POS_X"))
        y = session.call(io_read(bench, target, "POS_Y"))
        session.call(io_write(bench, target, "INT_STATUS", 0xFF))
        position = (regmap.field_value("POS_X", "STEPS", x), regmap.field_value("POS_Y", "STEPS", y))
        return list(session.log.edges), position, session.clocks, reason, session.log.path()
    finally:
        session.close()


def test_calls_give_the_same_pins_on_every_back_end():
    runs = {kind: session_run(kind) for kind in KINDS}
    ideal = expected_path(MOVES)
    for kind, (edges, position, clocks, reason, path) in runs.items():
        assert reason is Stop.INTERRUPT, kind
        assert position == ideal[-1], kind
        assert path == ideal, kind
        assert edges == runs["verilator"][0], kind
        assert clocks == runs["verilator"][2], kind


def test_a_closed_session_refuses_calls():
    session = CardSession("verilator")
    session.close()
    with pytest.raises(RuntimeError, match="closed"):
        session.wait(10)


def register_script(session):
    """Register accesses a driver makes, each answer kept: every register read,
    an out-of-range write (clamped, flagged), byte and word accesses, a
    write-1-to-clear, a read with a side effect (POS_X holds POS_Y)."""
    answers = {name: session.read(regmap.offset(name)) for name in (r.name for r in regmap.REGISTERS)}
    step_width = regmap.offset("STEP_WIDTH")
    session.write(step_width, 0x1FF)
    answers["clamped"] = session.read(step_width)
    answers["int_status"] = session.read(regmap.offset("INT_STATUS"))
    session.write(regmap.offset("INT_STATUS"), 0xFF)
    answers["cleared"] = session.read(regmap.offset("INT_STATUS"))
    feed = regmap.offset("FEED_RATE")
    session.write(feed, 0x1234, size=2)
    session.write(feed + 1, 0x56, size=1)
    answers["feed word"] = session.read(feed, size=2)
    answers["feed byte"] = session.read(feed + 1, size=1)
    answers["pos_x"] = session.read(regmap.offset("POS_X"))
    answers["pos_y"] = session.read(regmap.offset("POS_Y"))
    return answers


def test_registers_answer_the_same_through_bar0_and_bar2():
    """BAR2 is BAR0's registers in memory space: the same script gives the
    same answers through either, and the table's clamp and W1C hold."""
    answers = {}
    for bar in (0, 2):
        session = CardSession("verilator", register_bar=bar)
        try:
            answers[bar] = register_script(session)
        finally:
            session.close()
    assert answers[2] == answers[0]
    width = regmap.register("STEP_WIDTH")
    assert answers[2]["clamped"] == width.maximum
    clamped_bit = regmap.register("INT_STATUS").field("CLAMPED").mask
    assert answers[2]["int_status"] & clamped_bit and not answers[2]["cleared"] & clamped_bit
    assert (answers[2]["feed word"], answers[2]["feed byte"]) == (0x5634, 0x56)


def test_register_bar_is_0_or_2():
    with pytest.raises(ValueError, match="register_bar"):
        CardSession("verilator", register_bar=1)
