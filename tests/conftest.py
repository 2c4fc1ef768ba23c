"""Shared test fixtures."""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

REPO = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def emps_dir() -> Path:
    """Folder of the EMPS data (``VCNC_EMPS_DIR``); skips, saying so, where it is absent."""
    d = os.environ.get("VCNC_EMPS_DIR") or str(REPO.parent / "shared" / "data" / "emps")
    p = Path(d).resolve()  # absolute: examples run in other working directories
    if not (p / "DATA_EMPS.mat").is_file():
        pytest.skip(f"EMPS data not found in {p} (set VCNC_EMPS_DIR to the folder holding DATA_EMPS.mat)")
    return p
