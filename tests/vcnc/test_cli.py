"""Command-line conventions: exit statuses and one-line errors."""

from __future__ import annotations

import subprocess
import sys

from vcnc.cli import main


def test_no_command_is_usage_error(capsys):
    assert main([]) == 2


def test_unknown_option_exit_2():
    r = subprocess.run([sys.executable, "-m", "vcnc", "--no-such-option"], capture_output=True, text=True)
    assert r.returncode == 2
    assert "error:" in r.stderr
    assert "Traceback" not in r.stderr


def test_a_pipe_closed_by_its_reader_ends_quietly():
    # `vcnc machines --show NAME | head -1`: head exits after one line; vcnc used to end with
    # "internal error: BrokenPipeError"
    r = subprocess.run(f"{sys.executable} -m vcnc machines --show fadal-pid | head -1", shell=True,
                       capture_output=True, text=True)
    assert r.stdout.startswith("# fadal-pid:") and r.stdout.count("\n") == 1
    assert r.stderr == ""


def test_a_list_the_user_must_read_stays_whole_and_a_quoted_long_line_is_cut():
    from vcnc.core.errors import MAX_MESSAGE, InputError

    channels = ", ".join(f"'hm2_7i76e.0.encoder.{i:02d}.position'" for i in range(14))  # a recorder's channels
    err = InputError(f"no commanded position among the channels {channels}", file="scope.csv", line=3)
    assert channels in str(err) and " ... " not in str(err)
    line = "G1 X1 " * 7000  # a 42 kB program line quoted in a message
    err = InputError(f"cannot read {line}", file="p.nc", line=1, expected=line)
    shown = str(err)
    assert " ... " in shown and len(shown) < 1000 and MAX_MESSAGE < 1000
    assert shown.startswith("p.nc:1: cannot read G1 X1")
