"""Rotary axes A, B, C: read, fed and limited as LinuxCNC and RS274/NGC 3 define them.

Feed semantics (RS274/NGC 3, NISTIR 6556, Sec. 2.1.2.5; LinuxCNC G-code overview, "Feed Rate"):
with X, Y or Z moving, F is along the XYZ path and the rotary axes move in proportion; with only
rotary axes moving, F is in deg/min along ``sqrt(dA^2 + dB^2 + dC^2)``; under G93 a block takes
``1/F`` minutes.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest

from interpolators import DEFAULT_LIMITS, interpolate, load_program, parse_program
from interpolators.context import DEFAULT_CONTEXT, INTERPOLATION_CONTEXT, MachineContext
from interpolators.limits import DEFAULT_ROTARY_LIMITS, AxisLimits
from tests.interpolators.setpoint_checks import check_limits, trapezoid_time
from vcnc.cli import main
from vcnc.commands.interpolate import blocks_table
from vcnc.core.axes import AXIS_NAMES
from vcnc.engine.machine_file import parse_machine_text
from vcnc.errors import GCodeError, InputError

CTX = MachineContext(extra_axes=("a", "b", "c"))
LIMITS = {**DEFAULT_LIMITS, **DEFAULT_ROTARY_LIMITS}
CORPUS = Path(os.environ.get("VCNC_GCODE_CORPUS", Path(__file__).resolve().parents[3] / "shared" / "data"
                             / "gcode-corpus"))


def test_pure_rotary_move_feed_is_degrees_per_minute():
    prog = parse_program("G21 G90 G1 A90 F600\n", context=CTX)
    (b,) = prog.blocks
    assert prog.axes == ("a",) and b.feed == pytest.approx(10.0)  # 600 deg/min
    assert b.extra_length == 90 and np.all(b.target == 0)
    sp = interpolate(prog)
    lim = DEFAULT_ROTARY_LIMITS["a"]
    # time = angle / feed plus the acceleration ramp, rounded up to whole samples
    assert sp.duration == pytest.approx(trapezoid_time(90.0, 10.0, lim.acceleration), abs=1.5e-3)
    # (the profile is slowed uniformly by < 0.1 % so that it ends on a sample)
    assert sp.position[-1, 0] == pytest.approx(90.0) and sp.velocity[:, 0].max() == pytest.approx(10.0, rel=1e-3)


def test_two_rotary_axes_share_the_feed_along_their_euclidean_distance():
    prog = parse_program("G21 G90 G1 A30 B40 F600\n", context=CTX)
    sp = interpolate(prog)
    assert prog.axes == ("a", "b")
    speed = np.hypot(sp.velocity[:, 0], sp.velocity[:, 1])
    assert speed.max() == pytest.approx(10.0, rel=1e-3)  # along D = sqrt(30^2 + 40^2) = 50 deg
    assert sp.duration == pytest.approx(trapezoid_time(50.0, 10.0, 1800.0 / 0.8), abs=1.5e-3)
    assert np.allclose(sp.position[:, 1] * 3, sp.position[:, 0] * 4)


def test_xyz_feed_with_rotary_in_proportion():
    prog = parse_program("G21 G90 G1 X10 A90 F600\n", context=CTX)
    sp = interpolate(prog)
    x, a = sp.position[:, 0], sp.position[:, 1]
    assert sp.axes == ("x", "a")
    assert np.allclose(a, 9.0 * x) and np.allclose(sp.velocity[:, 1], 9.0 * sp.velocity[:, 0])
    assert sp.velocity[:, 0].max() == pytest.approx(10.0, rel=1e-3)  # F along X: 600 mm/min
    # A reaches its acceleration limit first: the path acceleration is 1800 / 9 = 200 mm/s^2
    assert sp.duration == pytest.approx(trapezoid_time(10.0, 10.0, 200.0), abs=1.5e-3)
    check_limits(sp, prog, LIMITS)


def test_rotary_limit_caps_the_xyz_feed():
    prog = parse_program("G21 G90 G1 X1 A360 F6000\n", context=CTX)
    sp = interpolate(prog)
    assert np.abs(sp.velocity[:, 1]).max() == pytest.approx(DEFAULT_ROTARY_LIMITS["a"].velocity)
    check_limits(sp, prog, LIMITS)


def test_incremental_rotary_words_and_rapids():
    prog = parse_program("G21 G91 G0 A30\nA30\nG1 B-45 F600\nG90 C10 F600\n", context=CTX)
    assert [b.extra_target[:3].tolist() for b in prog.blocks] == [[30, 0, 0], [60, 0, 0], [60, -45, 0],
                                                                   [60, -45, 10]]
    sp = interpolate(prog)
    assert sp.axes == ("a", "b", "c") and np.allclose(sp.position[-1], [60, -45, 10])
    assert np.abs(sp.velocity[:, 0]).max() <= DEFAULT_ROTARY_LIMITS["a"].rapid_rate
    check_limits(sp, prog, LIMITS)


def test_inverse_time_with_rotary():
    prog = parse_program("G21 G90 G93 G1 X10 A90 F6\nA0 F2\n", context=CTX)
    b1, b2 = prog.blocks
    assert b1.feed == pytest.approx(10.0 * 6 / 60)  # XYZ length over 1/6 min
    assert b2.feed == pytest.approx(90.0 * 2 / 60)  # pure rotary: its rotary distance over 1/2 min
    sp = interpolate(prog)
    t1 = trapezoid_time(10.0, 1.0, 200.0)
    t2 = trapezoid_time(90.0, 3.0, 1800.0)
    assert sp.duration == pytest.approx(t1 + t2, abs=3e-3)
    check_limits(sp, prog, LIMITS)


def test_arc_with_a_rotary_word_turns_it_along_the_arc():
    prog = parse_program("G21 G17 G90 G0 X10 Y0\nG3 X-10 Y0 I-10 J0 A180 F600\n", context=CTX)
    sp = interpolate(prog)
    on_arc = sp.block == 1
    x, y, a = (sp.position[on_arc, sp.axes.index(k)] for k in ("x", "y", "a"))
    angle = np.degrees(np.arctan2(y, x))
    assert np.allclose(a, angle, atol=1e-6)  # 180 deg over the half circle, in proportion to its length
    check_limits(sp, prog, LIMITS)


def test_reference_return_machine_coordinates_and_offsets():
    prog = parse_program("G21 G90 G54 G0 X5 A45\nG91 G28 A0\nG90 G53 G0 B30\nG0 A10\nG28\n",
                         context=MachineContext(extra_axes=("a", "b"), work_offsets={"G54": (1, 2, 3)}))
    ends = [b.extra_target[:3].tolist() for b in prog.blocks]
    # G28 A0 incremental: through the current angle (intermediate point +0) to the reference 0
    assert ends == [[45, 0, 0], [45, 0, 0], [0, 0, 0], [0, 30, 0], [10, 30, 0], [0, 0, 0]]
    assert prog.blocks[0].target.tolist() == [6, 0, 0]  # the work offset applies to X Y Z only


def test_rotary_g92_and_g10_offsets_as_linuxcnc():
    """LinuxCNC emccanon.cc rotate_and_offset_pos adds the G92 and work offsets of A, B, C too."""
    prog = parse_program("G21 G90 G0 A10\nG92 A0\nG0 A5\nG92.1\nG10 L2 P1 B-20\nG0 B0\nG91 B5\n", context=CTX)
    assert [b.extra_target[:3].tolist() for b in prog.blocks] == [[10, 0, 0], [15, 0, 0], [15, -20, 0],
                                                                   [15, -15, 0]]


def test_limits_held_both_profiles_on_a_mixed_program():
    text = ("G21 G90 G64 P0.01 G0 X0 Y0 Z5 A0\nG1 Z0 F1200\nG1 X20 A90 F3000\nG1 Y20 B-30\nG2 X0 Y20 I-10 J0 A180\n"
            "G1 A270 F6000\nG0 X0 Y0 A0 B0\nG1 X5 F3000\nX10\nY5\n")
    prog = parse_program(text, context=CTX)
    for profile in ("trapezoid", "scurve"):
        sp = interpolate(prog, profile=profile)
        assert sp.axes == ("x", "y", "z", "a", "b")
        ends = np.array([np.r_[b.target, b.extra_target[:2]] for b in prog.blocks])
        assert np.allclose(sp.position[-1], ends[-1])
        check_limits(sp, prog, LIMITS, jerk=profile == "scurve")


def test_non_rotary_program_has_no_rotary_positions():
    prog = parse_program("G21 G90 G1 X10 F600\n", context=CTX)
    assert prog.blocks[0].extra_start is None and prog.axes == ("x",)


def test_machine_without_the_axis_is_a_clear_error():
    with pytest.raises(GCodeError, match="this machine has no rotary axis B"):
        parse_program("G21 G0 X1 B10\n", context=DEFAULT_CONTEXT)
    with pytest.raises(GCodeError, match="no rotary axis C .*axis words it takes: X, Y, Z, A"):
        parse_program("G21 G0 C10\n", context=MachineContext(extra_axes=("a",)))
    with pytest.raises(InputError, match="no limits for rotary axis 'a'"):
        interpolate(parse_program("G21 G1 A10 F100\n", context=CTX),
                    limits={"x": AxisLimits(velocity=1, acceleration=1)})


def test_machine_file_declares_its_rotary_axes(tmp_path, capsys):
    fadal = (Path(__file__).resolve().parents[2] / "vcnc" / "machines" / "fadal-pid.toml").read_text()
    rotary = re.sub(r"\[axes\.y", "[axes.a", fadal)
    spec = parse_machine_text(rotary, file="rotary.toml", default_name="rotary")
    assert spec.context.extra_axes == ("a",)
    assert parse_machine_text(fadal, file="fadal.toml", default_name="fadal").context.extra_axes == ()
    prog = parse_program("G21 G1 X1 A10 F600\n", context=spec.context)
    assert prog.axes == ("x", "a")
    prog_file = tmp_path / "b.ngc"
    prog_file.write_text("G21 G90 G1 X1 B10 F600\n")
    assert main(["simulate", str(prog_file), "--machine", "fadal-pid", "-o", str(tmp_path / "c.csv")]) == 2
    err = capsys.readouterr().err
    assert f"{prog_file}:1:15: axis word 'B' is not supported: this machine has no rotary axis B" in err
    assert not (tmp_path / "c.csv").exists()


def test_cli_blocks_csv_has_rotary_columns(tmp_path, capsys):
    prog = tmp_path / "rot.ngc"
    prog.write_text("G21 G90 G0 X1 A10\nG1 A40 F600\nG4 P0.5\nG3 X-1 Y0 I-1 J0 A0 F600\n")
    out, blocks = tmp_path / "sp.csv", tmp_path / "blocks.csv"
    assert main(["interpolate", str(prog), "-o", str(out), "--blocks", str(blocks)]) == 0
    lines = blocks.read_text().splitlines()
    assert lines[0] == "block,line,kind,x,y,z,a,cx,cy,cz,feed"
    assert [r.split(",")[6] for r in lines[1:]] == ["10", "40", "40", "0"]
    assert lines[2].split(",")[-1] == "600"  # the pure rotary move's feed [deg/min]
    header = out.read_text().splitlines()[0].split(",")
    assert header[-4:] == ["a_ref", "a_vel", "a_acc", "block"]
    header_rows = blocks_table(parse_program("G21 G1 X1 F100\n", context=CTX))[0]
    assert "a" not in header_rows  # columns only for the rotary axes the program uses


CORPUS_ROTARY = ("0004_b-index.ngc", "0011_daisy.ngc", "0284_1-Spool.nc")


@pytest.mark.parametrize("name", CORPUS_ROTARY)
def test_corpus_rotary_programs_run_within_limits(name):
    path = CORPUS / name
    if not path.is_file():
        pytest.skip(f"G-code corpus absent ({CORPUS}): set VCNC_GCODE_CORPUS to run the rotary corpus programs")
    prog = load_program(path, context=INTERPOLATION_CONTEXT)
    assert any(a in prog.axes for a in "abc")
    sp = interpolate(prog, sample_time=2e-3)
    last = prog.blocks[-1]
    end = dict(zip(AXIS_NAMES, [*last.target, *last.extra_target]))
    assert np.allclose(sp.position[-1], [end[a] for a in sp.axes])
    check_limits(sp, prog, LIMITS)


def test_inch_programs_scale_xyz_but_not_angles():
    prog = parse_program("G20 G90 G1 A90 F600\nX1 A0\n", context=CTX)
    assert prog.blocks[0].feed == pytest.approx(10.0)  # 600 deg/min: angles are never scaled by G20
    assert prog.blocks[1].feed == pytest.approx(600 * 25.4 / 60) and prog.blocks[1].target[0] == 25.4


@pytest.mark.parametrize("text, feature", [
    ("G21 G0 Z5\nG81 X1 Y1 Z-1 R1 A10 F100\n", "G81 drilling cycle with axis word A"),
    ("G21 G4 X1 A10\n", "word A not allowed in a dwell block"),  # with P, A is the modal motion's (linuxcnc)
    ("G21 G41.1 D2 G1 X10 F100\nX20 A30\n", "axis word A under cutter compensation"),
    ("G21 G5.1 X2 I1 J1 A10 F100\n", "G5 spline with axis word A"),
])
def test_unsupported_rotary_uses_name_the_feature(text, feature):
    with pytest.raises(GCodeError, match=feature):
        parse_program(text, context=CTX)


def test_simulate_report_gives_rotary_errors_in_mdeg(tmp_path):
    """`vcnc simulate` on a machine with X and A: the A tracking error is labelled mdeg in the
    report's table and figure, and the path figure holds only the linear axes."""
    fadal = (Path(__file__).resolve().parents[2] / "vcnc" / "machines" / "fadal-pid.toml").read_text()
    machine = tmp_path / "xa.toml"
    machine.write_text(re.sub(r"\[axes\.y", "[axes.a", fadal))
    prog = tmp_path / "p.ngc"
    prog.write_text("G21 G90 G0 X0 A0\nG1 F600 X10 A30\nG0 A0\nM2\n")
    report = tmp_path / "sim"
    assert main(["simulate", str(prog), "--machine", str(machine), "-o", str(tmp_path / "c.csv"),
                 "--report", str(report)]) == 0
    html = (report / "index.html").read_text()
    assert "mdeg" in html and "um" in html
    assert (report / "tracking.png").is_file()
    assert not (report / "path.png").exists()  # one linear axis moves: no XY path to draw
