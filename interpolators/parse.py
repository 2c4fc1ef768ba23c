"""Entry points of the G-code readers: dialect detection, text and file input."""

from __future__ import annotations

import dataclasses
import os

from interpolators._words import program_text
from interpolators.context import DEFAULT_CONTEXT, MachineContext
from interpolators.heidenhain import looks_like_heidenhain, parse_heidenhain
from interpolators.iso import parse_iso
from interpolators.iso_flow import one_line_end, sinumerik_construct
from interpolators.program import Program
from vcnc.core.errors import GCodeError
from vcnc.core.text import BinaryDataError

__all__ = ["parse_program", "load_program", "detect_dialect"]


def detect_dialect(text: str) -> str:
    """``"heidenhain"`` for conversational text (a ``BEGIN PGM`` line, or a first block that is a
    block number followed by ``L``, ``C``, ``CC``, ``CR``, ``TOOL CALL``, ...), else ``"iso"``."""
    return "heidenhain" if looks_like_heidenhain(text) else "iso"


def parse_program(text: str, *, source: str | None = None, context: MachineContext = DEFAULT_CONTEXT) -> Program:
    """Parse program text, ISO or Heidenhain conversational (detected from the content).

    Parameters
    ----------
    text : str
        The program.
    source : str, optional
        Name of the file (or other label) reported in errors and kept in ``Program.source``.
    context : MachineContext
        The machine's work offsets, tool table, home positions and dialect (default: none).

    Returns
    -------
    Program
        Blocks with positions in mm and feeds in mm/s.

    Raises
    ------
    vcnc.GCodeError
        Bad input, with file, line, column, the offending text and what was expected.
    """
    if not isinstance(text, str):
        raise GCodeError(f"program text must be a str, got {type(text).__name__}", file=source)
    bare_cr = "\r" in text and "\n" not in text
    raw = text
    text = one_line_end(text)  # CR, LF and CR LF alike, for both readers
    if detect_dialect(text) == "heidenhain":
        return parse_heidenhain(text, source=source, context=context)
    try:
        prog = parse_iso(text, source=source, context=context)
    except GCodeError as exc:
        siemens = sinumerik_construct(text) if type(exc) is GCodeError else None
        if siemens is None:
            raise
        raise GCodeError(f"{exc.message} (this looks like a Siemens SINUMERIK program, whose own language vcnc does "
                         f"not read: {siemens})", file=exc.file, line=exc.line, column=exc.column, text=exc.text,
                         expected=exc.expected) from None
    if context.dialect.name == "linuxcnc":
        if bare_cr:
            prog = dataclasses.replace(prog, notes=(*prog.notes, _BARE_CR_NOTE))
        elif (long_line := _too_long_line(raw)) is not None:
            prog = dataclasses.replace(prog, notes=(*prog.notes, _LONG_LINE_NOTE.format(*long_line)))
    return prog


def load_program(path: str | os.PathLike[str], *, context: MachineContext = DEFAULT_CONTEXT) -> Program:
    """Read and parse a program file (:func:`vcnc.core.text.decode_text`: UTF-8 or UTF-16, else Windows-1252).

    Raises
    ------
    vcnc.GCodeError
        Unreadable file or bad program.
    """
    name = os.fspath(path)
    try:
        text = program_text(name)
    except OSError as exc:
        raise GCodeError(f"cannot read program: {exc.strerror or exc}", file=name) from None
    except BinaryDataError as exc:
        raise GCodeError(f"{exc}", file=name, line=exc.line, column=exc.column,
                         expected="a text part program (ISO G-code or Heidenhain conversational)") from None
    prog = parse_program(text, source=name, context=context)
    if prog.dialect == "iso" and context.dialect.name == "linuxcnc" and _utf8_bom(name):
        prog = dataclasses.replace(prog, notes=(*prog.notes, _BOM_NOTE))
    return prog


#: rs274 reads a line up to LF only (interp_read.cc ``read_text``: ``fgets``), so a file whose lines end in a
#: bare CR (classic Mac OS editors) is one line to it, refused beyond its line length ("Command too long"). vcnc
#: ends lines at a bare CR in a file without LF (:func:`interpolators.iso_flow.one_line_end`) and, under the
#: ``linuxcnc`` dialect, says so.
_BARE_CR_NOTE = ("lines ended by a bare CR (a file without LF) read as lines (LinuxCNC refuses it: it reads the "
                 "file as one line, \"Command too long\")")

#: LinuxCNC reads a line into a buffer of LINELEN (255, linuxcnc.h) with ``fgets`` and refuses a line that fills
#: it, 254 bytes or more with its line end (interp_read.cc ``read_text``: ``strlen(raw_line) == LINELEN - 1``,
#: "Command too long"). vcnc reads any length and, under the ``linuxcnc`` dialect, says so.
_LINELEN = 255
_LONG_LINE_NOTE = ("line {0} is {1} bytes long with its line end (LinuxCNC refuses it: \"Command too long\", it "
                   "takes at most 253 bytes, line end included)")


def _too_long_line(text: str) -> tuple[int, int] | None:
    """The first line (1-based) of ``text`` that LinuxCNC's ``read_text`` refuses as too long, and its length in
    bytes (UTF-8) with its line end (CR LF or LF; none at the end of the file); None if every line fits."""
    lines = text.split("\n")
    for number, line in enumerate(lines, start=1):
        size = len(line.encode("utf-8")) + (1 if number < len(lines) else 0)
        if size >= _LINELEN - 1:
            return number, size
    return None


#: rs274 2.9.0~pre1 refuses a file that begins with a UTF-8 byte-order mark: the bytes EF BB BF are no G-code
#: characters (interp_read.cc ``read_one_item``: "Bad character '\357' used", line 1). vcnc reads the text
#: without it (:func:`vcnc.core.text.decode_text`) and, under the ``linuxcnc`` dialect, says so.
_BOM_NOTE = ("UTF-8 byte-order mark at the start of the file skipped (LinuxCNC refuses it: "
             "\"Bad character '\\357' used\")")


def _utf8_bom(path: str) -> bool:
    with open(path, "rb") as fh:
        return fh.read(3) == b"\xef\xbb\xbf"
