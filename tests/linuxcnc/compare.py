"""Commanded joint positions (LinuxCNC's sampler) against the simulated card's STEP/DIR pins."""
import bisect
import json

from models import instructions as isa


def read_samples(path):
    """[(x_cmd, y_cmd, card clock at the period's end, fifo level, underruns, X enabled,
    drive-enable, drift-trim)] from ``halsampler -t``."""
    samples = []
    for line in open(path):
        fields = line.split()
        samples.append((float(fields[1]), float(fields[2]), int(fields[3]), int(fields[5]), int(fields[6]),
                        int(fields[7]), int(fields[8]), int(fields[9])))
    return samples


def pin_positions(card_log):
    """(clocks of the rises, X and Y step positions after each) from the card server's log."""
    clocks, xs, ys = [], [], []
    x = y = 0
    for clock, step_x, step_y, dir_x, dir_y in json.load(open(card_log))["rises"]:
        x += step_x * (1 if dir_x else -1)
        y += step_y * (1 if dir_y else -1)
        clocks.append(clock)
        xs.append(x)
        ys.append(y)
    return clocks, xs, ys


def deviations(samples, pins, scale, delay_clocks):
    """Per sample: the pins' position delay_clocks after the period's end minus the command, in steps."""
    clocks, xs, ys = pins
    result = []
    for x_cmd, y_cmd, clock, *_ in samples:
        i = bisect.bisect_right(clocks, clock + delay_clocks)
        x, y = (xs[i - 1], ys[i - 1]) if i else (0, 0)
        result.append((x - x_cmd * scale, y - y_cmd * scale))
    return result


def read_axis_samples(path, axes):
    """[((commanded joint positions), card clock at the period's end, fifo level, underruns,
    drive-enable)] from ``halsampler -t`` of ``session.MILL_RECORD_HAL`` (``axes`` joints)."""
    samples = []
    for line in open(path):
        fields = line.split()[1:]
        commands = tuple(float(f) for f in fields[:axes])
        clock, level, underruns, drive = (int(f) for f in fields[axes:axes + 4])
        samples.append((commands, clock, level, underruns, drive))
    return samples


def axis_pin_positions(card_log):
    """(clocks of the rises, every axis's step position after each) from the card server's
    log (its ``axis_rises``)."""
    rises = json.load(open(card_log))["axis_rises"]
    return [clock for clock, _ in rises], [tuple(point) for _, point in rises]


def axis_deviations(samples, pins, scale, delay_clocks):
    """Per sample of ``read_axis_samples``: the pins' position delay_clocks after the period's
    end minus the command, in steps, per axis."""
    clocks, points = pins
    result = []
    for commands, clock, *_ in samples:
        i = bisect.bisect_right(clocks, clock + delay_clocks)
        here = points[i - 1] if i else (0,) * len(commands)
        result.append(tuple(p - c * scale for p, c in zip(here, commands)))
    return result


def queued_position(fifo):
    """Where the LINEs of the FIFO bursts (the server's ``fifo`` record) lead, in steps."""
    x = y = 0
    for _, words in fifo:
        i = 0
        while i < len(words):
            op = isa.BY_CODE[words[i] >> isa.OPCODE_LSB]
            if op.name == "LINE":
                x += words[i + 1] - (words[i + 1] >> 31 << 32)
                y += words[i + 2] - (words[i + 2] >> 31 << 32)
            i += 1 + len(op.operands)
    return x, y
