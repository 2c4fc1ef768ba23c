"""LinuxCNC's active comments: operator messages, debug and print output, logging, abort.

LinuxCNC G-code overview (https://linuxcnc.org/docs/html/gcode/overview.html, "Comments",
"Messages", "Logging", "Abort Messages", "Debug Messages", "Print Messages", "Comment
Parameters") and its code, ``src/emc/rs274ngc/interp_convert.cc`` ``convert_comment`` and
``convert_param_comment``:

* a block's comment is its last ``( ... )`` comment (:func:`interpolators.iso_words.block_comment`);
  it is active when, after leading white space and ignoring case, it starts with ``msg,``,
  ``debug,``, ``print,``, ``log,``, ``logopen,``, ``logappend,``, ``abort,``, ``py,``, ``pyrun,``
  or ``pyreload``, or is ``logclose`` (no space before the comma: ``(MSG ,x)`` is a comment);
* ``(MSG, text)`` shows the text after the comma as written (``MESSAGE(" text")``);
* ``(DEBUG, text)`` shows it as MSG does, its parameters replaced by their values, while ``#5599``
  (on at start) is above 0; ``(PRINT, text)`` writes it so to the console (rs274 prints the line on
  its output, where ``tests/interp`` expected files have it), ``(LOG, text)`` to the log file,
  ``(ABORT, text)`` ends the run with it;
* in those texts ``#n`` and ``#<name>`` (white space in the name dropped, case ignored) become
  ``printf("%lf")`` of the value (6 decimals; a value within 1e-6 of 0 prints as 0); ``%d``,
  ``%f`` and ``%.Nf`` (N a digit) before them set 0, 4 and N decimals for the parameters after it
  in the comment; another ``%`` stays (``%.`` without a digit and ``f`` loses the ``%``). A
  parameter LinuxCNC does not have (a number above 5601, an unset name) prints ``######``, and a
  ``#`` ending the comment or a ``#<`` without ``>`` is LinuxCNC's error "named parameter not
  terminated".

vcnc shows no operator screen: the messages go to :attr:`interpolators.program.Program.messages`
and ``vcnc interpolate`` prints them. A parameter whose value vcnc does not model (a system
parameter it does not track, ``#<_ini[..]..>``) stays as written.
"""

from __future__ import annotations

import re

from interpolators._words import Where
from interpolators.iso_params import Parameters
from vcnc.core.errors import GCodeError

__all__ = ["ACTIVE_KEYWORDS", "active_comment", "comment_output", "expand", "DEBUG_SWITCH"]

#: Keywords of the active comments, in the order ``convert_comment`` tries them (``logclose``
#: alone, the others followed by a comma).
ACTIVE_KEYWORDS = ("msg", "debug", "print", "log", "logopen", "logappend", "py", "pyrun", "pyreload", "abort",
                   "logclose")
#: LinuxCNC's switch of (DEBUG,) output (``interp_parameter_def.hh`` DEBUG_LEVEL_FLAG; 1 at start).
DEBUG_SWITCH = 5599
#: LinuxCNC's number of numbered parameters (RS274NGC_MAX_PARAMETERS).
_MAX_PARAMETERS = 5602
#: LinuxCNC's predefined read-only named parameters (``interp_namedparams.cc`` ``init_named_parameters``):
#: one vcnc does not model prints as written, not as a missing one.
_PREDEFINED = frozenset(
    "_line _motion_mode _plane _ccomp _metric _imperial _absolute _incremental _inverse_time _units_per_minute "
    "_units_per_rev _coord_system _tool_offset _retract_r_plane _retract_old_z _control_mode _spindle_rpm_mode "
    "_spindle_css_mode _ijk_absolute_mode _lathe_diameter_mode _lathe_radius_mode _spindle_on _spindle_cw _mist "
    "_flood _speed_override _feed_override _adaptive_feed _feed_hold _feed _rpm _current_tool _current_pocket "
    "_selected_pocket _selected_tool _x _y _z _a _b _c _u _v _w _abs_x _abs_y _abs_z _abs_a _abs_b _abs_c _abs_u "
    "_abs_v _abs_w _value _value_returned _task _call_level _remap_level _vmajor _vminor _metric_machine".split())
#: What ``convert_param_comment`` writes for a parameter it cannot print.
_MISSING = "######"
#: Its buffer of a printed value (VAL_LEN): a longer value prints as :data:`_MISSING`.
_VALUE_LENGTH = 30


def active_comment(comment: str) -> tuple[str, str] | None:
    """``(keyword, text after it)`` of an active comment (its text without parentheses), else ``None``."""
    body = comment.lstrip(" \t\n\r\f\v")
    low = body.lower()
    for keyword in ACTIVE_KEYWORDS:
        if keyword == "logclose":
            if low == keyword:
                return keyword, ""
        elif keyword == "pyreload":
            if low.startswith(keyword):
                return keyword, body[len(keyword):]
        elif low.startswith(keyword + ","):
            return keyword, body[len(keyword) + 1:]
    return None


def comment_output(keyword: str, text: str, params: Parameters, where: Where) -> str | None:
    """What the active comment ``keyword`` (not ``abort``) shows or writes where the run reaches it:
    MSG, LOGOPEN, LOGAPPEND and PY texts as written, DEBUG, PRINT and LOG texts expanded
    (:func:`expand`); ``None`` for a DEBUG while ``#5599`` is 0 or less (LinuxCNC ``convert_comment``)."""
    if keyword == "debug" and params.numbered.get(DEBUG_SWITCH, 1.0) <= 0.0:
        return None
    return expand(text, params, where) if keyword in ("debug", "print", "log") else text


def expand(text: str, params: Parameters, where: Where) -> str:
    """``text`` with its parameters replaced by their values as ``convert_param_comment`` prints them.

    Raises
    ------
    vcnc.GCodeError
        A ``#`` that ends the text, or ``#<`` without its ``>`` (LinuxCNC's "named parameter not
        terminated").
    """
    out: list[str] = []
    decimals = 6  # "%lf"
    i, n = 0, len(text)
    while i < n:
        ch = text[i]
        if ch == "%":
            i += 1
            nxt = text[i:i + 1]
            if nxt == "d":
                decimals, i = 0, i + 1
            elif nxt == "f":
                decimals, i = 4, i + 1
            elif nxt == ".":
                if text[i + 1:i + 2].isdigit() and text[i + 2:i + 3] == "f":
                    decimals, i = int(text[i + 1]), i + 3
                else:
                    out.append(".")
                    i += 1
            else:
                out.append("%")
            continue
        if ch != "#":
            out.append(ch)
            i += 1
            continue
        i += 1
        if i >= n:
            _unterminated(text, where)
        if text[i].isdigit():
            m = re.match(r"\d+", text[i:])
            raw, i = "#" + m.group(0), i + m.end()
            out.append(_formatted(_numbered(int(m.group(0)), params, where, raw), decimals, raw))
        elif text[i] == "<":
            close = text.find(">", i)
            if close < 0:
                _unterminated(text, where)
            raw, i = text[i - 1:close + 1], close + 1
            out.append(_formatted(_named(raw[2:-1], params, where, raw), decimals, raw))
        else:
            out.append("#")
    return "".join(out)


def _unterminated(text: str, where: Where) -> None:
    where.fail(f"named parameter not terminated in the comment text {text!r} (LinuxCNC refuses it)",
               text=text, expected="#<name> closed by '>', or '#' followed by a parameter number or name")


def _numbered(number: int, params: Parameters, where: Where, raw: str) -> float | str | None:
    """The value of ``#number``: ``None`` for no such parameter, ``raw`` when vcnc cannot know it."""
    if number >= _MAX_PARAMETERS:
        return None
    try:
        value = params.get_numbered(number, where, 1, raw)
    except GCodeError:
        return raw
    if value is None:
        return 0.0 if number == 0 else raw  # LinuxCNC's #0 is a parameter (0); a vacant one is unknown
    return value


def _named(name: str, params: Parameters, where: Where, raw: str) -> float | str | None:
    """The value of ``#<name>``: ``None`` when unset (LinuxCNC ``find_named_param`` finds nothing),
    ``raw`` for a predefined or INI parameter whose value vcnc does not know."""
    key = "".join(name.split()).lower()
    if key.startswith("_ini[") or (key in _PREDEFINED and not params.exists(key)):
        try:
            return params.get_named(key, where, 1, raw)
        except GCodeError:
            return raw
    return params.get_named(key, where, 1, raw) if params.exists(key) else None


def _formatted(value: float | str | None, decimals: int, raw: str) -> str:
    if value is None:
        return _MISSING
    if isinstance(value, str):
        return value
    text = f"{0.0 if abs(value) < 1e-6 else value:.{decimals}f}"
    return _MISSING if len(text) >= _VALUE_LENGTH else text
