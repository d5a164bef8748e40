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
