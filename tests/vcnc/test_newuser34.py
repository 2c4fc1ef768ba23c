"""A demanding new user on the command line (session 34): a run stopped by Ctrl-C or ``kill`` exits 128 + the
signal's number with one line and leaves no output behind."""

from __future__ import annotations

import signal
from pathlib import Path

import pytest

from vcnc.cli import main

PROGRAM = "G21 G90 G94\nG0 X0 Y0\nG1 X5 Y0 F600\nG1 X5 Y5\nM2\n"


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    Path("part.nc").write_text(PROGRAM)
    return tmp_path


@pytest.mark.parametrize(("signum", "status"), [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_during_the_writing_exits_128_plus_its_number_leaving_no_output(work, capsys, monkeypatch, signum,
                                                                                    status):
    import vcnc.simulation_report as simulation_report

    summarize = simulation_report.summarize

    def signalled(*args, **kwargs):  # the summary is computed while the capture's temporary file is being written
        out = summarize(*args, **kwargs)
        signal.raise_signal(signum)
        return out

    monkeypatch.setattr(simulation_report, "summarize", signalled)
    before = {p.name for p in work.iterdir()}
    code = main(["simulate", "part.nc", "--machine", "fadal-pid", "-o", "cap.csv", "--json", "run.json"])
    err = capsys.readouterr().err.strip()
    assert code == status
    assert err == f"error: interrupted ({signal.Signals(signum).name})"
    assert {p.name for p in work.iterdir()} == before  # neither the outputs nor their temporary names
    assert signal.getsignal(signal.SIGTERM) == signal.SIG_DFL  # the handler is the command's only
