"""Machine TOML files: every schema error names key, unit, file and line."""

from __future__ import annotations

from pathlib import Path

import pytest

from vcnc.engine.machine import builtin_machine_text, load_machine
from vcnc.errors import MachineError


def write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "m.toml"
    p.write_text(text)
    return p


def fadal_with(replace: str, by: str) -> str:
    text = builtin_machine_text("fadal-pid")
    assert replace in text
    return text.replace(replace, by, 1)


def line_of(text: str, needle: str) -> int:
    return next(i for i, l in enumerate(text.splitlines(), 1) if needle in l)


def test_roundtrip_from_file(tmp_path: Path) -> None:
    p = write(tmp_path, builtin_machine_text("fadal-pid").replace('name = "fadal-pid"', 'name = "mine"'))
    m = load_machine(p)
    assert m.name == "mine" and m.axes == ("x", "y")
    assert m.axis("x").reduced_parameters() == load_machine("fadal-pid").axis("x").reduced_parameters()


@pytest.mark.parametrize(
    "old,new,needle,words",
    [
        ("inertia = 0.003 ", "inertia = -0.003 ", "inertia = -0.003", ["inertia", "kg m^2", "> 0"]),
        ("inertia = 0.003 ", 'inertia = "heavy" ', "heavy", ["inertia", "kg m^2", "number"]),
        ("lead = 10.0", "leed = 10.0", "leed", ["unknown key", "axes.x.drive.leed", "lead [mm/rev]"]),
        ("kp = 44.", "kp = -44.", "kp = -44.", ["kp", "V/mm"]),
        ("width = 0.003", "width = 20.0", "width = 20.0", ["width", "mm"]),
        ('type = "pid"', 'type = "fuzzy"', "fuzzy", ["type", "pid", "ppc"]),
        ("bits = 16", "bits = 16.5", "bits = 16.5", ["bits", "integer"]),
        ("acceleration = 2000.0", "acceleration = 0.0", "acceleration = 0.0", ["acceleration", "mm/s^2"]),
        ("sample_time = 0.001", "sample_time = -1", "sample_time = -1", ["sample_time", "[s]"]),
        ('feedback = "motor"', 'feedback = "tachometer"', "tachometer", ["feedback", "motor", "table"]),
        ("current_limit = 15.0", "current_limit = 15.0\nvoltage_limit = 5.0", "current_limit = 15.0",
         ["exactly one"]),
    ],
)
def test_schema_errors_name_key_unit_file_line(tmp_path: Path, old, new, needle, words) -> None:
    text = fadal_with(old, new)
    p = write(tmp_path, text)
    with pytest.raises(MachineError) as info:
        load_machine(p)
    err = info.value
    assert err.file == str(p)
    assert err.line == line_of(text, needle), str(err)
    for w in words:
        assert w in str(err), (w, str(err))


def test_missing_key_names_table_and_unit(tmp_path: Path) -> None:
    text = fadal_with("torque_constant = 0.95      # N m/A\n", "")
    p = write(tmp_path, text)
    with pytest.raises(MachineError, match=r"torque_constant' \[N m/A\]") as info:
        load_machine(p)
    assert info.value.line == line_of(text, "[axes.x.drive]")


def test_bad_toml_syntax(tmp_path: Path) -> None:
    p = write(tmp_path, "sample_time = 0.001\n[axes.x\n")
    with pytest.raises(MachineError) as info:
        load_machine(p)
    assert info.value.line == 2


def test_missing_file_and_unknown_name(tmp_path: Path) -> None:
    with pytest.raises(MachineError, match="cannot read"):
        load_machine(tmp_path / "absent.toml")
    with pytest.raises(MachineError, match="built-in"):
        load_machine("absent")


def test_fmu_axis_with_a_missing_file_names_file_and_line(tmp_path: Path) -> None:
    text = 'sample_time = 0.001\n[axes.x]\nfmu = "nope.fmu"\n[axes.x.limits]\nvelocity = 1.0\nacceleration = 9.0\n'
    p = write(tmp_path, text)
    with pytest.raises(MachineError) as info:
        load_machine(p)
    assert info.value.file == str(p) and info.value.line == 3
    assert "nope.fmu" in str(info.value)
