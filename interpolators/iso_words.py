"""Reading one line of ISO G-code into words: comments, block delete, words and their numbers.

Follows the LinuxCNC G-code overview (https://linuxcnc.org/docs/html/gcode/overview.html):
letters are case-insensitive, spaces may stand between a letter and its number, ``( ... )``
comments end at the first ``)`` (no nesting; a ``(`` inside a comment is text), ``;`` comments
run to the end of the line, ``/`` at the start of a line marks a block-delete line (executed: the
block-delete switch is off, as in LinuxCNC's default), and ``%`` lines demarcate the program.
Parameters (``#``), expressions (``[``) and O-words are named as such when met.
"""

from __future__ import annotations

import dataclasses

from interpolators._words import Where, read_number, token_at

__all__ = ["Word", "strip_comments", "read_words", "WORD_LETTERS"]

#: Word letters the reader knows (axis letters A B C U V W are read and judged by the executor).
WORD_LETTERS = set("ABCDFGHIJKLMNOPQRSTUVWXYZ")


@dataclasses.dataclass(frozen=True)
class Word:
    """One word: ``letter`` (upper case), ``value``, 1-based ``column``, source ``text``."""

    letter: str
    value: float
    column: int
    text: str


def strip_comments(raw: str, where: Where) -> str:
    """Blank out comments, keeping columns. An unclosed ``(`` is an error."""
    out = list(raw)
    i, n = 0, len(raw)
    while i < n:
        ch = raw[i]
        if ch == ";":
            out[i:] = " " * (n - i)
            break
        if ch == "(":
            j = raw.find(")", i + 1)
            if j < 0:
                where.fail("unclosed comment", column=i + 1, text=raw[i:], expected="')' closing the comment")
            out[i : j + 1] = " " * (j + 1 - i)
            i = j + 1
            continue
        if ch == ")":
            where.fail("')' without '('", column=i + 1, text=")", expected="a word")
        i += 1
    return "".join(out)


def read_words(code: str, where: Where) -> list[Word]:
    """The words of a comment-free line, left to right."""
    words: list[Word] = []
    i, n = 0, len(code)
    while i < n:
        ch = code[i]
        if ch in " \t\r\f\v":
            i += 1
            continue
        up = ch.upper()
        if ch == "#":
            tok = token_at(code, i)
            where.fail(f"parameter {tok!r}: numbered and named parameters (#) are not supported",
                       column=i + 1, text=tok, expected="plain numbers in words")
        if ch == "[":
            tok = token_at(code, i)
            where.fail(f"expression {tok!r}: [expressions] are not supported", column=i + 1, text=tok,
                       expected="plain numbers in words")
        if up == "O" and i + 1 < n and (code[i + 1] == "<" or not _number_follows(code, i + 1)):
            tok = token_at(code, i)
            where.fail(f"O-word {tok!r}: O-word subroutines and control flow are not supported",
                       column=i + 1, text=tok, expected="a program without O-word subroutines")
        if up == "O" and _oword_keyword_follows(code, i + 1):
            tok = code[i:].strip()
            where.fail(f"O-word {tok!r}: O-word subroutines and control flow are not supported",
                       column=i + 1, text=tok, expected="a program without O-word subroutines")
        if up not in WORD_LETTERS:
            tok = token_at(code, i)
            where.fail(f"unknown word {tok!r}", column=i + 1, text=tok,
                       expected="a word of the letters " + " ".join(sorted(WORD_LETTERS)))
        value, end = read_number(code, i + 1, where, what=f"word {up}", word_start=i)
        words.append(Word(up, value, i + 1, code[i:end].strip()))
        i = end
    return words


def _number_follows(code: str, pos: int) -> bool:
    j = pos
    while j < len(code) and code[j] in " \t":
        j += 1
    return j < len(code) and (code[j].isdigit() or code[j] in "+-.")


_O_KEYWORDS = ("sub", "endsub", "call", "if", "elseif", "else", "endif", "while", "endwhile", "do", "repeat",
               "endrepeat", "return", "break", "continue")


def _oword_keyword_follows(code: str, pos: int) -> bool:
    """True for ``o100 sub``-style lines (an O number followed by a control keyword)."""
    j = pos
    while j < len(code) and (code[j].isdigit() or code[j] in " \t"):
        j += 1
    rest = code[j:].lower()
    return any(rest.startswith(k) and (len(rest) == len(k) or not rest[len(k)].isalpha()) for k in _O_KEYWORDS)
