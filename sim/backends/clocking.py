"""The clock every bench runs on, and the stimulus of the unit benches."""
from myhdl import StopSimulation, always, block, delay, instance


@block
def clock_source(clock, period):
    """Toggle ``clock`` every ``period // 2`` time units (it starts at its initial value)."""
    half_period = period // 2

    @always(delay(half_period))
    def toggle():
        clock.next = not clock

    return toggle


@block
def reset_then_step(clock, reset, cycles, step, after=None):
    """Reset for two falling edges, then ``step(index)`` at each of
    ``cycles`` falling edges and, if given, ``after(index)`` one time unit
    later (combinational outputs of what ``step`` drove, before the rising
    edge); the simulation stops after the last."""

    @instance
    def stimulus():
        reset.next = 0
        yield clock.negedge
        yield clock.negedge
        reset.next = 1
        for index in range(cycles):
            yield clock.negedge
            step(index)
            if after:
                yield delay(1)
                after(index)
        raise StopSimulation

    return stimulus
