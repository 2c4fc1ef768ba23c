"""Review of session 28: defects found in the day's vcnc changes, each with a hand-written program."""

from __future__ import annotations

import json

import pytest

from tests.vcnc.test_compare_wild import model_files, models_of
from tests.vcnc.test_simulate_wild import write
from vcnc.cli import main

#: A square whose first corner is rounded by Fanuc's ',R' (FANUC 0i-MF operator's manual, "Chamfering and corner
#: R"): the linuxcnc dialect refuses it, --dialect fanuc reads it.
ROUNDED = "G21 G90 G17\nG0 X0 Y0\nG1 X10 Y0 ,R2 F3000\nG1 X10 Y10\nG1 X0 Y10\nM30\n"


def test_compare_reads_the_program_of_a_captured_truth_with_the_dialect_given(tmp_path, capsys):
    # vcnc compare --truth CAPTURE --toolpath PROGRAM --dialect fanuc read the program as LinuxCNC G-code whatever
    # --dialect said (only a simulated truth's program got the reader options) and refused the ',R' it was told
    # to read, naming '--dialect fanuc' as the way forward
    prog = write(tmp_path, ROUNDED)
    cap, sim = tmp_path / "cap.csv", tmp_path / "sim.json"
    assert main(["simulate", str(prog), "--machine", "fadal-pid", "--dialect", "fanuc", "-o", str(cap),
                 "--json", str(sim)]) == 0
    out = tmp_path / "c.json"
    assert main(["compare", "--truth", str(cap), *model_files(tmp_path, models_of()), "--toolpath", str(prog),
                 "--dialect", "fanuc", "--json", str(out)]) == 0
    # the capture's contour error on the program's feed moves, as vcnc simulate reported it
    true, simulated = json.loads(out.read_text())["true"], json.loads(sim.read_text())["contour"]
    assert true["contour_max_um"] == pytest.approx(simulated["max_um"], rel=1e-9)
    assert true["contour_rms_um"] == pytest.approx(simulated["rms_um"], rel=1e-9)
    capsys.readouterr()
    assert main(["compare", "--truth", str(cap), *model_files(tmp_path, models_of()), "--toolpath", str(prog),
                 "--json", str(out)]) == 2
    assert "',R2' corner rounding between two moves" in capsys.readouterr().err
