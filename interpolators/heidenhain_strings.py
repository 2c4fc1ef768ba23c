"""QS string parameters of Heidenhain conversational programs.

TNC 640 user's manual (conversational programming, "String parameters"; iTNC 530 the same): ``QS``
parameters hold texts of up to 255 characters (254 on older TNCs), e.g. for ``FN 16: F-PRINT`` logs, tool
and program names. A program writes ::

    DECLARE STRING QS10 = "WORKPIECE"          a text assigned (DECLARE STRING)
    QS11 = QS10 || "_2"                        a string formula: ``||`` concatenates
    QS12 = TOCHAR( DAT+Q50 DECIMALS3 )         a number as text (DECIMALS: the places after the point)
    QS13 = SUBSTR( SRC_QS10 BEG2 LEN4 )        the LEN characters from position BEG (0: the first)
    TOOL CALL QS12 Z S3000                     the tool whose name the parameter holds

This module keeps the texts (:class:`StringParameters`) and evaluates string formulas of these
terms; ``SYSSTR`` (system data) and ``CFGREAD`` (machine parameters) read data a simulation does
not have, and are refused by name. Where a program uses a string (``TOOL CALL QS..``, ``CALL PGM QS..``
/ ``SEL PGM QS..``), :meth:`StringParameters.get` gives its text.
"""

from __future__ import annotations

import re

from interpolators._words import Where
from interpolators.heidenhain_params import QParameters

__all__ = ["QS_NAME_RE", "STRING_KEYWORD_RE", "StringParameters"]

#: A string parameter's name.
QS_NAME_RE = re.compile(r"QS\s*(\d+)(?![\d.])", re.I)
#: The blocks that assign one: ``DECLARE STRING QSn =`` and ``QSn =``.
STRING_KEYWORD_RE = re.compile(r"(?:DECLARE\s+STRING\s+)?QS\s*(\d+)\s*=\s*", re.I)
#: The most characters a QS parameter holds (TNC 640 user's manual).
MAX_LENGTH = 255

_LITERAL_RE = re.compile(r"\s*(\"[^\"]*\"|'[^']*')")
_TOCHAR_RE = re.compile(r"\s*TOCHAR\s*\(\s*DAT\s*\+?\s*(.+?)(?:\s+DECIMALS\s*(\d+))?\s*\)", re.I)
_SUBSTR_RE = re.compile(r"\s*SUBSTR\s*\(\s*SRC_QS\s*(\d+)\s+BEG\s*(\S+?)\s+LEN\s*(\S+?)\s*\)", re.I)
_REFUSED_RE = re.compile(r"\s*(SYSSTR|CFGREAD)\b", re.I)
_JOIN_RE = re.compile(r"\s*\|\|")


class StringParameters:
    """The QS parameters of a run: number -> text."""

    def __init__(self) -> None:
        self.values: dict[int, str] = {}

    def get(self, name: str, where: Where, *, column: int) -> str:
        """The text of ``QSn`` (``name``); an error for one never assigned."""
        number = int(QS_NAME_RE.match(name).group(1))
        if number not in self.values:
            where.fail(f"string parameter QS{number} is used before it is assigned", column=column, text=name,
                       expected=f"DECLARE STRING QS{number} = \"..\" or QS{number} = .. before its use")
        return self.values[number]

    def assign(self, code: str, params: QParameters, where: Where, *, column: int) -> None:
        """Run ``[DECLARE STRING] QSn = <string formula>`` (``code`` from the keyword on, at 1-based ``column``)."""
        km = STRING_KEYWORD_RE.match(code)
        pos, parts = km.end(), []
        while True:
            text, pos = self._term(code, pos, params, where, column=column)
            parts.append(text)
            jm = _JOIN_RE.match(code, pos)
            if jm is None:
                break
            pos = jm.end()
        if code[pos:].strip():
            where.fail("malformed string formula", column=column + pos, text=code[pos:].strip(),
                       expected="texts in quotes, QS parameters, TOCHAR(..) or SUBSTR(..) joined by ||")
        self.values[int(km.group(1))] = "".join(parts)[:MAX_LENGTH]

    def _term(self, code: str, pos: int, params: QParameters, where: Where, *, column: int) -> tuple[str, int]:
        """One term of a string formula at ``pos``: its text and the position after it."""
        if (lm := _LITERAL_RE.match(code, pos)) is not None:
            return lm.group(1)[1:-1], lm.end()
        if (qm := re.compile(r"\s*(QS\s*\d+)(?![\d.])", re.I).match(code, pos)) is not None:
            return self.get(qm.group(1), where, column=column + qm.start(1)), qm.end()
        if (tm := _TOCHAR_RE.match(code, pos)) is not None:
            value = params.evaluate(tm.group(1), where, column=column + tm.start(1))
            places = int(tm.group(2)) if tm.group(2) is not None else 3  # our reading: no manual gives the default
            return f"{value:.{places}f}", tm.end()
        if (sm := _SUBSTR_RE.match(code, pos)) is not None:
            source = self.get("QS" + sm.group(1), where, column=column + sm.start(1))
            begin = int(params.evaluate(sm.group(2), where, column=column + sm.start(2)))
            length = int(params.evaluate(sm.group(3), where, column=column + sm.start(3)))
            return source[begin:begin + length], sm.end()
        rm = _REFUSED_RE.match(code, pos)
        if rm is not None:
            where.fail(f"string function {rm.group(1).upper()} (system or machine data) is not supported",
                       column=column + rm.start(1), text=rm.group(1),
                       expected="texts in quotes, QS parameters, TOCHAR(..) or SUBSTR(..)")
        where.fail("malformed string formula", column=column + pos, text=code[pos:].strip(),
                   expected="texts in quotes, QS parameters, TOCHAR(DAT+.. DECIMALS..) or SUBSTR(SRC_QS.. BEG.. LEN..) "
                            "joined by ||")
