"""A machine whose axis limits ask more than its drive delivers: ``vcnc simulate`` says that the actuator
saturated (stdout, summary JSON, report) instead of handing over the numbers of a saturated or diverged
loop as if they were the tuned machine's. Hand-written programs and machine files, real simulation."""

from __future__ import annotations

import json

import numpy as np

import interpolators
from vcnc.cli import main
from vcnc.engine.machine import builtin_machine_text, load_machine
from vcnc.facade import interpolate
from vcnc.simulation_report import saturation_note, summarize

#: Back and forth over 100 mm at 150 mm/s, then a diagonal move and a dwell.
PROGRAM = "G21 G90\nG0 X0 Y0\nG1 X100 F9000\nG1 X0\nG1 X100 Y20\nG4 P1\nM30\n"


def fast_smc(tmp_path, *, anti_windup: bool = True):
    """fadal-smc with an X acceleration limit of 20000 mm/s^2: its drive delivers about 7000 at the
    15 A current limit (K/J 1008 mm/(V s^2) x 7.5 V, less the Coulomb friction; machine file's header).
    ``anti_windup = false`` on X runs the bare law of the paper."""
    text = builtin_machine_text("fadal-smc")
    x, rest = text.split("[axes.y]", 1)
    x = x.replace("acceleration = 2000.0", "acceleration = 20000.0").replace("jerk = 40000.0", "jerk = 400000.0")
    x = x.replace("anti_windup = true", f"anti_windup = {str(anti_windup).lower()}")
    path = tmp_path / "fast-smc.toml"
    path.write_text(x + "[axes.y]" + rest)
    return path


def _simulate(tmp_path, machine, capsys):
    prog = tmp_path / "part.nc"
    prog.write_text(PROGRAM)
    js, rep = tmp_path / "s.json", tmp_path / "rep"
    assert main(["simulate", str(prog), "--machine", str(machine), "-o", str(tmp_path / "c.csv"),
                 "--json", str(js), "--report", str(rep)]) == 0
    return capsys.readouterr().out, json.loads(js.read_text()), (rep / "index.html").read_text(), prog


def test_saturated_run_is_said_on_stdout_in_the_summary_and_the_report(tmp_path, capsys):
    out, summary, html, prog = _simulate(tmp_path, fast_smc(tmp_path), capsys)
    assert f"{prog}: warning: the actuator was at its limit on axis x " in out
    assert set(summary["saturated"]) == {"x"}  # Y keeps the drive's 2000 mm/s^2
    x = summary["saturated"]["x"]
    # at each of the four accelerations and decelerations, about 20 ms each (measured 6.6 % of 5.1 s)
    assert 0.02 < x["share"] < 0.2 and x["longest_s"] > 0.01
    # the law's anti-windup (default) holds its adapted disturbance: the loop recovers after each move
    assert not x["error_beyond_travel"] and "the loop left its stable region" not in out
    assert "warning: the actuator was at its limit on axis x" in html


def test_the_bare_law_winds_up_and_leaves_its_stable_region(tmp_path, capsys):
    out, summary, html, _ = _simulate(tmp_path, fast_smc(tmp_path, anti_windup=False), capsys)
    x = summary["saturated"]["x"]
    assert 0.5 < x["share"] <= 1.0 and x["longest_s"] > 0.1
    # the adaptive sliding mode, its disturbance estimate winding up, leaves its stable region
    assert x["error_beyond_travel"]
    assert "the loop left its stable region" in out and "the loop left its stable region" in html


def test_a_run_within_the_drives_reach_has_no_saturation_entry(tmp_path, capsys):
    prog = tmp_path / "part.nc"
    prog.write_text(PROGRAM)
    js = tmp_path / "s.json"
    assert main(["simulate", str(prog), "--machine", "fadal-smc", "-o", str(tmp_path / "c.csv"),
                 "--json", str(js)]) == 0
    assert "warning" not in capsys.readouterr().out
    assert "saturated" not in json.loads(js.read_text())


def test_saturated_samples_are_those_at_the_actuator_limit_and_follow_the_axes_selected(tmp_path):
    setpoints = None
    for anti_windup in (False, True):
        machine = load_machine(fast_smc(tmp_path, anti_windup=anti_windup))
        setpoints = setpoints or interpolate(interpolators.parse_program(PROGRAM), machine)
        cap = machine.simulate(setpoints)
        limit = machine.axis("x").actuator_limit()
        assert limit == 7.5  # 15 A / 2 A/V (fadal-smc's saturation), below the 10 V DAC
        sat = cap.aux["saturated"]
        assert sat.shape == cap.control.shape and sat.dtype == bool
        clipped = np.abs(cap.control[:, 0]) == limit
        if anti_windup:  # the samples the actuator clipped, and those where the law held its adaptation
            assert (sat[:, 0] >= clipped).all() and sat[:, 0].sum() > clipped.sum() > 0
        else:
            np.testing.assert_array_equal(sat[:, 0], clipped)
    y = cap.select_axes(("y",))
    assert y.aux["saturated"].shape == (len(cap), 1) and not y.aux["saturated"].any()
    assert "saturated" not in summarize(y) and saturation_note(summarize(y)) is None
    assert saturation_note(summarize(cap)).startswith("warning: the actuator was at its limit on axis x ")
