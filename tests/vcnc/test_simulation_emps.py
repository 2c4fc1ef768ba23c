"""The ``emps`` machine against the real EMPS measurement (Janot, Gautier, Brunot 2019).

Simulating the measured reference ``qg`` must reproduce the measured motor position ``qm``. The
benchmark authors' own simulator reaches a relative position error of 0.0138 % (description,
Sec. 3.5); vcnc measured 2.27 um RMS, 0.0015 % relative, on DATA_EMPS.mat.
"""

from __future__ import annotations

import numpy as np

import vcnc
from vcnc.engine.machine import load_machine
from vcnc.setpoints import Setpoints


def test_emps_reproduces_measured_position(emps_dir) -> None:
    cap = vcnc.read_capture(emps_dir / "DATA_EMPS.mat")
    m = load_machine("emps")
    sp = Setpoints.from_positions(cap.reference[:, 0], sample_time=m.sample_time)
    sim = m.simulate(sp)
    d = sim.measured[:, 0] - cap.measured[:, 0]
    rms_um = float(np.sqrt(np.mean(d**2)) * 1e3)
    rel = 100 * np.linalg.norm(d) / np.linalg.norm(cap.measured[:, 0])
    track_um = float(np.sqrt(np.mean((cap.reference[:, 0] - cap.measured[:, 0]) ** 2)) * 1e3)
    u_rms = float(np.sqrt(np.mean((sim.control[:, 0] - cap.control[:, 0]) ** 2)))
    print(f"\nEMPS: simulated vs measured qm: RMS {rms_um:.2f} um, relative {rel:.4f} % "
          f"(authors' simulator 0.0138 %); tracking error itself {track_um:.1f} um RMS; "
          f"control signal RMS difference {u_rms:.3f} V")
    assert rms_um < 2.5
    assert rel < 0.0138
    assert u_rms < 0.1

