"""The simulated card's socket protocol, described once.

``sim/card/card_server.py`` serves the simulated card on a Unix socket and
the LinuxCNC driver's simulation transport (``linuxcnc/dda_transport.h``)
talks to it.  Every request is three little-endian 32-bit words ``op, a, b``
(FIFO is followed by ``a`` data words, at most ``MAX_BURST``); every answer is
two words ``status, value`` (status 0: done; else ``value`` is the length of
a UTF-8 message that follows).  The converter writes these numbers into the
C header (``gen/dda_card.h``, ``DDA_SIM_*``), so the driver never retypes them.

READ and WRITE name a register by its offset as a driver's mapping of BAR2
sees it: below BAR0's size the function registers (BAR0's offsets, so a
client that knows only BAR0 is served as before), from 0x100 on the
per-axis register blocks (``models.registers.axis_offset``), which BAR0
lacks; an offset outside BAR2 is answered with an error message.
"""

# (name, code, what a and b carry, what the answer's value is)
OPS = (
    ("READ", 1, "a = register offset: BAR0's, or beyond it BAR2's per-axis blocks", "the register"),
    ("WRITE", 2, "a = register offset as READ's, b = value", "0"),
    ("FIFO", 3, "a = word count, then the words (one burst into BAR1)", "0"),
    ("ADVANCE", 4, "a = card clocks", "card clocks since the server opened the card, low 32 bits"),
)
READ, WRITE, FIFO, ADVANCE = (code for _, code, _, _ in OPS)
REQUEST_WORDS = 3
ANSWER_WORDS = 2
MAX_BURST = 4096  # words in one FIFO request


def c_defines(prefix="DDA_SIM"):
    """C ``#define`` lines of the protocol."""
    lines = [f"#define {prefix}_{name} {code}u /* {request}; answer: {value} */" for name, code, request, value in OPS]
    lines += [f"#define {prefix}_REQUEST_WORDS {REQUEST_WORDS}u",
              f"#define {prefix}_ANSWER_WORDS {ANSWER_WORDS}u",
              f"#define {prefix}_MAX_BURST {MAX_BURST}u /* words in one FIFO request */"]
    return "\n".join(lines) + "\n"
