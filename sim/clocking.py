"""The clock every bench runs on."""
from myhdl import always, block, delay


@block
def clock_source(clock, period):
    """Toggle ``clock`` every ``period // 2`` time units (it starts at its initial value)."""
    half_period = period // 2

    @always(delay(half_period))
    def toggle():
        clock.next = not clock

    return toggle
