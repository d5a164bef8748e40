"""VCD traces a user opens in GTKWave, their save files, and reading them back in tests.

``run_traced(bench, name)`` runs a bench with MyHDL tracing and returns the
VCD's path; every traced run also gets a GTKWave save file (``.gtkw`` beside
the VCD): the view the caller gives (``groups``), or else the bench's own
signals.  Tracing costs a MyHDL run of the whole card about 40 % of its time,
so a bench is traced when its caller reads the VCD back (``trace=True``: its
assertions check the waveform) or when every bench's waves are asked for
(``trace_every_bench``: pytest's ``--waves``, the root ``conftest.py``);
otherwise it runs untraced and ``run_traced`` returns None (``trace=False``:
never traced, for runs too long to trace).  ``write_gtkw`` (re)writes the view of a finished run.
``Waveform`` reads a VCD back (pyvcd's tokenizer) so that assertions check
the very file a user opens.

File names follow the test that ran the bench: inside pytest (the root
``conftest.py`` calls ``named_after`` for every test), test
``sim/test_x.py::test_y[a-b]`` writes ``build/waves/sim/test_x/test_y[a-b].vcd``
and ``.gtkw``; a test that runs several simulations numbers the later ones
(``test_y[a-b].2.vcd``, ...).  Characters other than letters, digits and
``_.,=+-[]`` become ``_``.  Outside pytest the file is ``build/waves/<name>.vcd``.

GTKWave's names: MyHDL declares a vector without a bit range
(``$var reg 8 ! count $end``); GTKWave then knows it as ``count[7:0]`` and
silently leaves out a save-file trace spelled ``count``.  ``gtkwave_name``
is that rule; a save file lists every signal under it, and ``write_gtkw``
refuses to leave a file with a trace its VCD does not declare.

Views open on a window (by default the whole run) with the primary marker
on the event a bench is about.  GTKWave shows ``2**-zoom`` time units per
200 pixels of its wave area, which is the window width less the signal
column and a 64-pixel margin.
"""
import bisect
import hashlib
import math
import os
import re
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from vcd.gtkw import GTKWFlag, GTKWSave
from vcd.reader import TokenKind, tokenize

from rtl.convert import build_dir

WINDOW_SIZE = (1400, 800)  # pixels, the GTKWave window a save file asks for
SIGNALS_WIDTH = 380  # pixels of the signal-name column
WAVE_MARGIN = 64  # pixels of the window that are neither names nor waves
PIXELS_PER_FRAME = 200  # GTKWave: 2**-zoom time units per 200 pixels
WINDOW_SLACK = 1.03  # a view shows its window and 3 % more, so that its edges are visible
UNRANGED_KINDS = {"integer", "parameter", "real", "realtime", "string", "event"}
_UNSAFE = re.compile(r"[^A-Za-z0-9_.,=+\[\]-]")
_current = {"test": None, "runs": 0}
_every_bench = {"traced": False}


def waves_dir():
    return build_dir("waves")


def trace_every_bench(traced=True):
    """Have every bench write its waves (``traced``), or only those whose caller reads them."""
    _every_bench["traced"] = bool(traced)


def traced(asked=None):
    """Whether a run is traced: ``asked`` if the caller says (True or False), else
    whether every bench's waves are wanted."""
    return _every_bench["traced"] if asked is None else bool(asked)


@contextmanager
def named_after(test_id):
    """Name the traces run inside the block after pytest node ``test_id``."""
    before = dict(_current)
    _current.update(test=test_id, runs=0)
    try:
        yield
    finally:
        _current.update(before)


def trace_stem(name):
    """Folder and file name (no suffix) of the next trace: ``(Path, str)``."""
    if _current["test"] is None:
        return waves_dir(), _UNSAFE.sub("_", name)
    path, _, test = _current["test"].partition("::")
    folder = build_dir("waves", *[_UNSAFE.sub("_", part) for part in Path(path).with_suffix("").parts])
    stem = _UNSAFE.sub("_", test.replace("::", "."))
    _current["runs"] += 1
    if _current["runs"] > 1:
        stem += f".{_current['runs']}"
    return folder, stem


def run_traced(bench, name, duration=None, groups=None, *, trace=None, **view):
    """Run ``bench`` (a block instance); return the VCD path, or None if it ran untraced.

    ``trace``: True when the caller reads the VCD back, False never, None
    when every bench's waves are wanted (``traced``).  ``name`` is the VCD's top
    scope (and the file name outside pytest).  The save file shows ``groups``
    (``write_gtkw``'s arguments in ``view``) or else the bench's own signals;
    it is written also when the bench fails.  The simulation is always
    closed, so that the next bench can start (MyHDL allows one simulation at
    a time).
    """
    vcd = None
    if traced(trace):
        folder, stem = trace_stem(name)
        bench.config_sim(trace=True, directory=str(folder), name=name, filename=stem, tracebackup=False)
        vcd = folder / f"{stem}.vcd"
    try:
        bench.run_sim(duration, quiet=1)
    finally:
        if bench.sim is not None and not bench.sim._finished:
            bench.quit_sim()
        if vcd is not None and groups is None:
            write_gtkw(vcd, {"bench": bench_signals(vcd)})
        elif vcd is not None:
            write_gtkw(vcd, groups, **view)
    return vcd


@dataclass(frozen=True)
class Variable:
    """One ``$var`` of a VCD header."""
    scope: tuple
    reference: str
    kind: str
    size: int
    bit_index: object = None  # None, an int or (msb, lsb), as written after the reference

    @property
    def name(self):
        """Hierarchical name without any bit range (as the benches name signals)."""
        return ".".join(self.scope + (self.reference,))

    @property
    def gtkwave_name(self):
        return ".".join(self.scope + (gtkwave_name(self.kind, self.size, self.reference, self.bit_index),))


def gtkwave_name(kind, size, reference, bit_index=None):
    """The name GTKWave gives a VCD variable (and a save file must use).

    A range written in the declaration is kept (``[3:3]`` becomes ``[3]``);
    a vector declared without one gets ``[size-1:0]``, except the kinds
    GTKWave shows as plain values (integer, real, string, ...).
    """
    if isinstance(bit_index, int):
        return f"{reference}[{bit_index}]"
    if bit_index is not None:
        msb, lsb = bit_index
        return f"{reference}[{msb}]" if msb == lsb else f"{reference}[{msb}:{lsb}]"
    if kind in UNRANGED_KINDS or size <= 1:
        return reference
    return f"{reference}[{size - 1}:0]"


def declarations(vcd_path):
    """Every variable the VCD declares, in order (the header only is read)."""
    found, scope = [], []
    with open(vcd_path, "rb") as stream:
        for token in tokenize(stream):
            if token.kind is TokenKind.SCOPE:
                scope.append(token.scope.ident)
            elif token.kind is TokenKind.UPSCOPE:
                scope.pop()
            elif token.kind is TokenKind.VAR:
                var = token.var
                found.append(Variable(tuple(scope), var.reference, var.type_.value, var.size, var.bit_index))
            elif token.kind is TokenKind.ENDDEFINITIONS:
                break
    return found


def end_time(vcd_path, tail=1 << 16):
    """The last time stamp of a VCD (0 if it has none)."""
    with open(vcd_path, "rb") as stream:
        stream.seek(0, os.SEEK_END)
        size = stream.tell()
        stream.seek(max(0, size - tail))
        stamps = re.findall(rb"^#(\d+)", stream.read(), re.MULTILINE)
    if stamps or size <= tail:
        return int(stamps[-1]) if stamps else 0
    return end_time(vcd_path, tail * 16)


def _pattern(suffix):
    """A signal named by its trailing path: ``pulse_out.position_x`` also matches
    ``pulse_out2.position_x`` or ``pulse_out2_0_1.position_x`` (MyHDL numbers
    the instances of a block)."""
    *scopes, leaf = suffix.split(".")
    parts = [re.escape(s) + r"\d*(?:_\d+)*" for s in scopes] + [re.escape(leaf)]
    return re.compile(r"(?:^|\.)" + r"\.".join(parts) + "$")


def find(names, suffix):
    """The one name of ``names`` ending in ``suffix`` (the shortest if several), or None."""
    pattern = _pattern(suffix)
    hits = [n for n in names if pattern.search(n)]
    return min(hits, key=len) if hits else None


def bench_signals(vcd_path):
    """Suffixes of the signals declared at the bench's own level (its top scope)."""
    return [v.reference for v in declarations(vcd_path) if len(v.scope) == 1]


def write_gtkw(vcd_path, groups, signed=(), decimal=(), window=None, marker=None, optional=False,
               names=None):
    """Write ``<vcd>.gtkw`` showing ``groups`` ({group: [signal suffix]}); return its path.

    ``signed``, ``decimal``: suffixes shown as signed or unsigned decimals; ``names``: {suffix:
    {value: text}} shown as text (a GTKWave translate file); ``window``:
    (start, end) time shown when the file opens (default: the whole run);
    ``marker``: time of the primary marker.  A suffix the VCD does not
    declare raises KeyError, unless ``optional`` (it is then left out, and so
    is a group left empty).
    """
    vcd_path = Path(vcd_path)
    variables = {v.name: v for v in declarations(vcd_path)}
    resolved = {}
    for group, suffixes in groups.items():
        hits = []
        for suffix in suffixes:
            full = find(variables, suffix)
            if full is None and not optional:
                raise KeyError(f"{suffix} not in {vcd_path.name}")
            if full is not None:
                hits.append((suffix, variables[full]))
        if hits:
            resolved[group] = hits
    start, end = window if window is not None else (0, end_time(vcd_path))
    save_path = vcd_path.with_name(vcd_path.name[:-len(".vcd")] + ".gtkw")
    with open(save_path, "w") as out:
        save = GTKWSave(out)
        save.dumpfile(str(vcd_path.resolve()))
        save.size(*WINDOW_SIZE)
        save.signals_width(SIGNALS_WIDTH)
        save.sst_expanded(False)
        save.timestart(start)
        save.zoom_markers(zoom_for(end - start), -1 if marker is None else marker)
        for group, hits in resolved.items():
            with save.group(group):
                for suffix, variable in hits:
                    save.trace(variable.gtkwave_name, **_display(suffix, variable, signed, decimal, names))
    missing = missing_traces(save_path)
    if missing:
        raise ValueError(f"{save_path.name} lists signals GTKWave will not find: {missing}")
    return save_path


def zoom_for(span):
    """GTKWave's zoom that shows ``span`` time units (and a little more) in a view."""
    pixels = WINDOW_SIZE[0] - SIGNALS_WIDTH - WAVE_MARGIN
    return -math.log2(max(span, 1) * WINDOW_SLACK * PIXELS_PER_FRAME / pixels)


def _display(suffix, variable, signed, decimal, names):
    if suffix in (names or {}):
        return dict(datafmt="hex", translate_filter_file=str(_names_file(variable.size, names[suffix])))
    if suffix in signed:
        return dict(datafmt="dec", extraflags=GTKWFlag.signed)
    if suffix in decimal:
        return dict(datafmt="dec")
    return dict(datafmt="hex")


def _names_file(width, names):
    """A GTKWave translate file: each value as GTKWave prints it in hex, then its text."""
    digits = max(1, -(-width // 4))
    text = "".join(f"{value:0{digits}X} {label}\n" for value, label in sorted(names.items()))
    path = build_dir("waves", "names") / f"{hashlib.sha1(text.encode()).hexdigest()[:12]}.txt"
    if not path.exists():
        partial = path.with_name(f"{path.name}.{os.getpid()}")
        partial.write_text(text)
        os.replace(partial, path)
    return path


def saved_traces(save_path):
    """The signal names a save file lists, in order (groups and settings left out)."""
    traces = []
    for line in Path(save_path).read_text().splitlines():
        if line and line[0] not in "[*@-^#!":
            traces.append(line.split("} ", 1)[1] if line.startswith("+{") else line)
    return traces


def dump_file(save_path):
    """The VCD a save file opens."""
    match = re.search(r'^\[dumpfile\] "(.*)"$', Path(save_path).read_text(), re.MULTILINE)
    return Path(match.group(1))


def missing_traces(save_path):
    """Traces of a save file that its VCD does not declare under GTKWave's names."""
    known = {v.gtkwave_name for v in declarations(dump_file(save_path))}
    return [name for name in saved_traces(save_path) if name not in known]


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
        full = find(self.changes, suffix)
        if full is None:
            raise KeyError(f"{suffix} not in {self.path.name}")
        return full

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
