"""Traces in the layouts of realtrace11's real set (session 35): a drive logger's headerless rows whose time column
is mapped by ``--columns`` but whose unit nobody states (nicolazande/camber-control's LinA logs: ms stamps stepping
by 10), an electro-hydraulic actuator's experiment export (ivliev123/Electro-Hydraulic-Actuator:
``EXP_Time;EXP_PosRef;EXP_PosFb;...``) and a Universal Robots joint log without a header (swiatecki/ProjectMoose:
robot time in s, six actual joint angles, ..., six target angles, in rad), and a halscope log with channels not
enabled (luminize/machinekit-motion-components). Each file is a few lines written here
after the layout, not the export itself.
"""

from __future__ import annotations

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError

_ROWS = [(0, 4.99, 0.0, 0.0), (10, 4.99, 0.5, 0.1), (20, 4.99, 1.5, 0.6), (30, 4.99, 2.5, 1.5), (40, 4.99, 3.0, 2.4),
         (50, 4.99, 3.0, 2.9)]


def _logger_rows(tmp_path):
    f = tmp_path / "pp-square-wave.txt"
    f.write_text("".join(f"{t}\t{target}\t{demand}\t{actual}\t0\t272\n" for t, target, demand, actual in _ROWS))
    return f


def test_a_mapped_time_column_without_a_unit_is_not_read_as_a_slow_sampling(tmp_path):
    """``--columns t=1,..`` says which column is the time, not its unit: ms stamps stepping by 10 were read as a 10 s
    sampling without a word; they are now a question naming the column and ``--time-unit``, as a time column read
    from its name is."""
    f = _logger_rows(tmp_path)
    with pytest.raises(CaptureError) as err:
        read_capture(f, columns={"t": "1", "x_ref": "3", "x": "4"})
    msg = str(err.value)
    assert str(f) in msg and "the time column '1' (mapped by --columns) steps by 10" in msg
    assert "--time-unit ms|us|s" in msg
    cap = read_capture(f, columns={"t": "1", "x_ref": "3", "x": "4"}, time_unit="ms")
    assert cap.sample_time == pytest.approx(0.010)
    np.testing.assert_array_equal(cap.measured[:, 0], [r[3] for r in _ROWS])
    # a unit given as seconds is taken at its word, however slow
    assert read_capture(f, columns={"t": "1", "x_ref": "3", "x": "4"}, time_unit="s").sample_time == 10.0


def test_a_mapped_time_column_at_a_drive_rate_needs_no_unit(tmp_path):
    """Seconds stepping by 2 ms, mapped by --columns: read as seconds, as before."""
    f = tmp_path / "log.txt"
    f.write_text("".join(f"{k * 0.002:.3f}\t{r[2]}\t{r[3]}\n" for k, r in enumerate(_ROWS)))
    cap = read_capture(f, columns={"t": "1", "x_ref": "2", "x": "3"})
    assert cap.sample_time == pytest.approx(0.002)


def test_an_electro_hydraulic_actuators_export_reads_without_options(tmp_path):
    """``EXP_PosRef``/``EXP_PosFb`` beside pressures, speed and current, ``;``-separated, time in s at 1 ms: the
    commanded and the measured position are read from the names."""
    f = tmp_path / "exp_data_1_1.csv"
    head = "EXP_Time;EXP_PosRef;EXP_PosFb;EXP_Pressure_A;EXP_Pressure_B;EXP_Speed;EXP_Velocity;Exp_Current\n"
    rows = [(0.000, 0.0, 0.0), (0.001, 0.0, 0.0), (0.002, 0.025, 0.0), (0.003, 0.05, 0.025), (0.004, 0.075, 0.025)]
    f.write_text(head + "".join(f"{t:.3f};{r:.3f};{m:.3f};1.250;0.300;0.000;0.000;0.000\n" for t, r, m in rows))
    cap = read_capture(f)
    assert cap.axes == ("x",) and cap.sample_time == pytest.approx(0.001)
    assert "x_ref=EXP_PosRef, x=EXP_PosFb" in cap.meta["columns"]
    np.testing.assert_array_equal(cap.reference[:, 0], [r[1] for r in rows])


def test_a_robot_joint_log_without_a_header_asks_for_its_columns_and_reads_in_radians(tmp_path):
    """A Universal Robots joint log: robot time [s] from the controller's start, a PC counter, q actual x6, qd
    actual x6, qdd target x6, qd target x6, q target x6 [rad], a flag; 8 ms. Without --columns a question; with them
    and --unit rad the base joint in degrees at 8 ms."""
    f = tmp_path / "log_kp18_step03.txt"
    q = [1.0906855, 1.0906855, 1.1, 1.12, 1.15]
    target = [1.0906950, 1.0906855, 1.11, 1.14, 1.17]
    lines = []
    for k, (a, r) in enumerate(zip(q, target)):
        row = [f"{18613.008 + 0.008 * k:.3f}", str(32272 + 8100 * k), f"{a}", *["-1.38"] * 5, *["0"] * 18, f"{r}",
               *["-1.38"] * 5, "0"]
        lines.append(",".join(row))
    f.write_text("\n".join(lines) + "\n")
    with pytest.raises(CaptureError, match="33 unnamed"):
        read_capture(f)
    cap = read_capture(f, columns={"t": "1", "a_ref": "27", "a": "3"}, unit="rad")
    assert cap.axes == ("a",) and cap.sample_time == pytest.approx(0.008)
    assert cap.t[-1] - cap.t[0] == pytest.approx(0.032)
    np.testing.assert_allclose(cap.measured[:, 0], np.degrees(q))


def test_halscopes_unused_channels_are_no_repeated_name(tmp_path):
    """A LinuxCNC 2.8 halscope log (label value pairs) of a motion planner's positions alone, beside channels not
    enabled, which halscope labels '(null)' (luminize/machinekit-motion-components' log): refused for what it
    lacks, a measured position, not because '(null)' repeats."""
    f = tmp_path / "halscope.log"
    row = ("interpolator.1.0.curr-pos {p:+.14f} interpolator.1.0.curr-vel +0.00000000000000 jplanner.0.curr-pos "
           "{p:+.14f} (null) +0.00000000000000 (null) +0.00000000000000 \n")
    f.write_text("Sampling period is 1000000 nSec \n\n" + "".join(row.format(p=0.001 * k) for k in range(6)))
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    msg = str(err.value)
    assert "repeats a name" not in msg and "a position trace needs a commanded and a measured position" in msg
