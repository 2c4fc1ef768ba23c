"""Seeded trace-layout fuzzer: known captures written in random but plausible delimited layouts, read back by
:func:`vcnc.traces.read_trace` (``python -m benchmarks.trace_fuzz --n 2000 --seed 1``).

A capture (a random-moves reference and a measured position lagging it, 1-3 axes, linear and rotary) is written
as a drive tool or logger might: delimiter ``,`` ``;`` tab, runs of spaces or ``|``; decimal comma; thousands
separators (a spreadsheet's ``1,234.5`` in quoted cells); quoted cells; header names of the vocabularies
:mod:`vcnc.traces.names` knows (English, German, Japanese-style), with units in brackets, parentheses, after a
slash, or in a row of units, or given as ``unit=``; positions in nm, um, mm, m, in, deg, rad, rev or counts
with a stated resolution; time in s, ms, us, as date-time stamps, as sample numbers or absent under a stated
sampling period;
extra columns (velocity, current, following error, status bits); a preamble of metadata lines; a byte-order
mark, CRLF, delimiters ending every row, blank lines, comment lines, empty or ``NaN`` cells at the ends;
jittered time stamps (read with ``resample=True``); files of 3 to 30,000 rows.

Each file is read and judged (:func:`judge`): ``read`` (the capture is the truth: positions in mm or deg within
the written precision, the commanded and the measured position in their places, the axis letters, the time step),
``refused`` (a :class:`vcnc.core.errors.CaptureError` naming the file), or a failure: ``traceback`` (any other
exception), ``wrong-axes``, ``wrong-role`` (commanded and measured swapped), ``wrong-unit`` (off by a unit's
ratio), ``wrong-values`` (a shifted column or anything else), ``wrong-time``, ``error-without-file``.
"""

from __future__ import annotations

import argparse
import collections
import math
import random
import sys
import tempfile
import traceback
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from vcnc.core.errors import CaptureError
from vcnc.traces import read_trace

#: Units a position may be written in: mm (or deg) per unit.
_UNITS = {"mm": 1.0, "um": 1e-3, "nm": 1e-6, "m": 1e3, "in": 25.4, "deg": 1.0, "\u00b0": 1.0, "rad": math.degrees(1.0),
          "rev": 360.0}
#: Decimals added to the 3, 4 or 6 a position is written with, per unit.
_MORE_DECIMALS = {"um": -2, "nm": -5, "m": 3, "in": 1, "rad": 2, "rev": 3}
#: Time units: seconds per unit.
_TIME_UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6}
#: Header vocabularies: (commanded, measured, following error) name patterns, ``{A}`` the axis letter.
_VOCABULARY = {
    "english": ("{A} Commanded Position", "{A} Actual Position", "{A} Following Error"),
    "snake": ("{a}_cmd", "{a}_fb", "{a}_ferror"),
    "twincat": ("Axis_{A}.SetPos", "Axis_{A}.ActPos", "Axis_{A}.PosDiff"),
    "camel": ("{A}PosCmd", "{A}PosAct", "{A}PosLag"),
    "german": ("{A} Sollposition", "{A} Istposition", "{A} Schleppabstand"),
    "german2": ("Pos_Soll_{A}", "Pos_Ist_{A}", "Schleppfehler_{A}"),
    "japanese": ("{A}\u8ef8\u6307\u4ee4\u4f4d\u7f6e", "{A}\u8ef8\u30d5\u30a3\u30fc\u30c9\u30d0\u30c3\u30af\u4f4d\u7f6e",
                 "{A}\u8ef8\u6e9c\u308a"),
    "ref": ("{a}_ref", "{a}_act", "{a}_lag"),
    "kuka_rsi": ("{A}_RSol", "{A}_RIst", "{A}_Schleppfehler"),
}
#: The same without an axis letter, for a one-axis file (read as x).
_BARE = {"english": ("Commanded Position", "Actual Position", "Following Error"),
         "german": ("Pos_Soll", "Pos_Ist", "Schleppfehler"), "snake": ("pos_cmd", "pos_fb", "pos_ferror")}
_TIME_NAMES = ("t", "Time", "time", "Zeit", "Timestamp", "\u6642\u9593")


@dataclass
class Case:
    """One generated file: its text's parts and what it must read as."""

    seed: int
    axes: list[str]
    t: np.ndarray  #: written time [s]
    ref: np.ndarray  #: commanded [mm/deg], samples x axes
    meas: np.ndarray  #: measured [mm/deg]
    tol: np.ndarray  #: per axis [mm/deg]: the written precision
    kwargs: dict = field(default_factory=dict)
    jitter: bool = False
    layout: list[str] = field(default_factory=list)
    text: str = ""
    encoding_bom: bool = False
    crlf: bool = False


def _moves(rng: random.Random, n: int, ts: float, span: float) -> tuple[np.ndarray, np.ndarray]:
    """A random-moves reference (ramps between random targets, rests) and a first-order lag of it."""
    ref = np.empty(n)
    pos, k = rng.uniform(-span, span), 0
    while k < n:
        target = rng.uniform(-span, span)
        steps = max(1, int(rng.uniform(0.05, 0.3) / ts))
        ramp = pos + (target - pos) * np.linspace(0, 1, steps + 1)[1:]
        rest = np.full(max(1, int(rng.uniform(0.0, 0.1) / ts)), target)
        seg = np.concatenate([ramp, rest])[: n - k]
        ref[k:k + seg.size] = seg
        k += seg.size
        pos = target
    alpha = ts / (rng.uniform(0.005, 0.03) + ts)
    meas = np.empty(n)
    meas[0] = ref[0]
    for i in range(1, n):
        meas[i] = meas[i - 1] + alpha * (ref[i - 1] - meas[i - 1])
    return ref, meas


def _fmt(v: float, dec: int, comma: bool, thousands: str) -> str:
    s = f"{v:.{dec}f}"
    if thousands:
        sign, s = ("-", s[1:]) if s.startswith("-") else ("", s)
        whole, _, frac = s.partition(".")
        groups = [whole[max(0, i - 3):i] for i in range(len(whole), 0, -3)][::-1]
        # the decimal mark written as such (replacing '.' after grouping by '.' turned it into a group mark: seed
        # 41000863's '-52.920.3' for -52920.3 with a decimal comma, refused as no number)
        return sign + thousands.join(groups) + (("," if comma else ".") + frac if frac else "")
    return s.replace(".", ",") if comma else s


@dataclass
class _Spec:
    """The choices of one generated file, shared by the steps that write it."""

    rng: random.Random
    axes: list[str]
    n: int
    ts: float
    delim: str
    comma: bool
    quote: bool
    thousands: str
    unit: str  #: mm um m in deg counts
    unit_style: str  #: name row none given
    count: float  #: the size of one count [mm or deg]
    time_style: str  #: s ms us samples absent stamps-none
    jitter: bool
    lay: list[str]
    kwargs: dict = field(default_factory=dict)
    use_lag: bool = False

    @property
    def rotary(self) -> list[bool]:
        return [a in "abc" for a in self.axes]

    @property
    def mixed(self) -> bool:
        return len(set(self.rotary)) > 1


def _choose(rng: random.Random) -> _Spec:
    """The axes, delimiter, number format, units and time of a file."""
    n = rng.choice([3, 8, 50, 400, 1500, 3000]) if rng.random() < 0.9 else rng.choice([12000, 30000])
    pool = rng.choice([["x", "y", "z"], ["x", "y", "z"], ["a", "b", "c"], ["x", "y", "c"], ["x", "a"]])
    axes = sorted(rng.sample(pool, min(rng.choice([1, 1, 2, 3]), len(pool))), key="xyzuvwabc".index)
    delim = rng.choice([",", ";", "\t", " ", "|"])
    comma = delim != "," and rng.random() < 0.3
    quote = delim != " " and rng.random() < 0.2
    thousands = ""
    if rng.random() < 0.1 and (delim == "," or comma):  # a spreadsheet's "1,234.5" (quoted) or 1.234,5
        thousands = "." if comma else ","
        quote = quote or thousands == delim
    rotary = [a in "abc" for a in axes]
    mixed = len(set(rotary)) > 1
    unit_style = rng.choice(["name", "name", "row", "none", "given"] if not mixed else ["name", "row", "none"])
    if all(rotary):
        unit = rng.choice(["deg", "deg", "counts", "rad", "rev", "\u00b0"])
    else:
        unit = rng.choice(["mm", "um", "m", "in", "nm", "counts"] if not mixed else ["mm", "um"])
    if unit_style == "none" and unit != "counts":
        unit = "mm" if not all(rotary) else "deg"
    time_style = rng.choice(["s", "s", "ms", "us", "samples", "absent", "stamps-none", "date-time"])
    spec = _Spec(rng=rng, axes=axes, n=n, ts=rng.choice([0.001, 0.0005, 0.002, 0.004, 0.000125]), delim=delim,
                 comma=comma, quote=quote, thousands=thousands, unit=unit, unit_style=unit_style,
                 count=rng.choice([0.1e-3, 1e-3, 0.5e-3]) if not all(rotary) else rng.choice([1e-3, 1e-4]),
                 time_style=time_style, jitter=time_style in _TIME_UNITS and rng.random() < 0.15 and n >= 8, lay=[])
    spec.lay += [f"{len(axes)}ax:{''.join(axes)} n={n}", {"\t": "tab", " ": "spaces"}.get(delim, delim)]
    spec.lay += ["dec-comma"] * comma + ["quoted"] * quote + [f"thousands'{thousands}'"] * bool(thousands)
    spec.lay += [f"unit:{unit}/{unit_style}", f"time:{time_style}" + ("+jitter" if spec.jitter else "")]
    if spec.jitter:
        spec.kwargs["resample"] = True
    return spec


def _truth(spec: _Spec) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Written time [s], commanded and measured positions [mm/deg] (samples x axes)."""
    rng, ts = spec.rng, spec.ts
    t = np.arange(spec.n) * ts + (rng.choice([0.0, 0.0, 12.5]) if spec.time_style in ("s", "ms") else 0.0)
    if spec.jitter:
        t = t + np.array([rng.uniform(-0.2, 0.2) * ts for _ in range(spec.n)])
        t[0] = round(t[0] / ts) * ts
    pairs = [_moves(rng, spec.n, ts, rng.choice([5.0, 50.0, 200.0]) if a not in "abc" else rng.choice([30.0, 180.0]))
             for a in spec.axes]
    return t, np.column_stack([r for r, _ in pairs]), np.column_stack([m for _, m in pairs])


def _preamble(spec: _Spec) -> list[str]:
    """Metadata lines above the table: a device line, the count size, the sampling period."""
    rng, ts, preamble = spec.rng, spec.ts, []
    if rng.random() < 0.3:
        preamble += [rng.choice(["Device: Drive 1", "Date: 2024-05-02", "Operator: test", "Firmware V2.1.3"])]
    if spec.unit == "counts":
        preamble.append(f"Resolution: {spec.count * 1000:g} um" if not all(spec.rotary) else
                        f"Resolution: {spec.count:g} deg")
    if spec.time_style in ("samples", "absent", "stamps-none"):
        if rng.random() < 0.8:
            preamble.append(rng.choice([f"Sampling time: {ts * 1000:g} ms", f"Sample time [ms]: {ts * 1000:g}",
                                        f"Abtastzeit: {ts * 1e6:g} us"]))
        else:
            spec.kwargs["sample_time"] = ts
    if preamble and rng.random() < 0.5:
        preamble = ["# " + p for p in preamble]
    return preamble


def _header(spec: _Spec, pos_unit: str) -> tuple[list[str], list[tuple[str, int]], list[str] | None]:
    """The names, the kind of each column (``t``, ``n``, ``ref``, ``second`` or an extra, with its axis index) and
    a row of units or None."""
    rng, axes = spec.rng, spec.axes
    rotary = any(a in "abc" for a in axes)  # KUKA RSI's A, B, C are the tool's orientation, no axes (names.py)
    vocab = rng.choice([v for v in _VOCABULARY if not (rotary and v == "kuka_rsi")])
    spec.use_lag = rng.random() < 0.15
    bare = len(axes) == 1 and axes[0] == "x" and rng.random() < 0.3
    spec.lay.append(f"names:{'bare' if bare else vocab}" + ("+lag" if spec.use_lag else ""))
    header, cols = [], []
    if spec.time_style in _TIME_UNITS:
        header.append(rng.choice(_TIME_NAMES + ("IPOC",) * (spec.time_style == "ms")))
        cols.append(("t", 0))
    elif spec.time_style == "date-time":
        header.append(rng.choice(["Timestamp", "Time", "Zeitstempel"]))
        cols.append(("stamp", 0))
    elif spec.time_style in ("samples", "stamps-none"):
        header.append(rng.choice(["Sample #", "No.", "Index"]))
        cols.append(("n", 0))
    for j, a in enumerate(axes):
        pats = _BARE[rng.choice(list(_BARE))] if bare else _VOCABULARY[vocab]
        header += [pats[0].format(A=a.upper(), a=a), pats[2 if spec.use_lag else 1].format(A=a.upper(), a=a)]
        cols += [("ref", j), ("second", j)]
    extras = rng.sample(["vel", "cur", "status", "ferr"], rng.choice([0, 0, 1, 2]))
    for e in extras:
        a = axes[0].upper()
        header.append({"vel": f"{a} Velocity", "cur": f"{a} Current", "status": "Status",
                       "ferr": f"{a} Following Error" if not spec.use_lag else f"{a} Speed"}[e])
        cols.append((e, 0))
    spec.lay += ["extra:" + "+".join(extras)] * bool(extras)
    if spec.delim == " ":
        header = [h.replace(" ", "_") for h in header]
    t_unit = spec.time_style if spec.time_style in _TIME_UNITS else ""
    unit_of = {"t": t_unit, "n": "", "stamp": "", "vel": "mm/s", "cur": "A", "status": "", "ferr": pos_unit}
    units = [unit_of[kind] if kind not in ("ref", "second") else ("deg" if spec.mixed and spec.rotary[j] else pos_unit)
             for kind, j in cols]
    units_row = None
    if spec.unit_style == "name":
        bracket = rng.choice(["[{}]", "({})", "/{}", " [{}]", " ({})"])
        bracket = bracket.strip() if spec.delim == " " else bracket
        header = [h + bracket.format(u) if u else h for h, u in zip(header, units)]
    elif spec.unit_style == "row":
        units_row = [f"[{u}]" if u else "-" for u in units]
    elif spec.unit_style == "given":
        linear = not all(spec.rotary)
        spec.kwargs["unit"] = {"counts": f"{spec.count * (1000 if linear else 1):g}{'um' if linear else 'deg'}"}.get(
            spec.unit, spec.unit)
    if spec.time_style in _TIME_UNITS and spec.unit_style in ("none", "given") and (
            spec.time_style != "s" or rng.random() < 0.5):
        spec.kwargs["time_unit"] = spec.time_style
    return header, cols, units_row


def _rows(spec: _Spec, cols: list[tuple[str, int]], t: np.ndarray, ref: np.ndarray, meas: np.ndarray,
          scale_of: list[float], dec: int) -> list[list[str]]:
    """The cells of every row, in the file's units and number format."""
    lag = ref - meas
    second = lag if spec.use_lag else meas
    tdec = ({"s": 7, "ms": 4, "us": 1} if not spec.jitter else {"s": 9, "ms": 6, "us": 3}).get(spec.time_style, 0)
    rows = []
    for i in range(spec.n):
        cells = []
        for kind, j in cols:
            if kind == "t":
                cells.append(_fmt(t[i] / _TIME_UNITS[spec.time_style], tdec, spec.comma, ""))
            elif kind == "n":
                cells.append(str(i))
            elif kind == "stamp":  # a logger's local time stamps, to the microsecond
                us = round(t[i] * 1e6) + 56_376_000
                cells.append(f"2024-05-02{'T' if spec.delim == ' ' else ' '}15:{us // 60_000_000:02d}:"
                             f"{us // 1_000_000 % 60:02d}.{us % 1_000_000:06d}")
            elif kind in ("ref", "second"):
                v = (ref if kind == "ref" else second)[i, j] / scale_of[j]
                cells.append(_fmt(round(v) if dec == 0 else v, dec, spec.comma, spec.thousands))
            else:
                v = {"vel": 123.4 * math.sin(i / 7), "cur": 1.5 * math.cos(i / 9), "status": float(i % 4),
                     "ferr": lag[i, 0] / scale_of[0]}[kind]
                cells.append(_fmt(v, 0 if kind == "status" else 3, spec.comma, ""))
        rows.append(cells)
    if spec.rng.random() < 0.1 and spec.n > 6:  # empty or NaN cells before a column's first number, after its last
        blank = spec.rng.choice(["", "NaN", "nan"])
        c = spec.rng.randrange(len(cols))
        rows[0][c] = rows[-1][c] = blank
        spec.lay.append(f"ends:{blank or 'empty'}")
    return rows


def _lines(spec: _Spec, preamble: list[str], header: list[str], units_row: list[str] | None,
           rows: list[list[str]]) -> list[str]:
    """The file's lines: preamble, comment, names, units, rows, blank lines, each row joined as the layout says."""
    rng = spec.rng
    if spec.quote:
        header = [f'"{h}"' for h in header]
        rows = [[f'"{c}"' for c in r] for r in rows]
        units_row = [f'"{u}"' for u in units_row] if units_row else None
    trail = spec.delim != " " and rng.random() < 0.1
    if spec.delim == " ":
        width = max(len(c) for r in [header, *rows[:50], *rows[-50:]] for c in r) + 2

        def join(cells: list[str]) -> str:
            return "".join(c.rjust(width) for c in cells).strip()
    else:
        def join(cells: list[str]) -> str:
            return spec.delim.join(cells) + (spec.delim if trail else "")
    comment = rng.random() < 0.15
    lines = [*preamble, *["# exported by a fuzz tool"] * comment, join(header)]
    lines += [join(units_row)] if units_row else []
    lines += [join(r) for r in rows]
    blanks = rng.random() < 0.1
    lines += ["", ""] * blanks
    spec.lay += ["trailing-delim"] * trail + ["blank-lines"] * blanks + ["comment"] * comment
    spec.lay += [f"preamble:{len(preamble)}"] * bool(preamble)
    return lines


def generate(seed: int) -> Case:
    """The file of ``seed`` (module docstring)."""
    spec = _choose(random.Random(seed))
    rng = spec.rng
    t, ref, meas = _truth(spec)
    pos_unit = {"counts": "inc", "um": rng.choice(["um", "\u00b5m"])}.get(spec.unit, spec.unit)
    scale = spec.count if spec.unit == "counts" else _UNITS[spec.unit]
    scale_of = [1.0 if (spec.mixed and r) else scale for r in spec.rotary]
    dec = 0 if spec.unit == "counts" else max(0, rng.choice([3, 4, 6]) + _MORE_DECIMALS.get(spec.unit, 0))
    tol = np.array([0.5 * 10.0 ** -dec * s * 1.01 + 1e-12 for s in scale_of])
    preamble = _preamble(spec)
    header, cols, units_row = _header(spec, pos_unit)
    lines = _lines(spec, preamble, header, units_row, _rows(spec, cols, t, ref, meas, scale_of, dec))
    case = Case(seed=seed, axes=spec.axes, t=t, ref=ref, meas=meas, tol=tol, kwargs=spec.kwargs, jitter=spec.jitter,
                layout=spec.lay)
    case.encoding_bom = rng.random() < 0.1
    case.crlf = rng.random() < 0.2
    spec.lay += ["BOM"] * case.encoding_bom + ["CRLF"] * case.crlf
    case.text = "\n".join(lines) + "\n"
    if rng.random() < 0.1:
        case.text = case.text.replace("\n", "\n\n", 3)
    return case


def write(case: Case, path: Path) -> None:
    text = case.text.replace("\n", "\r\n") if case.crlf else case.text
    path.write_bytes((b"\xef\xbb\xbf" if case.encoding_bom else b"") + text.encode("utf-8"))


def judge(case: Case, path: Path) -> tuple[str, str]:
    """(outcome, detail) of reading ``path`` (module docstring)."""
    try:
        cap = read_trace(path, **case.kwargs)
    except CaptureError as exc:
        return ("refused" if str(path) in str(exc) else "error-without-file"), str(exc)
    except Exception:  # noqa: BLE001 - a traceback is the failure being looked for
        return "traceback", traceback.format_exc(limit=-3)
    if list(cap.axes) != case.axes:
        return "wrong-axes", f"read {list(cap.axes)}, written {case.axes}"
    ts = float(np.median(np.diff(case.t)))
    step = float(cap.t[1] - cap.t[0])
    if abs(step - ts) > (0.25 if case.jitter else 1e-6) * ts:
        return "wrong-time", f"step {step!r} s, written {ts!r} s"
    # the reader may start time at 0 and skips rows with empty cells at the ends: align on the first rows kept
    rel = cap.t - cap.t[0]
    best = min(range(3), key=lambda k0: _misfit(case, cap, rel, k0, ts))
    rel_t = case.t - case.t[best]
    for j, _ in enumerate(case.axes):
        if case.jitter:
            want_ref, want_meas = np.interp(rel, rel_t, case.ref[:, j]), np.interp(rel, rel_t, case.meas[:, j])
        else:
            idx = np.clip(best + np.round(rel / ts).astype(int), 0, case.t.size - 1)
            want_ref, want_meas = case.ref[idx, j], case.meas[idx, j]
        tol = case.tol[j] * (2.0 if case.jitter else 1.0) + (1e-5 if case.jitter else 1e-9)
        got_ref, got_meas = cap.reference[:, j], cap.measured[:, j]
        e_ref = float(np.max(np.abs(got_ref - want_ref)))
        e_meas = float(np.max(np.abs(got_meas - want_meas)))
        if e_ref <= tol and e_meas <= 2 * tol:
            continue
        if np.max(np.abs(got_ref - want_meas)) <= 2 * tol and np.max(np.abs(got_meas - want_ref)) <= 2 * tol:
            return "wrong-role", f"axis {case.axes[j]}: commanded and measured swapped"
        span = float(np.ptp(want_ref)) or 1.0
        ratio = float(np.ptp(got_ref)) / span
        if any(abs(ratio / r - 1) < 0.02 for r in (1e3, 1e-3, 25.4, 1 / 25.4, 1e6, 1e-6, 1e4, 1e-4, 10, 0.1)):
            return "wrong-unit", f"axis {case.axes[j]}: read {ratio:.6g} x the written positions"
        return "wrong-values", (f"axis {case.axes[j]}: commanded off by {e_ref:.3g}, measured by {e_meas:.3g} "
                                f"(tol {tol:.3g})")
    return "read", ""


def _misfit(case: Case, cap, rel: np.ndarray, k0: int, ts: float) -> float:
    """How far the capture's commanded positions are from the written ones ``k0`` rows on (every axis: one may rest),
    in each axis' written precision (an axis written to 0.1 deg must not outweigh one written to 0.1 um)."""
    if case.t.size <= k0 or cap.reference.shape[1] != case.ref.shape[1]:
        return math.inf
    if case.jitter:
        want = np.column_stack([np.interp(rel, case.t - case.t[k0], case.ref[:, j]) for j in range(case.ref.shape[1])])
    else:
        want = case.ref[np.clip(k0 + np.round(rel / ts).astype(int), 0, case.t.size - 1)]
    return float(np.max(np.abs(cap.reference - want) / case.tol))


FAILURES = ("traceback", "wrong-axes", "wrong-role", "wrong-unit", "wrong-values", "wrong-time", "error-without-file")


def run(n: int, seed: int, folder: Path, *, verbose: bool = False) -> collections.Counter:
    """Generate and judge ``n`` files from ``seed``; the counts of outcomes (and prints the failures)."""
    counts: collections.Counter = collections.Counter()
    for k in range(n):
        case = generate(seed * 1_000_003 + k)
        path = folder / f"fuzz_{case.seed}.csv"
        write(case, path)
        outcome, detail = judge(case, path)
        counts[outcome] += 1
        if outcome in FAILURES or (verbose and outcome == "refused"):
            print(f"{outcome}\t{case.seed}\t{' '.join(case.layout)}\t{case.kwargs}\t{detail.splitlines()[-1][:300]}")
        path.unlink()
    return counts


def _tncscope(ref: np.ndarray, meas: np.ndarray, ts: float) -> tuple[str, str]:
    """A TNCscope text export of axis Y (``%TNCscopeNT``, time in us, ``;`` rows)."""
    lines = ["%TNCscopeNT data file", "%[GLOBAL]", f"%SAMPLING={ts * 1e6:g}",
             "%[CURVE1]", "%NAME=s soll/Y", "%CHANNELTYPE=s soll", "%AXISTYPE=Y", "%DIMENSION=mm", "%COLUMN=1",
             "%[CURVE2]", "%NAME=s ist/Y", "%CHANNELTYPE=s ist", "%AXISTYPE=Y", "%DIMENSION=mm", "%COLUMN=2",
             "%[DATA]"]
    lines += [f"{k * ts * 1e6:.0f};{r:.6f};{m:.6f};" for k, (r, m) in enumerate(zip(ref, meas))]
    return "\n".join(lines) + "\n", "y"


def _halscope(ref: np.ndarray, meas: np.ndarray, ts: float) -> tuple[str, str]:
    """A LinuxCNC 2.8 halscope log (``label value`` pairs, one row past the record)."""
    lines = [f"Sampling period is {ts * 1e9:.0f} ns ", ""]
    lines += [f"joint.0.motor-pos-cmd {r:+.14f} joint.0.motor-pos-fb {m:+.14f} " for r, m in zip(ref, meas)]
    lines += [f"joint.0.motor-pos-cmd {0:+.14f} joint.0.motor-pos-fb {0:+.14f} "]
    return "\n".join(lines) + "\n", "x"


def _twincat(ref: np.ndarray, meas: np.ndarray, ts: float) -> tuple[str, str]:
    """A TwinCAT 3 Scope CSV export (tab, decimal comma, a time column per channel, ``EOF``)."""
    def row(key: str, a: str, b: str) -> str:
        return f"{key}\t{a}\t{key}\t{b}"

    lines = ["Name\taxis_trace", "File\tC:\\scope\\axis_trace.csv", "", row("Name", "MAIN.fPosCmd", "MAIN.fPosAct"),
             row("Data-Type", "REAL64", "REAL64"), row("SampleTime[ms]", f"{ts * 1e3:g}", f"{ts * 1e3:g}"),
             row("Unit", "mm", "mm"), ""]
    lines += ["\t".join(f"{v:.6f}".replace(".", ",") for v in (k * ts * 1e3, r, k * ts * 1e3, m))
              for k, (r, m) in enumerate(zip(ref, meas))]
    return "\n".join([*lines, "EOF"]) + "\n", "x"


#: Mutations that leave a file's meaning as it was (the read must not change), and ones that damage it (a read or
#: a clean refusal, never a traceback).
_BENIGN = ("crlf", "bom", "blank-end", "trailing-spaces")
_DAMAGING = ("drop-line", "bad-digit", "truncate", "duplicate-line")


def _mutate(text: str, how: str, rng: random.Random) -> str:
    lines = text.split("\n")
    k = rng.randrange(len(lines) // 2, max(len(lines) - 1, len(lines) // 2 + 1))
    if how == "crlf":
        return text.replace("\n", "\r\n")
    if how == "bom":
        return "\ufeff" + text
    if how == "blank-end":
        return text + "\n\n"
    if how == "trailing-spaces":
        return "\n".join(line + "  " if line else line for line in lines)
    if how == "drop-line":
        return "\n".join(lines[:k] + lines[k + 1:])
    if how == "duplicate-line":
        return "\n".join(lines[:k] + [lines[k]] + lines[k:])
    if how == "bad-digit":
        digits = [i for i, c in enumerate(lines[k]) if c.isdigit()]
        if digits:
            i = rng.choice(digits)
            lines[k] = lines[k][:i] + rng.choice("x-.,e") + lines[k][i + 1:]
        return "\n".join(lines)
    return text[: rng.randrange(len(text) // 2, len(text))]


def mutate_formats(n: int, seed: int, folder: Path, *, verbose: bool = False) -> collections.Counter:
    """``n`` TNCscope, halscope and TwinCAT files, each mutated once (:data:`_BENIGN`, :data:`_DAMAGING`); the counts
    of ``format:outcome`` (``same``, ``read``, ``refused``, ``changed``: a benign mutation read otherwise,
    ``traceback``)."""
    counts: collections.Counter = collections.Counter()
    for k in range(n):
        rng = random.Random(seed * 1_000_003 + k)
        ts = rng.choice([0.001, 0.0005, 0.003])
        ref, meas = _moves(rng, rng.choice([20, 300]), ts, 20.0)
        ref, meas = np.round(ref, 6), np.round(meas, 6)
        writer = rng.choice([_tncscope, _halscope, _twincat])
        text, axis = writer(ref, meas, ts)
        how = rng.choice(_BENIGN + _DAMAGING)
        path = folder / f"fmt_{seed}_{k}.txt"
        path.write_bytes(_mutate(text, how, rng).encode("utf-8"))
        name = writer.__name__.strip("_")
        try:
            cap = read_trace(path)
            got = "read"
            if how in _BENIGN:
                same = (cap.axes == (axis,) and np.allclose(cap.reference[:, 0], ref[: len(cap)], atol=1e-9)
                        and np.allclose(cap.measured[:, 0], meas[: len(cap)], atol=1e-9) and len(cap) == ref.size)
                got = "same" if same else "changed"
        except CaptureError as exc:
            got = "refused" if str(path) in str(exc) else "error-without-file"
            if how in _BENIGN:
                got = "changed"
        except Exception:  # noqa: BLE001 - a traceback is the failure being looked for
            got = "traceback"
        counts[f"{name}:{got}"] += 1
        if got in ("changed", "traceback", "error-without-file") or (verbose and got == "refused"):
            print(f"format-{got}\t{seed}:{k}\t{name} {how}")
        path.unlink()
    return counts


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=500)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--formats", type=int, default=200, help="TNCscope, halscope and TwinCAT files to mutate")
    ap.add_argument("--verbose", action="store_true", help="also print each refusal")
    ap.add_argument("--dump", type=int, metavar="SEED", help="write the file of one case's seed to --out and judge it")
    ap.add_argument("--out", type=Path, default=Path("."), help="folder for --dump")
    args = ap.parse_args(argv)
    if args.dump is not None:
        case = generate(args.dump)
        args.out.mkdir(parents=True, exist_ok=True)
        path = args.out / f"fuzz_{case.seed}.csv"
        write(case, path)
        print(path, " ".join(case.layout), case.kwargs, *judge(case, path), sep="\n")
        return 0
    with tempfile.TemporaryDirectory() as tmp:
        counts = run(args.n, args.seed, Path(tmp), verbose=args.verbose)
        counts.update(mutate_formats(args.formats, args.seed, Path(tmp), verbose=args.verbose))
    print(f"{'outcome':<20}{'files':>8}")
    for outcome, c in sorted(counts.items(), key=lambda kv: -kv[1]):
        print(f"{outcome:<20}{c:>8}")
    failed = any(counts[f] for f in FAILURES) or any(k.endswith((":changed", ":traceback", ":error-without-file"))
                                                     for k in counts)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
