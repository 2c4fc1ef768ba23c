"""Traces in layouts of tracewild37 (session 37): drive tools' channel names and units not read before, and the
fuzzer's cases (``benchmarks/trace_fuzz.py``, seeds 41-43). Each file is a few lines written here after the layout,
not an export itself."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError

_SET = [0.0, 100.0, 300.0, 600.0, 900.0, 1100.0]
_ACT = [0.0, 40.0, 200.0, 480.0, 790.0, 1020.0]


def _table(path, names, *, sep=",", step=1.0):
    rows = [sep.join([f"{k * step:g}", f"{s:g}", f"{a:g}"]) for k, (s, a) in enumerate(zip(_SET, _ACT))]
    path.write_text("\n".join([sep.join(names), *rows]) + "\n", encoding="utf-8")
    return path


def test_acopos_user_units_are_counts_of_a_size_given(tmp_path):
    """B&R ACOPOS drives trace their position setpoint and actual position (ParIDs ``PCTRL_S_SET``,
    ``PCTRL_S_ACT``) in the axis' user ``Units``, whose size the axis' scaling sets: ``[Units]`` asks for ``--unit``
    with the size of one unit, as ``[LU]`` and ``[reference units]`` do (it said no column was a position)."""
    f = _table(tmp_path / "acopos.csv", ["Time [ms]", "PCTRL_S_SET [Units]", "PCTRL_S_ACT [Units]"])
    with pytest.raises(CaptureError, match=r"increments \('units'\).*--unit") as err:
        read_capture(f)
    assert str(f) in str(err.value)
    cap = read_capture(f, unit="0.01mm")
    assert cap.axes == ("x",)
    np.testing.assert_allclose(cap.reference[:, 0], np.array(_SET) * 0.01)
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_ACT) * 0.01)
