"""Delimited traces in the layouts of recorders seen in tracewild3: channels named by their signal path, a joint's
command words side by side, positions in turns or radians, and files that cannot be a position trace. Each file is
a few lines written here after a real export's layout, not the export itself."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError
from vcnc.traces.columns import length_unit, position_scale, unit_in_name
from vcnc.traces.names import columns_from_names, no_positions
from vcnc.traces.preamble import stated_count_size


def _motion(n: int = 300, dt: float = 1e-3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Time [s], commanded and measured position of a 2 Hz cosine move lagging by up to 0.02."""
    t = np.arange(n) * dt
    ref = 0.4 * (1 - np.cos(2 * np.pi * 2 * t))
    return t, ref, ref - 0.02 * np.sin(2 * np.pi * 2 * t)


_JOINT = ["Test/MotorCmdKd#0", "Test/MotorCmdKp#0", "Test/MotorCmdPos#0", "Test/MotorCmdTor#0", "Test/MotorCmdVel#0",
          "Test/MotorFbPos#0", "Test/MotorFbTemp#0", "Test/MotorFbTor#0", "Test/MotorFbVel#0", "Test/TotalLostFrameCnt",
          "Test/t"]


@pytest.mark.parametrize(("header", "mapping"), [
    # a joint recorder's command words: gains and torque are no positions, the path's last element t is the time
    (_JOINT, {"t": "Test/t", "x_ref": "Test/MotorCmdPos#0", "x": "Test/MotorFbPos#0"}),
    (["MAIN.Axis.Time", "MAIN.Axis.SetPos", "MAIN.Axis.ActPos"],
     {"t": "MAIN.Axis.Time", "x_ref": "MAIN.Axis.SetPos", "x": "MAIN.Axis.ActPos"}),
    (["/joint/timestamp", "/joint/pos_cmd", "/joint/pos_fb"],
     {"t": "/joint/timestamp", "x_ref": "/joint/pos_cmd", "x": "/joint/pos_fb"}),
])
def test_signal_path_names(header, mapping):
    assert columns_from_names(header) == (mapping, "")


@pytest.mark.parametrize(("header", "why"), [
    # a path whose last element is more than a time word is not read as time
    (["MAIN.fTime", "MAIN.fSetPos", "MAIN.fActPos"],
     "no column is named as time (only names with more than time words: ['MAIN.fTime']; give --columns t=NAME,...)"),
    # ROS topics in a PlotJuggler export: positions without a command
    (["__time", "/psm/roll/position", "/psm/roll/velocity"],
     "no pair of a commanded and a measured position is named (positions that name neither a command nor a "
     "measurement: ['/psm/roll/position']; other quantities: ['/psm/roll/velocity']); a position trace needs a "
     "commanded and a measured position"),
    # two encoders of an ODrive GUI export: a question, not a guess
    (["time", "odrive0.axis0.encoder.pos_abs", "odrive0.axis0.encoder.second_pos_abs"],
     "axis x: several columns could be the measured position: ['odrive0.axis0.encoder.pos_abs', "
     "'odrive0.axis0.encoder.second_pos_abs']; none is named as the commanded position, which identification "
     "needs beside the measured one"),
    (["timestamp_ms", "setpoint_rpm", "actual_rpm"],
     "no pair of a commanded and a measured position is named (other quantities: ['setpoint_rpm', 'actual_rpm']); "
     "a position trace needs a commanded and a measured position"),
])
def test_names_that_are_not_read(header, why):
    assert columns_from_names(header) == (None, why)


def test_joint_recorder_counting_samples(tmp_path):
    # the path's t counts samples: without a period an error asking for it; with --sample-time read from the names
    t, ref, act = _motion()
    f = tmp_path / "joint.csv"
    f.write_text(",".join(_JOINT) + "\n" + "".join(
        f"0.1,1.0,{r:.10f},0,0,{a:.10f},24.0,0.01,0.0,0,{k}\n" for k, (r, a) in enumerate(zip(ref, act))))
    with pytest.raises(CaptureError, match=r"joint.csv:1: the time column 'Test/t' \(read from its name\) steps by 1 "
                                           r"and the file does not state its unit.*; expected --time-unit ms\|us\|s, "
                                           r"or --sample-time S when it counts samples"):
        read_capture(f)
    cap = read_capture(f, sample_time=0.002)
    np.testing.assert_allclose(cap.t, 2 * t, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], ref, atol=1e-10)
    np.testing.assert_allclose(cap.measured[:, 0], act, atol=1e-10)
    assert cap.meta["time_unit"] == "sample numbers x 0.002 s"
    assert cap.meta["commanded"] == "x:Test/MotorCmdPos#0"


@pytest.mark.parametrize(("unit", "base", "scale"), [
    ("rad", "rad", math.degrees(1.0)), ("rev", "rev", 360.0), ("turns", "rev", 360.0), ("0.5rev", "rev", 180.0)])
def test_angle_units(unit, base, scale):
    found = length_unit(unit)
    assert found is not None and found[0] == base and found[1] == pytest.approx(scale, rel=1e-15)
    assert position_scale(["a"], unit, "f") == pytest.approx(scale, rel=1e-15)


def test_turns_on_a_linear_axis_ask_for_the_lead():
    with pytest.raises(CaptureError, match=r"f: unit 'rev' is for rotary axes \(a, b, c: --columns a_ref=..,a=..\); "
                                           r"axes \['x'\] are linear; a linear axis logged in turns of its motor "
                                           r"takes the travel of one turn as its unit \(--unit 5mm for a screw of 5 "
                                           r"mm lead\)"):
        position_scale(["x"], "rev", "f")
    with pytest.raises(CaptureError, match=r"rotary positions are in deg, rad or rev"):
        position_scale(["a"], "mm", "f")


def test_positions_in_turns_from_the_header(tmp_path):
    # an ODrive-like export whose header names turns: read in degrees on a rotary axis, the lead asked on a linear one
    t, ref, act = _motion(50)
    f = tmp_path / "odrive.csv"
    f.write_text("time [s],axis0.controller.input_pos [turns],axis0.encoder.pos_estimate [turns]\n"
                 + "".join(f"{a:.3f},{b:.6f},{c:.6f}\n" for a, b, c in zip(t, ref, act)))
    assert unit_in_name("axis0.encoder.pos_estimate [turns]", "length") == "rev"
    columns = {"t": "time [s]", "a_ref": "axis0.controller.input_pos [turns]",
               "a": "axis0.encoder.pos_estimate [turns]"}
    cap = read_capture(f, columns=columns)
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref, 6) * 360.0, atol=1e-9)
    with pytest.raises(CaptureError, match=r"unit 'rev' is for rotary axes"):
        read_capture(f, columns={"t": "time [s]", "x_ref": columns["a_ref"], "x": columns["a"]})
    cap = read_capture(f, columns={"t": "time [s]", "x_ref": columns["a_ref"], "x": columns["a"]}, unit="5mm")
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act, 6) * 5.0, atol=1e-9)


def test_a_resolution_per_turn_states_no_count_size():
    # counts per turn say nothing of a linear axis' travel (its lead): nothing stated
    assert stated_count_size(["Encoder resolution = 8192 counts/rev"]) is None
    assert stated_count_size(["Resolution: 0.001 rad"]) is None
    assert stated_count_size(["Encoder resolution = 10000 inc/deg"]).value == "0.0001deg"


def test_a_row_vector_is_refused(tmp_path):
    f = tmp_path / "set_position.csv"
    f.write_text(",".join(f"{v:.6f}" for v in _motion(40)[1]) + "\n")
    with pytest.raises(CaptureError, match=r"set_position.csv:1: only one row of numbers \(40 values\): a trace has a "
                                           r"row per sample and a column per channel \(a saved row vector\? "
                                           r"transpose it\)"):
        read_capture(f)


def _gather_rows(n: int = 200) -> list[tuple[int, float, float]]:
    """Sample number, desired and actual position [counts] of a PMAC gather."""
    t, ref, act = _motion(n)
    return [(k, r * 1e4, a * 1e4) for k, (r, a) in enumerate(zip(ref, act))]


@pytest.mark.parametrize("header", [
    # dls-pmac-control's Turbo PMAC save (gather.py) and its Power PMAC save (ppmacgather.py), whose header spreads
    # each channel over three cells
    "point,CH0 Axis1 Motor present desired position,CH1 Axis1 Motor present actual position,",
    "point,CH0, Axis 1, Motor present desired position, CH1, Axis 1, Motor present actual position, ",
])
def test_pmac_gather_saves(tmp_path, header):
    f = tmp_path / "gather.csv"
    f.write_text(header + "\n" + "".join(f"{k},{r:f},{a:f},\n" for k, r, a in _gather_rows()))
    with pytest.raises(CaptureError, match=r"gather.csv:1: which columns .*\(not read from the names: no column is "
                                           r"named as time \('point' counts samples: give --sample-time S"):
        read_capture(f)
    with pytest.raises(CaptureError, match=r"gather.csv:1: x_ref='CH0 Axis ?1 Motor present desired position' is "
                                           r"logged in increments \('counts'\) and the file does not state their size"):
        read_capture(f, sample_time=0.000442)
    cap = read_capture(f, sample_time=0.000442, unit="0.0001mm")
    rows = _gather_rows()
    np.testing.assert_allclose(cap.t, [0.000442 * k for k, _, _ in rows], atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], [round(r, 6) * 1e-4 for _, r, _ in rows], atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], [round(a, 6) * 1e-4 for _, _, a in rows], atol=1e-12)
    assert cap.meta["commanded"].startswith("x:CH0 Axis") and cap.meta["measured"].endswith("actual position")


@pytest.mark.parametrize(("header", "result"), [
    (["point", "CH0 Axis 1 Motor present actual position", "CH1 Axis 4 Motor present actual position"],
     (None, "the positions belong to axes [1, 4], none with both a commanded and a measured position: "
            "['CH0 Axis 1 Motor present actual position', 'CH1 Axis 4 Motor present actual position']")),
    (["point", "CH0 Axis 1 Motor present desired position", "CH1 Axis 4 Motor present actual position",
      "CH2 Axis 4 Motor present desired position"],
     ({"t": "point", "x_ref": "CH2 Axis 4 Motor present desired position",
       "x": "CH1 Axis 4 Motor present actual position"}, "")),
    (["time", "joint 1 cmd", "joint 1 fb", "joint 2 cmd", "joint 2 fb"],
     (None, "axes [1, 2] each have a commanded and a measured position (['joint 1 cmd', 'joint 1 fb', 'joint 2 cmd', "
               "'joint 2 fb']): give --columns for one")),
])
def test_numbered_axes_pair_within_their_number(header, result):
    assert columns_from_names(header, period_known=True) == result


@pytest.mark.parametrize(("header", "none"), [
    (["timestamp_ms", "setpoint_rpm", "actual_rpm"], True),  # a speed loop's step response
    (["Tiempo (s)", "PWM", "Voltaje (V)", "Velocidad (rad/s)"], True),
    (["time", "odrive0.axis0.encoder.gear_vel_estimate", "odrive0.axis0.encoder.vel_estimate"], True),
    (["time", "pitch_position", "pitch_velocity"], False),  # a position, without its command
    (["Time (s)", "Thrust (kgf)", "Debug 0"], False),  # names that could be positions
])
def test_files_without_positions(tmp_path, header, none):
    assert no_positions(header) is none
    f = tmp_path / "log.csv"
    f.write_text(",".join(header) + "\n" + "".join(f"{k * 0.01:.2f}" + ",1" * (len(header) - 1) + "\n"
                                                    for k in range(20)))
    lead = r"no position in the file: its columns" if none else r"which columns are time, commanded and measured"
    with pytest.raises(CaptureError, match=rf"log.csv:1: {lead}"):
        read_capture(f)


def test_labelled_header_rows(tmp_path):
    # a recorder's text file whose header rows are labelled ("SIGNAL", "VERT_UNITS"), a cell wider than the rows,
    # with a "DATA" line between them and the numbers (Hioki memory recorders' layout)
    t, ref, act = _motion()
    f = tmp_path / "mem.csv"
    f.write_text('"COMMENT","MEM DATA"\n"NUM_SIGS", 3\n"INTERVAL", 1.000E-03\n"VERT_UNITS", "ms", "um", "um"\n'
                 '"SIGNAL","TIME", "X Soll", "X Ist"\n"DATA"\n'
                 + "".join(f"{a * 1e3:+.6E}, {b * 1e3:+.6E}, {c * 1e3:+.6E}\n" for a, b, c in zip(t, ref, act)))
    cap = read_capture(f)
    np.testing.assert_allclose(cap.t, t, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], ref, rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], act, rtol=1e-6, atol=1e-12)
    assert cap.meta["columns"] == "from the header names: t=TIME, x_ref=X Soll, x=X Ist (--columns, --time-unit, " \
                                  "--unit set them)"
    assert cap.meta["unit"] == "um"
