"""VCD traces a user opens in GTKWave, and reading them back in tests.

``run_traced(bench, name)`` runs a bench with MyHDL tracing into
``build/waves/<name>.vcd``.  ``write_gtkw`` writes a GTKWave save file that
groups the signals a user looks at.  ``Waveform`` reads a VCD back (pyvcd's
tokenizer) so that assertions check the very file a user opens.
"""
import bisect
from pathlib import Path

from vcd.gtkw import GTKWSave
from vcd.reader import TokenKind, tokenize

from sim.paths import build_dir


def waves_dir():
    return build_dir("waves")


def run_traced(bench, name, duration=None):
    """Run ``bench`` (a block instance) with a VCD trace; return the VCD path.

    The simulation is always closed, also when the bench fails, so that the
    next bench can start (MyHDL allows one simulation at a time).
    """
    directory = waves_dir()
    bench.config_sim(trace=True, directory=str(directory), name=name, tracebackup=False)
    try:
        bench.run_sim(duration, quiet=1)
    finally:
        if bench.sim is not None and not bench.sim._finished:
            bench.quit_sim()
    return directory / f"{name}.vcd"


def write_gtkw(vcd_path, groups, signed=()):
    """Write ``<vcd>.gtkw`` showing ``groups`` ({group: [signal suffix]})."""
    vcd_path = Path(vcd_path)
    wave = Waveform(vcd_path)
    save_path = vcd_path.with_suffix(".gtkw")
    with open(save_path, "w") as out:
        save = GTKWSave(out)
        save.dumpfile(str(vcd_path.resolve()))
        save.zoom_markers(-8)
        for group, suffixes in groups.items():
            with save.group(group):
                for suffix in suffixes:
                    full = wave.full_name(suffix)
                    datafmt = "dec" if suffix in signed else "hex"
                    save.trace(full, datafmt=datafmt)
    return save_path


class Waveform:
    """Value changes of every variable of a VCD, by hierarchical name."""

    def __init__(self, path):
        self.path = Path(path)
        self.changes = {}
        self._names_by_id = {}
        scope = []
        time = 0
        with open(self.path, "rb") as stream:
            for token in tokenize(stream):
                kind = token.kind
                if kind is TokenKind.SCOPE:
                    scope.append(token.scope.ident)
                elif kind is TokenKind.UPSCOPE:
                    scope.pop()
                elif kind is TokenKind.VAR:
                    full = ".".join(scope + [token.var.reference])
                    self._names_by_id.setdefault(token.var.id_code, []).append(full)
                    self.changes[full] = ([], [])
                elif kind is TokenKind.CHANGE_TIME:
                    time = token.data
                elif kind in (TokenKind.CHANGE_SCALAR, TokenKind.CHANGE_VECTOR,
                              TokenKind.CHANGE_STRING, TokenKind.CHANGE_REAL):
                    for full in self._names_by_id.get(token.data.id_code, ()):
                        times, values = self.changes[full]
                        times.append(time)
                        values.append(token.data.value)

    def full_name(self, suffix):
        """The one hierarchical name ending in ``suffix`` (shortest if several)."""
        hits = [n for n in self.changes if n == suffix or n.endswith("." + suffix)]
        if not hits:
            raise KeyError(f"{suffix} not in {self.path.name}")
        return min(hits, key=len)

    def at(self, suffix, time):
        """Value of a variable at ``time`` (after the changes at that time)."""
        times, values = self.changes[self.full_name(suffix)]
        index = bisect.bisect_right(times, time) - 1
        if index < 0:
            raise ValueError(f"{suffix} has no value at {time}")
        return values[index]

    def edges(self, suffix, value):
        """Times at which a variable takes ``value``."""
        times, values = self.changes[self.full_name(suffix)]
        return [t for t, v in zip(times, values) if v == value]
