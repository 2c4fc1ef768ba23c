"""A record that moves one way only (a weld seam, a one-way feed test): the loop is identified, only the Coulomb level
of the direction never travelled is not (realfit35; a KUKA RSI weld log's y and z axes were refused whole before)."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest

from identification.capture_checks import travelled_direction
from identification.identify import fit_reduced_model
from identification.poles import denominator
from identification.synthetic import FADAL_PID_X, random_moves_reference, synthetic_capture
from vcnc.core.capture import Capture
from vcnc.core.errors import IdentificationError

#: A PI loop without overshoot (omega_n 30 Hz, zeta 1.0, p 2 Hz; the friction levels of the thesis' PID x axis,
#: Table 3.4 'Actual'): the thesis' own loop (zeta 0.45) moves back at every stop, 237 samples of a one-way reference,
#: which is two-way motion for its friction (its d1 is then identified, -303 for -302).
LOOP = dict(zip(("a1", "a2", "a3"), denominator(2 * math.pi * 2.0, 2 * math.pi * 30.0, 1.0), strict=True)) | {
    "b0": 0.0, "b1": 0.0, "d0": FADAL_PID_X["d0"], "d1": FADAL_PID_X["d1"]}
LOOP["b2"] = LOOP["a2"]


def _one_way(sign: float) -> Capture:
    """:data:`LOOP` on 40 moves all the same way (the random moves' distances, each travelled forwards, ``sign`` +1,
    or backwards, -1), recorded with a 1 um encoder, cut at its last stop (after it the model, its friction gone at
    rest, creeps back 91 samples by the integrator's hold-up)."""
    xr = random_moves_reference(moves=40, seed=5)
    one_way = xr[0] + sign * np.concatenate(([0.0], np.cumsum(np.abs(np.diff(xr)))))
    return synthetic_capture(LOOP, one_way, resolution=1e-3, seed=3).slice(0, 4600)


@pytest.mark.parametrize(("sign", "known", "unknown"), [(1.0, "d0", "d1"), (-1.0, "d1", "d0")])
def test_a_one_way_record_is_identified_with_the_other_level_mirrored(sign, known, unknown, tmp_path):
    cap = _one_way(sign)
    m = fit_reduced_model(cap)
    true = LOOP
    assert m.parameters["a2"] == pytest.approx(true["a2"], rel=0.05)
    assert m.parameters["a3"] == pytest.approx(true["a3"], rel=0.1)
    assert m.parameters[known] == pytest.approx(true[known], rel=0.1)  # the travelled direction's level
    assert m.parameters[unknown] == -m.parameters[known]
    assert m.fit["rms_um"] < 2.0
    rec = m.fit["friction"]
    direction = "positive" if sign > 0 else "negative"
    assert rec["travelled"] == direction and rec["identified"] == known and rec["assumed"] == {unknown: f"-{known}"}
    assert f"({unknown}) is unknown" in rec["statement"] and f"{unknown} = -{known}" in rec["statement"]
    m.to_json(tmp_path / "m.json")
    assert json.loads((tmp_path / "m.json").read_text())["fit"]["friction"] == rec


def test_a_record_that_barely_moves_either_way_is_still_refused():
    v = np.zeros(2000)
    v[100:110], v[500:505] = 1.0, -1.0  # 10 samples forwards, 5 back: neither direction travelled
    with pytest.raises(IdentificationError, match=r"too little motion to identify on axis 'x': 10 samples with "
                                                  r"positive and 5 with negative measured velocity"):
        travelled_direction(np.cumsum(v), 1e-3, "x")
    assert travelled_direction(np.cumsum(np.abs(np.sin(np.arange(2000) * 0.01))), 1e-3, "x") == "positive"


def test_the_diagnosis_of_a_one_way_record_divides_by_no_zero_column():
    # its regressor's -NV column is zero: the equation-error base of the searches scaled it by its norm, 0 (NaN, and
    # LAPACK's "DLASCL parameter number 4 had an illegal value" on stderr for each search)
    from identification import identify

    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        m = identify(_one_way(1.0))
    assert m.fit["friction"]["travelled"] == "positive" and m.validation
