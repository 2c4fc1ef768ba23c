"""Sampled axis setpoints (defined in :mod:`vcnc.core.setpoints`, re-exported here)."""

from vcnc.core.axes import AXIS_NAMES
from vcnc.core.setpoints import Setpoints

__all__ = ["Setpoints", "AXIS_NAMES"]
