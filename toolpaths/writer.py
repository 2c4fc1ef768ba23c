"""Writing part programs in either dialect (ISO G-code or Heidenhain conversational)."""

from __future__ import annotations

import os
from collections.abc import Sequence

from vcnc.core.errors import InputError
from vcnc.core.io import atomic_path

__all__ = ["ProgramWriter", "write_program", "DIALECTS"]

#: Program dialects the writers produce (and the parser reads).
DIALECTS: tuple[str, ...] = ("iso", "heidenhain")


def _check_dialect(dialect: str) -> str:
    if dialect not in DIALECTS:
        raise InputError(f"unknown dialect {dialect!r}", expected=" or ".join(DIALECTS))
    return dialect


class ProgramWriter:
    """Accumulates the blocks of a program (mm, absolute, XY plane, exact stop).

    Parameters
    ----------
    dialect : {"iso", "heidenhain"}
        Output language.
    name : str
        Program name (Heidenhain ``BEGIN PGM``; ISO comment).
    comment : str, optional
        One comment line after the header.
    decimals : int
        Decimals of coordinates [mm].
    """

    def __init__(self, dialect: str = "iso", *, name: str = "VCNC", comment: str | None = None,
                 decimals: int = 4) -> None:
        self.dialect = _check_dialect(dialect)
        self.name = name
        self.decimals = decimals
        self._lines: list[str] = []
        self._n = 0
        self._feed: float | None = None
        if self.dialect == "heidenhain":
            self._block(f"BEGIN PGM {name} MM")
            if comment:
                self._lines.append(f";{comment}")
        else:
            self._lines.append("%")
            self._lines.append(f"({name}{': ' + comment if comment else ''})")
            self._block("G21 G90 G17 G61")

    def _block(self, text: str) -> None:
        if self.dialect == "heidenhain":
            self._lines.append(f"{self._n} {text}")
            self._n += 1
        else:
            self._lines.append(f"N{self._n:04d} {text}")
            self._n += 10

    def _coords(self, point: dict[str, float]) -> str:
        d = self.decimals
        if self.dialect == "heidenhain":
            return " ".join(f"{a.upper()}{v:+.{d}f}" for a, v in point.items())
        return " ".join(f"{a.upper()}{v:.{d}f}" for a, v in point.items())

    def _feed_word(self, feed: float) -> str:
        if self._feed == feed:
            return ""
        self._feed = feed
        return " F" + f"{feed:.3f}".rstrip("0").rstrip(".")

    def rapid(self, point: dict[str, float]) -> None:
        """Rapid move to ``point`` (axis letter -> mm)."""
        if self.dialect == "heidenhain":
            self._block(f"L {self._coords(point)} R0 FMAX")
        else:
            self._block(f"G00 {self._coords(point)}")

    def line(self, point: dict[str, float], *, feed: float) -> None:
        """Straight feed move to ``point`` at ``feed`` [mm/min]."""
        if self.dialect == "heidenhain":
            self._block(f"L {self._coords(point)}{self._feed_word(feed)}")
        else:
            self._block(f"G01 {self._coords(point)}{self._feed_word(feed)}")

    def arc(self, end: Sequence[float], center: Sequence[float], start: Sequence[float], *, ccw: bool,
            feed: float) -> None:
        """XY arc from ``start`` to ``end`` about ``center`` (x, y pairs [mm]) at ``feed`` [mm/min]."""
        d = self.decimals
        if self.dialect == "heidenhain":
            self._block(f"CC X{center[0]:+.{d}f} Y{center[1]:+.{d}f}")
            self._block(f"C X{end[0]:+.{d}f} Y{end[1]:+.{d}f} DR{'+' if ccw else '-'}{self._feed_word(feed)}")
        else:
            i, j = center[0] - start[0], center[1] - start[1]
            self._block(f"G0{3 if ccw else 2} X{end[0]:.{d}f} Y{end[1]:.{d}f} I{i:.{d}f} J{j:.{d}f}"
                        f"{self._feed_word(feed)}")

    def end(self) -> str:
        """Close the program (M30) and return its text."""
        if self.dialect == "heidenhain":
            self._block("M30")
            self._block(f"END PGM {self.name} MM")
        else:
            self._block("M30")
            self._lines.append("%")
        return "\n".join(self._lines) + "\n"


def write_program(text: str, path: str | os.PathLike[str]) -> None:
    """Write program text to ``path`` atomically (no partial file on failure)."""
    with atomic_path(path) as tmp, open(tmp, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(text)
