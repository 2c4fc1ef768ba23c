"""Secondary linear axes U, V, W: read, fed, offset and limited as LinuxCNC defines them.

Sources: LinuxCNC G-code overview, "Feed Rate" (https://linuxcnc.org/docs/html/gcode/overview.html)
and RS274/NGC 3 (NISTIR 6556, Sec. 2.1.2.5); LinuxCNC ``src/emc/task/emccanon.cc``
(``getStraightVelocity``: a move's distance is along XYZ if X, Y or Z moves, else along UVW, else
along ABC; ``rotate_and_offset_pos``: G92 and work offsets on all nine axes, the G10 R rotation on
X and Y only). U, V, W are parallel to X, Y, Z, in mm (inches under G20).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest

from interpolators import DEFAULT_SECONDARY_LIMITS, interpolate, load_program, parse_program
from interpolators.context import DEFAULT_CONTEXT, INTERPOLATION_CONTEXT, MachineContext
from interpolators.limits import DEFAULT_LIMITS, DEFAULT_ROTARY_LIMITS
from tests.interpolators.setpoint_checks import check_limits, trapezoid_time
from vcnc.cli import main
from vcnc.core.axes import AXIS_NAMES
from vcnc.engine.machine_file import parse_machine_text
from vcnc.errors import GCodeError, InputError

CTX = INTERPOLATION_CONTEXT
LIMITS = {**DEFAULT_LIMITS, **DEFAULT_ROTARY_LIMITS, **DEFAULT_SECONDARY_LIMITS}
CORPUS = Path(os.environ.get("VCNC_GCODE_CORPUS", Path(__file__).resolve().parents[3] / "shared" / "data"
                             / "gcode-corpus"))
U, V, W = 3, 4, 5  # columns of u, v, w in Block.extra_target (a, b, c, u, v, w)


def test_pure_uvw_move_feed_is_along_the_uvw_distance():
    prog = parse_program("G21 G90 G1 U30 V40 F600\n", context=CTX)
    (b,) = prog.blocks
    assert prog.axes == ("u", "v") and np.all(b.target == 0)
    assert b.feed == pytest.approx(10.0) and b.extra_length == pytest.approx(50.0)  # 600 mm/min along 50 mm
    sp = interpolate(prog)
    speed = np.hypot(sp.velocity[:, 0], sp.velocity[:, 1])
    assert speed.max() == pytest.approx(10.0, rel=1e-3)
    # V reaches its acceleration limit first: the path acceleration is 2000 / 0.8 mm/s^2
    assert sp.duration == pytest.approx(trapezoid_time(50.0, 10.0, 2000.0 / 0.8), abs=1.5e-3)
    assert np.allclose(sp.position[-1], [30, 40]) and np.allclose(sp.position[:, 0] * 4, sp.position[:, 1] * 3)
    check_limits(sp, prog, LIMITS)


def test_xyuv_move_feed_is_along_xy_with_uv_in_proportion():
    """A foam cutter's ruled surface: F along the XY path, U and V coordinated."""
    prog = parse_program("G21 G90 G1 X30 Y40 U60 V80 F600\n", context=CTX)
    sp = interpolate(prog)
    assert sp.axes == ("x", "y", "u", "v")
    x, y, u, v = sp.position.T
    assert np.hypot(sp.velocity[:, 0], sp.velocity[:, 1]).max() == pytest.approx(10.0, rel=1e-3)
    assert np.allclose(u, 2 * x) and np.allclose(v, 2 * y)
    # V (1.6 mm per mm of path) limits the path acceleration to 2000 / 1.6
    assert sp.duration == pytest.approx(trapezoid_time(50.0, 10.0, 2000.0 / 1.6), abs=1.5e-3)
    check_limits(sp, prog, LIMITS)


def test_uvw_with_rotary_and_no_xyz_feeds_along_uvw():
    """emccanon.cc getStraightVelocity: cartesian (U V W) and angular motion, X Y Z still: the
    distance is the U V W one, the rotary axis in proportion."""
    prog = parse_program("G21 G90 G1 W20 A90 F1200\n", context=CTX)
    (b,) = prog.blocks
    assert b.feed == pytest.approx(20.0) and b.extra_length == pytest.approx(20.0)
    sp = interpolate(prog)
    a, w = sp.position.T
    assert np.allclose(a, 4.5 * w)
    assert sp.velocity[:, 1].max() == pytest.approx(20.0, rel=1e-3)
    check_limits(sp, prog, LIMITS)


def test_xyz_with_uvw_feeds_along_xyz_only():
    prog = parse_program("G21 G90 G1 Z10 W30 F600\n", context=CTX)
    sp = interpolate(prog)
    assert sp.axes == ("z", "w") and sp.velocity[:, 0].max() == pytest.approx(10.0, rel=1e-3)
    assert sp.velocity[:, 1].max() == pytest.approx(30.0, rel=1e-3)


def test_incremental_inch_and_inverse_time():
    prog = parse_program("G21 G91 G1 U10 F600\nU10 V-5\nG20 U1 F600\nG90 G21 G93 U0 F2\nG94 G0 W3\n", context=CTX)
    ends = [b.extra_target[3:].tolist() for b in prog.blocks]
    assert ends == [[10, 0, 0], [20, -5, 0], [45.4, -5, 0], [0, -5, 0], [0, -5, 3]]
    assert prog.blocks[2].feed == pytest.approx(600 * 25.4 / 60)  # G20 F in/min, U in inches
    assert prog.blocks[3].feed == pytest.approx(45.4 * 2 / 60)  # G93: 45.4 mm in 1/2 min
    sp = interpolate(prog)
    assert sp.axes == ("u", "v", "w") and np.allclose(sp.position[-1], [0, -5, 3])
    on_g93 = sp.block == 3
    assert sp.duration > 30 and np.sum(on_g93) * sp.sample_time == pytest.approx(30.0, abs=0.05)
    check_limits(sp, prog, LIMITS)


def test_offsets_g92_g10_g53_and_reference_return():
    """Work and G92 offsets on U V W as on X Y Z (LinuxCNC rotate_and_offset_pos), G53 machine
    positions, G28 through the intermediate point to the reference."""
    text = ("G21 G90 G10 L2 P1 U5 V-2\n"  # G54's U V offsets
            "G0 U10 V10\n"  # machine U15 V8
            "G92 U0\n"  # the current U is now 0: G92 offset 10
            "G1 U1 F600\n"  # machine U16
            "G10 L20 P1 W7\n"  # the current W (0) is 7 in G54: offset -7
            "G0 W8\n"  # machine W1
            "G53 G0 U3\n"  # machine U3
            "G92.1\nG0 U1\n"  # G92 cleared: machine 1 + 5
            "G28 V0\n"  # through V0 (machine -2) to V's reference 0
            "G28\n")  # every axis to its reference
    prog = parse_program(text, context=CTX)
    ends = [b.extra_target[3:].tolist() for b in prog.blocks]
    assert ends == [[15, 8, 0], [16, 8, 0], [16, 8, 1], [3, 8, 1], [6, 8, 1], [6, -2, 1], [6, 0, 1], [0, 0, 0]]
    assert all(np.all(b.target == 0) for b in prog.blocks)  # the U V W offsets leave X Y Z alone


def test_arc_with_uv_words_moves_them_in_proportion():
    prog = parse_program("G21 G17 G90 G0 X10 Y0\nG3 X-10 Y0 I-10 J0 U20 V10 F600\n", context=CTX)
    sp = interpolate(prog, profile="scurve")
    on_arc = sp.block == 1
    x, y, u = (sp.position[on_arc, sp.axes.index(k)] for k in ("x", "y", "u"))
    turned = np.arctan2(y, x) / np.pi  # 0 .. 1 along the half circle
    assert np.allclose(u, 20 * turned, atol=1e-6)
    check_limits(sp, prog, LIMITS, jerk=True)


def test_limits_held_on_a_mixed_program_both_profiles():
    text = ("G21 G90 G64 P0.01 G0 X0 Y0 U0 V0\nG1 X10 Y10 U22.5 V22.5 F3000\nG1 Y35 U10 V35\n"
            "G2 R25 X35 Y60 U35 V60\nG1 U80 F6000\nG0 W50\nG1 X0 Y0 Z-5 U0 V0 W0 A30 F20000\n")
    prog = parse_program(text, context=CTX)
    for profile in ("trapezoid", "scurve"):
        sp = interpolate(prog, profile=profile)
        assert sp.axes == ("x", "y", "z", "a", "u", "v", "w")
        assert np.allclose(sp.position[-1], [0, 0, -5, 30, 0, 0, 0])
        check_limits(sp, prog, LIMITS, jerk=profile == "scurve")


def test_machine_without_the_axis_is_a_clear_error():
    with pytest.raises(GCodeError, match=r":1:\d+: axis word 'U' is not supported: this machine has no secondary "
                                         r"linear axis U \(axis words it takes: X, Y, Z\)"):
        parse_program("G21 G0 X1 U10\n", context=DEFAULT_CONTEXT)
    with pytest.raises(GCodeError, match="no secondary linear axis W .*axis words it takes: X, Y, Z, A, U"):
        parse_program("G21 G0 W10\n", context=MachineContext(extra_axes=("a", "u")))
    prog = parse_program("G21 G0 X1 U0\n", context=DEFAULT_CONTEXT)  # a U0 that moves nothing: a note
    assert prog.axes == ("x",) and any("U0" in n for n in prog.notes)
    with pytest.raises(InputError, match="no limits for secondary linear axis 'u'"):
        interpolate(parse_program("G21 G1 U10 F100\n", context=CTX), limits=DEFAULT_LIMITS)


@pytest.mark.parametrize("text, feature", [
    ("G21 G0 Z5\nG81 X1 Y1 Z-1 R1 W10 F100\n", "G81 drilling cycle with axis word W"),
    ("G21 G4 X1 U10\n", "word U not allowed in a dwell block"),  # with P, U is the modal motion's (linuxcnc)
    ("G21 G41.1 D2 G1 X10 F100\nX20 U30\n", "axis word U under cutter compensation"),
    ("G21 G5.1 X2 I1 J1 V10 F100\n", "G5 spline with axis word V"),
])
def test_unsupported_uses_name_the_feature(text, feature):
    with pytest.raises(GCodeError, match=feature):
        parse_program(text, context=CTX)


def test_machine_file_with_a_u_axis(tmp_path):
    fadal = (Path(__file__).resolve().parents[2] / "vcnc" / "machines" / "fadal-pid.toml").read_text()
    spec = parse_machine_text(re.sub(r"\[axes\.y", "[axes.u", fadal), file="xu.toml", default_name="xu")
    assert spec.context.extra_axes == ("u",) and "u" in spec.limits
    prog = parse_program("G21 G1 X1 U10 F600\n", context=spec.context)
    sp = interpolate(prog, limits=spec.limits)
    assert sp.axes == ("x", "u") and np.allclose(sp.position[-1], [1, 10])
    with pytest.raises(GCodeError, match="no secondary linear axis V"):
        parse_program("G21 G1 V1 F600\n", context=spec.context)


def test_cli_blocks_csv_columns_in_linuxcnc_order(tmp_path):
    prog = tmp_path / "uv.ngc"
    prog.write_text("G21 G90 G0 X1 U2 B3\nG1 W4 F600\n")
    out, blocks = tmp_path / "sp.csv", tmp_path / "blocks.csv"
    assert main(["interpolate", str(prog), "-o", str(out), "--blocks", str(blocks)]) == 0
    lines = blocks.read_text().splitlines()
    assert lines[0] == "block,line,kind,x,y,z,b,u,w,cx,cy,cz,feed"
    assert lines[2].split(",")[6:9] == ["3", "2", "4"] and lines[2].split(",")[-1] == "600"  # mm/min on W
    header = out.read_text().splitlines()[0].split(",")
    assert [h[:-4] for h in header[1:-1:3]] == ["x", "b", "u", "w"]
    assert AXIS_NAMES == ("x", "y", "z", "a", "b", "c", "u", "v", "w")


@pytest.mark.parametrize("name, axes", [("0010_cone.ngc", ("x", "y", "z", "b", "c", "w")),
                                        ("0105_foam.ngc", ("x", "y", "u", "v"))])
def test_corpus_uvw_programs_run_within_limits(name, axes):
    path = CORPUS / name
    if not path.is_file():
        pytest.skip(f"G-code corpus absent ({CORPUS}): set VCNC_GCODE_CORPUS to run the U V W corpus programs")
    prog = load_program(path, context=INTERPOLATION_CONTEXT)
    assert prog.axes == axes
    sp = interpolate(prog, sample_time=2e-3)
    last = prog.blocks[-1]
    end = dict(zip(AXIS_NAMES, [*last.target, *last.extra_target]))
    assert np.allclose(sp.position[-1], [end[a] for a in sp.axes])
    check_limits(sp, prog, LIMITS)
