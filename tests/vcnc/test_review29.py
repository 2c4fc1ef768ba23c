"""Review of session 29's trace readers: defects found by hand, each with the file that showed it."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture


def test_a_bracketed_time_stamp_above_a_header_is_no_matrix(tmp_path):
    # a logger's first line opening with a bracketed time stamp, its header's last name ending with a bracketed unit:
    # read as a MATLAB matrix from the one to the other, the header lost its ']' and with it the um of 'Ist'
    f = tmp_path / "log.csv"
    f.write_text("[2024-05-01 10:22:13] Messung 1\nZeit [ms];Soll [mm];Ist [um]\n"
                 + "".join(f"{k:.3f};{0.1 * k:.3f};{100 * k - 10:.3f}\n" for k in range(20)))
    cap = read_capture(f)
    assert cap.meta["measured"] == "x:Ist [um]"
    np.testing.assert_allclose(cap.measured[:3, 0], [-0.01, 0.09, 0.19], atol=1e-12)
    assert cap.t[1] == pytest.approx(1e-3)
