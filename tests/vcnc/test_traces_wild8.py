"""Traces in the layouts of tracewild9: DIAdem DAT headers with their binary companion files, as KUKA.Trace (KR C4)
records a drive's channels (``Zeit``, ``Sollposition``, ``Istposition`` in a ``.dat`` beside a ``.r64``) and as other
recorders write them (channel storage, integers with a calibration factor). Each file is a few samples written here
after NI's documented header keys and the KUKA channel names a KR C4 client reads, not a real export."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from vcnc.capture import read_capture
from vcnc.errors import CaptureError

_GLOBAL = ["DIAEXTENDED  {@:ENGLISH", "", "#BEGINGLOBALHEADER", "  1,WINDOWS 32Bit", "#ENDGLOBALHEADER", ""]


def _implicit(name: str, unit: str, step: float, count: int) -> list[str]:
    return ["#BEGINCHANNELHEADER", f"200,{name}", f"202,{unit}", "210,IMPLIZIT", "213,BLOCK", "214,REAL64",
            f"220,{count}", "240,0", f"241,{step}", "#ENDCHANNELHEADER", ""]


def _explicit(name: str, unit: str, file: str, count: int, place: int, *, storage: str = "BLOCK",
              dtype: str = "REAL64", factor: float = 1.0) -> list[str]:
    return ["#BEGINCHANNELHEADER", f"200,{name}", f"202,{unit}", "210,EXPLIZIT", f"211,{file}", f"213,{storage}",
            f"214,{dtype}", f"220,{count}", f"221,{place}", "240,0", f"241,{factor}", "#ENDCHANNELHEADER", ""]


_SOLL = [0.0, 0.0, 0.5, 1.5, 3.0, 4.5, 5.5, 6.0, 6.0, 6.0]
_IST = [0.0, 0.0, 0.0, 0.4, 1.3, 2.8, 4.3, 5.4, 5.9, 6.0]


def _kuka_drive(folder: Path, *, with_data: bool = True) -> Path:
    """A KUKA.Trace drive file: Zeit (implicit, 1 ms), Sollposition, Istposition [Grad], Iststrom [A], a .r64 of
    REAL64 records beside it."""
    n = len(_SOLL)
    lines = _GLOBAL + _implicit("Zeit", "s", 0.001, n)
    for k, (name, unit) in enumerate((("Sollposition", "Grad"), ("Istposition", "Grad"), ("Iststrom", "A")), 1):
        lines += _explicit(name, unit, "T1_NextGenDrive#1.r64", n, k)
    dat = folder / "T1_NextGenDrive#1.dat"
    dat.write_text("\r\n".join(lines) + "\r\n", encoding="latin-1")
    if with_data:
        np.column_stack([_SOLL, _IST, np.zeros(n)]).astype("<f8").tofile(folder / "T1_NextGenDrive#1.r64")
    return dat


def test_kuka_trace_drive_joint_in_degrees_asks_for_a_rotary_axis(tmp_path):
    with pytest.raises(CaptureError) as err:
        read_capture(_kuka_drive(tmp_path))
    msg = str(err.value)
    assert "unit 'deg' is for rotary axes (a, b, c: --columns a_ref=..,a=..)" in msg
    assert "T1_NextGenDrive#1.dat:7:" in msg  # the first channel header


def test_kuka_trace_drive_reads_its_channels_by_their_names_without_units(tmp_path):
    cap = read_capture(_kuka_drive(tmp_path), columns={"t": "Zeit", "a_ref": "Sollposition", "a": "Istposition"})
    assert cap.axes == ("a",)
    np.testing.assert_allclose(cap.t, np.arange(10) * 0.001, atol=1e-12)
    np.testing.assert_allclose(cap.reference[:, 0], _SOLL)
    np.testing.assert_allclose(cap.measured[:, 0], _IST)
    assert cap.meta["format"] == "DIAdem DAT header with T1_NextGenDrive#1.r64"
    assert cap.meta["commanded"] == "a:Sollposition [deg]"


def test_diadem_channel_storage_applies_the_calibration_factor(tmp_path):
    counts_ref = np.array([0, 0, 100, 400, 900, 1500, 2000, 2300, 2400, 2400], dtype="<i4")
    counts_act = np.array([0, 0, 0, 80, 500, 1100, 1700, 2150, 2380, 2400], dtype="<i4")
    n = counts_ref.size
    lines = (_GLOBAL + _implicit("Time", "s", 0.002, n)
             + _explicit("X Sollposition", "mm", "x.i32", n, 1, storage="CHANNEL", dtype="INT32", factor=0.0005)
             + _explicit("X Istposition", "mm", "x.i32", n, n + 1, storage="CHANNEL", dtype="INT32", factor=0.0005))
    (tmp_path / "x.dat").write_text("\n".join(lines) + "\n", encoding="latin-1")
    np.concatenate([counts_ref, counts_act]).tofile(tmp_path / "x.i32")
    cap = read_capture(tmp_path / "x.dat")
    assert cap.axes == ("x",)
    np.testing.assert_allclose(cap.reference[:, 0], counts_ref * 0.0005)
    np.testing.assert_allclose(cap.measured[:, 0], counts_act * 0.0005)
    assert cap.measured[-1, 0] == pytest.approx(1.2)
    np.testing.assert_allclose(cap.t[:3], [0.0, 0.002, 0.004])
    assert cap.meta["unit_given"] == "stated in the file: x_ref in mm, x in mm"


def test_diadem_header_without_its_data_file_names_it(tmp_path):
    with pytest.raises(CaptureError) as err:
        read_capture(_kuka_drive(tmp_path, with_data=False))
    msg = str(err.value)
    assert ("DIAdem channel 'Sollposition': its values are in 'T1_NextGenDrive#1.r64', which is not beside the "
            "header") in msg
    assert "T1_NextGenDrive#1.dat:18:" in msg  # the channel's header


def test_diadem_data_file_shorter_than_the_header_says(tmp_path):
    dat = _kuka_drive(tmp_path)
    np.zeros(12, dtype="<f8").tofile(tmp_path / "T1_NextGenDrive#1.r64")  # 4 records of 3, not 10
    with pytest.raises(CaptureError) as err:
        read_capture(dat)
    assert "holds 12 values of REAL64, fewer than the header's 10 at place 1" in str(err.value)


def test_diadem_ascii_channel_is_refused_naming_its_type(tmp_path):
    lines = _GLOBAL + _implicit("Zeit", "s", 0.001, 3) + _explicit("Sollposition", "mm", "a.asc", 3, 1,
                                                                    dtype="ASCII")
    (tmp_path / "a.dat").write_text("\n".join(lines) + "\n", encoding="latin-1")
    (tmp_path / "a.asc").write_text("1\n2\n3\n", encoding="latin-1")
    with pytest.raises(CaptureError) as err:
        read_capture(tmp_path / "a.dat")
    assert "DIAdem channel 'Sollposition' has data type 'ASCII'; read are REAL64, REAL32" in str(err.value)


def test_kuka_positionsschleppfehler_is_a_following_error(tmp_path):
    """KUKA.Trace's German compound for the following error is read as one (names.py's ``_LAG_PARTS``)."""
    n = len(_SOLL)
    lag = [s - i for s, i in zip(_SOLL, _IST)]
    lines = _GLOBAL + _implicit("Zeit", "s", 0.001, n)
    lines += _explicit("Sollposition", "Grad", "d.r64", n, 1)
    lines += _explicit("Positionsschleppfehler", "Grad", "d.r64", n, 2)
    (tmp_path / "d.dat").write_text("\r\n".join(lines) + "\r\n", encoding="latin-1")
    np.column_stack([_SOLL, lag]).astype("<f8").tofile(tmp_path / "d.r64")
    with pytest.raises(CaptureError) as err:  # the pair is found by the names; the joint's degrees ask for an axis
        read_capture(tmp_path / "d.dat")
    assert "unit 'deg' is for rotary axes" in str(err.value)
    cap = read_capture(tmp_path / "d.dat", columns={"t": "Zeit", "a_ref": "Sollposition",
                                                     "a_lag": "Positionsschleppfehler"})
    np.testing.assert_allclose(cap.measured[:, 0], _IST, atol=1e-12)
    assert cap.meta["following_error"].startswith("a:Positionsschleppfehler [deg]")


def test_signal_amplitude_in_db_is_no_position(tmp_path):
    """A logger of a signal's amplitude (an antenna aligner's ``amp_dB``) holds no position: said so, not asked."""
    f = tmp_path / "trace.csv"
    f.write_text("time_s,amp_dB\n0.268,-7.1256\n1.329,-7.0089\n2.393,-7.0085\n", encoding="utf-8")
    with pytest.raises(CaptureError) as err:
        read_capture(f)
    assert "no position in the file: its columns ['time_s', 'amp_dB'] are time" in str(err.value)


def test_kuka_trace_data_file_given_names_its_header(tmp_path):
    """The .r64 given instead of its .dat: the header beside it that names it as its channels' data is named."""
    _kuka_drive(tmp_path)
    with pytest.raises(CaptureError) as err:
        read_capture(tmp_path / "T1_NextGenDrive#1.r64")
    msg = str(err.value)
    assert "the binary data of the DIAdem header 'T1_NextGenDrive#1.dat' beside it" in msg
    assert "expected the header: vcnc convert 'T1_NextGenDrive#1.dat'" in msg


def test_binary_file_without_a_diadem_header_stays_a_binary_file(tmp_path):
    np.array([1.0, 2.0, 3.0, 4.0], dtype="<f8").tofile(tmp_path / "alone.r64")
    (tmp_path / "other.dat").write_text("t,x\n0,1\n", encoding="utf-8")  # a .dat beside it, not a DIAdem header
    with pytest.raises(CaptureError) as err:
        read_capture(tmp_path / "alone.r64")
    assert "binary file (NUL bytes and no UTF-16 byte-order mark)" in str(err.value)
