"""Findings of the session-34 review (review34), each with a hand-written input."""

from __future__ import annotations


def test_a_rotary_axis_warning_speaks_of_degrees_not_micrometres():
    """A backlash of 0.6 deg and a noise of 0.2 deg on axis a: the reason is a rotary table's, and no 'in um?' slip
    (a value in deg is no slip of um into mm)."""
    from vcnc.engine.plausibility import plausibility_warnings

    data = {"sample_time": 0.001, "axes": {"a": {"backlash": {"width": 0.6}, "noise": {"std": 0.2}}}}
    messages = plausibility_warnings(data, file="m.toml", line=lambda *path: 7)
    assert messages == [
        "m.toml:7: axes.a.noise.std = 0.2 [deg] is above 0.1 deg, implausible for a real machine: angle encoders "
        "resolve arc-seconds (1 arc-second = 0.00028 deg)",
        "m.toml:7: axes.a.backlash.width = 0.6 [deg] is above 0.5 deg, implausible for a real machine: the lost motion "
        "of a worm or gear stage of a rotary table is arc-minutes (1 arc-minute = 0.017 deg)",
    ]


def test_a_linear_axis_noise_in_um_still_names_the_slip():
    from vcnc.engine.plausibility import plausibility_warnings

    (message,) = plausibility_warnings({"axes": {"x": {"noise": {"std": 0.5}}}}, file="m.toml", line=lambda *p: 3)
    assert message.endswith("; in um? 0.5 um is 0.0005 mm")


def test_the_settling_note_gives_a_rotary_axis_band_in_millidegrees():
    """x settles to within 1 um, c (deg) within 0.02 deg: the note said 'within 20 um' for the c axis' 0.02 deg."""
    from vcnc.engine.settling import SettlingTail

    tail = SettlingTail(samples=10, seconds=0.2, settled=True, band={"x": 0.001, "c": 0.02})
    assert "following error within 1 um (20 mdeg on a rotary axis) of its final value" in tail.note(2.0)
    assert "within 3 um of its final value" in SettlingTail(samples=10, seconds=0.2, settled=True,
                                                            band={"x": 0.003}).note(2.0)
