"""The card's refusals as the host reports them: ``CardError`` carries the
card's error name (STATUS.ERROR, docs/instructions.md) and the command that
caused it, found in the ``CommandRecord`` of the words queued since the last
stop: the words the card has consumed end inside the command it refused (for
DDA_REJECTED, the ARC among the last two: the instruction register fetches
the next command while the DDA checks an arc).
"""
import bisect

from models import instructions as isa

ARC_OPCODE = isa.encode("ARC", 1, 0, 1, 0)[0] >> 28
ERROR_NAMES = {code: name for code, name, _ in isa.ERRORS}


class CardError(RuntimeError):
    """The card refused a command: ``name`` (e.g. ``DDA_REJECTED``), ``code``
    (STATUS.ERROR) and ``command`` (what the host queued, as it was named)."""

    def __init__(self, name, code, command):
        super().__init__(f"the card refused {command}: {name}" if command else f"card error {name}")
        self.name, self.code, self.command = name, code, command


def error_name(code):
    """The name of STATUS.ERROR ``code`` (docs/instructions.md)."""
    return ERROR_NAMES.get(code, f"UNKNOWN_{code}")


class CommandRecord:
    """The commands queued since the last stop: where each starts in the
    words written, its name and its opcode."""

    def __init__(self):
        self.written = 0
        self._starts, self._names, self._opcodes = [], [], []

    def add(self, words, commands):
        """``words`` written to the FIFO; ``commands``: [(words, name)] in order."""
        offset = 0
        for length, what in commands:
            self._starts.append(self.written)
            self._names.append(what)
            self._opcodes.append(words[offset] >> 28)
            self.written += length
            offset += length

    def refused(self, code, consumed):
        """The name of the command the card refused with ``code``, given the
        words it has consumed: the one they end in; for DDA_REJECTED the ARC
        among the last two consumed commands (the earlier if both are)."""
        last = bisect.bisect_right(self._starts, consumed - 1) - 1
        if last < 0:
            return None
        if ERROR_NAMES[code] == "DDA_REJECTED":
            for index in (last - 1, last):
                if index >= 0 and self._opcodes[index] == ARC_OPCODE:
                    return self._names[index]
        return self._names[last]
