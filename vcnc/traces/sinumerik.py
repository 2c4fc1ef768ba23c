"""Siemens SINUMERIK Solution Line trace export (XML, root ``<traceSession>``).

Layout (issue #17, checked against the open-source reader ``eliasrhoden/Trace-Tools``,
``tracetools.parse_trace_file``)::

    <traceSession ...>
      <traceData>
        <dataFrame>
          <frameHeader .../>
          <dataSignal id="f1" key="s14" name="/Nck/!SD/nckServoDataCmdPos2ndEnc64 [u1, 7]"
                      description="Position setpoint (64 bit)" interval="0.002000"
                      datapointCount="..." unitsType="posn"/>
          ...
          <rec time="0.004000" f1="-0.000172" f4="..."/>

- A ``rec`` row names a signal (attribute = the signal's ``id``) **only when its value changed**:
  the value holds until the next row that names it. A value above 9.2e18 is the control's
  "no value" marker and holds the previous value too.
- Signals run at different intervals: servo-rate signals (position setpoint, following error)
  at e.g. 2 ms, IPO-rate signals (``measPos1`` / ``measPos2``, "Actual position value for
  measuring system 1/2") at e.g. 4 ms.
- ``[u1, N]`` in a signal's name is the machine axis number N.
- ``<frameHeader dropOuts="N">`` counts records the control lost; a trace with N > 0 is refused
  (a lost record cannot be told from an unchanged value).

The capture's grid is the coarser interval of the two signals that form it, so every value on it
was recorded at that instant (no interpolation). The measured position is the setpoint minus the
following error when the trace has both at the same rate (the control's own measured value at
servo rate), otherwise the measuring system's actual value (system 1 before system 2). The
following error is read as setpoint - actual position, and its sign is checked on the data
(:func:`vcnc.traces.lag.check_lag_sign`: a measured position that would lead the setpoint is an
error naming the signal).
"""

from __future__ import annotations

import dataclasses
import os
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from vcnc.core.axes import AXIS_NAMES
from vcnc.core.capture import Capture
from vcnc.core.errors import CaptureError
from vcnc.traces.lag import subtract_following_error

__all__ = ["read_sinumerik", "MAGIC", "MAGICS", "measurement_reason"]

#: Root element that identifies the format (read by content).
MAGIC = "<traceSession"
#: The root elements of SINUMERIK trace files (``<traceDataRoot>`` in older versions, as the
#: open-source viewer ``hailongchenn/sinumerik-trace-viewer`` reads them).
MAGICS = (MAGIC, "<traceDataRoot")

#: An attribute of every element of SINUMERIK Operate's measuring-function and auto-servo-tuning files
#: (``<ResponseTestCustom satclassid="174" ver="4.7.6.0.3">``, Trace-Tools' ``demo/freq_trace.XML``; its
#: ``tuning_files.py`` reads them).
SAT_CLASS = "satclassid="


def measurement_reason(root: str, head: str) -> str | None:
    """Why a SINUMERIK Operate measurement (a control loop's frequency or step response, from Setup/Optimize) or an
    auto servo tuning result is no trace, when ``head`` (the file's first bytes) is one: its root element ``root``
    carries ``satclassid`` (Trace-Tools' readme: trace files come from the Diagnostics menu, measurements and
    auto-tuning results from Setup/Optimize); else None."""
    m = re.search(r"<" + re.escape(root) + r"\b[^>]*>", head)
    if m is None or SAT_CLASS not in m.group(0):
        return None
    return (f"a SINUMERIK Operate measurement or auto servo tuning file (root <{root}>): a control loop's frequency or "
            "step response under its excitation, no commanded and measured position of a move; record the axis with "
            "SINUMERIK Operate's trace (Diagnostics > Trace) and save that as XML")


#: Values above this are the control's "no value" marker (about 2**63, as Trace-Tools reads them).
NO_VALUE = 9.2e18

#: Most samples a capture is built with (a bad time stamp must not allocate without bound).
MAX_SAMPLES = 1e8

#: How the following error is signed (module docstring).
LAG_CONVENTION = "setpoint - actual position (the reader's reading since issue #17)"

_AXIS_NUMBER = re.compile(r"\[\s*u\d+\s*,\s*(\d+)\s*\]")


@dataclasses.dataclass
class _Signal:
    """One ``dataSignal`` and its change-only samples."""

    id: str
    name: str
    description: str
    interval: float
    axis_number: int | None
    times: list[float] = dataclasses.field(default_factory=list)
    values: list[float] = dataclasses.field(default_factory=list)
    decimals: int = 0  # most digits after the decimal point in the values as printed

    @property
    def label(self) -> str:
        return f"{self.name} ({self.description})" if self.description else self.name

    def role(self) -> str | None:
        """``"setpoint"``, ``"following_error"``, ``"measured1"``, ``"measured2"`` or None."""
        text = f"{self.name} {self.description}".lower()
        if "cmdpos" in text or "position setpoint" in text:
            return "setpoint"
        if "following error" in text or "follerr" in text or "contdev" in text:
            return "following_error"
        if "measpos1" in text or "measuring system 1" in text:
            return "measured1"
        if "measpos2" in text or "measuring system 2" in text:
            return "measured2"
        return None

    def on_grid(self, grid: np.ndarray, src: str) -> np.ndarray:
        """The held value at each grid time [s] (last change at or before it)."""
        if not self.times:
            raise CaptureError(f"signal {self.label!r} has no values", file=src)
        t = np.asarray(self.times)
        k = np.searchsorted(t, grid + 1e-9 * max(self.interval, 1e-6), side="right") - 1
        if k[0] < 0:
            raise CaptureError(f"signal {self.label!r} has no value at t = {grid[0]:.6g} s", file=src)
        return np.asarray(self.values)[k]


def read_sinumerik(path: str | os.PathLike[str], *, axes: tuple[str, ...] | None = None) -> Capture:
    """Read a SINUMERIK trace XML into a capture.

    Parameters
    ----------
    path : path-like
        The trace export.
    axes : tuple of str, optional
        Names of the traced machine axes in the order of their numbers ``[u1, N]``; default x, y, z...

    Returns
    -------
    Capture
        Time [s] from the first grid point, commanded and measured position [mm]; ``meta`` records
        the format, the axis numbers, the signals used and how the measured position was formed.

    Raises
    ------
    CaptureError
        Not a trace XML, a ``rec`` row before the signals or with an unknown signal, time going
        backwards, or no commanded/measured pair (naming the signals found).
    """
    src = str(Path(path))
    signals, end = _parse(src)
    found = [s.label for s in signals.values()]
    by_axis: dict[int | None, dict[str, _Signal]] = {}
    for s in signals.values():
        role = s.role()
        if role is not None:
            by_axis.setdefault(s.axis_number, {}).setdefault(role, s)
    pairs = {n: _pair(roles) for n, roles in by_axis.items()}
    pairs = {n: p for n, p in pairs.items() if p is not None}
    if not pairs:
        raise CaptureError(f"no position setpoint with a following error or measured position; signals found: {found}",
                           file=src)
    numbers = sorted(pairs, key=lambda n: -1 if n is None else n)
    names = tuple(axes) if axes else AXIS_NAMES[: len(numbers)]
    if len(names) != len(numbers):
        raise CaptureError(f"{len(names)} axis name(s) {list(names)} given for the {len(numbers)} traced axes "
                           f"{numbers}", file=src)
    used = [s for p in pairs.values() for s in p[1:]]
    empty = [s.label for s in used if not s.times]
    if empty:
        raise CaptureError(f"signal(s) {empty} hold no value", file=src)
    coarse = max(used, key=lambda s: s.interval)
    interval = coarse.interval
    # on the coarse signal's own sampling instants, from the first time every signal has a value
    late = max(s.times[0] for s in used) - coarse.times[0]
    start = coarse.times[0] + interval * np.ceil(late / interval - 1e-6)
    with np.errstate(over="ignore", invalid="ignore"):  # a corrupted time: inf or nan, refused just below
        span = (end - start) / interval
    if not span < MAX_SAMPLES:
        raise CaptureError(f"the rows span {end - start:.6g} s at {interval:.6g} s: more than "
                           f"{MAX_SAMPLES:.0e} samples", file=src)
    n = int(np.floor(span + 1e-6)) + 1
    if n < 2:
        raise CaptureError(f"fewer than two common samples of the signals used; signals found: {found}", file=src)
    grid = start + interval * np.arange(n)
    ref, meas, how = [], [], []
    for number in numbers:
        kind, setpoint, other = pairs[number]
        r = setpoint.on_grid(grid, src)
        found = ""
        if kind == "setpoint - following error":
            m, lags = subtract_following_error(r, other.on_grid(grid, src), interval, channel=other.label, src=src,
                                               expected=LAG_CONVENTION)
            # the difference of two decimals is a decimal of as many digits: printed as it is exactly
            digits = max(setpoint.decimals, other.decimals)
            m = np.array([float(f"{v:.{digits}f}") for v in m])
            found = f", {lags}"
        else:
            m = other.on_grid(grid, src)
        ref.append(r)
        meas.append(m)
        how.append(f"axis {number}: commanded {setpoint.name}, measured {kind} ({other.name}{found})")
    meta = {"format": "SINUMERIK trace XML", "sample_time_s": f"{interval:.9g}",
            "axis_numbers": ",".join(f"{a}:{'?' if n is None else n}" for a, n in zip(names, numbers)),
            "signals": "; ".join(how)}
    return Capture(t=np.round(grid - grid[0], 12), axes=names, reference=np.column_stack(ref),
                   measured=np.column_stack(meas), meta=meta, source=src)


def _pair(roles: dict[str, _Signal]) -> tuple[str, _Signal, _Signal] | None:
    """``(how, setpoint, other)``: the setpoint and the signal that gives the measured position."""
    sp = roles.get("setpoint")
    if sp is None:
        return None
    fe = roles.get("following_error")
    if fe is not None and abs(fe.interval - sp.interval) <= 1e-9:
        return "setpoint - following error", sp, fe
    for key, how in (("measured1", "measuring system 1"), ("measured2", "measuring system 2")):
        if key in roles:
            return how, sp, roles[key]
    if fe is not None:
        return "setpoint - following error", sp, fe
    return None


def _parse(src: str) -> tuple[dict[str, _Signal], float]:
    """The signals of the file with their change-only samples, and the time of the last row [s]."""
    signals: dict[str, _Signal] = {}
    described: dict[str, ET.Element] = {}  # the setup's <signal key=...>, naming a bare <dataSignal>
    last_time = -np.inf
    rows = 0
    try:
        for _, el in ET.iterparse(src, events=("end",)):
            tag = el.tag.rpartition("}")[2]
            if tag == "signal" and el.get("key"):
                described.setdefault(el.get("key"), el)
            elif tag == "dataSignal":
                s = _signal(el, described.get(el.get("key", "")), src)
                signals[s.id] = s
            elif tag == "frameHeader":
                _drop_outs(el, src)
            elif tag == "rec":
                rows += 1
                last_time = _record(el, signals, last_time, rows, src)
                el.clear()
    except ET.ParseError as exc:
        line, col = exc.position
        raise CaptureError(f"not well-formed XML ({exc.msg})", file=src, line=line, column=col + 1) from None
    except CaptureError:
        raise
    except (LookupError, ValueError) as exc:  # an unknown encoding in the XML declaration, bytes not in it
        raise CaptureError(f"cannot decode the XML ({exc})", file=src, line=1) from None
    if not signals:
        raise CaptureError(f"no <dataSignal> elements; expected a SINUMERIK trace (root {MAGIC[1:]})", file=src)
    return signals, last_time


def _drop_outs(el: ET.Element, src: str) -> None:
    """CaptureError when the ``<frameHeader>`` counts records the control lost (``dropOuts``):
    with change-only rows a lost record cannot be told from an unchanged value."""
    text = el.get("dropOuts", "0").strip()
    if text not in ("", "0"):
        raise CaptureError(f"the trace lost records (<frameHeader dropOuts={text!r}>): with change-only rows the "
                           "values across them are unknown; trace again with fewer signals or a shorter time",
                           file=src)


def _signal(el: ET.Element, setup: ET.Element | None, src: str) -> _Signal:
    """A ``<dataSignal>``; its name and description from the setup's ``<signal>`` of the same key
    when it has none itself."""
    sid = el.get("id")
    name = el.get("name") or (setup.get("name", "") if setup is not None else "")
    description = el.get("description") or (setup.get("description", "") if setup is not None else "")
    try:
        interval = float(el.get("interval", "nan"))
    except ValueError:
        interval = float("nan")
    if not sid or not 0 < interval < np.inf:
        raise CaptureError(f"<dataSignal name={name!r}> needs an id and an interval > 0 [s] "
                           f"(got id={sid!r}, interval={el.get('interval')!r})", file=src)
    m = _AXIS_NUMBER.search(name)
    return _Signal(id=sid, name=name, description=description, interval=interval,
                   axis_number=int(m.group(1)) if m else None)


def _record(el: ET.Element, signals: dict[str, _Signal], last_time: float, row: int, src: str) -> float:
    """Append the values of one ``rec`` row; returns its time [s]."""
    where = f"<rec> number {row}"
    try:
        t = float(el.get("time", "nan"))
    except ValueError:
        t = float("nan")
    if not np.isfinite(t):
        raise CaptureError(f"{where}: time {el.get('time')!r} is not a number", file=src)
    if t <= last_time:
        raise CaptureError(f"{where}: time goes backwards ({t!r} s after {last_time!r} s)", file=src)
    for key, text in el.attrib.items():
        if key == "time":
            continue
        s = signals.get(key)
        if s is None:
            raise CaptureError(f"{where}: attribute {key!r} names no <dataSignal>; signals: {sorted(signals)}",
                               file=src)
        try:
            v = float(text)
        except ValueError:
            raise CaptureError(f"{where}: {key}={text!r} is not a number", file=src) from None
        if abs(v) < NO_VALUE and np.isfinite(v):
            s.times.append(t)
            s.values.append(v)
            mantissa, dot, digits = text.strip().lower().partition("e")[0].partition(".")
            s.decimals = max(s.decimals, len(digits) if dot else 0)
    return t
