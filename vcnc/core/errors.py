"""Exception types of vcnc.

Every error raised on purpose by vcnc derives from :class:`VcncError`. Errors caused by bad input
(a malformed program, capture, machine or model file, an impossible parameter) also derive from
:class:`ValueError` through :class:`InputError`; the command line turns those into one line
``error: FILE:LINE:COLUMN: message`` on stderr and exit status 2.
"""

from __future__ import annotations

__all__ = [
    "VcncError",
    "InputError",
    "GCodeError",
    "ProgramTooLongError",
    "CaptureError",
    "MachineError",
    "ModelFileError",
    "IdentificationError",
    "SimulationError",
    "ExportError",
    "VcncWarning",
    "PlausibilityWarning",
]


#: Longest offending text an error message quotes [characters]; a longer one (a 40 kB line) is cut, with its
#: length, and an ``expected`` longer than twice this keeps its start and end, so that the error stays one line.
MAX_SHOWN_TEXT: int = 120
#: Longest message kept whole [characters]: a list a user must read in full (the channels of a recorder's file,
#: 16 of a halscope log: about 500 characters) stays whole; a message quoting a whole long line (a 40 kB
#: program line) loses its middle. With the cut ``expected`` and the location, an error stays under 1000.
MAX_MESSAGE: int = 560


class VcncError(Exception):
    """Base class of every error vcnc raises on purpose."""


class InputError(VcncError, ValueError):
    """Bad input: names where it is (file, line, column), what came and what was expected.

    Parameters
    ----------
    message : str
        What is wrong, naming the parameter and its unit where there is one.
    file : str, optional
        The file at fault.
    line, column : int, optional
        1-based position in the file.
    text : str, optional
        The offending text.
    expected : str, optional
        What was expected instead.
    """

    def __init__(
        self,
        message: str,
        *,
        file: str | None = None,
        line: int | None = None,
        column: int | None = None,
        text: str | None = None,
        expected: str | None = None,
    ) -> None:
        self.message = message
        self.file = None if file is None else str(file)
        self.line = line
        self.column = column
        self.text = text
        self.expected = expected
        super().__init__(self.__str__())

    @property
    def location(self) -> str:
        """``FILE:LINE:COLUMN`` (the parts that are known), or ``""``."""
        parts = [self.file or "<input>"] if (self.file or self.line) else []
        if self.line is not None:
            parts.append(str(self.line))
            if self.column is not None:
                parts.append(str(self.column))
        return ":".join(parts)

    def __str__(self) -> str:
        msg = self.message
        if len(msg) > MAX_MESSAGE:  # a message quoting a whole long line: its middle goes
            msg = msg[:MAX_MESSAGE // 2] + " ... " + msg[-MAX_MESSAGE // 2:]
        if self.text is not None and repr(self.text) not in msg:
            if len(self.text) <= MAX_SHOWN_TEXT:
                msg += f" (got {self.text!r})"
            else:
                msg += f" (got {self.text[:MAX_SHOWN_TEXT] + '...'!r}, {len(self.text)} characters)"
        if self.expected is not None and "expected" not in msg:
            expected = self.expected
            if len(expected) > 2 * MAX_SHOWN_TEXT:
                expected = expected[:MAX_SHOWN_TEXT] + " ... " + expected[-MAX_SHOWN_TEXT:]
            msg += f"; expected {expected}"
        loc = self.location
        return f"{loc}: {msg}" if loc else msg

    def at(self, *, file: str | None = None, line: int | None = None) -> InputError:
        """Fill in a location not known where the error was raised; returns self."""
        if file is not None and self.file is None:
            self.file = str(file)
        if line is not None and self.line is None:
            self.line = line
        self.args = (self.__str__(),)
        return self


class GCodeError(InputError):
    """A part program that cannot be parsed or interpolated."""


class ProgramTooLongError(GCodeError):
    """A part program that needs more samples than the interpolation may hold (``max_samples``).

    ``samples`` is the number it needs (a lower bound when ``at_least``), ``sample_time`` [s] theirs."""

    samples: int = 0
    at_least: bool = False
    sample_time: float = 0.0


class CaptureError(InputError):
    """A capture (CSV or EMPS .mat) that cannot be read or used."""


class MachineError(InputError):
    """A machine definition (TOML or built-in name) that is malformed or physically impossible."""


class ModelFileError(InputError):
    """A model JSON file that does not follow the ``vcnc.axis-model/1`` contract."""


class IdentificationError(InputError):
    """Data from which the requested model cannot be identified (says why)."""


class SimulationError(VcncError):
    """A simulation that failed at run time (e.g. diverged)."""


class ExportError(VcncError):
    """An FMU that could not be built or did not validate."""


class VcncWarning(UserWarning):
    """Base class of the warnings vcnc issues on purpose (``warnings.warn``); the command line prints each as one
    line ``warning: ...`` on stderr."""


class PlausibilityWarning(VcncWarning):
    """A legal input value no real machine has (``velocity = 150000`` [mm/s], a lead of 0.01 mm), most often a unit
    slip: the message names the file, line, key, value, unit and the reason (:mod:`vcnc.engine.plausibility`)."""
