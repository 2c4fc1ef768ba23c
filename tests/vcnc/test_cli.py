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
