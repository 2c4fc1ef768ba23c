"""Delimited traces in the layouts seen in tracewild4: a test rig's logger that prefixes every channel, a CNC's
variable trace that numbers its axes by array index in internal increments, maxon EPOS Studio's data recorder export
(its time column unnamed over a units row) and Mitsubishi's hexadecimal sampling output. Each file is a few lines
written here after a real export's layout (or the tool's reader or manual), not the export itself."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError
from vcnc.traces.names import columns_from_names, counted
from vcnc.traces.preamble import stated_turn_travel


def _motion(n: int = 300, dt: float = 1e-3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Time [s], commanded and measured position of a 2 Hz cosine move lagging by up to 0.02."""
    t = np.arange(n) * dt
    ref = 0.4 * (1 - np.cos(2 * np.pi * 2 * t))
    return t, ref, ref - 0.02 * np.sin(2 * np.pi * 2 * t)


_EHA = ["EXP_Time", "EXP_PosRef", "EXP_PosFb", "EXP_Pressure_A", "EXP_Pressure_B", "EXP_Speed", "EXP_Velocity",
        "Exp_Current"]


@pytest.mark.parametrize(("header", "result"), [
    # a logger's tag before every channel is set aside (ivliev123/Electro-Hydraulic-Actuator's processed exports)
    (_EHA, ({"t": "EXP_Time", "x_ref": "EXP_PosRef", "x": "EXP_PosFb"}, "")),
    (["run1.time", "run1.cmd", "run1.act"], ({"t": "run1.time", "x_ref": "run1.cmd", "x": "run1.act"}, "")),
    # a shared axis letter, role or numbering word means something and stays: not read as before
    (["X_time", "X_cmd", "X_act"],
     (None, "no column is named as time (only names with more than time words: ['X_time']; give --columns "
            "t=NAME,...)")),
    (["Set_time", "Set_x", "Set_y"],
     (None, "no column is named as time (only names with more than time words: ['Set_time']; give --columns "
            "t=NAME,...)")),
    # a shared quantity is no tag: velocities are not read as positions
    (["Geschw_Zeit", "Geschw_Soll", "Geschw_Ist"],
     (None, "no column is named as time (only names with more than time words: ['Geschw_Zeit']; give --columns "
            "t=NAME,...)")),
    (["Vel_time", "Vel_cmd", "Vel_act"],
     (None, "no column is named as time (only names with more than time words: ['Vel_time']; give --columns "
            "t=NAME,...)")),
    # a prefix on some names only is no shared tag
    (["EXP_Time", "PosRef", "EXP_PosFb"],
     (None, "no column is named as time (only names with more than time words: ['EXP_Time']; give --columns "
            "t=NAME,...)")),
])
def test_a_prefix_every_name_shares(header, result):
    assert columns_from_names(header) == result


def test_prefixed_logger_export_is_read(tmp_path):
    t, ref, act = _motion()
    f = tmp_path / "exp_data_1_1.csv"
    f.write_text(";".join(_EHA) + "\n" + "".join(f"{a:.3f};{b:.6f};{c:.6f};4.638;3.942;0.000;0.000;1420.900\n"
                                                  for a, b, c in zip(t, ref, act)))
    cap = read_capture(f)
    np.testing.assert_allclose(cap.t, t, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], ref, atol=1e-6)
    np.testing.assert_allclose(cap.measured[:, 0], act, atol=1e-6)
    assert cap.meta["columns"] == ("from the header names: t=EXP_Time, x_ref=EXP_PosRef, x=EXP_PosFb; not stated in "
                                   "the file, assumed t in s, x_ref in mm, x in mm (--columns, --time-unit, --unit set "
                                   "them)")


_PA = ["SSetPos[1]", "CommandedMachinePosCorr[1]", "SActMachinePos[1]", "SSetPos[2]", "CommandedMachinePosCorr[2]",
       "SActMachinePos[2]", "PathVelocity", "BlockNoActive"]


def test_an_array_index_is_no_unit_and_numbers_the_axis():
    # PA CNC's CNCVariableTrace: "[2]" is the axis' index, not a unit; two axes with a pair each are a question
    # naming the candidates, as is one axis with two commands (set position and corrected commanded position)
    assert counted("SActMachinePos[2]") == "internal increments"
    assert columns_from_names(_PA, period_known=True) == (
        None, "axes [1, 2] each have a commanded and a measured position (['CommandedMachinePosCorr[1]', "
              "'CommandedMachinePosCorr[2]', 'SActMachinePos[1]', 'SActMachinePos[2]', 'SSetPos[1]', 'SSetPos[2]']): "
              "give --columns for one")
    assert columns_from_names(_PA[:3], period_known=True) == (
        None, "axis x: several columns could be the commanded position: ['SSetPos[1]', 'CommandedMachinePosCorr[1]']")
    assert columns_from_names(["SSetPos[3]", "SActMachinePos[3]", "PathVelocity"], period_known=True) == (
        {"x_ref": "SSetPos[3]", "x": "SActMachinePos[3]"}, "")


def test_pa_variable_trace_in_internal_increments(tmp_path):
    # names separated by tabs, no time column (the machine's cycle), positions in internal increments (1 um by
    # default, PaDataAnalyze.py), a trailer line: read only with the sampling period and the increment's size
    t, ref, act = _motion()
    f = tmp_path / "CNCVariableTrace.txt"
    f.write_text("SSetPos[1]\tSActMachinePos[1]\tPathVelocity\n"
                 + "".join(f"{r * 1e3:.3f}\t{a * 1e3:.3f}\t62.800\n" for r, a in zip(ref, act)) + "PLC end\n")
    with pytest.raises(CaptureError, match=r"CNCVariableTrace.txt:1: which columns are time.*no column is named as "
                                           r"time \(a file without one needs --sample-time S"):
        read_capture(f)
    with pytest.raises(CaptureError, match=r"CNCVariableTrace.txt:1: x_ref='SSetPos\[1\]' is logged in increments "
                                           r"\('internal increments'\) and the file does not state their size"):
        read_capture(f, sample_time=0.001)
    cap = read_capture(f, sample_time=0.001, unit="1um")
    np.testing.assert_allclose(cap.t, t, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], ref, atol=1e-6)
    np.testing.assert_allclose(cap.measured[:, 0], act, atol=1e-6)
    assert cap.meta["commanded"] == "x:SSetPos[1]" and cap.meta["measured"] == "x:SActMachinePos[1]"


_EPOS_PREAMBLE = ("Date:;2020-07-08 21:54:05\nFirmware Version:;0x0120;0x6150;0x0000;0x0000\n"
                  "EPOS Studio Version:;3.6.1.0\nIndex:;0x6062;0x6064;0x0000;0x0000\nSubindex:;0x00;0x00;0x00;0x00\n"
                  "Max. samples:;300\nRecorded samples:;300\nSampling period:;1.000\n")


def test_epos_studio_recorder_export(tmp_path):
    # the time column's name is blank over "ms" in the units row; positions in quadcounts ask for their size
    t, ref, act = _motion()
    f = tmp_path / "epos.csv"
    f.write_text(_EPOS_PREAMBLE + ";Position demand value;Position actual value\nms;qc;qc\n"
                 + "".join(f"{a * 1e3:.3f};{round(b * 2000)};{round(c * 2000)}\n" for a, b, c in zip(t, ref, act)))
    with pytest.raises(CaptureError, match=r"epos.csv:9: x_ref='Position demand value' is logged in increments "
                                           r"\('qc'\) and the file does not state their size"):
        read_capture(f)
    cap = read_capture(f, unit="0.0005mm")
    np.testing.assert_allclose(cap.t, t, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref * 2000) / 2000, atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act * 2000) / 2000, atol=1e-12)
    assert cap.meta["columns"].startswith("from the header names: t=time, x_ref=Position demand value, "
                                          "x=Position actual value")


def test_epos_studio_speeds_and_torques_only(tmp_path):
    f = tmp_path / "200.csv"
    f.write_text(_EPOS_PREAMBLE + ";Velocity actual value averaged;Torque actual value averaged\nms;rpm;%\n"
                 + "".join(f"{k * 40:.3f};{k};0.5\n" for k in range(50)))
    with pytest.raises(CaptureError, match=r"200.csv:9: no position in the file: its columns \['time', 'Velocity "
                                           r"actual value averaged', 'Torque actual value averaged'\] are time"):
        read_capture(f)


def test_hexadecimal_sampling_output_is_named(tmp_path):
    # Mitsubishi CNC sampling with "#6 OUTPUT FORM" 1: one 8-digit hexadecimal value per channel per line
    f = tmp_path / "sampling.txt"
    f.write_text("".join(f"{v & 0xFFFFFFFF:08X}\n" for k in range(20) for v in (200000 + k, -3, 3)))
    with pytest.raises(CaptureError, match=r"sampling.txt:1: no rows of numbers separated by tab, ';', ',', '\|' or "
                                           r"spaces: "
                                           r"lines of one hexadecimal number each \(00030D40\) are a hexadecimal dump"):
        read_capture(f)


@pytest.mark.parametrize(("lines", "travel"), [
    (["Screw lead: 5 mm"], 5.0),
    (["Spindelsteigung [mm/U]; 10"], 10.0),
    (["lead = 0.2 in/rev", "Gear ratio: 3:1"], 0.2 * 25.4 / 3),
    (["# Screw lead: 5 mm", "# \u00dcbersetzung: 2"], 2.5),
    (["pitch: 0.5 rad"], None),  # an angle, no lead
    (["Lead: 5 deg"], None),
    (["Gear ratio: 3"], None),  # a ratio without a lead states no travel
    (["Screw lead: 5 mm", "Screw lead: 10 mm"], None),  # two leads that disagree state nothing
    (["Screw lead: 5 mm", "Gear ratio: 3:0"], None),  # a ratio stated unreadably: the lead alone would be a guess
    (["Screw lead: 5 mm", "Gear ratio: 2", "Gear ratio: 3"], None),  # two ratios that disagree
])
def test_stated_travel_of_a_motor_turn(lines, travel):
    found = stated_turn_travel(lines)
    assert (found[0] if found else None) == (pytest.approx(travel, rel=1e-12) if travel is not None else None)


@pytest.mark.parametrize(("unit", "per_unit"), [("turns", 2.5), ("rad", 2.5 / (2 * np.pi))])
def test_motor_turns_on_a_linear_axis_with_a_stated_lead(tmp_path, unit, per_unit):
    # a drive's log of its motor in turns (or radians) above which the screw's lead and the gear ratio are stated
    t, ref, act = _motion(50)
    f = tmp_path / "drive.csv"
    f.write_text("# Screw lead: 5 mm\n# Gear ratio: 2:1\n"
                 f"time [s],input_pos [{unit}],pos_estimate [{unit}]\n"
                 + "".join(f"{a:.3f},{b:.6f},{c:.6f}\n" for a, b, c in zip(t, ref, act)))
    cap = read_capture(f, columns={"t": "time [s]", "x_ref": f"input_pos [{unit}]", "x": f"pos_estimate [{unit}]"})
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref, 6) * per_unit, atol=1e-9)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act, 6) * per_unit, atol=1e-9)
    assert cap.meta["turn_travel"] == ("2.5 mm per motor turn for x_ref, x (lead stated in line 1 ('# Screw lead: 5 "
                                       "mm'), gear ratio in line 2 ('# Gear ratio: 2:1'))")
    # on a rotary axis turns stay turns, whatever the lead
    cap = read_capture(f, columns={"t": "time [s]", "a_ref": f"input_pos [{unit}]", "a": f"pos_estimate [{unit}]"})
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref, 6) * (360.0 if unit == "turns" else 180 / np.pi),
                               atol=1e-9)
    assert "turn_travel" not in cap.meta


@pytest.mark.parametrize(("header", "mapping"), [
    # Heidenhain scope channel types: "I ist" is a current, "v ist" a velocity (two axis letters), "s ist" the position
    (["x_s_soll", "x_s_ist", "x_s_diff", "x_v_ist", "x_i_ist"], {"x_ref": "x_s_soll", "x": "x_s_ist"}),
    (["s soll X", "s ist X", "v ist X", "I ist X"], {"x_ref": "s soll X", "x": "s ist X"}),
    # a PLC's Hungarian "i" (an integer) before act/set stays a position
    (["iSetPos", "iActPos"], {"x_ref": "iSetPos", "x": "iActPos"}),
])
def test_heidenhain_channel_types_in_names(header, mapping):
    assert columns_from_names(header, period_known=True) == (mapping, "")


def test_pylsv2_scope_csv(tmp_path):
    # pyLSV2's scope2csv.py: signal_channel names, values scaled to mm, no time column (its -i interval in us)
    t, ref, act = _motion()
    f = tmp_path / "scope.csv"
    f.write_text("x_s_soll,x_s_ist,x_v_ist,x_i_ist\n"
                 + "".join(f"{b:.6f},{c:.6f},1200.0,1.25\n" for b, c in zip(ref, act)))
    cap = read_capture(f, sample_time=0.003)
    np.testing.assert_allclose(cap.t, 3 * t, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], ref, atol=1e-6)
    np.testing.assert_allclose(cap.measured[:, 0], act, atol=1e-6)
    assert cap.meta["time_unit"] == "rows every 0.003 s"


def _camonitor_log(path, prefix: str, records: tuple[str, ...]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A camonitor log of the PVs ``prefix:record`` every 10 ms: the first record the command, the others the
    measured position."""
    t, ref, act = _motion(60, dt=0.01)
    lines = []
    for a, b, c in zip(t, ref, act):
        for k, record in enumerate(records):
            lines.append(f"{prefix}:{record} 2022-05-05 14:26:{11 + a:09.6f} {(b if k == 0 else c):.8f}")
    path.write_text("\n".join(lines) + "\n")
    return t, ref, act


def test_camonitor_pvs_are_read_by_their_record_names(tmp_path):
    # the device prefix TARGET_DU (ESS's target) names no command: X-PosCmd / X-PosAct read from the records
    f = tmp_path / "x.log"
    t, ref, act = _camonitor_log(f, "TARGET_DU", ("X-PosCmd", "X-PosAct", "X-LimitMax"))
    cap = read_capture(f)
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref, 8), atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act, 8), atol=1e-12)
    assert cap.meta["columns"] == "from the PV names: x_ref=TARGET_DU:X-PosCmd, x=TARGET_DU:X-PosAct"
    g = tmp_path / "rot.log"
    _camonitor_log(g, "TARGET_DU", ("Rotation-VelLastSectorAct", "Rotation-PosAct"))
    with pytest.raises(CaptureError, match=r"rot.log: which PVs are the commanded and measured positions\? .*by their "
                                           r"record names \['Rotation-VelLastSectorAct', 'Rotation-PosAct'\]: no pair "
                                           r"of a commanded and a measured position is named \(positions found: "
                                           r"\['Rotation-PosAct'\]"):
        read_capture(g)
