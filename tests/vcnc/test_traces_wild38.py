"""Traces in layouts of traces38 (session 38): drive tools' pulse counters, ``rostopic echo -p`` tables of a joint
controller's state, and the fuzzer's cases (``benchmarks/trace_fuzz.py``, seeds 44-46). Each file is a few lines
written here after the layout, not an export itself."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError

_SET = [0.0, 100.0, 300.0, 600.0, 900.0, 1100.0]
_ACT = [0.0, 40.0, 200.0, 480.0, 790.0, 1020.0]


def _table(path, names, *, sep=",", above=()):
    rows = [sep.join([f"{k:g}", f"{s:g}", f"{a:g}", "12.5"]) for k, (s, a) in enumerate(zip(_SET, _ACT))]
    path.write_text("\n".join([*above, sep.join(names), *rows]) + "\n", encoding="utf-8")
    return path


def test_pulse_counters_are_positions_in_counts(tmp_path):
    """Yaskawa's monitors "Input Reference Pulse Counter" (reference units) and "Feedback Pulse Counter" (encoder
    pulses), as a SigmaWin+ trace names them, are the commanded and measured position in counts: the file asks for
    their size and names the two count units, which an electronic gear may make differ (it said the file held no
    position: "counter" named another quantity)."""
    f = _table(tmp_path / "sigma.csv", ["Time[ms]", "Reference pulse counter[reference unit]",
                                        "Feedback pulse counter[pulse]", "Torque Reference[%]"])
    with pytest.raises(CaptureError, match=r"increments \('reference unit'\).*'reference unit' and x 'pulse'.*"
                                           r"electronic gear.*--unit") as err:
        read_capture(f)
    assert str(f) in str(err.value)
    cap = read_capture(f, unit="0.1um")
    assert cap.axes == ("x",)
    np.testing.assert_allclose(cap.reference[:, 0], np.array(_SET) * 1e-4)
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_ACT) * 1e-4)
    np.testing.assert_allclose(np.diff(cap.t), 0.001)


def test_pulse_counters_without_a_unit_in_brackets(tmp_path):
    """Panasonic MINAS' "command pulse counter" and "feedback pulse counter" (read out by its RS232 command 2) name
    their counts by the word pulse alone: the command's pulses (before the electronic gear) and the encoder's, so the
    question and a given unit's note name the gear."""
    f = _table(tmp_path / "minas.csv", ["Time [ms]", "Command pulse counter", "Feedback pulse counter",
                                        "Torque command [%]"])
    with pytest.raises(CaptureError, match=r"increments \('pulse'\) and the file does not state their size; "
                                           r"x_ref counts 'pulse' and x 'pulse'.*electronic gear"):
        read_capture(f)
    cap = read_capture(f, unit="1um")
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_ACT) * 1e-3)
    assert "electronic gear" in cap.meta["count_units"]
    same = _table(tmp_path / "puu.csv", ["Time [ms]", "Position Command (PUU)", "Feedback Position (PUU)", "Speed"])
    assert "count_units" not in read_capture(same, unit="1um").meta  # Delta's user units: one size on both sides


def test_a_counter_of_samples_stays_no_position(tmp_path):
    """A counter that counts no pulses (a status or sample counter) is still another quantity beside a pair."""
    f = _table(tmp_path / "counter.csv", ["Time [ms]", "X Sollposition", "X Istposition", "Cycle counter"])
    cap = read_capture(f)
    assert cap.meta["commanded"] == "x:X Sollposition" and cap.meta["measured"] == "x:X Istposition"


def _rostopic(path, joints=1, *, stamp0=1_700_000_000_123_456_789):
    """A ``rostopic echo -p`` table of a control_msgs/JointTrajectoryControllerState topic (positions in m)."""
    names = ["%time", "field.header.seq", "field.header.stamp", "field.header.frame_id"]
    names += [f"field.joint_names{j}" for j in range(joints)]
    for point in ("desired", "actual", "error"):
        names += [f"field.{point}.{what}{j}" for what in ("positions", "velocities") for j in range(joints)]
        names += [f"field.{point}.time_from_start"]
    rows = []
    for k, (s, a) in enumerate(zip(_SET, _ACT)):
        ns = stamp0 + k * 1_000_000
        cells = [ns + 40_000, k, ns, ""] + [f"joint_{j}" for j in range(joints)]
        for pos, vel in ((s, 0.5), (a, 0.4), (s - a, 0.1)):
            cells += [pos * 1e-6] * joints + [vel] * joints + [0]
        rows.append(",".join(map(str, cells)))
    path.write_text("\n".join([",".join(names), *rows]) + "\n", encoding="utf-8")
    return path


def test_rostopic_controller_state_reads_desired_and_actual_positions(tmp_path):
    """``rostopic echo -p`` of a joint controller's state: ``field.desired.positions0`` and
    ``field.actual.positions0`` are joint 0's commanded and measured position (``...velocities0`` is a velocity: it
    was read as a second commanded position), ``%time`` counts nanoseconds since 1970 (read to 256 ns as a float,
    so kept to the microsecond from the first row), and the positions' SI unit (REP 103: m or rad) is asked for,
    never taken as mm."""
    f = _rostopic(tmp_path / "state.csv")
    with pytest.raises(CaptureError, match=r"REP 103.*expected --unit m .*a_ref=field\.desired\.positions0,"
                                           r"a=field\.actual\.positions0 --unit rad") as err:
        read_capture(f)
    assert str(f) in str(err.value)
    cap = read_capture(f, unit="m")
    assert cap.axes == ("x",)
    assert cap.meta["commanded"] == "x:field.desired.positions0"
    np.testing.assert_allclose(cap.reference[:, 0], np.array(_SET) * 1e-3)
    np.testing.assert_allclose(cap.measured[:, 0], np.array(_ACT) * 1e-3)
    np.testing.assert_array_equal(np.diff(cap.t), 0.001)
    rad = read_capture(f, unit="rad", columns={"t": "time", "a_ref": "field.desired.positions0",
                                               "a": "field.actual.positions0"})
    np.testing.assert_allclose(rad.measured[:, 0], np.degrees(np.array(_ACT) * 1e-6))


def test_rostopic_controller_state_of_several_joints_is_a_question(tmp_path):
    """The elements of ``field.desired.positionsN`` number the joints: several joints with both positions are a
    question naming them, never one axis with several commanded positions."""
    f = _rostopic(tmp_path / "arm.csv", joints=3)
    with pytest.raises(CaptureError, match=r"axes \[0, 1, 2\] each have a commanded and a measured position"):
        read_capture(f, unit="rad")


def test_numbers_split_at_their_decimal_commas_are_no_text_column(tmp_path):
    """Rows separated by ``|`` with decimal commas and digits grouped by points: split at the commas each row read
    as a number, a text cell (``5000000|23.024.915|...|0``) and a number, a table of three unnamed columns, and the
    file was refused as having no header (trace_fuzz seed 44000455; 44000332 the same with spaces). A cell of numbers
    set apart by another delimiter is no text: the digit grouping is named."""
    rows = ["Time|X Soll [nm]|X Ist [nm]|X Velocity [mm/s]"]
    rows += [f"12,{k:03d}|{23 + k}.024.915|{23 + k}.000.{100 + k}|17,5" for k in range(20)]
    f = tmp_path / "grouped.csv"
    f.write_text("\n".join(rows) + "\n", encoding="utf-8")
    with pytest.raises(CaptureError, match=r"'2\d\.024\.915' .*grouped by thousands") as err:
        read_capture(f)
    assert str(f) in str(err.value)


def test_klipper_log_is_named(tmp_path):
    """Klipper's klippy.log holds statistics lines (``Stats 100.0: ... print_time=...``), no positions: named, with
    its figures (it was 'no rows of numbers')."""
    f = tmp_path / "klippy.log"
    f.write_text("Starting Klippy...\n" + "".join(
        f"Stats {100 + k}.0: gcodein=0  mcu: mcu_awake=0.003 bytes_write=1234 print_time={k}.125 buffer_time=0.000 "
        f"print_stall=0 extruder: target=0 temp=25.0 pwm=0.000\n" for k in range(5)), encoding="utf-8")
    with pytest.raises(CaptureError, match=r"Klipper's klippy.log \(5 statistics lines.*mcu_awake.*open loop") as err:
        read_capture(f)
    assert str(f) in str(err.value)


def test_a_log_without_time_and_without_a_pair_names_the_positions_first(tmp_path):
    """A VESC Tool log (``ms_today;...;encoder_position;...``) has neither a time column by name nor a commanded
    position: the question names the missing pair before the missing time (it named the time alone, as if
    ``--sample-time`` would read it)."""
    rows = ["ms_today;input_voltage;current_motor;erpm;encoder_position;fault_code"]
    rows += [f"{36000000 + 10 * k};24.1;1.5;1000;{3.6 * k:.2f};0" for k in range(10)]
    f = tmp_path / "vesc.csv"
    f.write_text("\n".join(rows) + "\n", encoding="utf-8")
    with pytest.raises(CaptureError, match=r"no pair of a commanded and a measured position is named \(positions "
                                           r"found: \['encoder_position'\].*; and no column is named as time"):
        read_capture(f)


def test_rostopic_joint_states_name_the_missing_command(tmp_path):
    """``rostopic echo -p`` of sensor_msgs/JointState holds measured positions only: the question names the message
    and the topic that holds both (it listed ``field.position0`` as a position naming no role)."""
    rows = ["%time,field.header.seq,field.header.stamp,field.header.frame_id,field.name0,field.name1,field.position0,"
            "field.position1,field.velocity0,field.velocity1,field.effort0,field.effort1"]
    rows += [f"{1_700_000_000_000_000_000 + k * 1_000_000},{k},{1_700_000_000_000_000_000 + k * 1_000_000},,j0,j1,"
             f"{0.001 * k},{0.002 * k},0.1,0.2,0.0,0.0" for k in range(6)]
    f = tmp_path / "joint_states.csv"
    f.write_text("\n".join(rows) + "\n", encoding="utf-8")
    with pytest.raises(CaptureError, match=r"the joints' measured positions field\.positionN \(N = "
                                           r"\[0, 1\]\).*JointTrajectoryControllerState") as err:
        read_capture(f)
    assert str(f) in str(err.value)
