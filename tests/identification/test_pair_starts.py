"""The output-error refinement started across the pair's frequency when the equation error does not pin the poles
(:mod:`identification.pair_starts`), and what ``vcnc identify`` says when distinct poles predict alike."""

from __future__ import annotations

import pytest

from benchmarks.gcode_corpus import corpus_dir
from identification import load_model
from identification.pair_starts import pole_magnitudes_hz
from identification.reduced_model import ReducedAxisModel
from identification.synthetic import FADAL_PID_X
from vcnc.cli import main
from vcnc.commands.identify import pair_pinned_line

CORPUS = corpus_dir()


@pytest.mark.skipif(CORPUS is None, reason="gcode corpus absent (../shared/data/gcode-corpus)")
def test_fadal_ppi_on_15_s_of_a_cam_program_is_refined_near_the_truth_or_said_not_pinned(tmp_path, capsys):
    """fadal-ppi (P-PI, no feedforward: p 4.68 Hz, a pair at 36.3 Hz / 0.753, ``vcnc machines --show fadal-ppi``)
    running the first 15 s of corpus program 0136 (15,001 samples at 1 ms): the equation error's valley spans
    omega_n 9.2-80 Hz, and the refinement from its solution ended at omega_n 5.97 Hz / 1.03 with p on 146 Hz,
    3.32 um RMS (identfit34, before the starts); started across the pair's frequency it ended at 39.2 Hz / 0.71,
    p 4.62 Hz, 0.292 um. The cost over the pair frequency is rough: which basin a refinement ends in moves with the
    platform's rounding and 1e-9 mm changes of the capture (session 34: the pair restart alone ended at 65.2 Hz /
    0.999, 0.337 um, on the merged main, where the starts, then gated on zeta >= 1, did not run). What must hold on any
    platform: p and the prediction are right, and the pair is near the truth or the poles are said not to be
    trusted."""
    csv, js = tmp_path / "c.csv", tmp_path / "m.json"
    assert main(["simulate", str(CORPUS / "0136_1003.nc"), "--machine", "fadal-ppi+z", "--max-seconds", "15",
                 "-o", str(csv)]) == 0
    capsys.readouterr()
    assert main(["identify", str(csv), "--axis", "x", "--no-diagnose", "--json", str(js)]) == 0
    out = capsys.readouterr().out
    m = load_model(js)
    assert abs(m.poles["p_hz"] - 4.68) < 0.02 * 4.68
    assert m.fit["rms_um"] < 0.5
    near = abs(m.poles["omega_n_hz"] - 36.3) < 0.15 * 36.3 and abs(m.poles["zeta"] - 0.753) < 0.1
    rec = m.fit["output_error"]["pair_starts"]  # the valley does not pin the pair: the starts run, whatever zeta
    assert len(rec["omega_n_hz"]) == 8 and rec["window"] == 15_001  # each refined on the whole record
    assert rec["fits"][rec["kept"]][3] == min(f[3] for f in rec["fits"])
    warned = "not pinned" in out or "trust the model's prediction" in out
    assert near or warned, (m.poles, out)


def _model(poles: dict, fit: dict) -> ReducedAxisModel:
    return ReducedAxisModel(parameters=FADAL_PID_X, sample_time=1e-3, axis="x", poles=poles, fit=fit,
                            bounds={"p_hz": (0.2, 500.0), "omega_n_hz": (0.2, 500.0), "zeta": (0.2, 2.0)})


def test_pole_magnitudes_of_a_complex_and_a_real_pair():
    assert pole_magnitudes_hz({"omega_n_hz": 36.0, "zeta": 0.7, "p_hz": 4.6}) == [4.6, 36.0, 36.0]
    z = pole_magnitudes_hz({"omega_n_hz": 10.0, "zeta": 1.25, "p_hz": 500.0})  # roots 10 (1.25 -+ 0.75)
    assert z == pytest.approx([5.0, 20.0, 500.0])


def test_pair_pinned_line_says_which_poles_predict_alike():
    """fadal-ppi on the first 8 s of corpus program 0136 (session 34): the best fit 33.4 Hz / 0.76, p 4.62 Hz at
    0.1999 um, the refinement from the equation error 57.6 Hz / 1.19 at 0.2072 um: distinct poles within 5 %."""
    fits = [[57.58, 1.1906, 4.617, 0.2072], [33.37, 0.7557, 4.621, 0.1999]]
    rec = {"omega_n_hz": [12.8, 184.0], "zeta": 0.7, "fits": fits, "kept": 1, "pinned": False,
           "tied": {"omega_n_hz": [33.37, 57.58], "zeta": [0.7557, 1.1906], "p_hz": [4.617, 4.621]}}
    line = pair_pinned_line(_model({"omega_n_hz": 33.37, "zeta": 0.7557, "p_hz": 4.621},
                                   {"output_error": {"pair_starts": rec}}))
    assert line == (
        "poles not pinned by this record: refined from 2 starts across the pair's frequency, fits with omega_n "
        "33.4-57.6 Hz, zeta 0.76-1.19, p 4.62-4.62 Hz predict within 5% of the best (0.1999 um RMS); the poles above "
        "are the best of them, not a measurement of the loop's: trust the prediction, not the poles")
    pinned = _model({"omega_n_hz": 33.37, "zeta": 0.7557, "p_hz": 4.621},
                    {"output_error": {"pair_starts": {**rec, "pinned": True}}})
    assert pair_pinned_line(pinned) is None
    assert pair_pinned_line(_model({"omega_n_hz": 33.37, "zeta": 0.7557, "p_hz": 4.621}, {})) is None
