"""The EMPS benchmark's ``.mat`` files (Janot et al., electro-mechanical positioning system; see
``../shared/data/emps/README``): ``qg`` reference and ``qm`` measured position [m, converted to
mm], ``vir`` control signal [V], ``t`` time [s]."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from vcnc.core.capture import Capture, check_sampling
from vcnc.core.errors import CaptureError

__all__ = ["read_emps_mat", "MAGIC"]

#: First bytes of a MATLAB 5 MAT-file (the EMPS files are version 5).
MAGIC = b"MATLAB 5.0 MAT-file"


def read_emps_mat(p: Path) -> Capture:
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
