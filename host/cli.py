"""``python -m host``: plan a G-code program or an SVG drawing for the card, run it.

``python -m host plan FILE [options]`` reads FILE (``.svg``: the SVG front end,
anything else: G-code), plans it, runs the commands through the DDA's golden
model and prints the segments, commands, steps, the largest deviation from
the drawing and the job time; ``--preview out.png`` draws the path over the
drawing, ``--list`` prints every command, ``--words out.txt`` writes the FIFO
words (hex, one a line).  Bad options are refused before anything is read or
written; a bad program line is one error line naming it.

``run``, ``info`` and ``selftest`` talk to a card (``host/cli_card.py``).
"""
import argparse
import collections
import importlib.util
import math
import sys
from pathlib import Path

from host import cli_card, gcode, svg
from host.card import CardError, IdentityError
from host.check import check
from host.errors import ProgramError
from host.machine import DEFAULT_CLOCK_HZ, DEFAULT_COORD_WIDTH, Machine
from host.planner import plan
from host.transports.base import TransportError
from models.axes import AXIS_NAMES
from models.commands import command_words
from models.parameters import AXES
from models.registers import RATE_MAX

PROG = "python -m host"


def positive(text):
    value = float(text)
    if not value > 0 or not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r} is not a positive number")
    return value


def scales(text):
    """Steps per mm (per degree for A, B, C): one value for every axis, or one per axis."""
    parts = text.split(",")
    if not 1 <= len(parts) <= len(AXIS_NAMES):
        raise argparse.ArgumentTypeError(f"{text!r}: give one value, or one per axis ({','.join(AXIS_NAMES)})")
    return tuple(positive(p) for p in parts)


def axis_count(text):
    """The ``axes`` build parameter's value (models/parameters.py)."""
    try:
        return AXES.parse(text)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def per_axis(values, axes, refuse):
    """``values`` (from ``scales``) for ``axes`` axes: one value for all, or exactly one each."""
    if len(values) == 1:
        return values * axes
    if len(values) != axes:
        refuse(f"--steps-per-mm: {len(values)} values for {axes} axes ({', '.join(AXIS_NAMES[:axes])}): "
               "give one value, or one per axis")
    return values


def width(text):
    value = int(text)
    if not 8 <= value <= 32:
        raise argparse.ArgumentTypeError(f"{text!r}: the coordinate width is 8..32 bits")
    return value


def count(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r} is not a positive whole number")
    return value


class _Parser(argparse.ArgumentParser):
    """Reports a bad command line in one line (no usage block) and exits 2."""

    def error(self, message):
        self.exit(2, f"{PROG}: error: {message}\n")


def parser():
    top = _Parser(prog=PROG, allow_abbrev=False, description=__doc__.split("\n\n")[0])
    commands = top.add_subparsers(dest="command", required=True, parser_class=_Parser)
    plan_cmd = commands.add_parser("plan", help="plan FILE and measure the path against the drawing")
    plan_cmd.add_argument("file", type=Path, help="G-code program, or an .svg drawing")
    plan_cmd.add_argument("--axes", type=axis_count, default=AXES.default,
                          help=f"plan for a card with this many axes, X, Y, Z, A, B, C in order: "
                               f"{AXES.bounds()} (default {AXES.default}); a program naming another axis is "
                               "refused with its line")
    plan_cmd.add_argument("--steps-per-mm", type=scales, default=(200.0,), metavar="X[,Y,...]",
                          help="steps per mm of each axis (per degree for A, B, C): one value for all, or "
                               "one per axis (default 200)")
    plan_cmd.add_argument("--clock-hz", type=positive, default=DEFAULT_CLOCK_HZ,
                          help=f"the card's clock frequency (default {DEFAULT_CLOCK_HZ})")
    plan_cmd.add_argument("--coord-width", type=width, default=DEFAULT_COORD_WIDTH,
                          help=f"the card's coordinate width in bits (default {DEFAULT_COORD_WIDTH})")
    plan_cmd.add_argument("--rapid", type=positive, default=3000.0, help="rapid feed, mm/min (default 3000)")
    plan_cmd.add_argument("--acceleration", type=positive, default=500.0, help="mm/s^2 (default 500)")
    plan_cmd.add_argument("--start-feed", type=positive, default=60.0,
                          help="mm/min a move starts and stops with (default 60)")
    plan_cmd.add_argument("--feed", type=positive, default=1200.0,
                          help="SVG: feed of the drawn moves, mm/min (default 1200)")
    plan_cmd.add_argument("--tolerance", type=positive, default=0.01,
                          help="SVG: curves as arcs within this many mm (default 0.01)")
    plan_cmd.add_argument("--mark-interval", type=count, default=256, help="words between MARKs (default 256)")
    plan_cmd.add_argument("--list", action="store_true", help="print every command")
    plan_cmd.add_argument("--words", type=Path, help="write the FIFO words here (hex, one a line)")
    plan_cmd.add_argument("--preview", type=Path, help="draw the path over the drawing into this PNG")
    cli_card.add_commands(commands, positive, scales, count, axis_count)
    return top


def main(argv=None):
    options = parser().parse_args(argv)
    command = {"plan": _plan, "run": lambda o: cli_card.run_command(o, _refuse, per_axis),
               "info": lambda o: cli_card.info_command(o, _refuse),
               "selftest": lambda o: cli_card.selftest_command(o, _refuse)}[options.command]
    try:
        return command(options)
    except (ProgramError, ValueError, CardError, IdentityError, TransportError, TimeoutError) as error:
        print(f"{PROG}: error: {error}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:  # before the card runs anything (the streamer handles SIGINT itself)
        print(f"{PROG}: interrupted", file=sys.stderr)
        return 130


def _refuse(message):
    parser().error(message)


def _plan(options):
    if not options.file.is_file():
        _refuse(f"{options.file}: no such file")
    for out in (options.words, options.preview):
        if out is not None and not out.parent.is_dir():
            _refuse(f"{out}: its folder does not exist")
    if options.preview and importlib.util.find_spec("matplotlib") is None:
        _refuse("--preview needs matplotlib: pip install -e '.[plot]'")
    machine = Machine(steps_per_mm=per_axis(options.steps_per_mm, options.axes, _refuse), clock_hz=options.clock_hz,
                      coord_width=options.coord_width, rapid=options.rapid,
                      acceleration=options.acceleration, start_feed=options.start_feed,
                      mark_interval=options.mark_interval)
    if options.file.suffix.lower() == ".svg":
        drawing = svg.parse(str(options.file), options.tolerance, options.feed, options.file.name)
    else:
        drawing = gcode.parse(options.file.read_text(), options.file.name, options.axes)
    planned = plan(drawing, machine)
    result = check(planned)
    if options.list:
        for entry in planned.entries:
            print(f"{entry.where:24} {entry.command}")
    for line in summary(planned, result):
        print(line)
    if options.words:
        options.words.write_text("".join(f"{w:08x}\n" for e in planned.entries for w in command_words(e.command)))
        print(f"words:      {options.words}")
    if options.preview:
        from host.preview import draw

        draw(planned, result, options.preview)
        print(f"preview:    {options.preview}")
    return 0


def summary(planned, result):
    """The figures ``plan`` prints."""
    machine = planned.machine
    kinds = collections.Counter(type(e.command).__name__.replace("Command", "").upper()
                                for e in planned.entries)
    primitives = collections.Counter(type(item).__name__.lower() for item in planned.drawing)
    fed = [r for r in planned.runs if not r.rapid]
    feeds = sorted({round(r.achieved_feed(machine), 1) for r in fed})
    lines = [
        f"segments:   {len(planned.drawing)} ({', '.join(f'{n} {k}' for k, n in sorted(primitives.items()))})",
        f"commands:   {sum(kinds.values())} ({', '.join(f'{n} {k}' for k, n in sorted(kinds.items()))}), "
        f"{len(planned.words())} words",
        f"runs:       {len(planned.runs)} (stops between them), {sum(r.capped for r in planned.runs)} "
        f"slowed so that their last move can decelerate",
        f"steps:      {', '.join(f'{AXIS_NAMES[a]} {n}' for a, n in enumerate(result.steps))}; "
        f"{result.iterations} DDA iterations; ends at {result.end}",
        f"deviation:  max {result.max_deviation_mm:.5f} mm = {result.max_deviation_steps:.3f} steps "
        f"(at {result.worst_where})",
        f"feed:       fed runs at {', '.join(f'{f:g}' for f in feeds) or '-'} mm/min "
        f"(FEED_RATE unit: {machine.iterations_per_second(1):.1f} iterations/s, at most {RATE_MAX})",
        f"ramps:      up to {_steepest(planned):.0f} mm/s^2 at the top of a ramp (asked "
        f"{machine.acceleration:g}; RAMP_STEP is at least 1 per iteration)",
        f"job time:   {result.job_seconds:.3f} s at the planned rates and ramps "
        f"(length / programmed feed: {result.ideal_seconds:.3f} s)",
    ]
    return lines


def _steepest(planned):
    """The largest acceleration of any run's ramp, at its top speed (mm/s^2):
    ``v * RAMP_STEP * f_clk / 65536`` (the ramp is linear in distance)."""
    machine = planned.machine
    return max((machine.iterations_per_second(run.feed_rate) * run.mm_per_iteration
                * machine.iterations_per_second(run.ramp_step) for run in planned.runs), default=0.0)
