"""A demanding new user on the command line (session 34): a run stopped by Ctrl-C or ``kill`` exits 128 + the
signal's number with one line and leaves no output behind."""

from __future__ import annotations

import signal
from pathlib import Path

import pytest

from vcnc.cli import main

PROGRAM = "G21 G90 G94\nG0 X0 Y0\nG1 X5 Y0 F600\nG1 X5 Y5\nM2\n"


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("part.nc").write_text(PROGRAM)
    return tmp_path


@pytest.mark.parametrize(("signum", "status"), [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_during_the_writing_exits_128_plus_its_number_leaving_no_output(work, capsys, monkeypatch, signum,
                                                                                    status):
    import vcnc.simulation_report as simulation_report

    summarize = simulation_report.summarize

    def signalled(*args, **kwargs):  # the summary is computed while the capture's temporary file is being written
        out = summarize(*args, **kwargs)
        if signum == signal.SIGINT:
            # what Python's own SIGINT handler does (signal.default_int_handler raises KeyboardInterrupt); raised
            # here, not by raise_signal, whose handler ran too late to stop the run in 2 of 4 loaded xdist runs
            # (session 35: exit 0; never alone): this case tests vcnc's handling of Ctrl-C, not the delivery
            raise KeyboardInterrupt
        signal.raise_signal(signum)  # SIGTERM: the handler vcnc installs turns it into Interrupted
        return out

    monkeypatch.setattr(simulation_report, "summarize", signalled)
    before = {p.name for p in work.iterdir()}
    code = main(["simulate", "part.nc", "--machine", "fadal-pid", "-o", "cap.csv", "--json", "run.json"])
    err = capsys.readouterr().err.strip()
    assert code == status, err
    assert err == f"error: interrupted ({signal.Signals(signum).name})"
    assert {p.name for p in work.iterdir()} == before  # neither the outputs nor their temporary names
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL  # the handler is the command's only


def _slipped_machine(tmp_path: Path, **changes: str) -> Path:
    """fadal-pid's file with some lines replaced (``key = value`` written as ``key="value"`` pairs on the x axis)."""
    from vcnc.engine.machine import builtin_machine_text

    lines = builtin_machine_text("fadal-pid").splitlines()
    for key, value in changes.items():
        i = next(i for i, line in enumerate(lines) if line.split("=")[0].strip() == key)  # the first: axis x's
        lines[i] = f"{key} = {value}"
    path = tmp_path / "slip.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_a_feed_in_mm_per_min_and_a_lead_in_m_are_warned_naming_file_line_key_and_reason(tmp_path):
    import vcnc
    from vcnc.core.errors import PlausibilityWarning

    path = _slipped_machine(tmp_path, velocity="150000.0", lead="0.01")
    lines = path.read_text().splitlines()
    with pytest.warns(PlausibilityWarning) as record:
        machine = vcnc.machine(str(path))
    assert machine.axis("x").limits.velocity == 150000.0  # a warning, not an error: the file is read as written
    messages = [str(w.message) for w in record]
    velocity_line = lines.index("velocity = 150000.0") + 1
    lead_line = lines.index("lead = 0.01") + 1
    assert messages == [
        f"{path}:{velocity_line}: axes.x.limits.velocity = 150000 [mm/s] is above 3000 mm/s, implausible for a real "
        "machine: machine tools feed at up to 2-3 m/s (180 m/min) and rotary tables turn up to a few thousand rpm; "
        "in mm/min? 150000 mm/min is 2500 mm/s",
        f"{path}:{lead_line}: axes.x.drive.lead = 0.01 [mm/rev] is below 0.5 mm/rev, implausible for a real machine: "
        "ball screws have leads of 1-50 mm per turn; in m or cm? 0.01 m is 10 mm",
    ]


def test_the_command_line_prints_each_plausibility_warning_as_one_line(tmp_path, capsys):
    path = _slipped_machine(tmp_path, sample_time="0.05", acceleration="0.5")
    lines = path.read_text().splitlines()
    code = main(["machines", "--show", str(path)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 0
    assert err == [
        f"warning: {path}:{lines.index('sample_time = 0.05') + 1}: sample_time = 0.05 [s] is above 0.02 s, "
        "implausible for a servo period: position loops close every 31.25 us to a few ms (20 ms and more is a PLC "
        "task's cycle)",
        f"warning: {path}:{lines.index('acceleration = 0.5') + 1}: axes.x.limits.acceleration = 0.5 [mm/s^2] is below "
        "1 mm/s^2, implausible for a real machine: linear motors accelerate at up to 2-5 g, ball screws at 0.3-1.5 g "
        "(1 g = 9810 mm/s^2); in m/s^2? 0.5 m/s^2 is 500 mm/s^2",
    ]


@pytest.mark.parametrize("name", ["fadal-pid", "fadal-ppi", "fadal-smc", "emps", "ballscrew-ppc", "ballscrew-zpetc",
                                  "chevalier-pdf"])
def test_the_built_in_machines_are_plausible(name, recwarn):
    import vcnc
    from vcnc.core.errors import PlausibilityWarning

    vcnc.machine(name)
    assert not [w for w in recwarn if issubclass(w.category, PlausibilityWarning)]


def _fadal_models(tmp_path: Path, sample_time: float) -> list[str]:
    """--model arguments: fadal-pid's exact reduced models of x and y, identified from a record at ``sample_time``."""
    from identification import ReducedAxisModel
    from vcnc.engine.machine import load_machine

    m = load_machine("fadal-pid")
    out = []
    for a in ("x", "y"):
        model = ReducedAxisModel(parameters=m.axis(a).reduced_parameters(), sample_time=sample_time, axis=a)
        model.to_json(tmp_path / f"{a}.json")
        out += ["--model", f"{a}={tmp_path / f'{a}.json'}"]
    return out


@pytest.mark.parametrize("model_ts", [0.0005, 0.002])
def test_compare_warns_when_the_true_machines_servo_period_differs_from_the_models(tmp_path, capsys, model_ts):
    truth = _slipped_machine(tmp_path, sample_time="0.001")  # fadal-pid's own period, in a file
    code = main(["compare", "--truth", str(truth), *_fadal_models(tmp_path, model_ts), "--toolpath", "diamond",
                 "--truth-runs", "1"])
    out = capsys.readouterr().out
    assert code == 0
    assert (f"warning: the true machine's servo period 0.001 s ('sample_time' [s] of {truth}) differs from the "
            f"{model_ts:g} s of the record the model of x, y was identified from") in out


def test_compare_says_nothing_of_servo_periods_that_agree(tmp_path, capsys):
    code = main(["compare", "--truth", "fadal-pid", *_fadal_models(tmp_path, 0.001), "--toolpath", "diamond",
                 "--truth-runs", "1"])
    assert code == 0
    assert "servo period" not in capsys.readouterr().out


def test_the_settling_tail_ends_where_an_exponential_decay_is_within_a_tenth_of_a_percent():
    import numpy as np

    from vcnc.core.capture import Capture
    from vcnc.engine.settling import WINDOW_S, settling_tail

    ts, tau, start = 0.001, 0.05, 200  # a following error of 10 um decaying with 50 ms after the reference stopped
    t = np.arange(start + 1500) * ts
    ref = np.full((len(t), 1), 5.0)
    err = np.where(t >= t[start - 1], 0.01 * np.exp(-(t - t[start - 1]) / tau), 0.01)
    cap = Capture(t=t, axes=("x",), reference=ref, measured=ref - err[:, None])
    tail = settling_tail(cap, start)
    assert tail.settled and tail.band["x"] == pytest.approx(1e-5, rel=1e-2)  # 0.1 % of the 10 um
    # the error's mean over the next 20 ms is within 0.1 % of 10 um from tau ln(1000) - 20 ms on (mean over 20 ms of
    # the decay = e(t) tau/20ms (1 - exp(-20/50))), then WINDOW_S at rest
    settle = tau * np.log(1000 * tau / 0.02 * (1 - np.exp(-0.02 / tau)))
    assert tail.seconds == pytest.approx(settle + WINDOW_S, abs=2 * ts)


def test_the_settling_tail_keeps_the_bound_for_an_axis_that_never_settles():
    import numpy as np

    from vcnc.core.capture import Capture
    from vcnc.engine.settling import settling_tail

    t = np.arange(1000) * 0.001
    ref = np.zeros((1000, 2))
    measured = np.column_stack([np.zeros(1000), 1e-3 * t])  # y's measured channel creeps 1 um/s
    tail = settling_tail(Capture(t=t, axes=("x", "y"), reference=ref, measured=measured), 300)
    assert not tail.settled and tail.unsettled == ("y",) and tail.samples == 1000
    assert tail.note(0.7).startswith("axis y had not settled 0.7 s after the last setpoint")


def test_simulate_records_the_axis_settling_after_the_reference_stops(work, capsys):
    from vcnc.capture import read_capture

    assert main(["simulate", "part.nc", "--machine", "fadal-pid", "-o", "plain.csv", "--settle", "0"]) == 0
    assert main(["simulate", "part.nc", "--machine", "fadal-pid", "-o", "tail.csv"]) == 0
    out = capsys.readouterr().out
    assert "part.nc: the capture runs on " in out and "until every axis settled (following error within" in out
    plain, tail = read_capture("plain.csv"), read_capture("tail.csv")
    n = len(plain)
    assert n < len(tail) <= n + 2000  # the tail is bounded by --settle's default 2 s
    assert tail.meta["settle"].startswith("the capture runs on ")
    import numpy as np

    np.testing.assert_array_equal(tail.reference[:n], plain.reference)  # the same run, longer
    np.testing.assert_array_equal(tail.reference[n:], np.repeat(plain.reference[-1:], len(tail) - n, axis=0))
    e_end = np.abs(plain.reference[-1] - plain.measured[-1]).max()
    e_last = np.abs(tail.reference[-1] - tail.measured[-1]).max()
    assert e_end > 5 * e_last  # when the reference stopped the axis had not arrived; at the tail's end it had


@pytest.mark.parametrize("value", ["-1", "nan", "1000"])
def test_a_bad_settle_bound_is_refused_naming_the_option(work, capsys, value):
    assert main(["simulate", "part.nc", "--machine", "fadal-pid", "-o", "c.csv", "--settle", value]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: --settle {value}: ") and not Path("c.csv").exists()


def test_compare_notes_a_model_from_a_finer_record_than_the_captured_truth(tmp_path, capsys):
    # the truth: a capture of the diamond at 2 ms (fadal-pid's file at 2 ms, simulated); the models: of a 1 ms record
    truth = _slipped_machine(tmp_path, sample_time="0.002")
    Path(tmp_path / "d.nc").write_text("G21 G90\nG0 X0 Y0\nG1 X10 Y10 F3000\nG1 X20 Y0\nG1 X0 Y0\nM2\n")
    assert main(["simulate", str(tmp_path / "d.nc"), "--machine", str(truth), "-o", str(tmp_path / "c.csv")]) == 0
    capsys.readouterr()
    code = main(["compare", "--truth", str(tmp_path / "c.csv"), *_fadal_models(tmp_path, 0.001), "--toolpath",
                 str(tmp_path / "d.nc")])
    out = capsys.readouterr().out
    assert code == 0
    assert ("note: the model of x, y was identified from a record sampled every 0.001 s, finer than the capture's "
            "0.002 s") in out


@pytest.mark.parametrize("command", ["export-fmu", "compare"])
def test_a_capture_given_as_the_model_is_named_for_what_it_is(work, capsys, command):
    Path("cap.csv").write_text("# machine: fadal-pid\nt,x_ref,x\n0,0,0\n0.001,0,0\n")
    argv = (["export-fmu", "cap.csv", "-o", "d.fmu"] if command == "export-fmu"
            else ["compare", "--truth", "fadal-pid", "--model", "cap.csv"])
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: cap.csv: this is a capture (CSV), not a model file; expected a model file")
    assert not Path("d.fmu").exists()
