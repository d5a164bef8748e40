"""Print a counterexample or cover trace (the VCD SymbiYosys writes) as a
table, one row per step: ``python -m formal.trace FILE.vcd [SIGNAL ...]``.

Signals are matched by the end of their hierarchical name (``trdy_n`` finds
``pci_target_harness.trdy_n``); without names, the top level's ports.
"""
import sys

from sim.backends.waves import Waveform, find

# SymbiYosys writes a step every 10 time units, the clock high at +0 / low at +5
STEP_TIME = 10


def _text(value):
    return f"{value:x}" if isinstance(value, int) else str(value)


def table(path, wanted=()):
    """The trace as text lines."""
    wave = Waveform(path)
    if wanted:
        chosen = [name for name in (find(wave.changes, w) for w in wanted) if name is not None]
    else:
        chosen = sorted(name for name in wave.changes if name.count(".") == 1)
    last = max((times[-1] for times, _ in wave.changes.values() if times), default=0)
    lines = ["step " + " ".join(name.split(".")[-1] for name in chosen)]
    for index in range(last // STEP_TIME + 1):
        cells = []
        for name in chosen:
            try:
                value = _text(wave.at(name, index * STEP_TIME))
            except ValueError:
                value = "x"
            cells.append(value.rjust(len(name.split(".")[-1])))
        lines.append(f"{index:4d} " + " ".join(cells))
    return lines


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not argv:
        print(__doc__.strip())
        return 2
    print("\n".join(table(argv[0], argv[1:])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
