"""Reference dead time ``delay_s`` (identification.dead_time) on captures of the project's virtual machines.

fadal-pid runs a random-moves program with 1 s of idle before and after the moves; the recorded
reference is then shifted with ``delay_reference(ref, -D)`` so that it leads the loop by D, as a
trace sampled elsewhere in the interpolation chain does. The estimate includes the sampled loop's
own lag (about 1.1-1.3 samples at 1 ms, measured by the lead on fadal-pid), so it lies in
[D, D + 2 samples]. The noise floor is the fit of the unshifted capture.
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

import toolpaths
import vcnc
from identification import ReducedAxisModel, identify, load_model
from identification.dead_time import MIN_DELAY_SAMPLES, delay_reference
from vcnc.capture import Capture
from vcnc.cli import main
from vcnc.commands.identify import delay_lines
from vcnc.errors import ModelFileError


@pytest.fixture(scope="module")
def machine():
    return vcnc.machine("fadal-pid")


@pytest.fixture(scope="module")
def setpoints(machine):
    lines = toolpaths.random_moves(20, 10.0, 12000.0, seed=1).splitlines()
    # 1 s of idle before and after the moves (lines[-1] is M30)
    program = "\n".join(lines[:2] + ["G04 P1"] + lines[2:-1] + ["G04 P1", lines[-1]]) + "\n"
    return vcnc.interpolate(vcnc.parse_program(program), machine)


def _capture(cap: Capture, delay_s: float, step: int) -> Capture:
    """``cap`` decimated by ``step``, its reference leading the loop by ``delay_s`` [s]."""
    T = cap.sample_time * step
    ref = delay_reference(cap.reference[::step, 0], -delay_s / T)
    x = cap.measured[::step, 0]
    return Capture(t=cap.t[::step], axes=("x",), reference=ref[:, None], measured=x[:, None],
                   meta={"source": f"fadal-pid, reference leading by {delay_s} s"})


@pytest.fixture(scope="module")
def capture(machine, setpoints) -> Capture:
    return machine.simulate(setpoints, seed=1)


@pytest.mark.parametrize(("delay_s", "step"), [(0.1, 3), (-0.05, 1)])
def test_reference_shift_is_estimated_and_predicts_at_the_noise_floor(capture, delay_s, step):
    floor = identify(_capture(capture, 0.0, step), axis="x", diagnose=False)
    model = identify(_capture(capture, delay_s, step), axis="x", diagnose=False)
    T = model.sample_time
    assert T == pytest.approx(0.001 * step)
    # the loop's own lag adds 0..2 samples; at 3 ms the refinement on sub-steps ends 0.02 samples short since the
    # spline's ringing into the rests is taken out (identification.substeps.RING_SHARE): 0.05 samples allowed
    assert delay_s - 0.05 * T <= model.delay_s <= delay_s + 2 * T
    if step == 3:  # issue #16's case, a reference 0.1 s ahead at 3 ms: the estimate is within one sample
        assert abs(model.delay_s - delay_s) <= T
    rec = model.fit["delay"]
    assert rec["estimated"] and rec["samples"] == pytest.approx(model.delay_s / T)
    assert rec["objective_ratio"] < 0.5
    assert model.fit["rms_um"] <= 3 * floor.fit["rms_um"]
    # without the dead time the same capture is far off: the test measures something
    assert rec["rms_without_um"] > 20 * model.fit["rms_um"]


def test_no_shift_estimates_zero(capture):
    model = identify(_capture(capture, 0.0, 3), axis="x", diagnose=False)
    assert model.delay_s == 0.0
    assert abs(model.fit["delay"]["samples"]) < MIN_DELAY_SAMPLES


def test_cli_says_why_the_best_shift_was_not_used(capture, tmp_path, capsys):
    path = tmp_path / "cap.csv"
    _capture(capture, 0.0, 3).to_csv(path)
    assert main(["identify", str(path), "--no-diagnose"]) == 0
    out = capsys.readouterr().out.replace("\n    ", " ")  # its lines unwrapped (wrapped at 100 columns)
    line = next(s for s in out.splitlines() if s.startswith("reference dead time"))
    assert line.startswith("reference dead time: 0 s (0 samples; estimated ")
    assert line.endswith("; not used: shorter than 5 samples, which the loop model's own lag cannot be told from)")
    # a shift long enough that lowers the equation error too little (dead_time.MAX_OBJECTIVE_RATIO) is named so
    weak = dataclasses.replace(ReducedAxisModel(parameters=dict.fromkeys(("a1", "a2", "a3", "b0", "b1", "b2", "d0",
                                                                          "d1"), 1.0), sample_time=0.001, axis="x"),
                               fit={"delay": {"estimated": True, "samples": 11.6, "objective_ratio": 0.803}})
    assert delay_lines(weak) == ["reference dead time: 0 s (0 samples; estimated 11.6 samples (objective ratio 0.803)"
                                 "; not used: it lowers the equation error to 80.3 % only, where a reference recorded "
                                 "ahead of the loop lowers it below 50 %)"]


def test_in_loop_delay_is_not_taken_for_a_reference_shift(machine, setpoints):
    """A one-sample control delay is an effect of the loop: delay_s stays 0 so the diagnosis can name it."""
    cap = machine.with_effect("x", "delay", {"samples": 1}).simulate(setpoints, seed=1)
    model = identify(_capture(cap, 0.0, 1), axis="x", diagnose=False)
    assert model.delay_s == 0.0
    assert abs(model.fit["delay"]["samples"]) < MIN_DELAY_SAMPLES


def test_model_file_round_trip_and_garbage_delay(tmp_path):
    params = {"a1": 600.0, "a2": 1.5e5, "a3": 1.2e7, "b0": 0.02, "b1": 300.0, "b2": 1.4e5, "d0": 80.0, "d1": -70.0}
    model = ReducedAxisModel(parameters=params, sample_time=0.003, axis="x", delay_s=0.1)
    path = tmp_path / "m.json"
    model.to_json(path)
    d = json.loads(path.read_text())
    assert d["format"] == "vcnc.axis-model/2" and d["delay_s"] == 0.1
    back = load_model(path)
    assert back.delay_s == 0.1
    ref = np.concatenate([np.zeros(50), np.linspace(0.0, 5.0, 200), np.full(100, 5.0)])
    np.testing.assert_array_equal(back.simulate(ref), model.simulate(ref))
    plain = dataclasses.replace(model, delay_s=0.0)
    plain.to_json(path)
    assert json.loads(path.read_text())["format"] == "vcnc.axis-model/1"
    for garbage in ("0.1 s", None, [0.1]):
        d["delay_s"] = garbage
        path.write_text(json.dumps(d))
        with pytest.raises(ModelFileError, match="delay_s"):
            load_model(path)


def test_cli_identify_given_delay_is_printed(capture, tmp_path, capsys):
    cap = _capture(capture, 0.1, 3)
    path = tmp_path / "cap.csv"
    cap.to_csv(path)
    assert main(["identify", str(path), "--delay", "0.1", "--no-diagnose", "--json", str(tmp_path / "m.json")]) == 0
    out = capsys.readouterr().out
    assert "reference dead time: 0.1 s (33.33 samples; given)" in out
    assert load_model(tmp_path / "m.json").delay_s == 0.1
    with pytest.raises(SystemExit) as exc:
        main(["identify", str(path), "--delay", "soon"])
    assert exc.value.code == 2
    assert "expected 'auto' or a finite number of seconds, got 'soon'" in capsys.readouterr().err


def test_compare_runs_the_model_on_the_delayed_reference():
    """vcnc compare predicts with the model's simulate: a dead time delays the predicted contour."""
    from vcnc.contour_compare import compare
    from vcnc.engine.machine import Machine

    m = vcnc.machine("fadal-pid")
    models = {a: ReducedAxisModel(parameters=m.axis(a).reduced_parameters(), sample_time=m.sample_time, axis=a)
              for a in m.axes}
    truth = Machine.from_axes(models, sample_time=m.sample_time, limits=m.limits, name="exact")
    late = {a: dataclasses.replace(md, delay_s=0.01) for a, md in models.items()}
    exact, delayed = compare(truth, models, "circle", feed=100.0), compare(truth, late, "circle", feed=100.0)
    assert exact.to_dict()["prediction_error_pct"] == {"max": 0.0, "rms": 0.0}
    assert np.max(np.abs(delayed.predicted["identified"].error - exact.predicted["identified"].error)) > 1e-3
    assert all("reference dead time 0.01 s" in text for text in delayed.models["identified"].values())


def test_pure_delay_baseline_ranks_many_shifts_by_fft_and_sums_the_best_exactly():
    """A hand-made record at 125 us (8000 shifts tried) whose measured position is the reference 400 samples late
    plus a small ripple: the fast path (:data:`identification.dead_time.BASELINE_CANDIDATES` shifts ranked by the
    Fourier transform) returns what summing every shift returns, to the last bit, with and without a mask."""
    import numpy as np

    import identification.dead_time as dt

    T = 125e-6
    t = np.arange(60_000) * T
    xr = 10.0 * np.sin(2 * np.pi * 0.7 * t) + 3.0 * np.sin(2 * np.pi * 2.3 * t)
    x = dt.delay_reference(xr, 400.0) + 1e-4 * np.sin(2 * np.pi * 31.0 * t)
    mask = (np.arange(t.size) // 997) % 3 != 0
    for m in (None, mask):
        fast = dt.pure_delay_baseline(xr, x, T, mask=m)
        every = dt.BASELINE_EXACT_SHIFTS
        try:
            dt.BASELINE_EXACT_SHIFTS = 10**9
            slow = dt.pure_delay_baseline(xr, x, T, mask=m)
        finally:
            dt.BASELINE_EXACT_SHIFTS = every
        assert fast == slow and fast["pure_delay_samples"] == 400
