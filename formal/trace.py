"""Print a counterexample or cover trace (the VCD SymbiYosys writes) as a
table, one row per step: ``python -m formal.trace FILE.vcd [SIGNAL ...]``.

Signals are matched by the end of their hierarchical name (``trdy_n`` finds
``pci_target_harness.trdy_n``); without names, the top level's ports.
"""
import sys

from vcd.reader import TokenKind, tokenize


def read_vcd(path):
    """(names, steps): ``names`` maps each id code to its full names,
    ``steps`` is a list of {id code: value string}, one per sampled step."""
    names, scope, values, changes = {}, [], {}, []
    time = None
    with open(path, "rb") as stream:
        for token in tokenize(stream):
            if token.kind is TokenKind.SCOPE:
                scope.append(token.scope.ident)
            elif token.kind is TokenKind.UPSCOPE:
                scope.pop()
            elif token.kind is TokenKind.VAR:
                names.setdefault(token.var.id_code, []).append(".".join(scope + [token.var.reference]))
            elif token.kind is TokenKind.CHANGE_TIME:
                if time is not None:
                    changes.append((time, dict(values)))
                time = token.time_change
            elif token.kind is TokenKind.CHANGE_SCALAR:
                values[token.data.id_code] = str(token.data.value)
            elif token.kind is TokenKind.CHANGE_VECTOR:
                value = token.data.value
                values[token.data.id_code] = f"{value:x}" if isinstance(value, int) else str(value)
    if time is not None:
        changes.append((time, dict(values)))
    # SymbiYosys writes a step every 10 time units, the clock high at +0 / low at +5
    steps = [state for t, state in changes if t % 10 == 0]
    return names, steps


def table(path, wanted=()):
    """The trace as text lines."""
    names, steps = read_vcd(path)
    everything = [(name, code) for code, full in names.items() for name in full]
    if wanted:
        chosen = []
        for w in wanted:
            found = [item for item in everything if item[0].endswith("." + w) or item[0] == w]
            if found:
                chosen.append(min(found, key=lambda item: item[0].count(".")))
    else:
        chosen = sorted(item for item in everything if item[0].count(".") == 1)
    lines = ["step " + " ".join(name.split(".")[-1] for name, _ in chosen)]
    for index, state in enumerate(steps):
        cells = []
        for name, code in chosen:
            value = state.get(code, "x")
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
