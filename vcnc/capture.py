"""Reading captures in any supported format, detected by content: the capture CSV, control trace
exports and the EMPS benchmark ``.mat`` files (:mod:`vcnc.traces`).

The :class:`Capture` type and the CSV contract live in :mod:`vcnc.core.capture`; they are
re-exported here, where the public API has always had them.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence

from vcnc.core.capture import OPTIONAL_SUFFIXES, Capture, check_sampling
from vcnc.traces import read_trace

__all__ = ["Capture", "read_capture", "check_sampling", "OPTIONAL_SUFFIXES"]


def read_capture(path: str | os.PathLike[str], *, columns: Mapping[str, str] | None = None,
                 time_unit: str | None = None, unit: str | None = None,
                 axes: Sequence[str] | None = None, resample: bool = False,
                 sample_time: float | None = None) -> Capture:
    """Read a capture: the CSV of ARCHITECTURE.md, a control's trace export or an EMPS ``.mat``
    file, detected by content (:func:`vcnc.traces.read_trace`, which documents the options).

    Raises
    ------
    CaptureError
        Naming the file, line (or element) and column at fault, and the channels found.
    """
    return read_trace(path, columns=columns, time_unit=time_unit, unit=unit, axes=axes, resample=resample,
                      sample_time=sample_time)
