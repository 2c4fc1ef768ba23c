"""Shared synthetic data for the identification tests (fixed seeds)."""

from __future__ import annotations

import numpy as np
import pytest

from identification.regressor import statistics
from identification.synthetic import FADAL_PID_X, random_moves_reference, synthetic_capture


@pytest.fixture(scope="session")
def pid_reference() -> np.ndarray:
    """Table 3.2-style reference: 200 random moves within +/-10 mm, 200 mm/s, 2000 mm/s^2, Ts 1 ms."""
    return random_moves_reference(seed=1)


@pytest.fixture(scope="session")
def pid_capture(pid_reference):
    """The thesis' PID x axis (Table 3.4 'Actual') simulated by the reduced model, 0.2 um noise, 1 um encoder."""
    return synthetic_capture(FADAL_PID_X, pid_reference, noise=2e-4, resolution=1e-3, seed=3)


@pytest.fixture(scope="session")
def pid_statistics(pid_capture):
    return statistics(pid_capture.reference[:, 0], pid_capture.measured[:, 0], pid_capture.sample_time)
