"""grbl's system commands and real-time characters in a program file (``grbl`` dialect only).

Files written for grbl often carry lines a grbl sender streams to the controller along with the
G-code: ``$`` system commands (``$$`` settings report, ``$G`` parser state, ``$I`` build info,
``$100=100.5`` a setting) and the ``?`` status query. grbl 1.1 reads them so (gnea/grbl
``grbl/protocol.c`` ``protocol_main_loop``, ``grbl/system.c`` ``system_execute_line``,
``grbl/serial.c`` ``ISR(SERIAL_RX)``):

* The serial receive interrupt picks the real-time characters ``?`` (status report), ``~`` (cycle
  start), ``!`` (feed hold) and Ctrl-X (soft reset) out of the stream wherever they are: they never
  reach a line. A ``?`` is dropped here (a report does not move the tool); ``!``, ``~`` and Ctrl-X
  stop or resume the machine as the operator would, and stay errors naming them.
* A line whose first character (after grbl strips spaces and comments) is ``$`` is a system command,
  run instead of the G-code parser. Reports (``$``, ``$$``, ``$#``, ``$G``, ``$I``, ``$N``), the
  alarm unlock ``$X``, stored build info ``$I=..`` and startup lines ``$Nx=..`` (run at the next reset,
  not now) and settings ``$x=value`` (steps, rates, accelerations of the machine, which vcnc takes
  from its own limits) do not move the tool: they become blank lines, with a note. Homing ``$H``,
  jogging ``$J=``, check mode ``$C`` (the G-code after it is checked, not run), ``$RST=`` (restores
  settings and work offsets) and sleep ``$SLP`` change what the program does and are errors naming
  the command.
"""

from __future__ import annotations

import re

from interpolators._words import Where, lines_of
from interpolators.iso_words import comment_spans

__all__ = ["system_lines"]

#: ``$`` commands that neither move the tool nor change the program's geometry (grbl ``system.c``).
_PASSIVE = re.compile(r"\$(?:|\$|#|G|I(?:=.*)?|N(?:\d+=.*)?|X|\d+=[-+]?[\d.]+)")
#: ``$`` commands that do, by their name in grbl's documentation.
_ACTIVE = {"H": "$H homing cycle", "J": "$J= jog", "C": "$C check g-code mode", "R": "$RST= restore",
           "S": "$SLP sleep"}


def system_lines(text: str, source: str | None) -> tuple[str, int]:
    """The program text with grbl's system-command lines blanked and ``?`` dropped (line numbers
    kept), and the number of system-command lines blanked.

    Raises
    ------
    vcnc.GCodeError
        A ``$`` command that moves the machine or changes the program's run (``$H``, ``$J=``, ``$C``,
        ``$RST=``, ``$SLP``), or one grbl does not know.
    """
    out = []
    blanked = 0
    for number, raw in enumerate(lines_of(text), start=1):
        where = Where(source, number, raw)
        spans, semicolon = comment_spans(raw, where)
        code = list(raw[:semicolon])
        for start, end in spans:
            code[start:end] = " " * (end - start)
        command = "".join(code).replace(" ", "").replace("\t", "").upper()
        if command.startswith("$"):
            column = raw.index("$") + 1
            if _PASSIVE.fullmatch(command.replace("?", "")):
                out.append("")
                blanked += 1
                continue
            name = _ACTIVE.get(command[1:2])
            if name is not None:
                where.fail(f"grbl {name}: not supported (it moves the machine or changes how the program runs)",
                           column=column, text=command,
                           expected="G-code, or grbl reports and settings ($$, $G, $I, $#, $N, $X, $x=value)")
            where.fail("unknown grbl system command", column=column, text=command,
                       expected="$$, $#, $G, $I, $N, $X, $x=value (reports and settings), or G-code")
        out.append(_without_status_queries(raw, spans, semicolon))
    return "\n".join(out), blanked


def _without_status_queries(raw: str, spans: list[tuple[int, int]], semicolon: int) -> str:
    """``raw`` with each ``?`` outside its comments replaced by a space (grbl's receive interrupt takes
    it out of the stream as the status-report query)."""
    if "?" not in raw:
        return raw
    chars = list(raw)
    for i in range(semicolon):
        if chars[i] == "?" and not any(a <= i < b for a, b in spans):
            chars[i] = " "
    return "".join(chars)
