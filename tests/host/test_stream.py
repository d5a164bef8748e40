"""The streamer on the simulated card: jobs far longer than the FIFO, the
pins against the golden model (``host.check``), and the starvation measure
(``host.pin_measure``) on the pins, shown to fail when the host is late."""
import pytest

from bench.host_jobs import streaming_job
from host import gcode
from host.card import Card
from host.machine_io import MachineStopped
from host.check import check
from host.pin_measure import junction_gaps, period_violations, pin_moves
from host.planner import plan
from host.stream import command_list, stream
from host.transports.simulated import SimTransport
from models.sim_machine import MachineConfig, Switch
from sim.card.card_e2e import DEFAULT_FIFO

FAST_PULSES = dict(step_width_ns=30, dir_setup_ns=30, dir_hold_ns=30)  # one clock each at 33 MHz
GIVE_UP_CLOCKS = 3_000_000   # the job (200 steps at 600 mm/min) takes about 660,000 clocks


def run_stream(kind, segments, seed=1, **options):
    """Stream a ``streaming_job`` on ``kind``; (plan, model check, result, rises, progress calls, clocks)."""
    with SimTransport(kind) as transport:
        card = Card(transport)
        drawing, machine = streaming_job(segments, card.identity.clock_hz, card.identity.coord_width, seed=seed)
        card.configure(steps_per_mm=machine.steps_per_mm, **FAST_PULSES)
        planned = plan(drawing, machine)
        model = check(planned)
        calls = []
        first, clocks = len(transport.pins.rises), transport.clocks
        result = stream(card, planned, progress=lambda done, total: calls.append((done, total)), **options)
        return planned, model, result, transport.pins.rises[first:], calls, transport.clocks - clocks


def assert_streamed_without_starvation(planned, model, result, rises):
    (run,) = planned.runs  # one blended run at one rate
    assert run.ramp_step == 0
    assert result.position == planned.end
    got = [p for _, points in pin_moves(planned, model, rises) for p in points[1:]]
    assert got == [p for _, points in model.points for p in points[1:]]
    measured, over = junction_gaps(planned, model, rises)
    assert measured == len(planned.moves()) - 1 and over == []
    assert period_violations(rises, run.feed_rate) == []


def test_a_job_many_times_the_fifo_streams_with_no_gap_on_the_pins():
    planned, model, result, rises, calls, clocks = run_stream("verilator", 3000)
    assert result.words == len(planned.words()) > 15 * DEFAULT_FIFO
    assert result.bursts > 15 and result.interrupts >= result.bursts - 1
    assert result.marks and result.marks[-1][0] == max(planned.marks)
    assert_streamed_without_starvation(planned, model, result, rises)
    consumed = [done for done, _ in calls]
    assert consumed == sorted(consumed) and calls[-1] == (len(planned.words()), len(planned.words()))


@pytest.mark.slow(reason="100,000 segments; the short streams run by default")
def test_100000_segments_stream_with_no_gap_on_the_pins():
    planned, model, result, rises, _, clocks = run_stream("verilator", 100_000, seed=7)
    assert len(planned.drawing) == 100_000
    assert_streamed_without_starvation(planned, model, result, rises)


@pytest.mark.parametrize("kind", ["myhdl", "icarus"])
def test_a_short_stream_on_the_event_simulators(kind):
    planned, model, result, rises, _, _ = run_stream(kind, 40)
    assert_streamed_without_starvation(planned, model, result, rises)


def test_the_starvation_measure_sees_a_late_host():
    with SimTransport("verilator") as transport:
        card = Card(transport)
        drawing, machine = streaming_job(60, card.identity.clock_hz, card.identity.coord_width)
        card.configure(steps_per_mm=machine.steps_per_mm, **FAST_PULSES)
        planned = plan(drawing, machine)
        model = check(planned)
        commands = command_list(planned)
        half = len(commands) // 2
        first = len(transport.pins.rises)
        card.start()
        for part in (commands[:half], commands[half:]):
            card.queue([w for words, _ in part for w in words], [(len(words), name) for words, name in part])
            transport.sleep(200e-6)  # the host comes back only after the FIFO ran empty
        card.wait_done()
        rises = transport.pins.rises[first:]
        assert card.position() == planned.end
        _, over = junction_gaps(planned, model, rises)
        assert len(over) == 1
        assert len(period_violations(rises, planned.runs[0].feed_rate)) >= 1


def test_a_bad_low_water_mark_is_refused():
    with SimTransport("verilator") as transport:
        card = Card(transport)
        drawing, machine = streaming_job(5, card.identity.clock_hz, card.identity.coord_width)
        with pytest.raises(ValueError, match="low-water"):
            stream(card, plan(drawing, machine), low_water=card.identity.fifo_words)


def test_a_stop_mid_stream_raises_instead_of_waiting_for_the_busy_card():
    # the card stops on X's positive limit with the job's last lines still in its FIFO: STATUS.BUSY stays
    # set while it is stopped, so the streamer must look at STATUS.STOPPED too (it waited for ever before)
    config = MachineConfig(switches={"LIMIT_POS_X": Switch(60)})
    with SimTransport("verilator", machine=config) as transport:
        card = Card(transport)
        machine = card.configure(steps_per_mm=(100.0, 100.0), **FAST_PULSES)
        card.drive(True)
        planned = plan(gcode.parse("G1 X0.5 F600\nG1 X1\nG1 X1.5\nG1 X2\n", "limit.ngc"), machine)
        start = transport.clocks
        with pytest.raises(MachineStopped, match="LIMIT"):
            stream(card, planned, should_stop=lambda: transport.clocks - start > GIVE_UP_CLOCKS, slice_seconds=1e-3)
        assert 60 <= card.position()[0] < 100 and transport.clocks - start < GIVE_UP_CLOCKS
