"""``vcnc machines`` and ``vcnc simulate``: output contracts, exit statuses, no partial output."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

import interpolators
import vcnc
from interpolators.context import DEFAULT_CONTEXT
from vcnc.cli import main
from vcnc.commands.machines import PROGRAM_TABLE_DOC
from vcnc.engine.machine import builtin_machine_text, builtin_machines, load_machine
from vcnc.errors import GCodeError, InputError

PROGRAM = "G90 G21\nG00 X0 Y0\nG01 X5 F3000\nG01 X5 Y5\nG01 X0 Y0\nM30\n"


@pytest.fixture
def program(tmp_path: Path) -> Path:
    p = tmp_path / "part.nc"
    p.write_text(PROGRAM)
    return p


def test_machines_lists_all(capsys) -> None:
    assert main(["machines"]) == 0
    out = capsys.readouterr().out
    for n in builtin_machines():
        assert n in out


def test_machines_show_prints_toml(capsys, tmp_path) -> None:
    assert main(["machines", "--show", "fadal-pid"]) == 0
    out = capsys.readouterr().out
    text = builtin_machine_text("fadal-pid").strip()
    assert out.startswith(text) and out.rstrip().endswith(PROGRAM_TABLE_DOC.rstrip())
    # the documented [program] table, uncommented, is a valid machine file whose defaults change nothing
    doc = "\n".join(ln[2:] if ln.startswith(("# [", "# G54", "# length", "# radius", "# offset_")) or
                    (ln.startswith("# ") and ln[2:3].islower() and " = " in ln) else ln
                    for ln in PROGRAM_TABLE_DOC.splitlines())
    uncommented = text + "\n" + doc
    f = tmp_path / "m.toml"
    f.write_text(uncommented.replace('tool_table = "tools.tbl"', "").replace('datum_table = "ZEROSHIFT.D"', ""))
    m = load_machine(f)
    assert m.context.dialect.tolerance == interpolators.DEFAULT_TOLERANCE  # the documented value is the default
    assert dataclasses.replace(m.context.dialect, tolerance=None) == DEFAULT_CONTEXT.dialect
    assert m.context.tools[1].length == 0.0 and m.context.tools[1].offset_x == 0.0
    assert m.context.offset("G54").tolist() == [0, 0, 0] and m.context.home.tolist() == [0, 0, 0]


@pytest.mark.parametrize("name", builtin_machines())
def test_a_built_in_machine_plus_z_has_a_z_axis_that_is_a_copy_of_its_x_axis(name, capsys, tmp_path) -> None:
    base = load_machine(name)
    added = "".join(a for a in "yz" if a not in base.axes)
    m = load_machine(f"{name}+{added}")
    assert m.name == f"{name}+{added}" and m.axes == (*base.axes, *added)
    assert "Z a copy of the X axis" in m.description or "Y and Z copies of the X axis" in m.description
    for a in added:
        assert m.axis(a) == dataclasses.replace(base.axis("x"), name=a) and m.limits[a] == base.limits["x"]
    for a in base.axes:
        assert m.axis(a) == base.axis(a)
    # --show prints a file that loads as the same machine, for a user to edit
    assert main(["machines", "--show", m.name]) == 0
    f = tmp_path / "m.toml"
    f.write_text(capsys.readouterr().out)
    from_file = load_machine(f)
    assert from_file.name == m.name and from_file.axes == m.axes
    assert all(from_file.axis(a) == m.axis(a) for a in m.axes)


@pytest.mark.parametrize(("name", "words"), [
    ("fadal-pid+y", ["fadal-pid has the axes x, y", "e.g. fadal-pid+z"]),  # Y is there already
    ("fadal-pid+w", ["the linear axes to add", "(y, z, the ones it lacks)"]),
    ("emps+", ["e.g. emps+yz"]),
    ("emps+zz", ["e.g. emps+yz"]),
])
def test_a_built_in_name_with_axes_it_cannot_add_is_an_error(name, words, capsys) -> None:
    assert main(["machines", "--show", name]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: machine {name!r}:") and all(w in err for w in words)


def test_machines_show_unknown_exit_2(capsys) -> None:
    assert main(["machines", "--show", "nope"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error:") and "fadal-pid" in err


def test_simulate_writes_capture_json_report(tmp_path: Path, program: Path, caplog) -> None:
    out, js, rep = tmp_path / "c.csv", tmp_path / "s.json", tmp_path / "rep"
    rc = main(["simulate", str(program), "--machine", "fadal-pid", "-o", str(out), "--json", str(js),
               "--report", str(rep), "--seed", "3"])
    assert rc == 0
    cap = vcnc.read_capture(out)
    assert cap.axes == ("x", "y") and cap.control is not None and cap.meta["machine"] == "fadal-pid"
    s = json.loads(js.read_text())
    assert s["samples"] == len(cap) and s["sample_time"] == 0.001 and s["axes"] == ["x", "y"]
    for a in "xy":
        e = (cap.reference[:, "xy".index(a)] - cap.measured[:, "xy".index(a)]) * 1e3
        assert s["tracking"][a]["max_um"] == pytest.approx(np.max(np.abs(e)), rel=1e-6)
    import importlib.util

    if importlib.util.find_spec("vcnc.contour") is None:
        assert "contour" not in s
    assert (rep / "tracking.png").is_file() and (rep / "path.png").is_file() and (rep / "index.html").is_file()


def test_simulate_same_seed_same_capture(tmp_path: Path, program: Path) -> None:
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    for p in (a, b):
        assert main(["simulate", str(program), "--machine", "fadal-ppi", "-o", str(p), "--seed", "7"]) == 0
    assert a.read_text() == b.read_text()


def test_simulate_bad_machine_file_exit_2_nothing_written(tmp_path: Path, program: Path, capsys) -> None:
    bad = tmp_path / "bad_machine.toml"
    bad.write_text(builtin_machine_text("fadal-pid").replace("inertia = 0.003 ", "inertia = -1 ", 1))
    out = tmp_path / "c.csv"
    rc = main(["simulate", str(program), "--machine", str(bad), "-o", str(out), "--json", str(tmp_path / "s.json")])
    assert rc == 2
    err = capsys.readouterr().err
    assert err.startswith("error:") and f"{bad}:" in err and "inertia" in err and "kg m^2" in err
    assert set(tmp_path.iterdir()) == {bad, program}


def test_simulate_bad_program_exit_2(tmp_path: Path, capsys) -> None:
    prog = tmp_path / "bad.nc"
    prog.write_text("G90 G21\nG00 X0 Y0\nG01 X5 Q5 F3000\n")  # Q outside a canned cycle, on line 3
    rc = main(["simulate", str(prog), "--machine", "fadal-pid", "-o", str(tmp_path / "c.csv")])
    assert rc == 2
    assert not (tmp_path / "c.csv").exists()
    assert "bad.nc:3" in capsys.readouterr().err


def test_machine_file_tool_offsets_apply_with_g43(tmp_path) -> None:
    """[program.tools.N] offset_x/offset_y: G43 applies them with the length (machine = program + offsets,
    LinuxCNC g-code.adoc "G43": all the tool's offsets)."""
    f = tmp_path / "m.toml"
    f.write_text(builtin_machine_text("fadal-pid") + "\n[program.tools.1]\nlength = 10.0\noffset_x = 2.5\n"
                 "offset_y = -1.0\n")
    m = load_machine(f)
    prog = interpolators.parse_program("G21 G90\nG43 H1\nG0 X10 Y0 Z0\nG49\nG0 X10 Y0 Z0\n", context=m.context)
    assert [b.target.tolist() for b in prog.blocks][-2:] == [[12.5, -1.0, 10.0], [10.0, 0.0, 0.0]]
    f.write_text(builtin_machine_text("fadal-pid") + "\n[program.tools.1]\noffset_z = 1.0\n")
    with pytest.raises(InputError, match="offset_z"):
        load_machine(f)


def test_machine_file_tools_may_carry_a_name(tmp_path) -> None:
    """[program.tools.N] name: the tool a Heidenhain ``TOOL CALL "NAME"`` calls (TNC tool names are upper
    case, and the call names one exactly)."""
    f = tmp_path / "m.toml"
    f.write_text(builtin_machine_text("fadal-pid") + '\n[program.tools.4]\nlength = 50.0\nname = "ENGRAVER"\n')
    ctx = load_machine(f).context
    assert ctx.tool_named("ENGRAVER").number == 4 and ctx.tool_named("ENGRAVER").length == 50.0
    assert ctx.tool_named("engraver") is None


def test_machine_file_tools_may_carry_a_point_angle(tmp_path) -> None:
    """[program.tools.N] point_angle: a drill's T-ANGLE (TNC cycles 200/203/205 Q395=1, 240 Q343=1)."""
    f = tmp_path / "m.toml"
    f.write_text(builtin_machine_text("fadal-pid") + "\n[program.tools.2]\nradius = 3.0\npoint_angle = 118.0\n")
    assert load_machine(f).context.tool(2).point_angle == 118.0
    f.write_text(builtin_machine_text("fadal-pid") + "\n[program.tools.2]\npoint_angle = 200.0\n")
    with pytest.raises(InputError, match=r"program.tools.2: tool 2: point angle must lie in \[0, 180\]"):
        load_machine(f)


def test_machine_file_subroutine_path_finds_a_library_subroutine(tmp_path) -> None:
    """[program] subroutine_path (LinuxCNC INI [RS274NGC] SUBROUTINE_PATH): a program in parts/ calls
    o<peck> from the shop's library lib/, named relative to the machine file. The subroutine feeds Z to
    its first argument and rapids back to 2: from (0, 0, 5) over X3 Y4 to Z-1 and back."""
    (tmp_path / "lib").mkdir()
    (tmp_path / "parts").mkdir()
    (tmp_path / "lib" / "peck.ngc").write_text("o<peck> sub\nG1 Z#1 F100\nG0 Z2\no<peck> endsub\nM2\n")
    part = tmp_path / "parts" / "part.ngc"
    part.write_text("G21 G90\nG0 X0 Y0 Z5\nG0 X3 Y4\no<peck> call [-1]\nM2\n")
    f = tmp_path / "m.toml"
    f.write_text(builtin_machine_text("fadal-pid") + '\n[program]\nsubroutine_path = ["lib"]\nuser_m_path = "/m"\n')
    m = load_machine(f)
    assert m.context.dialect.subroutine_path == (str(tmp_path / "lib"),)
    assert m.context.dialect.user_m_path == ("/m",)  # USER_M_PATH: an absolute folder stays as it is
    # parse_program: this module's fixture stands in for load_program
    prog = interpolators.parse_program(part.read_text(), source=str(part), context=m.context)
    assert [b.target.tolist() for b in prog.blocks] == [[0, 0, 5], [3, 4, 5], [3, 4, -1], [3, 4, 2]]
    with pytest.raises(GCodeError, match="neither in this file nor in peck.ngc"):
        interpolators.parse_program(part.read_text(), source=str(part))  # without the machine's path
    f.write_text(builtin_machine_text("fadal-pid") + "\n[program]\nsubroutine_path = 3\n")
    with pytest.raises(InputError, match="'program.subroutine_path' must be a folder path string"):
        load_machine(f)
    f.write_text(builtin_machine_text("fadal-pid") + "\n[program]\nuser_m_path = [\"\"]\n")
    with pytest.raises(InputError, match="'program.user_m_path' must be a folder path string"):
        load_machine(f)
