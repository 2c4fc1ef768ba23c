"""Heidenhain TNCscope text export (``%TNCscopeNT data file``).

Format as described in issue #17: CRLF, Latin-1; ``%[GLOBAL]`` with ``%SAMPLING`` [us];
one ``%[CURVEn]`` block per channel (``%CHANNELTYPE`` ``s soll``/``s nom`` commanded position [mm],
``s ist``/``s act`` actual position [mm], ``%AXISTYPE``, ``%COLUMN``); then ``%[DATA]`` and
``;``-separated rows whose column 0 is time [us].
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from vcnc.core.capture import Capture
from vcnc.core.errors import CaptureError

MAGIC = "%TNCscopeNT"
COMMANDED = ("s soll", "s nom")
MEASURED = ("s ist", "s act")


def read_tncscope(path: str | os.PathLike[str]) -> Capture:
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
    p = Path(path)
    src = str(p)
    lines = p.read_bytes().decode("latin-1").splitlines()
    if not lines or not lines[0].startswith(MAGIC):
        raise CaptureError(f"first line must start with {MAGIC!r}", file=src, line=1)
    curves: list[dict[str, str]] = []
    data_line = None
    for i, line in enumerate(lines[1:], start=2):
        s = line.strip()
        if s.upper() == "%[DATA]":
            data_line = i
            break
        if s.upper().startswith("%[CURVE"):
            curves.append({"_line": str(i)})
        elif s.startswith("%") and "=" in s and curves:
            key, value = s[1:].split("=", 1)
            curves[-1][key.strip().upper()] = value.strip()
    if data_line is None:
        raise CaptureError("no %[DATA] line", file=src, line=len(lines))
    found = [c.get("NAME", "?") for c in curves]
    ref: dict[str, int] = {}
    meas: dict[str, int] = {}
    for c in curves:
        ctype = c.get("CHANNELTYPE", "").lower()
        name = c.get("NAME", "")
        axis = (c.get("AXISTYPE") or name.rpartition("/")[2]).lower()
        col = int(c.get("COLUMN", "0"))
        if ctype in COMMANDED:
            ref[axis] = col
        elif ctype in MEASURED:
            meas[axis] = col
    axes = tuple(a for a in ref if a in meas)
    if not axes:
        raise CaptureError(f"no commanded/measured position pair; channels found: {found}", file=src, line=data_line)
    rows: list[list[float]] = []
    width = None
    for i, line in enumerate(lines[data_line:], start=data_line + 1):
        s = line.strip().rstrip(";")
        if not s:
            continue
        try:
            vals = [float(v) for v in s.split(";")]
        except ValueError:
            raise CaptureError(f"non-numeric value in row {s!r}; channels: {found}", file=src, line=i) from None
        if width is None:
            width = len(vals)
        elif len(vals) != width:
            raise CaptureError(f"row has {len(vals)} values, expected {width}; channels: {found}", file=src, line=i)
        rows.append(vals)
    a = np.asarray(rows, dtype=float)
    t = a[:, 0] * 1e-6
    if np.any(np.diff(t) <= 0):
        k = int(np.argmax(np.diff(t) <= 0)) + 1
        raise CaptureError("time does not increase", file=src, line=data_line + 1 + k)
    meta = {"format": "TNCscope", "commanded": ",".join(f"{x}:col{ref[x]}" for x in axes),
            "measured": ",".join(f"{x}:col{meas[x]}" for x in axes)}
    return Capture(t=t, axes=axes, reference=a[:, [ref[x] for x in axes]],
                   measured=a[:, [meas[x] for x in axes]], meta=meta, source=src)
