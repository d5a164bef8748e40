"""Reading G-code lines into words (letter, value), with comments removed.

The project reads G-code itself rather than with ``gcodeparser`` 0.3.0: that
tokeniser drops what it does not match without a word, and the host must
name every such line.  Measured with 0.3.0: ``X10 Y20`` (a modal move with no
G word) gives nothing, ``G90.1`` gives ``G90``, ``G1 X1 (move) Y2`` loses
``Y2`` and ``G1 X1 @ Y2`` loses ``@ Y2``.  The grammar needed is small:
words are a letter and a number (spaces allowed between), comments are
``( ... )`` and ``;`` to the end of the line, ``%`` alone marks the start or
end of a program.
"""
import re
from dataclasses import dataclass

from host.errors import ProgramError

_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)"
_WORD = re.compile(rf"\s*([A-Za-z])\s*({_NUMBER})")
_LETTER = re.compile(r"\s*([A-Za-z])")


@dataclass(frozen=True)
class Word:
    letter: str  # upper case
    value: float
    text: str    # the number as written

    @property
    def code(self):
        """G and M numbers in tenths: G90.1 is 901, G1 is 10."""
        return round(self.value * 10)

    def __str__(self):
        return f"{self.letter}{self.text}"


def strip_comments(text, where):
    """``text`` without ``( ... )`` and ``;`` comments."""
    out, rest = [], text
    while rest:
        opening, semicolon = rest.find("("), rest.find(";")
        if semicolon >= 0 and (opening < 0 or semicolon < opening):
            out.append(rest[:semicolon])
            break
        if opening < 0:
            out.append(rest)
            break
        closing = rest.find(")", opening)
        if closing < 0:
            raise ProgramError(where, "comment '(' is not closed on this line")
        out.append(rest[:opening] + " ")
        rest = rest[closing + 1:]
    body = "".join(out)
    if ")" in body:
        raise ProgramError(where, "')' without a '('")
    return body


def words(text, where):
    """The words of one line, in order; ProgramError for anything else on it."""
    body = strip_comments(text, where).strip()
    if body == "%":
        return []
    found, position = [], 0
    while position < len(body):
        if body[position:].strip() == "":
            break
        match = _WORD.match(body, position)
        if match is None:
            letter = _LETTER.match(body, position)
            if letter:
                raise ProgramError(where, f"word {letter.group(1).upper()} has no number")
            raise ProgramError(where, f"cannot read {body[position:].strip()!r}")
        found.append(Word(match.group(1).upper(), float(match.group(2)), match.group(2)))
        position = match.end()
    return found


def read_lines(text, name):
    """(where, words) for every line of a program called ``name``, numbered from 1."""
    for number, line in enumerate(text.splitlines(), start=1):
        where = f"{name}:{number}"
        yield where, words(line, where)
