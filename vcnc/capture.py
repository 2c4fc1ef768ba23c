"""Reading captures in any supported format: the capture CSV, the EMPS benchmark ``.mat`` files
(metres converted to mm) and the control trace exports of :mod:`vcnc.traces`, detected by content.

The :class:`Capture` type and the CSV contract live in :mod:`vcnc.core.capture`; they are
re-exported here, where the public API has always had them.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from vcnc.core.capture import OPTIONAL_SUFFIXES, Capture, check_sampling, read_capture_csv
from vcnc.core.errors import CaptureError

__all__ = ["Capture", "read_capture", "check_sampling", "OPTIONAL_SUFFIXES"]


def read_capture(path: str | os.PathLike[str]) -> Capture:
    """Read a capture CSV (contract of ARCHITECTURE.md) or an EMPS benchmark ``.mat`` file.

    Raises
    ------
    CaptureError
        Naming the file, line and column at fault: missing file, bad header, unknown column,
        non-numeric/NaN/inf value, non-increasing or non-uniform time, too few samples.
    """
    p = Path(path)
    if not p.is_file():
        raise CaptureError("no such capture file", file=str(p))
    if p.suffix.lower() == ".mat":
        return _read_emps_mat(p)
    with p.open("rb") as f:
        head = f.read(16)
    if head.startswith(b"%TNCscopeNT"):
        from vcnc.traces.tncscope import read_tncscope  # traces import this module; detected by content

        return read_tncscope(p)
    return read_capture_csv(p)


def _read_emps_mat(p: Path) -> Capture:
    """EMPS benchmark file: ``qg`` reference, ``qm`` measured (m -> mm), ``vir`` control (V)."""
    import scipy.io

    src = str(p)
    try:
        d = scipy.io.loadmat(src)
    except Exception as exc:  # scipy raises several types for a bad file
        raise CaptureError(f"cannot read MATLAB file ({exc})", file=src) from exc
    for key in ("t", "qg", "qm"):
        if key not in d:
            raise CaptureError(f"variable {key!r} missing; expected the EMPS variables t, qg, qm, vir", file=src)
    t = np.asarray(d["t"], dtype=float).ravel()
    qg = np.asarray(d["qg"], dtype=float).ravel() * 1000.0
    qm = np.asarray(d["qm"], dtype=float).ravel() * 1000.0
    for name, arr in (("t", t), ("qg", qg), ("qm", qm)):
        if not np.all(np.isfinite(arr)):
            raise CaptureError(f"variable {name!r} holds NaN or inf at index {int(np.argmin(np.isfinite(arr)))}",
                               file=src)
    check_sampling(t, src)
    vir = np.asarray(d["vir"], dtype=float).ravel()[:, None] if "vir" in d else None
    meta = {k: float(np.asarray(d[k]).ravel()[0]) for k in ("kp", "kv", "gtau") if k in d}
    meta["source_units"] = "m (converted to mm)"
    aux = {k: np.asarray(d[k], dtype=float).ravel() for k in ("pulses_N",) if k in d}
    return Capture(
        t=t - t[0],
        axes=("x",),
        reference=qg[:, None],
        measured=qm[:, None],
        control=vir,
        aux=aux,
        meta=meta,
        source=src,
    )
