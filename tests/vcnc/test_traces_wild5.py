"""Traces in the layouts seen in tracewild5: the ODrive GUI's export (``NaN`` before a channel arrives, positions
without a command), an MTConnect agent's streams document and an adapter's SHDR lines (named, not read), halsampler
output beside a LinuxCNC INI, a motor's degrees on a linear axis under a stated lead, and words of hexadecimal letters
that are no hexadecimal dump. Each file is a few lines written here after a real export's layout (or the tool's
documentation), not the export itself."""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError
from vcnc.traces import trace_format
from vcnc.traces.preamble import stated_turn_travel


def _motion(n: int = 300, dt: float = 1e-3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Time [s], commanded and measured position of a 2 Hz cosine move lagging by up to 0.02."""
    t = np.arange(n) * dt
    ref = 0.4 * (1 - np.cos(2 * np.pi * 2 * t))
    return t, ref, ref - 0.02 * np.sin(2 * np.pi * 2 * t)


def test_nan_cells_are_missing_values_and_the_header_stays(tmp_path):
    # the ODrive GUI writes NaN for a channel not yet received; before, the rows with many NaN ended the table and a
    # row of numbers became the header
    t, ref, act = _motion(40)
    f = tmp_path / "odrive.csv"
    rows = [f"{a:.3f},NaN,{c:.6f},NaN\n" if k < 3 else f"{a:.3f},{b:.6f},{c:.6f},{0.1 * k:.3f}\n"
            for k, (a, b, c) in enumerate(zip(t, ref, act))]
    f.write_text("time,input_pos,pos_estimate,Iq_measured\n" + "".join(rows))
    cap = read_capture(f, columns={"t": "time", "x_ref": "input_pos", "x": "pos_estimate"})
    assert cap.t.size == 37  # the three rows without a commanded position are skipped, as empty cells are
    np.testing.assert_allclose(cap.t, t[3:] - t[3], atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref[3:], 6), atol=1e-9)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act[3:], 6), atol=1e-9)


def test_positions_without_a_command_are_named(tmp_path):
    # the ODrive GUI's export of a cable robot: positions, velocities and currents of four drives, no setpoint
    f = tmp_path / "up1.csv"
    names = [f"ODrive {k} {q}" for q in ("Position", "Velocity", "Current") for k in range(2)]
    f.write_text("time," + ",".join(names) + "\n"
                 + "".join(f"{0.05 * k:.3f},NaN,{1.49 + 1e-4 * k:.6f},NaN,0.001,NaN,0.17\n" for k in range(30)))
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    msg = str(err.value)
    assert "up1.csv:1: which columns are time, commanded and measured position?" in msg
    assert ("positions that name neither a command nor a measurement: ['ODrive 0 Position', 'ODrive 1 Position']; "
            "other quantities: ['ODrive 0 Velocity', 'ODrive 1 Velocity', 'ODrive 0 Current', 'ODrive 1 Current']); "
            "a position trace needs a commanded and a measured position)") in msg


_STREAMS = """<?xml version="1.0" encoding="UTF-8"?>
<MTConnectStreams xmlns="urn:mtconnect.org:MTConnectStreams:1.3">
  <Header creationTime="2015-12-30T15:58:38Z" sender="agent" instanceId="1" version="1.3.0.15"/>
  <Streams><DeviceStream name="MachiningCenter" uuid="mc1">
    <ComponentStream component="Linear" name="X" componentId="x1"><Samples>
{samples}
    </Samples></ComponentStream>
    <ComponentStream component="Path" name="path" componentId="p1"><Samples>
      <PathPosition dataItemId="p1pos" timestamp="2015-12-30T15:15:15.820Z" name="p1LPathPos"
        sequence="9">1 2 3</PathPosition>
    </Samples></ComponentStream>
  </DeviceStream></Streams>
</MTConnectStreams>
"""


def _position(name: str, sub: str, k: int) -> str:
    return (f'      <Position dataItemId="M{name}" timestamp="2015-10-15T03:54:52.{k:03d}Z" name="{name}" '
            f'sequence="{k}" subType="{sub}">{93.2 + k:.3f}</Position>')


def test_mtconnect_streams_document_is_named_with_its_positions(tmp_path):
    # an agent's /sample answer (an Okuma machining center's: ACTUAL positions in machine and work coordinates)
    f = tmp_path / "sample.xml"
    f.write_text(_STREAMS.format(samples="\n".join(_position(n, "ACTUAL", k) for k in range(3)
                                                    for n in ("X1actm", "X1actw"))))
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    msg = str(err.value)
    assert msg.startswith(f"{f}: an MTConnect streams document (an agent's /sample or /current answer)")
    assert ("its position samples: X1actm (ACTUAL) x3, X1actw (ACTUAL) x3, p1LPathPos (PathPosition) x1; no "
            "COMMANDED position among them.") in msg


def test_mtconnect_streams_with_commanded_positions_is_still_no_trace(tmp_path):
    f = tmp_path / "sample.xml"
    text = _STREAMS.format(samples="\n".join(_position(n, s, k) for k in range(2)
                                             for n, s in (("Xcom", "COMMANDED"), ("Xact", "ACTUAL"))))
    f.write_text(text.replace("<MTConnectStreams", "<m:MTConnectStreams").replace("</MTConnectStreams",
                                                                                  "</m:MTConnectStreams"))
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    msg = str(err.value)
    assert "its position samples: Xcom (COMMANDED) x2, Xact (ACTUAL) x2, p1LPathPos (PathPosition) x1. vcnc" in msg
    assert "no COMMANDED" not in msg


def test_mtconnect_shdr_stream_is_named_with_its_keys(tmp_path):
    # an adapter's lines as the cppagent wiki's "SHDR 2.0" shows them
    f = tmp_path / "adapter.log"
    f.write_text("2009-06-15T00:00:00.000000|power|ON|execution|ACTIVE|line|412\n"
                 + "".join(f"2009-06-15T00:00:00.{k:03d}000|Xact|{-1.17 + k:.4f}|Xcom|{-1.16 + k:.4f}\n"
                           for k in range(5)))
    assert trace_format(f) == "shdr"
    with pytest.raises(CaptureError, match=r"adapter.log: an MTConnect SHDR adapter stream \(timestamp\|key\|value "
                                           r"lines, cppagent wiki 'SHDR 2.0'\).*keys: \['power', 'execution', 'line', "
                                           r"'Xact', 'Xcom'\]"):
        read_capture(f)


def test_a_table_with_a_bar_in_a_cell_is_no_shdr(tmp_path):
    t, ref, act = _motion(20)
    f = tmp_path / "log.csv"
    f.write_text("time;X|cmd;X|act\n" + "".join(f"{a:.3f};{b:.6f};{c:.6f}\n" for a, b, c in zip(t, ref, act)))
    assert trace_format(f) == "delimited"


def _halsampler(tmp_path):
    t, ref, act = _motion(50)
    f = tmp_path / "data.txt"
    f.write_text("".join(f"{b:f} {c:f} \n" for b, c in zip(ref, act)))
    return f


def test_halsampler_output_names_the_servo_period_an_ini_beside_it_states(tmp_path):
    f = _halsampler(tmp_path)
    (tmp_path / "mill.ini").write_text("[EMC]\nMACHINE = mill\n\n[EMCMOT]\nEMCMOT = motmod\nSERVO_PERIOD = 1000000\n")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert str(err.value).endswith("(not read from the names: the file has no header line); mill.ini beside it states "
                                   "[EMCMOT] SERVO_PERIOD (line 6): if the sampler ran in the servo thread, give "
                                   "--sample-time 0.001")
    with pytest.raises(CaptureError, match=r"--columns needs t=NAME \(the time column\), or --sample-time S for a file "
                                           r"without one \(halsampler\); mill.ini beside it states \[EMCMOT\] "
                                           r"SERVO_PERIOD \(line 6\).*--sample-time 0.001"):
        read_capture(f, columns={"x_ref": "1", "x": "2"})
    cap = read_capture(f, columns={"x_ref": "1", "x": "2"}, sample_time=0.001)  # given, it reads
    assert cap.t.size == 50 and cap.t[1] == pytest.approx(0.001)


@pytest.mark.parametrize("inis", [
    {"a.ini": "[EMCMOT]\nSERVO_PERIOD = 1000000\n", "b.ini": "[EMCMOT]\nSERVO_PERIOD = 500000\n"},  # they disagree
    {"a.ini": "[TRAJ]\nSERVO_PERIOD = 1000000\n"},  # not the motion section's
    {},
])
def test_no_servo_period_is_named_unless_one_ini_states_one(tmp_path, inis):
    f = _halsampler(tmp_path)
    for name, text in inis.items():
        (tmp_path / name).write_text(text)
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert str(err.value).endswith("(not read from the names: the file has no header line)")


def test_motor_degrees_on_a_linear_axis_with_a_stated_lead(tmp_path):
    t, ref, act = _motion(50)
    f = tmp_path / "drive.csv"
    f.write_text("# Screw lead: 5 mm\n# Gear ratio: 2:1\ntime [s],pos_cmd [deg],pos_act [deg]\n"
                 + "".join(f"{a:.3f},{b:.6f},{c:.6f}\n" for a, b, c in zip(t, ref, act)))
    cap = read_capture(f, columns={"t": "time [s]", "x_ref": "pos_cmd [deg]", "x": "pos_act [deg]"})
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref, 6) * 2.5 / 360, atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], np.round(act, 6) * 2.5 / 360, atol=1e-12)
    assert cap.meta["turn_travel"].startswith("2.5 mm per motor turn for x_ref, x (lead stated in line 1")
    # without a lead, degrees on a linear axis stay an error that says how to give the travel of one degree
    g = tmp_path / "nolead.csv"
    g.write_text(f.read_text().split("\n", 2)[2])
    with pytest.raises(CaptureError, match=r"axes \['x'\] are linear; a linear axis logged in degrees of its motor "
                                           r"takes the travel of one degree as its unit \(the lead over 360"):
        read_capture(g, columns={"t": "time [s]", "x_ref": "pos_cmd [deg]", "x": "pos_act [deg]"})


def test_a_gear_ratio_below_one_is_named_in_the_note():
    travel, said = stated_turn_travel(["Screw lead: 5 mm", "Gear ratio: 1:2"])
    assert travel == pytest.approx(10.0)
    assert said.endswith("a ratio below 1 (the motor slower than the screw) is read as motor turns per screw turn "
                         "all the same: if the file means screw turns per motor turn, give --unit with the travel of "
                         "one turn")
    assert "below 1" not in stated_turn_travel(["Screw lead: 5 mm", "Gear ratio: 3"])[1]


@pytest.mark.parametrize("lines", [
    ["Added", "Faced", "Decade"],  # words of hexadecimal letters, no digit
    ["DEADBEEF", "CAFEBABE"],
    ["1234", "5678", "9012"],  # decimal numbers, one per line
    ["00030D40", "FFFFFFFD1"],  # widths differ
    ["00030D40"],  # one line
])
def test_words_of_hex_letters_are_no_hexadecimal_dump(tmp_path, lines):
    f = tmp_path / "notes.txt"
    f.write_text("\n".join(lines) + "\n")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    msg = str(err.value)
    assert "no rows of numbers separated by tab, ';', ',', '|' or spaces" in msg
    assert "hexadecimal dump" not in msg


def test_a_nan_between_numbers_is_a_lost_value(tmp_path):
    # leading NaN cells are a channel not yet recorded; one between two numbers of a used column is an error naming it
    t, ref, act = _motion(20)
    cells = [f"{a:.3f},{b:.6f},{c:.6f}" for a, b, c in zip(t, ref, act)]
    cells[0] = f"{t[0]:.3f},NaN,{act[0]:.6f}"
    cells[7] = f"{t[7]:.3f},{ref[7]:.6f},nan"
    f = tmp_path / "log.csv"
    f.write_text("time,cmd,act\n" + "\n".join(cells) + "\n")
    with pytest.raises(CaptureError, match=r"log.csv:9:3: not a number in column 3 \('act', used as x\).*'nan'"):
        read_capture(f, columns={"t": "time", "x_ref": "cmd", "x": "act"})
