"""Readers for the axis traces CNC controls export, each producing a :class:`vcnc.core.capture.Capture`.

:func:`read_trace` detects the format by content, not by file name:

- the capture CSV of ARCHITECTURE.md (header ``t,<axis>_ref,<axis>,...``);
- Heidenhain TNCscope text export (:mod:`vcnc.traces.tncscope`);
- Siemens SINUMERIK trace XML (:mod:`vcnc.traces.sinumerik`);
- EPICS camonitor logs (:mod:`vcnc.traces.camonitor`);
- LinuxCNC halscope logs, Beckhoff TwinCAT Scope CSV exports and other delimited text (LinuxCNC
  halsampler output among it), with a column mapping (:mod:`vcnc.traces.delimited`);
- the EMPS benchmark's MATLAB files (:mod:`vcnc.traces.emps`);
- Rexroth IndraWorks oscilloscope XML, read as a table of its signals (:mod:`vcnc.traces.indraworks`);
- DIAdem DAT headers, read with the binary files beside them (KUKA.Trace of a KR C4 among their writers,
  :mod:`vcnc.traces.diadem`), as delimited text under the channels' names.

MTConnect data (an agent's streams XML, an adapter's SHDR lines) is recognised and refused, naming the positions it
holds (:mod:`vcnc.traces.mtconnect`); so is a sender's log of Grbl's status reports (:mod:`vcnc.traces.grbl`).
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

from vcnc.core.axes import ROTARY_AXES
from vcnc.core.capture import UNIT_GIVEN, Capture, read_capture_csv
from vcnc.core.errors import CaptureError
from vcnc.traces import emps, grbl, indraworks, klipper, mtconnect, sinumerik, tncscope, twincat
from vcnc.traces.columns import read_text, within_reach
from vcnc.traces.delimited import (
    looks_like_camonitor,
    looks_like_halscope,
    looks_like_twincat,
    parse_columns,
    read_delimited,
)
from vcnc.traces.emps import read_emps_mat
from vcnc.traces.names import columns_from_names
from vcnc.traces.sinumerik import read_sinumerik
from vcnc.traces.tncscope import read_tncscope

__all__ = ["read_trace", "trace_format", "read_tncscope", "read_sinumerik", "read_delimited", "read_emps_mat",
           "parse_columns"]


def trace_format(path: str | os.PathLike[str]) -> str:
    """The format of a trace file, from its first bytes: ``"emps-mat"``, ``"tncscope"``,
    ``"sinumerik"``, ``"halscope"``, ``"twincat"``, ``"camonitor"``, ``"indraworks"``, ``"capture-csv"``,
    ``"delimited"``, or
    ``"xml"`` for other XML, ``"shdr"`` for an MTConnect adapter's stream and ``"grbl"`` for a log of Grbl's status
    reports and ``"klipper"`` for Klipper's klippy.log (which no reader takes)."""
    src = str(path)
    try:
        with Path(path).open("rb") as f:
            head = f.read(20000)
    except OSError as exc:
        raise CaptureError(f"cannot read the file ({exc.strerror})", file=src) from None
    if head.startswith(emps.MAGIC):
        return "emps-mat"
    text = _head_text(head)
    if text.startswith(tncscope.MAGIC):
        return "tncscope"
    if any(m in text[:4096] for m in sinumerik.MAGICS):
        return "sinumerik"
    if grbl.looks_like_status_log(text):
        return "grbl"
    if klipper.looks_like_klippy_log(text):
        return "klipper"
    if indraworks.looks_like_oscilloscope(text[:4000]):
        return "indraworks"
    if text.startswith("<"):
        return "xml"
    if looks_like_halscope(text):
        return "halscope"
    if looks_like_twincat(text):
        return "twincat"
    if looks_like_camonitor(text[:4000]):
        return "camonitor"
    if mtconnect.looks_like_shdr(text):
        return "shdr"
    for line in text.splitlines():
        s = line.strip().lstrip("\ufeff")
        if s and not s.startswith("#"):
            return "capture-csv" if s.split(",")[0].strip() == "t" else "delimited"
    return "delimited"


def _head_text(head: bytes) -> str:
    """The first bytes of a file as text for telling the format: UTF-16 after its byte-order
    mark, else Latin-1 (every byte a character); without a leading BOM or blanks."""
    if head.startswith((b"\xff\xfe", b"\xfe\xff")):
        text = head[: len(head) // 2 * 2].decode("utf-16", errors="replace")
    else:
        text = head.decode("latin-1").replace("\xef\xbb\xbf", "", 1)
    return text.lstrip("\ufeff \t\r\n")


def _xml_head(path: Path) -> str:
    """The first 20 kB of an XML file as text (:func:`_head_text`)."""
    with path.open("rb") as f:
        return _head_text(f.read(20000))


def _xml_root(head: str) -> str:
    """The name of the first element of an XML file's ``head`` ('?' when none is found in it)."""
    m = re.search(r"<([A-Za-z_][\w.:-]*)", re.sub(r"<\?.*?\?>|<!--.*?-->|<!DOCTYPE[^>]*>", "", head, flags=re.S))
    return m.group(1) if m else "?"


def _capture_csv(path: Path, *, axes: Sequence[str] | None, resample: bool) -> Capture:
    """vcnc's capture CSV (ARCHITECTURE.md); a header starting with ``t`` whose names are not the contract's
    (``t,X Commanded Position,...``, ``t,x_cmd,x_fb``) is another logger's, read by its names
    (:func:`vcnc.traces.names.columns_from_names`) when they leave no doubt, else the capture CSV's error at the
    header (tracefuzz: ``t`` is the commonest name of a time column). When the names are read but the logger's file
    is refused for another reason, that refusal is the one raised: ``# Resolution: 0.5 um`` above ``t,X Commanded
    Position,...`` asks whether the positions are counts, where the capture CSV's "unknown column" sent the user to
    map the columns the names had mapped (traces40, trace_fuzz seed 52000248)."""
    try:
        return read_capture_csv(path)
    except CaptureError as exc:
        lines = read_text(path, str(path)).splitlines()
        header = next((i for i, s in enumerate(lines, start=1) if s.strip() and not s.lstrip("\ufeff").startswith("#")),
                      None)
        if exc.line != header:
            raise
        try:
            return read_delimited(path, axes=axes, resample=resample)
        except CaptureError as other:
            names = [c.strip().strip('"') for c in lines[header - 1].lstrip("\ufeff").split(",")]
            mapped = columns_from_names(names)[0] or {}
            # a logger's names read (not the contract's own: t,x_ref,x,q keeps the capture CSV's unknown column)
            raise (other if any(k != v for k, v in mapped.items()) else exc) from None


def read_trace(path: str | os.PathLike[str], *, columns: Mapping[str, str] | None = None,
               time_unit: str | None = None, unit: str | None = None,
               axes: Sequence[str] | None = None, resample: bool = False,
               sample_time: float | None = None) -> Capture:
    """Read any supported trace (module docstring) into a capture.

    Parameters
    ----------
    path : path-like
        The trace file.
    columns : mapping, optional
        Capture column -> source column for delimited text (``{"t": "Time", "x_ref": "PosCmd",
        "x": "PosAct"}``; ``"x_lag": "Lag"`` for a following error instead of ``"x"``); given, the
        file is read as delimited text.
    time_unit, unit : str, optional
        Units of time (s, ms, us) and positions (mm, um, m, in, deg) in delimited text.
    axes : sequence of str, optional
        Names of the axes of a SINUMERIK trace (in axis-number order) or a halscope log (joint order).
    resample : bool
        TNCscope, TwinCAT and delimited text: interpolate time stamps that are not uniform
        (jitter, dropped samples) linearly onto the median step; without it they are an error.
    sample_time : float, optional
        Delimited text: the sampling period [s] of a file without a time column, or whose ``t``
        column counts samples (LinuxCNC ``halsampler``, :mod:`vcnc.traces.delimited`).

    Raises
    ------
    CaptureError
        Missing file, or a file its reader rejects (naming the file, the line or element, and the
        channels found).
    """
    p = Path(path)
    if not p.is_file():
        raise CaptureError("no such capture file", file=str(p))
    fmt = trace_format(p)
    delimited_options = columns is not None or time_unit is not None or unit is not None or sample_time is not None
    if fmt in ("emps-mat", "tncscope", "sinumerik") and delimited_options:
        raise CaptureError(f"--columns/--time-unit/--unit/--sample-time apply to delimited text, not to a {fmt} file",
                           file=str(p))
    if fmt == "shdr":
        raise CaptureError(mtconnect.shdr_reason(read_text(p, str(p))), file=str(p))
    if fmt == "grbl":
        raise CaptureError(grbl.status_reason(read_text(p, str(p))), file=str(p))
    if fmt == "klipper":
        raise CaptureError(klipper.klippy_reason(read_text(p, str(p))), file=str(p))
    if fmt == "xml":
        head = _xml_head(p)
        root = _xml_root(head)
        local = root.rpartition(":")[2]  # also with a prefix (m:MTConnectStreams)
        if local == "MTConnectStreams":
            raise CaptureError(mtconnect.streams_reason(read_text(p, str(p))), file=str(p))
        reason = mtconnect.document_reason(local)
        if reason is not None:
            raise CaptureError(reason, file=str(p))
        reason = sinumerik.measurement_reason(root, head) or twincat.scope_project_reason(root)
        if reason is not None:
            raise CaptureError(reason, file=str(p))
        raise CaptureError(f"an XML file with root <{root}>, not a SINUMERIK trace (<traceSession> or "
                           "<traceDataRoot>); export the trace from SINUMERIK Operate's trace, or give a text export",
                           file=str(p))
    if fmt == "emps-mat":
        cap = read_emps_mat(p)
    elif fmt == "tncscope":
        cap = read_tncscope(p, resample=resample)
    elif fmt == "sinumerik":
        cap = read_sinumerik(p, axes=tuple(axes) if axes else None)
    elif fmt == "capture-csv" and not delimited_options:
        cap = _capture_csv(p, axes=axes, resample=resample)
    else:
        cap = read_delimited(p, columns=columns, time_unit=time_unit, unit=unit, axes=axes, resample=resample,
                             sample_time=sample_time)
    # every reader's numbers, whatever its format: finite and within a machine's reach (the delimited reader
    # names the file's line; this names the sample)
    within_reach(cap.t, "time", "s", str(p))
    for name in ("reference", "measured"):
        values = getattr(cap, name)
        for j, axis in enumerate(cap.axes):
            within_reach(values[:, j], f"the {name} position of axis {axis}", "deg" if axis in ROTARY_AXES else "mm",
                         str(p))
    if unit is not None:  # a unit given is not second-guessed (vcnc.core.capture.UNIT_GIVEN)
        cap.meta[UNIT_GIVEN] = f"unit {unit} given"
    return cap
