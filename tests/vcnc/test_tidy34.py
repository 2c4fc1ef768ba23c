"""Places that share one home after tidy34: a ZIP archive is told by one signature
(:data:`vcnc.core.text.ZIP_SIGNATURE`) wherever vcnc meets one, as a part program or as a trace."""

from __future__ import annotations

import zipfile
from pathlib import Path

import pytest

from vcnc.capture import read_capture
from vcnc.cli import main
from vcnc.core.text import ZIP_SIGNATURE
from vcnc.errors import CaptureError


def _zip(path: Path, members: dict[str, str]) -> Path:
    with zipfile.ZipFile(path, "w") as z:
        for name, text in members.items():
            z.writestr(name, text)
    return path


def test_the_signature_is_what_zipfile_writes(tmp_path):
    # PKWARE APPNOTE.TXT 4.3.7: local file header signature 0x04034b50, little-endian
    assert _zip(tmp_path / "a.zip", {"a.txt": "1"}).read_bytes().startswith(ZIP_SIGNATURE)
    assert ZIP_SIGNATURE == (0x04034B50).to_bytes(4, "little")


def test_an_fmu_given_as_a_part_program_is_named_a_zip_archive(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    _zip(tmp_path / "drive.fmu", {"modelDescription.xml": "<fmiModelDescription/>"})
    assert main(["interpolate", "drive.fmu", "-o", "sp.csv"]) == 2
    assert capsys.readouterr().err.strip() == (
        "error: drive.fmu: this is a zip archive (an FMU?), not a part program; expected a part program (ISO G-code "
        "or Heidenhain conversational)")
    assert not (tmp_path / "sp.csv").exists()


def test_a_zip_archive_given_as_a_trace_names_its_members(tmp_path):
    f = _zip(tmp_path / "trace.zip", {"run1.csv": "t,x_ref,x\n0,0,0\n"})
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert "a ZIP archive of ['run1.csv']: give vcnc the trace export inside it" in str(err.value)


def test_a_zip_archive_beside_a_diadem_header_naming_it_stays_a_zip_archive(tmp_path):
    # the header's key 211 names the archive as its channel's data; the archive's own reason is the better one
    (tmp_path / "t.dat").write_text("DIAEXTENDED  {@:ENGLISH\n#BEGINGLOBALHEADER\n  1,WINDOWS 32Bit\n"
                                    "#ENDGLOBALHEADER\n#BEGINCHANNELHEADER\n200,X\n210,EXPLIZIT\n211,t.zip\n"
                                    "#ENDCHANNELHEADER\n", encoding="latin-1")
    f = _zip(tmp_path / "t.zip", {"t.r64": "\0" * 8})
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert "a ZIP archive of ['t.r64']" in str(err.value) and "DIAdem" not in str(err.value)


# ident_fuzz seed 31 case 42 (tests/identification/test_ident_fuzz_cases.py): ballscrew-zpetc's x, 2 samples of
# delay and an 84.7 Hz mode of damping 0.074 with 54 % of the mass on the table
MODE = {"frequency_hz": 84.7, "damping": 0.074, "load_fraction": 0.54}


def _zpetc(mode: dict | None, feedback: str = "motor"):
    import dataclasses

    import vcnc

    m = vcnc.machine("ballscrew-zpetc").with_effect("x", "delay", {"samples": 2})
    if mode is not None:
        m = m.with_effect("x", "resonance", mode)
    return m.with_axis("x", dataclasses.replace(m.axis("x"), feedback=feedback))


def test_unstable_axes_sees_the_structural_mode_in_the_loop():
    assert _zpetc(None).unstable_axes() == {}  # the rigid loop with the delay: |z| = 0.962
    assert _zpetc(MODE).unstable_axes() == {"x": pytest.approx(1.1248, abs=1e-4)}
    assert _zpetc({**MODE, "damping": 0.5}).unstable_axes() == {}


def test_a_mode_behind_a_linear_scale_rings_the_loop_the_table_share_says_is_unstable():
    import numpy as np

    import vcnc

    m = _zpetc({**MODE, "damping": 0.5}, feedback="table")  # stable on the motor encoder (above)
    assert m.unstable_axes() == {"x": pytest.approx(1.0619, abs=1e-4)}
    cap = m.simulate(vcnc.interpolate(vcnc.parse_program("G21 G90\nG1 X20 F3000\nG4 P1.5\nM2\n"), m), seed=1)
    assert cap.aux["saturated"][:, 0].mean() > 0.3  # a limit cycle its current limit holds
    assert np.ptp(cap.measured[-500:, 0]) > 0.1  # still ringing 0.1 mm peak to peak after 1 s at rest
