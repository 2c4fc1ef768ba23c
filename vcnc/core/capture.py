"""Captures: commanded and measured axis positions sampled at a fixed period.

A capture is what a CNC's motion-capture feature records and what the simulator produces. File
format (ARCHITECTURE.md, "Capture file"): optional ``# key: value`` comment lines, then a CSV
header; ``t`` in s (uniform), then per axis ``<a>_ref`` (commanded) and ``<a>`` (measured) in mm
(deg for rotary axes), optionally ``<a>_u`` (control signal, V). Simulated captures may also carry
the documented optional columns ``<a>_table`` (true table position, mm), ``<a>_vel`` (true
velocity, mm/s) and ``<a>_friction`` (friction force expressed as control-signal equivalent, V).
Other formats (control trace exports, the EMPS ``.mat`` files) are read by ``vcnc.read_capture``.
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Callable
from pathlib import Path

import numpy as np

from vcnc.core.axes import AXIS_NAMES
from vcnc.core.errors import CaptureError
from vcnc.core.io import atomic_path, write_rows

__all__ = ["Capture", "read_capture_csv", "check_sampling", "OPTIONAL_SUFFIXES"]

#: Optional per-axis columns and the Capture attribute each fills.
OPTIONAL_SUFFIXES: dict[str, str] = {"u": "control", "table": "table", "vel": "velocity", "friction": "friction"}

#: Relative jitter of the time step accepted as uniform (float32 time stamps, as in EMPS, jitter
#: by about 2.4e-5 relative).
_REL_SAMPLING_TOL = 1e-4
#: The fields of a capture with one column per axis, shape (N, n_axes).
_AXIS_ARRAYS = ("reference", "measured", "control", "table", "velocity", "friction")


#: Key of :attr:`Capture.meta` saying the positions' unit is stated, not assumed: given by the user
#: (:func:`vcnc.traces.read_trace`'s ``unit``, ``--unit``) or stated by the file (a unit in every position column's
#: name or units row, a stated count size, TNCscope's ``%DIMENSION``; :func:`vcnc.traces.columns.unit_stated`). The
#: capture checks then do not second-guess a small motion as metres (``identification.capture_checks``).
UNIT_GIVEN = "unit_given"

@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class Capture:
    """Commanded and measured motion of one or more axes.

    Attributes
    ----------
    t : ndarray, shape (N,)
        Time [s], uniform sampling.
    axes : tuple of str
        Axis names in column order.
    reference : ndarray, shape (N, n_axes)
        Commanded position [mm].
    measured : ndarray, shape (N, n_axes)
        Measured position [mm]: what the capture records (the feedback encoder, or on a
        simulated axis with ``measurement = "table"`` a linear scale on the table).
    control : ndarray, shape (N, n_axes), optional
        Control signal [V].
    table, velocity, friction : ndarray, shape (N, n_axes), optional
        Simulation only: true table position [mm], true velocity [mm/s], friction [V equivalent].
    aux : dict of str to ndarray
        Further signals of the source that are not part of the model (e.g. EMPS ``pulses_N``; a
        simulation's ``measured_true``, the true position of the measured point without sensor
        noise, quantisation and drift, shape (N, n_axes), and ``saturated``, where the actuator
        clipped the control signal, bool (N, n_axes)); identification never reads them. A 2-D
        entry holds one column per axis, in ``axes`` order, and follows :meth:`select_axes`.
    meta : dict
        ``# key: value`` lines of the file, provenance.
    source : str, optional
        File the capture was read from (for error messages).
    path : object, optional
        Programmed geometry when the capture comes from a simulated program.
    """

    t: np.ndarray
    axes: tuple[str, ...]
    reference: np.ndarray
    measured: np.ndarray
    control: np.ndarray | None = None
    table: np.ndarray | None = None
    velocity: np.ndarray | None = None
    friction: np.ndarray | None = None
    aux: dict = dataclasses.field(default_factory=dict)
    meta: dict = dataclasses.field(default_factory=dict)
    source: str | None = None
    path: object = None

    def __post_init__(self) -> None:
        n, k = len(self.t), len(self.axes)
        for name in _AXIS_ARRAYS:
            arr = getattr(self, name)
            if arr is not None and arr.shape != (n, k):
                raise CaptureError(f"Capture.{name} has shape {arr.shape}, expected ({n}, {k})", file=self.source)
        bad = [a for a in self.axes if a not in AXIS_NAMES]
        if bad:
            raise CaptureError(f"unknown axis name(s) {bad}; expected some of {AXIS_NAMES}", file=self.source)

    def __len__(self) -> int:
        return len(self.t)

    @property
    def sample_time(self) -> float:
        """Sampling period Ts [s]: the mean step, rounded to 9 significant digits (so that time
        stamps written as decimals, or stored as float32 as in EMPS, give the nominal period)."""
        if len(self.t) < 2:
            raise CaptureError("a capture needs at least two samples to have a sample time", file=self.source)
        ts = (float(self.t[-1]) - float(self.t[0])) / (len(self.t) - 1)
        return float(f"{ts:.9g}")

    def axis_index(self, axis: str) -> int:
        """Column of ``axis``; CaptureError naming the axes present otherwise."""
        try:
            return self.axes.index(axis)
        except ValueError:
            raise CaptureError(
                f"axis {axis!r} is not in the capture (axes: {', '.join(self.axes)})", file=self.source
            ) from None

    def axis(self, axis: str) -> Capture:
        """A one-axis capture (views, no copy)."""
        i = self.axis_index(axis)
        return self._columns((axis,), slice(i, i + 1))

    def select_axes(self, axes: tuple[str, ...]) -> Capture:
        """The capture of ``axes`` only, in that order (CaptureError naming the axes present)."""
        return self._columns(tuple(axes), [self.axis_index(a) for a in axes])

    def _axis_arrays(self, f: Callable[[np.ndarray], np.ndarray]) -> dict[str, np.ndarray | None]:
        """``f`` applied to each field with one column per axis (absent ones stay None)."""
        return {name: None if (a := getattr(self, name)) is None else f(a) for name in _AXIS_ARRAYS}

    def _columns(self, axes: tuple[str, ...], cols: slice | list[int]) -> Capture:
        return dataclasses.replace(
            self,
            axes=axes,
            **self._axis_arrays(lambda a: a[:, cols]),
            aux={k: v[:, cols] if np.ndim(v) == 2 else v for k, v in self.aux.items()},
        )

    def slice(self, start: int, stop: int) -> Capture:
        """Samples ``start:stop`` (time kept as recorded)."""
        return dataclasses.replace(
            self,
            t=self.t[start:stop],
            **self._axis_arrays(lambda a: a[start:stop]),
            aux={k: v[start:stop] for k, v in self.aux.items()},
        )

    # ------------------------------------------------------------------ files
    def to_csv(self, path: str | os.PathLike[str]) -> None:
        """Write the capture in the CSV contract (atomic: nothing half-written on failure)."""
        header = ["t"]
        cols = [self.t[:, None]]
        for i, a in enumerate(self.axes):
            header += [f"{a}_ref", a]
            cols += [self.reference[:, i : i + 1], self.measured[:, i : i + 1]]
            for suffix, attr in OPTIONAL_SUFFIXES.items():
                arr = getattr(self, attr)
                if arr is not None:
                    header.append(f"{a}_{suffix}")
                    cols.append(arr[:, i : i + 1])
        with atomic_path(path) as tmp, open(tmp, "w", encoding="utf-8", newline="\n") as out:
            for key, value in self.meta.items():
                if isinstance(value, (str, int, float)) and "\n" not in str(value):
                    out.write(f"# {key}: {value}\n")
            out.write(",".join(header) + "\n")
            write_rows(out, cols, ["%.12g"] * len(header))  # the columns side by side, a chunk of rows at a time


def read_capture_csv(path: str | os.PathLike[str]) -> Capture:
    """Read a capture CSV (the contract of ARCHITECTURE.md, "Capture file").

    Raises
    ------
    CaptureError
        Naming the file, line and column at fault: bad header, unknown column, non-numeric/NaN/inf
        value, non-increasing or non-uniform time, too few samples.
    """
    p = Path(path)
    src = str(p)
    try:
        lines = p.read_text(encoding="utf-8-sig").splitlines()
    except UnicodeDecodeError as exc:
        raise CaptureError("capture file is not text (expected CSV)", file=src) from exc
    meta, header_idx = _comment_lines(lines, src)
    names = [c.strip() for c in lines[header_idx].split(",")]
    axes = _header_axes(names, src, header_idx + 1)
    data, row_lines = _data_rows(lines, header_idx, names, src)
    check_sampling(data[:, 0], src, row_lines)

    def stack(suffix: str | None) -> np.ndarray | None:
        wanted = [a if suffix is None else f"{a}_{suffix}" for a in axes]
        cs = [data[:, names.index(c)] if c in names else None for c in wanted]
        if all(c is None for c in cs):
            return None
        if any(c is None for c in cs):
            missing = [a for a, c in zip(axes, cs) if c is None]
            raise CaptureError(
                f"column '_{suffix}' given for some axes but not for {missing}", file=src, line=header_idx + 1
            )
        return np.column_stack(cs)

    kwargs = {attr: stack(suffix) for suffix, attr in OPTIONAL_SUFFIXES.items()}
    return Capture(
        t=data[:, 0],
        axes=tuple(axes),
        reference=stack("ref"),
        measured=stack(None),
        meta=meta,
        source=src,
        **kwargs,
    )


def _comment_lines(lines: list[str], src: str) -> tuple[dict[str, str], int]:
    """The ``# key: value`` lines before the header, and the header's index in ``lines``."""
    meta: dict[str, str] = {}
    for i, line in enumerate(lines):
        s = line.strip()
        if not s:
            continue
        if s.startswith("#"):
            body = s[1:].strip()
            if ":" in body:
                k, v = body.split(":", 1)
                meta[k.strip()] = v.strip()
            continue
        return meta, i
    raise CaptureError("no header line found; expected 't,<axis>_ref,<axis>,...'", file=src)


def _header_axes(names: list[str], src: str, hline: int) -> list[str]:
    """Axes of a header ``t,<a>_ref,<a>,...`` (line ``hline``), checked against the contract."""
    if names[0] != "t":
        raise CaptureError(
            "first column must be 't' (time, s)", file=src, line=hline, column=1, text=names[0]
        )
    seen: set[str] = set()
    for j, c in enumerate(names):
        if c in seen:
            raise CaptureError(f"duplicate column {c!r}", file=src, line=hline, column=j + 1)
        seen.add(c)
    axes: list[str] = []
    for j, c in enumerate(names[1:], start=2):
        base, _, suffix = c.partition("_")
        if base not in AXIS_NAMES or (suffix and suffix not in ("ref", *OPTIONAL_SUFFIXES)):
            raise CaptureError(
                f"unknown column {c!r}",
                file=src,
                line=hline,
                column=j,
                expected="'<axis>_ref', '<axis>', '<axis>_u|_table|_vel|_friction' (vcnc's capture CSV); another "
                "logger's file needs a column mapping (--columns t=NAME,x_ref=NAME,x=NAME)",
            )
        if base not in axes:
            axes.append(base)
    for a in axes:
        for need in (f"{a}_ref", a):
            if need not in seen:
                raise CaptureError(f"axis {a!r} has no column {need!r}", file=src, line=hline)
    if not axes:
        raise CaptureError("no axis columns; expected '<axis>_ref' and '<axis>'", file=src, line=hline)
    return axes


def _data_rows(lines: list[str], header_idx: int, names: list[str], src: str) -> tuple[np.ndarray, list[int]]:
    """The numeric rows after the header, and the file line of each (finite numbers, as many as
    the header's columns, at least two rows).

    A file as vcnc writes it (a number in every field) is read by numpy's compiled reader in one call (a
    1.24-million-row capture of three axes: 39 s and 1.8 GB before); blank and ``#`` comment lines among the
    rows are set aside first, as the row-by-row reading skips them (a capture edited by hand, or two
    captures joined, went through it: tracewild10). Anything else, or any doubt, goes through the row-by-row
    reading, which names the line and column at fault."""
    kept = [i for i in range(header_idx + 1, len(lines)) if (s := lines[i].lstrip()) and not s.startswith("#")]
    if len(kept) >= 2:
        body = lines[header_idx + 1:] if len(kept) == len(lines) - header_idx - 1 else [lines[i] for i in kept]
        try:
            data = np.loadtxt(body, delimiter=",", comments=None, dtype=float, ndmin=2)
        except ValueError:
            data = None
        if (data is not None and data.shape == (len(body), len(names)) and np.isfinite(data).all()):
            return data, [i + 1 for i in kept]
    return _data_rows_checked(lines, header_idx, names, src)


def _data_rows_checked(lines: list[str], header_idx: int, names: list[str], src: str) -> tuple[np.ndarray, list[int]]:
    """:func:`_data_rows` row by row, each field read by ``float`` and checked (the error names its line and column)."""
    rows: list[list[float]] = []
    row_lines: list[int] = []
    for i in range(header_idx + 1, len(lines)):
        s = lines[i].strip()
        if not s or s.startswith("#"):
            continue
        fields = s.split(",")
        if len(fields) != len(names):
            raise CaptureError(
                f"{len(fields)} fields, expected {len(names)} (as in the header)", file=src, line=i + 1
            )
        vals = []
        for j, f in enumerate(fields):
            try:
                v = float(f)
            except ValueError:
                raise CaptureError(
                    f"column {names[j]!r} is not a number", file=src, line=i + 1, column=j + 1, text=f.strip()
                ) from None
            if not math.isfinite(v):
                raise CaptureError(
                    f"column {names[j]!r} is not finite", file=src, line=i + 1, column=j + 1, text=f.strip()
                )
            vals.append(v)
        rows.append(vals)
        row_lines.append(i + 1)
    if len(rows) < 2:
        raise CaptureError(f"only {len(rows)} data row(s); a capture needs at least 2", file=src)
    return np.asarray(rows), row_lines


def check_sampling(t: np.ndarray, src: str | None, row_lines: list[int] | None = None) -> None:
    """Raise CaptureError unless ``t`` [s] increases with a uniform step (relative jitter
    below 1e-4); names the line in ``src`` when ``row_lines`` maps samples to file lines."""
    dt = np.diff(t)
    bad = np.flatnonzero(dt <= 0)
    if bad.size:
        k = int(bad[0]) + 1
        line = row_lines[k] if row_lines else None
        raise CaptureError(
            f"time is not increasing: t = {float(t[k])!r} s after {float(t[k - 1])!r} s", file=src, line=line, column=1
        )
    ts = float(np.median(dt))
    off = np.flatnonzero(np.abs(dt - ts) > _REL_SAMPLING_TOL * ts)
    if off.size:
        k = int(off[0]) + 1
        line = row_lines[k] if row_lines else None
        raise CaptureError(
            f"sampling is not uniform: step {float(dt[k - 1]):.9g} s at t = {float(t[k]):.9g} s, expected {ts:.9g} s",
            file=src,
            line=line,
            column=1,
        )
