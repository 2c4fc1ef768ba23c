"""Sweep specs: strict validation (file, line, key in every message), expansion and stable ids."""

from __future__ import annotations

import textwrap

import pytest

from vcnc.errors import InputError
from vcnc.sweeps.spec import MAGNITUDE_KEYS, load_spec, parse_spec


def spec(text: str, **kw):
    return parse_spec(textwrap.dedent(text), file="study.toml", **kw)


def test_grid_is_the_product_of_the_values():
    s = spec("""
        [parameters]
        toolpath = ["circle", "diamond"]
        feed = {min = 3000, max = 9000, num = 3}
        gain = [0.8, 1.0]
    """)
    pts = s.points()
    assert len(pts) == 2 * 3 * 2
    assert sorted({p["feed"] for p in pts}) == [3000.0, 6000.0, 9000.0]
    assert len({p["id"] for p in pts}) == len(pts)
    assert all(p["machine"] == "fadal-pid" and p["seed"] == 0 for p in pts)


def test_ids_are_stable_and_depend_on_what_changes_the_result():
    a = spec("[parameters]\nfeed = [3000, 6000]\n").points()
    b = spec("[parameters]\nfeed = [6000, 3000, 9000]\n").points()
    ids_a = {p["feed"]: p["id"] for p in a}
    ids_b = {p["feed"]: p["id"] for p in b}
    assert ids_a[3000.0] == ids_b[3000.0] and ids_a[6000.0] == ids_b[6000.0]
    c = spec("[parameters]\nfeed = [3000]\n[outputs]\nidentify = true\n").points()
    d = spec("[parameters]\nfeed = [3000]\n[toolpath]\nradius = 5.0\n").points()
    assert c[0]["id"] != ids_a[3000.0] and d[0]["id"] != ids_a[3000.0]


def test_points_that_come_out_identical_are_merged():
    # magnitude means nothing without an effect: 2 effects x 3 magnitudes -> 1 + 3 points
    pts = spec("""
        [parameters]
        effect = ["none", "backlash"]
        magnitude = [0.005, 0.01, 0.02]
    """).points()
    assert len(pts) == 4
    assert sum(p["effect"] == "none" for p in pts) == 1


def test_random_mode_is_reproducible_and_respects_ranges():
    text = """
        [sweep]
        mode = "random"
        n = 40
        seed = 7
        [parameters]
        feed = {min = 1000, max = 12000}
        gain = {min = 0.5, max = 2.0, log = true}
        seed = {min = 0, max = 99}
        toolpath = ["circle", "diamond"]
    """
    p1, p2 = spec(text).points(), spec(text).points()
    assert [p["id"] for p in p1] == [p["id"] for p in p2]
    assert all(1000 <= p["feed"] <= 12000 and 0.5 <= p["gain"] <= 2.0 for p in p1)
    assert all(isinstance(p["seed"], int) and 0 <= p["seed"] <= 99 for p in p1)
    assert {p["toolpath"] for p in p1} == {"circle", "diamond"}


def test_program_file_is_read_relative_to_the_spec(tmp_path):
    (tmp_path / "part.nc").write_text("G01 X10 Y5 F3000\nG01 X0 Y0\nM30\n")
    f = tmp_path / "s.toml"
    f.write_text('[parameters]\ntoolpath = "part.nc"\nfeed = [3000, 6000]\n')
    pts = load_spec(f).points()
    # feed does not apply to a program file: both feeds are the same point
    assert len(pts) == 1 and pts[0]["feed"] is None and "G01 X10" in pts[0]["program_text"]


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        ("[sweep]\nmode = \"grid\"\nbogus = 1\n", 3, ["[sweep] bogus", "unknown key"]),
        ("[sweep]\nmode = \"lattice\"\n", 2, ["[sweep] mode", "grid, random"]),
        ("[sweep]\nmode = \"random\"\n", 1, ["[sweep] n", "needs n"]),
        ("[sweep]\nn = 5\n", 2, ["[sweep] n", "only for"]),
        ("[parameters]\n\nfeed = \"fast\"\n", 3, ["[parameters] feed", "finite number", "mm/min"]),
        ("[parameters]\nfeed = -100\n", 2, ["[parameters] feed", "> 0"]),
        ("[parameters]\nfeed = {min = 1000, max = 2000}\n", 2, ["[parameters] feed", "needs num"]),
        ("[parameters]\ngain = {min = 2, max = 1, num = 3}\n", 2, ["[parameters] gain", "below min"]),
        ("[parameters]\nspeed = [1]\n", 2, ["[parameters] speed", "unknown key"]),
        ("[parameters]\neffect = [\"none\", \"gremlins\"]\n", 2, ["[parameters] effect", "backlash"]),
        ("[parameters]\nseed = [1.5]\n", 2, ["[parameters] seed", "integer"]),
        ("[parameters]\nmachine = {min = 1, max = 2}\n", 2, ["[parameters] machine", "not a range"]),
        ("[outputs]\nidentify = \"yes\"\n", 2, ["[outputs] identify", "true or false"]),
        ("[outputs]\ndiagnose = true\n", 2, ["[outputs] diagnose", "identify = true"]),
        ("[toolpath]\nradius = 0\n", 2, ["[toolpath] radius", "> 0"]),
        ("[extra]\na = 1\n", 1, ["extra", "unknown table"]),
        ("[parameters\nfeed = 1\n", 1, ["not valid TOML"]),
    ],
)
def test_bad_specs_name_file_line_and_key(text, line, words):
    with pytest.raises(InputError) as ei:
        spec(text).points()
    msg = str(ei.value)
    assert msg.startswith(f"study.toml:{line}:") or msg.startswith(f"study.toml:{line}: "), msg
    for w in words:
        assert w in msg, msg


def test_unknown_machine_and_missing_files_are_input_errors(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text('[parameters]\nmachine = ["fadal-pid", "no-such-machine"]\n')
    with pytest.raises(InputError, match=r"s.toml:2: \[parameters\] machine: 'no-such-machine'"):
        load_spec(f).points()
    f.write_text('[parameters]\ntoolpath = ["circle", "missing.nc"]\n')
    with pytest.raises(InputError, match=r"s.toml:2: \[parameters\] toolpath: 'missing.nc' is neither"):
        load_spec(f).points()
    f.write_text('[sweep]\naxis = "z"\n')
    with pytest.raises(InputError, match=r"s.toml:2: \[sweep\] axis: machine 'fadal-pid' has no axis 'z'"):
        load_spec(f).points()


def test_every_effect_has_a_magnitude_parameter():
    from vcnc.engine.machine import EFFECTS

    assert set(MAGNITUDE_KEYS) == set(EFFECTS)


def test_machine_variant_applies_gain_noise_and_every_effect():
    from vcnc.engine.machine import EFFECTS, load_machine
    from vcnc.sweeps.point import machine_variant

    base = load_machine("fadal-pid")
    pts = spec("""
        [parameters]
        gain = [1.25]
        noise = [0.0]
    """).points()
    m = machine_variant(pts[0])
    for a in ("x", "y"):
        assert m.axis(a).controller.kp == pytest.approx(1.25 * base.axis(a).controller.kp)
        assert m.axis(a).controller.ki == pytest.approx(1.25 * base.axis(a).controller.ki)
        assert m.axis(a).controller.kv == base.axis(a).controller.kv  # feedforward is not a feedback gain
        assert m.axis(a).noise is None and base.axis(a).noise is not None
    sizes = {"delay": 3, "friction_stribeck": 2.0, "friction_viscous_asymmetric": 0.5, "resonance": 0.3}
    for effect in EFFECTS:
        task = spec(f'[parameters]\neffect = "{effect}"\nmagnitude = {sizes.get(effect, 0.5)}\n').points()[0]
        assert machine_variant(task).axis("x") != base.axis("x"), effect
    backlash = spec('[parameters]\neffect = "backlash"\nmagnitude = 0.02\n').points()[0]
    assert machine_variant(backlash).axis("x").backlash.width == 0.02
    assert machine_variant(backlash).axis("y").backlash == base.axis("y").backlash
