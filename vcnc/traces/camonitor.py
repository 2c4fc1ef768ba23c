"""EPICS ``camonitor`` logs: one channel update per line, as EPICS motion users (the ecmc EtherCAT motion
controller's ``Axis1-PosSet`` / ``Axis1-PosAct`` / ``Axis1-PosErr`` records) record an axis.

Each line is ``<PV name> <date> <time> <value>`` with an optional alarm status and severity after the
value (EPICS Base, Channel Access reference manual, "camonitor": "the PV name, the time stamp and the
value"), e.g. ``IOC:Axis1-PosAct 2020-12-09 15:05:40.306118 19.49976563``. A monitor reports a channel
when it changes, so the channels are held at their last value (sample and hold) on the union of the
time stamps of the channels used, from the first time stamp at which every one has a value; those
time stamps come from the IOC's clock and are not uniform, so the capture needs ``--resample``
(:func:`vcnc.traces.columns.on_uniform_grid`), without which the timing error says so.

Which channel is what is read from the PV names (:func:`vcnc.traces.names.columns_from_names`: ``PosSet``
the commanded, ``PosAct`` the measured position, a following error ``PosErr``; the record names after the last
``:`` first, the whole names where those read nothing or name the axis too: :func:`_channels_from_records`) or given as
``columns={"x_ref": PV, "x": PV}``. Our reading of the documented output, tracewild2 (a real ecmc log).
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from vcnc.core.capture import Capture
from vcnc.core.errors import CaptureError
from vcnc.traces.columns import (
    LAG_SUFFIX,
    assumed_unit,
    axis_of,
    mapped_axes,
    mapping_meta,
    on_uniform_grid,
    parse_number,
    parse_time_stamp,
    position_scale,
    read_text,
    with_following_errors,
)
from vcnc.traces.names import channels_from_names, mapping_note

__all__ = ["read_camonitor", "looks_like_camonitor"]

_LINE = re.compile(r"^\s*(?P<pv>\S+)\s+(?P<stamp>\d{4}-\d{2}-\d{2}\s+\d{1,2}:\d{2}:\d{2}(?:\.\d+)?)\s+"
                   r"(?P<value>\S+)(?:\s+\S+){0,2}\s*$")
#: The following error of ecmc (and of the EPICS motor record) is setpoint - actual position.
LAG_CONVENTION = "setpoint - actual position (ecmc's PosErr)"


def looks_like_camonitor(text: str) -> bool:
    """True when the first ten non-blank lines are camonitor lines (module docstring)."""
    lines = [s for s in text.splitlines() if s.strip()][:10]
    return len(lines) >= 2 and all(_LINE.match(s) for s in lines)


def _channels_from_records(pvs: list[str]) -> tuple[dict[str, str] | None, str]:
    """:func:`vcnc.traces.names.channels_from_names` of the PVs' record names, the part after the last ``:``
    (``X-PosCmd`` of ``TARGET_DU:X-PosCmd``), mapped back to the PVs; of the whole names when that reads nothing
    (the records' reason), or when the whole names map the same PVs in the same roles (an axis letter in the
    prefix, ``IOC:Z:PosSet``, is the axis). The prefix names the IOC or device (ESS's ``TARGET_DU``, ``IOC_TEST``),
    whose words (a "target") say nothing of the signal: our reading of the ecmc logs seen (tracewild4)."""
    records = [pv.rsplit(":", 1)[-1] for pv in pvs]
    if len(set(records)) < len(records):
        return channels_from_names(pvs, "PV")
    named, why = channels_from_names(records, "PV")
    whole, _ = channels_from_names(pvs, "PV")
    if named is not None:
        mapped = {k: pvs[records.index(v)] for k, v in named.items()}
        same = whole is not None and {(k[1:], v) for k, v in whole.items()} == {(k[1:], v) for k, v in mapped.items()}
        return (whole if same else mapped), ""
    return (whole, "") if whole is not None else (None, f"by their record names {records}: {why}")


def read_camonitor(path: str | os.PathLike[str], *, columns: Mapping[str, str] | None = None,
                   unit: str | None = None, resample: bool = False) -> Capture:
    """Read a camonitor log (module docstring) into a capture.

    Raises
    ------
    CaptureError
        A line that is not a camonitor line, a value that is not a number of a PV the mapping uses (naming the
        line; another PV's words, a binary input's ``One``/``Zero``, stay unread: tracewild8), a PV of the
        mapping not found, channels whose names leave the mapping in doubt, non-uniform time
        stamps without ``resample``.
    """
    src = str(Path(path))
    updates: dict[str, list[tuple[float, float, int]]] = {}
    texts: dict[str, tuple[int, str]] = {}  # a PV's first value that is no number ('One' of a binary input)
    seen: dict[str, None] = {}
    for i, line in enumerate(read_text(path, src).splitlines(), start=1):
        if not line.strip():
            continue
        m = _LINE.match(line)
        if not m:
            raise CaptureError("not a camonitor line (PV name, date, time, value)", file=src, line=i,
                               text=line.strip()[:80])
        seen.setdefault(m["pv"])
        try:
            value = parse_number(m["value"])
        except ValueError:
            texts.setdefault(m["pv"], (i, m["value"]))
            continue
        updates.setdefault(m["pv"], []).append((parse_time_stamp(" ".join(m["stamp"].split())), value, i))
    found = list(seen)
    if columns:
        mapping = {k: v for k, v in columns.items() if k != "t"}
    else:
        named, why = _channels_from_records(found)
        if named is None:
            raise CaptureError("which PVs are the commanded and measured positions? give --columns x_ref=PV,x=PV; "
                               f"PVs found: {found} (not read from the names: {why})", file=src)
        mapping = named
    axes = mapped_axes(mapping, src)
    for pv in mapping.values():
        if pv in texts:
            raise CaptureError(f"the value of {pv} is not a number", file=src, line=texts[pv][0], text=texts[pv][1])
    missing = [v for v in mapping.values() if v not in updates]
    if missing:
        raise CaptureError(f"PV(s) {missing} not found; PVs found: {found}", file=src)
    series = {k: np.array(updates[v], dtype=float) for k, v in mapping.items()}
    start = max(s[0, 0] for s in series.values())
    stamps = np.unique(np.concatenate([s[:, 0] for s in series.values()]))
    stamps = stamps[stamps >= start]
    if stamps.size < 2:
        raise CaptureError(f"PVs {list(mapping.values())} have fewer than two time stamps in common", file=src)

    def held(k: str) -> np.ndarray:  # each PV's last value at every time stamp (a monitor reports changes)
        s = series[k][np.argsort(series[k][:, 0], kind="stable")]
        return s[np.searchsorted(s[:, 0], stamps, side="right") - 1, 1] * position_scale([axis_of(k)], unit, src)

    t, (ref, second), how = on_uniform_grid(
        np.round(stamps - stamps[0], 6), [np.column_stack([held(f"{a}_ref") for a in axes]),
                                          np.column_stack([held(a if a in mapping else a + LAG_SUFFIX)
                                                           for a in axes])], src, resample=resample)
    meas, lag = with_following_errors(axes, mapping, ref, second, float(t[1] - t[0]), src, expected=LAG_CONVENTION)
    meta = {"format": "EPICS camonitor log", "time_unit": "time stamps (sample and hold per PV)",
            "unit": unit or ",".join(sorted({assumed_unit(a) for a in axes})), **mapping_meta(axes, mapping), **lag,
            **how}
    if not columns:
        meta["columns"] = mapping_note("PV", mapping)
    return Capture(t=t, axes=tuple(axes), reference=ref, measured=meas, meta=meta, source=src)
