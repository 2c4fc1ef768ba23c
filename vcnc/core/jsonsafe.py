"""One rule for writing results as JSON: plain Python types, and no NaN or infinity (JSON has
neither; they are written as ``null``)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

__all__ = ["plain"]


def plain(obj: Any) -> Any:
    """A JSON-safe copy of ``obj``: dict keys as str, tuples and arrays as lists, numpy scalars as
    Python numbers, non-finite floats as None."""
    if isinstance(obj, Mapping):
        return {str(k): plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [plain(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return plain(obj.tolist())
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj
