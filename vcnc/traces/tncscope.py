"""Heidenhain TNCscope text export (``%TNCscopeNT data file``).

Format as described in issue #17: CRLF, Latin-1; ``%[GLOBAL]`` with ``%SAMPLING`` [us];
one ``%[CURVEn]`` block per channel (``%CHANNELTYPE`` ``s soll``/``s nom`` commanded position [mm],
``s ist``/``s act`` actual position [mm], ``%AXISTYPE``, ``%COLUMN``); then ``%[DATA]`` and
``;``-separated rows whose column 0 is time [us]. Also read: a UTF-8 or UTF-16 export (with its
byte-order mark), a decimal comma, and Heidenhain's English abbreviations ``s noml`` / ``s actl``.

A curve without ``%COLUMN`` is read from the column of its place among the curves (the first
curve column 1, as the MATLAB reader ``read_tncscope_file.m`` published with real ``.sco`` files
reads every curve; no Heidenhain document of the layout was found, so this is our reading), and
a curve without ``%NAME`` is named by its ``%CHANNELTYPE`` and ``%AXISTYPE`` in messages; ``%``
lines closing a block (as in those files) are skipped. A file that gives ``%COLUMN`` for some
curves and not for others is an error naming the curve.

Each position curve is converted from its own ``%DIMENSION`` (``mm``, ``µm``, ``inch`` on a
control running in inches, ``°`` on a rotary axis; none: mm) to mm or deg: a control in inches,
or a channel exported in um beside one in mm, would otherwise be read 25.4 or 1000 times off
without a word (found by the traceid truth harness). A dimension that is no position unit is an
error naming the curve.

**Following error.** An axis traced with its commanded position and ``s diff`` (the following error,
servo lag) but no actual position is read with the actual position = commanded - ``s diff``.
Heidenhain's user's manuals define the servo lag (position display ``LAG``) as "the difference
between nominal and actual positions" (TNC 426/TNC 425/TNC 415 B/TNC 407 user's manual, MOD
functions, "Position Display Types"); no TNCscope document of the channel's sign was found, so
reading ``s diff`` as nominal - actual is our reading, and the sign is checked on the data
(:mod:`vcnc.traces.lag`: an ``s diff`` by which the result would lead the command is an error naming
the curve's column). With both ``s actl`` and ``s diff`` the actual position is used: it is the
measurement, and needs no convention.

The lag is taken against the nominal position of the same sample, as the manual's definition reads (traces40):
``s noml - s diff`` is then the actual position however far ``s noml`` leads the position loop, and the lead stays
in the record for identification's dead-time scan, as with ``s actl`` (``tests/vcnc/test_traces_40.py``). A lag
taken against the loop's own command while ``s noml`` leads it by ``d`` would put ``s noml(t) - s noml(t - d)``
(the speed times ``d``) into the measured position; no check on the data tells it apart: the share of the
command's first step out of rest that the lag takes up is 1 on fadal-pid, emps and ballscrew-ppc, but a median
0.25 on fadal-smc and -0.25 on ballscrew-zpetc, where such a shifted lag takes up 0 (vcnc's virtual machines,
dwells between 8 moves, the first step after each dwell). A file exported so must be traced with ``s actl``.

(The iTNC 530 service manual's "Pos.Diff." between the motor
encoder and the scale is another signal; it is no following error.)
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

from vcnc.core.axes import AXIS_NAMES, ROTARY_AXES
from vcnc.core.capture import Capture
from vcnc.core.errors import CaptureError
from vcnc.traces.columns import (
    LAG_SUFFIX,
    LENGTH_UNITS,
    mapping_meta,
    on_uniform_grid,
    parse_number,
    read_text,
    unit_named,
    unit_stated,
    with_following_errors,
)

MAGIC = "%TNCscopeNT"
COMMANDED = ("s soll", "s nom", "s noml", "s nominal")
MEASURED = ("s ist", "s act", "s actl", "s actual")
#: Channel types of the following error (servo lag).
LAG = ("s diff",)
#: How the servo lag is signed, and where Heidenhain says so (module docstring).
LAG_CONVENTION = ("nominal - actual position (Heidenhain TNC 426/425/415 B/407 user's manual, MOD functions, "
                  "'Position Display Types': servo lag, the difference between nominal and actual positions; "
                  "our reading for TNCscope's s diff)")


def read_tncscope(path: str | os.PathLike[str], *, resample: bool = False) -> Capture:
    """Read a TNCscope text export into a capture.

    Parameters
    ----------
    path : path-like
        The ``.sco``/text export.

    Returns
    -------
    Capture
        Time [s], commanded and measured position [mm] per axis; ``meta`` names the channels used.

    Raises
    ------
    CaptureError
        Not a TNCscope file, no commanded/measured pair, or rows of the wrong length.
    """
    src = str(Path(path))
    lines = read_text(path, src).lstrip("\ufeff").splitlines()
    if not lines or not lines[0].startswith(MAGIC):
        raise CaptureError(f"first line must start with {MAGIC!r}", file=src, line=1)
    curves, data_line = _curves(lines, src)
    found = [c.get("NAME") or f"{c.get('CHANNELTYPE', '?')} {c.get('AXISTYPE', '')}".strip() for c in curves]
    numbered = sum("COLUMN" in c for c in curves)
    ref: dict[str, int] = {}
    meas: dict[str, int] = {}
    lag: dict[str, int] = {}
    lag_lines: dict[str, int] = {}  # the file line and name of each axis' s diff curve
    lag_names: dict[str, str] = {}
    scale: dict[int, float] = {}
    dims: dict[int, str | None] = {}  # each position column's %DIMENSION, None where the curve states none
    for k, (c, name) in enumerate(zip(curves, found), start=1):
        ctype = " ".join(c.get("CHANNELTYPE", "").lower().split())
        axis = (c.get("AXISTYPE") or re.split(r"[/\s]", name)[-1]).lower()
        if 0 < numbered < len(curves) and "COLUMN" not in c:
            raise CaptureError(f"curve {name!r} has no %COLUMN while {numbered} other curve(s) have one", file=src,
                               line=int(c["_line"]))
        col = c.get("COLUMN", str(k))
        if not col.isdigit() or int(col) < 1:
            raise CaptureError(f"curve {name!r}: %COLUMN={col!r} is not a column number >= 1", file=src,
                               line=int(c["_line"]))
        if ctype in COMMANDED + MEASURED + LAG:
            scale[int(col)] = _position_scale(c, axis, src)
            dims[int(col)] = c.get("DIMENSION", "").strip() or None
        for kind, table in ((COMMANDED, ref), (MEASURED, meas), (LAG, lag)):
            if ctype in kind:
                table.setdefault(axis, int(col))
        if ctype in LAG:
            lag_lines.setdefault(axis, int(c["_line"]))
            lag_names.setdefault(axis, name)
    axes = tuple(a for a in ref if a in meas or a in lag)
    if not axes:
        raise CaptureError(f"no commanded position with an actual position or following error (s diff); channels "
                           f"found: {found}", file=src, line=data_line)
    second = {x: meas.get(x, lag.get(x)) for x in axes}
    bad = [a for a in axes if a not in AXIS_NAMES]
    if bad:
        raise CaptureError(f"axis {bad[0]!r} (from %AXISTYPE or the curve name): expected one of "
                           f"{' '.join(AXIS_NAMES)}", file=src, line=data_line)
    a, row_lines = _rows(lines, data_line, found, src)
    need = max(max(ref[x], second[x]) for x in axes)
    if a.shape[1] <= need:
        raise CaptureError(f"rows have {a.shape[1]} values; %COLUMN={need} needs {need + 1}; channels: {found}",
                           file=src, line=row_lines[0])
    t = a[:, 0] * 1e-6
    bad_t = np.flatnonzero(np.diff(t) <= 0)
    if bad_t.size:
        k = int(bad_t[0]) + 1
        raise CaptureError(f"time does not increase ({a[k, 0]:.9g} us after {a[k - 1, 0]:.9g} us)", file=src,
                           line=row_lines[k])
    r_cols, m_cols = [ref[x] for x in axes], [second[x] for x in axes]
    t, (r, m), how = on_uniform_grid(t, [a[:, r_cols] * [scale[k] for k in r_cols],
                                         a[:, m_cols] * [scale[k] for k in m_cols]], src, row_lines, resample=resample)
    mapping = {**{f"{x}_ref": f"col{ref[x]}" for x in axes}, **{x: f"col{meas[x]}" for x in axes if x in meas},
               **{x + LAG_SUFFIX: f"col{lag[x]} ({lag_names[x]})" for x in axes if x not in meas}}
    m, lag_meta = with_following_errors(axes, mapping, r, m, float(t[1] - t[0]), src, line=lag_lines,
                                        expected=LAG_CONVENTION)
    meta = {"format": "TNCscope", **mapping_meta(axes, mapping), **lag_meta, **how,
            **unit_stated({f"col{k}": dims[k] for k in r_cols + m_cols}, "stated by %DIMENSION")}
    converted = {k: v for k, v in scale.items() if v != 1.0 and k in r_cols + m_cols}
    if converted:
        meta["converted"] = ",".join(f"col{k}x{v:g}" for k, v in sorted(converted.items()))
    return Capture(t=t, axes=axes, reference=r, measured=m, meta=meta, source=src)


def _position_scale(curve: dict[str, str], axis: str, src: str) -> float:
    """mm (deg on a rotary axis) per unit of a position curve's ``%DIMENSION`` (none: mm)."""
    dim = curve.get("DIMENSION", "").strip()
    if not dim:
        return 1.0
    unit = unit_named(dim.strip("[]()"), "length")
    rotary = axis in ROTARY_AXES
    name = curve.get("NAME", "?")
    expected = "°" if rotary else "mm, µm or inch"
    if unit is None or unit == "m" or (unit == "deg") != rotary:
        raise CaptureError(f"curve {name!r}: %DIMENSION={dim!r} is not a position unit of a "
                           f"{'rotary' if rotary else 'linear'} axis (expected {expected})", file=src,
                           line=int(curve["_line"]))
    return LENGTH_UNITS[unit]


def _curves(lines: list[str], src: str) -> tuple[list[dict[str, str]], int]:
    """The ``%[CURVEn]`` blocks as ``{KEY: value}`` (with ``_line``), and the ``%[DATA]`` line."""
    curves: list[dict[str, str]] = []
    for i, line in enumerate(lines[1:], start=2):
        s = line.strip()
        if s.upper() == "%[DATA]":
            return curves, i
        if s.upper().startswith("%[CURVE"):
            curves.append({"_line": str(i)})
        elif s.startswith("%") and "=" in s and curves:
            key, value = s[1:].split("=", 1)
            curves[-1][key.strip().upper()] = value.strip()
    raise CaptureError("no %[DATA] line", file=src, line=len(lines))


def _rows(lines: list[str], data_line: int, found: list[str], src: str) -> tuple[np.ndarray, list[int]]:
    """The ``;`` rows after ``%[DATA]`` (a decimal comma accepted) and the file line of each."""
    rows: list[list[float]] = []
    row_lines: list[int] = []
    for i, line in enumerate(lines[data_line:], start=data_line + 1):
        s = line.strip().rstrip(";")
        if not s:
            continue
        try:
            vals = [parse_number(v, decimal_comma=True) for v in s.split(";")]
        except ValueError:
            raise CaptureError(f"non-numeric value in row {s!r}; channels: {found}", file=src, line=i) from None
        if any(v != v for v in vals):
            raise CaptureError(f"an empty value in row {s!r}; channels: {found}", file=src, line=i)
        if rows and len(vals) != len(rows[0]):
            raise CaptureError(f"row has {len(vals)} values, expected {len(rows[0])}; channels: {found}", file=src,
                               line=i)
        rows.append(vals)
        row_lines.append(i)
    if len(rows) < 2:
        raise CaptureError(f"{len(rows)} data row(s) after %[DATA]; a capture needs at least 2", file=src,
                           line=data_line)
    return np.asarray(rows, dtype=float), row_lines
