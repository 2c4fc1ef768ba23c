"""TNCscope curves in their own %DIMENSION: um, inch and deg read back as mm and deg.

Fixtures are written here from fadal-pid's x axis (random moves, 1 ms). Before this fix the
reader ignored %DIMENSION: a control in inches was read 25.4 times small, a curve in um 1000
times large, without a word (the traceid truth harness).
"""

from __future__ import annotations

import numpy as np
import pytest

import toolpaths
import vcnc
from vcnc.capture import read_capture
from vcnc.cli import main


@pytest.fixture(scope="module")
def capture():
    machine = vcnc.machine("fadal-pid")
    program = vcnc.parse_program(toolpaths.random_moves(4, 5.0, 6000.0, seed=3))
    return machine.simulate(vcnc.interpolate(program, machine), seed=0).select_axes(("x",)).slice(0, 400)


def _tnc(path, axis, dims, ref, act, fmt):
    lines = ["%TNCscopeNT data file", "%[GLOBAL]", "%CONTROL=TNC640", "%SAMPLING=1000"]
    for n, (ctype, dim) in enumerate(zip(("s soll", "s ist"), dims), start=1):
        lines += [f"%[CURVE{n}]", f"%NAME={ctype}/{axis}", f"%CHANNELTYPE={ctype}", f"%AXISTYPE={axis}",
                  f"%DIMENSION={dim}", f"%COLUMN={n}"]
    lines.append("%[DATA]")
    lines += [f"{k * 1000};{fmt.format(r)};{fmt.format(a)};" for k, (r, a) in enumerate(zip(ref, act))]
    path.write_bytes("\r\n".join(lines).encode("latin-1") + b"\r\n")


@pytest.mark.parametrize(("dims", "scale", "fmt"), [(("µm", "µm"), (1e3, 1e3), "{:.3f}"),
                                                    (("inch", "inch"), (1 / 25.4, 1 / 25.4), "{:.7f}"),
                                                    (("mm", "µm"), (1.0, 1e3), "{:.4f}")])
def test_position_curves_are_read_in_their_dimension(capture, tmp_path, dims, scale, fmt):
    ref, act = capture.reference[:, 0], capture.measured[:, 0]
    f = tmp_path / "x.sco"
    _tnc(f, "X", dims, ref * scale[0], act * scale[1], fmt)
    cap = read_capture(f)
    printed = [np.array([float(fmt.format(v)) for v in a * s]) / s for a, s in zip((ref, act), scale)]
    np.testing.assert_allclose(cap.reference[:, 0], printed[0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(cap.measured[:, 0], printed[1], rtol=0, atol=1e-12)
    assert "converted" in cap.meta


def test_rotary_axis_in_degrees_and_wrong_dimensions(capture, tmp_path, capsys):
    ref, act = capture.reference[:, 0] * 9, capture.measured[:, 0] * 9
    f = tmp_path / "c.sco"
    _tnc(f, "C", ("°", "°"), ref, act, "{:.4f}")
    cap = read_capture(f)
    assert cap.axes == ("c",) and "converted" not in cap.meta
    np.testing.assert_allclose(cap.reference[:, 0], np.round(ref, 4), atol=1e-12)
    _tnc(f, "C", ("mm", "mm"), ref, act, "{:.4f}")
    out = tmp_path / "c.csv"
    assert main(["convert", str(f), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "c.sco:5: curve 's soll/C': %DIMENSION='mm' is not a position unit of a rotary axis (expected °)" in err
    assert not out.exists()
    _tnc(f, "X", ("mm/min", "mm/min"), ref, act, "{:.4f}")
    assert main(["convert", str(f), "-o", str(out)]) == 2
    assert "%DIMENSION='mm/min' is not a position unit of a linear axis (expected mm, µm or inch)" in \
        capsys.readouterr().err
