"""Shared pieces of the two G-code readers: numbers, source positions, error raising."""

from __future__ import annotations

import dataclasses
import re

from vcnc.core.errors import GCodeError
from vcnc.core.text import decode_text

#: A decimal number as written in part programs: optional sign, digits with an optional point
#: (``12``, ``-0.79``, ``+.5``, ``5.``); no exponent.
NUMBER_RE = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)")

#: Largest accepted magnitude of a programmed number (mm, mm/min, ms, ...).
MAX_MAGNITUDE: float = 1e9

#: mm per inch.
INCH: float = 25.4


@dataclasses.dataclass(frozen=True)
class Where:
    """Source position for error messages."""

    file: str | None
    line: int
    text: str

    def fail(self, message: str, *, column: int | None = None, text: str | None = None, expected: str | None = None):
        """Raise a GCodeError at this line (``column`` 1-based)."""
        raise GCodeError(message, file=self.file, line=self.line, column=column, text=text, expected=expected)


def lines_of(text: str) -> list[str]:
    """Lines split at newline only (editors' numbering), without a trailing carriage return."""
    return [ln[:-1] if ln.endswith("\r") else ln for ln in text.split("\n")]


def token_at(line: str, pos: int) -> str:
    """The run of characters at ``pos`` up to the next space or tab (at least one character)."""
    m = re.compile(r"[^ \t]+").match(line, pos)
    return m.group(0) if m else line[pos : pos + 1]


def checked_float(tok: str, where: Where, *, column: int, what: str) -> float:
    """``float(tok)`` with the magnitude check of :data:`MAX_MAGNITUDE`."""
    value = float(tok)
    if abs(value) > MAX_MAGNITUDE:
        where.fail(f"number out of range for {what}", column=column, text=tok,
                   expected=f"a magnitude <= {MAX_MAGNITUDE:g}")
    return value


def read_number(line: str, pos: int, where: Where, *, what: str, word_start: int | None = None) -> tuple[float, int]:
    """Read a number at ``pos`` (spaces before it allowed); returns (value, end position).

    Errors point at ``word_start`` (the address letter) when given.
    """
    w0 = pos if word_start is None else word_start
    n = len(line)
    j = pos
    while j < n and line[j] in " \t":
        j += 1
    m = NUMBER_RE.match(line, j)
    if m is None:
        zero = j < n and line[j] in "oO" and re.match(r"[oO0-9.]+(?![A-Za-z])", line[j:])  # "GOO", "X1O": O for 0?
        # "PRINT", "ASKBOOL": a statement of a control's own language (KinetiC-NC's BASIC-like lines), not a word
        keyword = re.match(r"[A-Za-z]{4,}\b", line[w0:]) if not zero else None
        hint = (" (the letter O where the digit 0 was meant?)" if zero else
                f" ({keyword.group(0)!r}: a statement of another control's language, such as KinetiC-NC's PRINT?)"
                if keyword else "")
        where.fail(
            f"malformed number for {what}{hint}",
            column=w0 + 1,
            text=token_at(line, w0),
            expected="a decimal number such as 12, -0.79 or +.5",
        )
    end = m.end()
    value = float(m.group(0))
    if abs(value) > MAX_MAGNITUDE:
        where.fail(f"number out of range for {what}", column=w0 + 1, text=token_at(line, w0),
                   expected=f"a magnitude <= {MAX_MAGNITUDE:g}")
    # a number glued to another point or digit-like junk ("1.2.3", "5x") is malformed
    if end < n and (line[end] == "." or line[end].isdigit()):
        where.fail(f"malformed number for {what}", column=w0 + 1, text=token_at(line, w0),
                   expected="a decimal number")
    return value, end


def program_text(path: str) -> str:
    """A program file's text (:func:`vcnc.core.text.decode_text`: UTF-8 or UTF-16 by its byte-order mark,
    else UTF-8, else Windows-1252), without a BOM.

    Raises ``OSError`` when the file cannot be read and ``vcnc.core.text.BinaryDataError`` when it holds no
    text (the callers name the file).
    """
    with open(path, "rb") as fh:
        raw = fh.read()
    text = decode_text(raw)
    return text[1:] if text.startswith("\ufeff") else text
