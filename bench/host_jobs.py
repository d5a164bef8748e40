"""Long synthetic jobs for the streamer: one blended run of many short lines.

``wandering_lines(segments, seed)`` is a polyline of ``segments`` lines of 3
to 12 steps whose heading turns by at most ``max_turn`` degrees at each
corner and drifts back towards the origin, so it stays near it however long
it is.  Planned with the start feed equal to the feed (``streaming_job``)
every corner blends and RAMP_STEP is 0: the whole job is one run at one
rate, the harshest case for the FIFO (no stop in which to catch up).
"""
import math
import random

from host.geometry import Line
from host.machine import Machine

STEPS_PER_MM = 40.0


def wandering_lines(segments, seed=1, max_turn=40.0, feed=600.0):
    """[Line] in mm (``feed`` mm/min), from the origin."""
    rng = random.Random(seed)
    x = y = 0.0
    heading = 0.0
    lines = []
    for index in range(segments):
        home = math.atan2(-y, -x) if (x, y) != (0.0, 0.0) else heading
        pull = math.remainder(home - heading, math.tau)
        turn = math.radians(max_turn) * max(-1.0, min(1.0, 0.2 * pull + rng.uniform(-0.8, 0.8)))
        heading += turn
        length = rng.randint(3, 12) / STEPS_PER_MM
        end = (x + length * math.cos(heading), y + length * math.sin(heading))
        lines.append(Line((x, y), end, feed=feed, where=f"segment {index + 1}"))
        x, y = end
    return lines


def streaming_job(segments, clock_hz, coord_width, feed_rate=2048, seed=1):
    """(drawing, machine): ``wandering_lines`` at a feed that runs a diagonal
    line at ``feed_rate`` FEED_RATE units on a card clocked at ``clock_hz``;
    the start feed equals the feed (no ramps)."""
    mm_per_iteration = math.sqrt(2) / STEPS_PER_MM  # the longest iteration: a diagonal step
    feed = feed_rate / 65536 * clock_hz * mm_per_iteration * 60
    machine = Machine(steps_per_mm=(STEPS_PER_MM, STEPS_PER_MM), clock_hz=clock_hz, coord_width=coord_width,
                      rapid=feed, start_feed=feed, acceleration=1e12)
    return wandering_lines(segments, seed, feed=feed), machine
