"""Ready-made programs: style of the thesis tables, determinism, parse and interpolate."""

from __future__ import annotations

import re

import numpy as np
import pytest

import toolpaths as tp
from interpolators import interpolate, load_program, parse_program


def test_random_moves_table_3_2_style():
    text = tp.random_moves(200, 10.0, 12000.0, seed=7)
    lines = text.splitlines()
    assert lines[0] == "G21 G61"  # mm and exact stop stated, not left to the control's default
    assert lines[1] == "N0000 G00 X0.000 F12000"
    for ln in lines[2:-1]:
        assert re.fullmatch(r"N\d{4} G01 X[ -]\d\.\d{3}", ln), ln
    assert lines[-1].endswith("M30")
    assert text == tp.random_moves(200, 10.0, 12000.0, seed=7)
    assert text != tp.random_moves(200, 10.0, 12000.0, seed=8)
    prog = parse_program(text)
    targets = np.array([b.target[0] for b in prog.blocks[1:]])
    assert len(targets) == 200 and np.abs(targets).max() <= 10.0
    assert all(b.feed == pytest.approx(200.0) for b in prog.blocks[1:])  # F12000 mm/min = 200 mm/s


@pytest.mark.parametrize("kind, bound", [("slow", 0.030), ("fast", 10.0)])
def test_heidenhain_identification(kind, bound):
    text = tp.heidenhain_identification(kind, seed=1)
    assert text.startswith("0 BEGIN PGM RAPIDIDENT MM\n;Rapid Identification")
    assert "3 TOOL CALL 0 Z" in text and "F 15000.000" in text
    prog = parse_program(text)
    assert prog.dialect == "heidenhain"
    x = [b.target[0] for b in prog.blocks if b.kind == "line"]
    assert max(abs(v) for v in x) <= bound
    assert all(b.feed == pytest.approx(250.0) for b in prog.blocks if b.kind == "line")


@pytest.mark.parametrize("dialect", ["iso", "heidenhain"])
def test_shapes_parse_and_interpolate(dialect, tmp_path):
    for text, n_axes in ((tp.circle(5.0, 6000.0, center=(1, 2), dialect=dialect), 2),
                         (tp.diamond(10.0, 6000.0, dialect=dialect), 2),
                         (tp.back_and_forth(20.0, 4242.6, dialect=dialect), 2),
                         (tp.back_and_forth(5.0, 600.0, axes=("z",), dialect=dialect), 1)):
        f = tmp_path / "p.nc"
        tp.write_program(text, f)
        prog = load_program(f)
        assert prog.dialect == dialect and len(prog.axes) == n_axes
        sp = interpolate(prog)
        assert np.abs(sp.position[-1] - prog.end_position[[("x", "y", "z").index(a) for a in sp.axes]]).max() == 0


def test_circle_geometry():
    prog = parse_program(tp.circle(10.0, 12000.0, center=(1.0, -1.0), ccw=False))
    arc = prog.blocks[-1].segment
    assert np.allclose(arc.center[:2], [1.0, -1.0]) and arc.radius == pytest.approx(10.0)
    assert arc.sweep == pytest.approx(-2 * np.pi)


def test_back_and_forth_is_thesis_validation_move():
    prog = parse_program(tp.back_and_forth())
    ends = [b.target[:2] for b in prog.blocks if b.kind == "line"]
    assert np.allclose(np.linalg.norm(ends[0]), 20.0, atol=1e-4)
    assert np.allclose(ends[0], [14.1421, 14.1421])
    assert prog.blocks[1].feed == pytest.approx(70.71, abs=1e-3)


def test_bad_arguments():
    from vcnc.errors import InputError

    with pytest.raises(InputError):
        tp.circle(-1.0)
    with pytest.raises(InputError):
        tp.random_moves(0)
    with pytest.raises(InputError):
        tp.heidenhain_identification("medium")
    with pytest.raises(InputError):
        tp.diamond(10.0, dialect="fanuc")
