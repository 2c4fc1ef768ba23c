"""Review of session 26's trace readers: defects found by hand, each with the file that showed it."""

from __future__ import annotations

import numpy as np

from vcnc.traces.camonitor import read_camonitor


def _log(path, pvs: tuple[str, str]) -> None:
    lines = []
    for i in range(40):
        stamp = f"2020-12-09 15:05:{40 + 0.01 * i:09.6f}"
        lines += [f"{pvs[0]} {stamp} {0.1 * i:.4f}", f"{pvs[1]} {stamp} {0.1 * i - 0.01:.4f}"]
    path.write_text("\n".join(lines) + "\n")


def test_camonitor_axis_letter_in_the_pv_prefix_is_the_axis(tmp_path):
    # IOC:Z:PosSet / IOC:Z:PosAct: the records PosSet / PosAct name no axis, the whole names do (Z); the record names
    # alone made it axis x
    f = tmp_path / "z.log"
    _log(f, ("IOC:Z:PosSet", "IOC:Z:PosAct"))
    cap = read_camonitor(f, resample=True)
    assert cap.axes == ("z",)
    assert cap.meta["columns"] == "from the PV names: z_ref=IOC:Z:PosSet, z=IOC:Z:PosAct"
    np.testing.assert_allclose(cap.reference[[0, -1], 0], [0.0, 3.9], atol=1e-9)
