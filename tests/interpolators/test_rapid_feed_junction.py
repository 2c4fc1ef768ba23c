"""The junction of a rapid and a feed move: a stop where the control stops there, passed at speed where it blends.

LinuxCNC (``src/emc/tp/tp.c`` ``handleModeChange``: "can't blend between rapid and feed motions"), Fanuc (G00:
"decelerated at the end of a block ... after confirming the in-position"), Haas and Fadal stop there under G64 too;
grbl (``planner.c`` ``plan_buffer_line``: the junction deviation bounds every junction) and the TNC (an FMAX block
within cycle 32's tolerance) pass it at speed (:attr:`interpolators.context.Dialect.rapid_feed_stop`).
"""

from __future__ import annotations

import numpy as np
import pytest

from interpolators import AxisLimits, interpolate, parse_program
from interpolators.context import DIALECTS, INTERPOLATION_CONTEXT
from tests.interpolators.setpoint_checks import check_limits

LIMITS = {a: AxisLimits(velocity=200.0, acceleration=2000.0, jerk=40_000.0, rapid=400.0) for a in "xyz"}

#: A rapid along X into a feed move on along X (collinear: the geometry alone passes the junction at the feed),
#: the same the other way, and a rapid into a tangent arc; the junction is at X50 Y0 in each.
ISO = {
    "rapid, then feed": "G21 G90 G64 P0.05\nG0 X50 Y0\nG1 X100 F3000\nM2\n",
    "feed, then rapid": "G21 G90 G64 P0.05\nG1 X50 Y0 F3000\nG0 X100\nM2\n",
    "rapid, then arc": "G21 G90 G64 P0.05\nG0 X50 Y0\nG2 X60 Y-10 I0 J-10 F3000\nM2\n",
}
TNC = {
    "rapid, then feed": "L X+50 Y+0 R0 FMAX\nL X+100 F3000\n",
    "feed, then rapid": "L X+50 Y+0 R0 F3000\nL X+100 FMAX\n",
}


def _junction_speed(text: str, dialect: str, profile: str) -> float:
    """The path speed [mm/s] of the sample at the end of the first block (the junction at X50 Y0) and the limits
    checked on the whole run."""
    prog = parse_program(text, context=INTERPOLATION_CONTEXT.with_dialect(dialect))
    assert prog.rapid_feed_stop == DIALECTS[dialect].rapid_feed_stop
    sp = interpolate(prog, limits=LIMITS, sample_time=0.001, profile=profile)
    check_limits(sp, prog, LIMITS, jerk=profile == "scurve", feed=True)
    k = int(np.argmin(np.linalg.norm(sp.position[:, :2] - [50.0, 0.0], axis=1)))
    assert np.linalg.norm(sp.position[k, :2] - [50.0, 0.0]) < 0.1
    return float(np.linalg.norm(sp.velocity[k]))


@pytest.mark.parametrize("dialect", ["linuxcnc", "fanuc", "haas", "fadal"])
@pytest.mark.parametrize("case", list(ISO))
@pytest.mark.parametrize("profile", ["trapezoid", "scurve"])
def test_the_control_stops_where_a_rapid_meets_a_feed_move_under_g64(dialect, case, profile):
    # before session 35 the rapid and the feed move were one look-ahead chain under G64 and the junction passed
    # at the feed, 50 mm/s (F3000); these controls stop there (sources: the module's docstring)
    assert _junction_speed(ISO[case], dialect, profile) < 1e-6


@pytest.mark.parametrize("case", list(ISO))
@pytest.mark.parametrize("profile", ["trapezoid", "scurve"])
def test_grbl_passes_the_junction_of_a_rapid_and_a_feed_move_at_speed(case, profile):
    # grbl has no G64: its planner blends every junction by the junction deviation; the text without G64 P
    text = ISO[case].replace(" G64 P0.05", "")
    assert _junction_speed(text, "grbl", profile) > 0.9 * 50.0  # at the feed F3000 = 50 mm/s, less a sample's change


@pytest.mark.parametrize("case", list(TNC))
def test_the_tnc_passes_an_fmax_block_s_junction_with_a_feed_move_at_speed(case):
    # within cycle 32's tolerance the TNC's look-ahead takes an L .. FMAX block as any straight line
    text = ("BEGIN PGM J MM\nCYCL DEF 32.0 TOLERANCE\nCYCL DEF 32.1 T0.05\nL X+0 Y+0 Z+0 R0 FMAX\n"
            + TNC[case] + "END PGM J MM\n")
    assert _junction_speed(text, "heidenhain", "trapezoid") > 0.9 * 50.0


def test_the_stop_costs_the_deceleration_and_the_start_it_adds():
    # the same program under linuxcnc and grbl: the rapid at 400 mm/s (reached: 40 mm to accelerate, 40 to
    # decelerate, of 200) decelerates to 0 instead of to the feed's 50 mm/s at 2000 mm/s^2: 50 / 2000 s more, less
    # the 50^2 / (2 * 2000) mm it then crosses at 400 mm/s instead (23.4 ms); the feed move starts from 0 and takes
    # 50 / 2000 s for its first 0.625 mm, which take 12.5 ms at 50 mm/s (12.5 ms); 35.9 ms in all, each chain's
    # end rounded to the 1 ms sample
    text = "G21 G90\nG0 X200 Y0\nG1 X250 F3000\nM2\n"
    times = [interpolate(parse_program(text, context=INTERPOLATION_CONTEXT.with_dialect(d)), limits=LIMITS,
                         sample_time=0.001).t[-1] for d in ("linuxcnc", "grbl")]
    assert times[0] - times[1] == pytest.approx(0.025 - 0.625 / 400 + 0.0125, abs=0.0015)
