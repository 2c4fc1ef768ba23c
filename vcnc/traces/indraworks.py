"""Rexroth IndraWorks oscilloscope data saved as XML: its signals as a table under their names.

IndraWorks' oscilloscope (IndraDrive) saves a recording as XML in the namespace
``http://www.boschrexroth.de/indraworks.textformatter.xsd``: ``root / OscilloscopeData / Devices / Device /
Measurements / Measurement / Signals / Signal``, each ``Signal`` with its ``Name`` (the parameter's IDN and name:
``S-0-0047.0.0 Position command value``, ``S-0-0051.0.0 Position feedback value 1``, ``S-0-0040.0.0 Velocity
feedback value``), its time stamps ``XValue`` and its values ``YValue``, each a list of numbers joined by ``|``. Our
reading of the layout a parser of real exports walks (a plant-data script reading these four signals by these
names); an element of a signal whose name ends in ``Unit`` (``XUnit``, ``YUnit``), where one is written, gives the
unit of its time stamps or of its values. The signals make a table, one column per signal beside one of the shared
time stamps, which :mod:`vcnc.traces.delimited` maps by the names as any table's (``S-0-0047`` Position command
value, the commanded position; ``S-0-0051``/``S-0-0053`` Position feedback value 1/2, the measured one; the SERCOS
IDNs, IEC 61800-7-204); a signal on other time stamps than the first one's is an error naming it. The time stamps'
unit is never assumed (the parser seen does not say it; the oscilloscope shows ms): without a unit element it is
given with ``--time-unit``.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import NamedTuple

import numpy as np

from vcnc.core.errors import CaptureError

__all__ = ["looks_like_oscilloscope", "OscilloscopeSignals", "read_oscilloscope_signals"]

#: The namespace of the export (module docstring).
NAMESPACE = "indraworks.textformatter"


def looks_like_oscilloscope(head: str) -> bool:
    """True for the first characters of an IndraWorks oscilloscope XML file (module docstring)."""
    return head.lstrip("\ufeff \t\r\n").startswith("<") and NAMESPACE in head and "OscilloscopeData" in head


class OscilloscopeSignals(NamedTuple):
    """The signals of an export as a table: names (with a unit in brackets where one is written) and values."""

    names: list[str]  #: the time column's name, then each signal's
    values: np.ndarray  #: samples x (1 + signals)


def _local(tag: str) -> str:
    return tag.rpartition("}")[2]


def _numbers(text: str | None, what: str, src: str) -> np.ndarray:
    try:
        return np.array([float(v) for v in (text or "").split("|") if v.strip()], dtype=float)
    except ValueError:
        raise CaptureError(f"{what} holds a value that is no number; expected numbers joined by '|'",
                           file=src) from None


def read_oscilloscope_signals(text: str, src: str) -> OscilloscopeSignals:
    """The signals of an IndraWorks oscilloscope XML export (module docstring).

    Raises
    ------
    CaptureError
        Not well-formed XML, no signal with time stamps and values, a signal whose time stamps and values differ in
        number, or whose time stamps are not the first signal's.
    """
    try:
        root = ET.fromstring(text.lstrip("\ufeff"))
    except ET.ParseError as exc:
        line, col = exc.position
        raise CaptureError(f"not well-formed XML ({exc.msg})", file=src, line=line, column=col + 1) from None
    names, columns, time, time_name = [], [], None, "Time"
    for sig in (e for e in root.iter() if _local(e.tag) == "Signal"):
        parts = {_local(c.tag): (c.text or "").strip() for c in sig}
        name = parts.get("Name") or f"signal {len(names) + 1}"
        if "XValue" not in parts or "YValue" not in parts:
            continue
        x = _numbers(parts["XValue"], f"the time stamps (XValue) of signal {name!r}", src)
        y = _numbers(parts["YValue"], f"the values (YValue) of signal {name!r}", src)
        if x.size != y.size:
            raise CaptureError(f"signal {name!r} has {x.size} time stamps and {y.size} values", file=src)
        units = {k[:-4]: v for k, v in parts.items() if k.endswith("Unit") and v}
        if time is None:
            time = x
            time_name += f" [{units['X']}]" if "X" in units else ""
        elif x.size != time.size or not np.allclose(x, time, rtol=0, atol=1e-9 * max(1.0, float(np.abs(time).max()))):
            raise CaptureError(f"signal {name!r} is sampled on other time stamps than {names[0]!r}; expected the "
                               "signals of one measurement, on one time base", file=src)
        names.append(name + (f" [{units['Y']}]" if "Y" in units else ""))
        columns.append(y)
    if time is None:
        raise CaptureError("an IndraWorks oscilloscope export without a Signal holding its time stamps (XValue) and "
                           "values (YValue)", file=src)
    return OscilloscopeSignals([time_name, *names], np.column_stack([time, *columns]))
