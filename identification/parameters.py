"""The parameters of the reduced closed-loop model, Eq. (3.3) of the thesis: their names and units
(defined in :mod:`vcnc.core.axes`, shared with the FMU export) and the search variables the
refinements (output error, the diagnosis' joint refits) move in."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from identification.bounds import PoleBounds
from identification.poles import TWO_PI, denominator
from vcnc.core.axes import PARAMETER_NAMES, PARAMETER_UNITS

__all__ = ["PARAMETER_NAMES", "PARAMETER_UNITS", "N_SEARCH", "to_search", "from_search", "poles_of_search",
           "search_box"]


# ------------------------------------------------------------------ search variables
# The refinements search in z = (log p, log omega_n, zeta, b2/a2, b1/a2, b0/a2, d0/a2, d1/a2)
# (poles in rad/s): the pole box of Eq. (3.8) is a box in z, every z in it is a stable loop
# (a1, a2, a3 follow from the poles, Eq. 3.7), and the numerator and load terms scale with a2.

#: Number of search variables of the reduced model.
N_SEARCH = 8


def to_search(parameters: Mapping[str, float], p: float, omega_n: float, zeta: float) -> np.ndarray:
    """Search variables ``z`` of a model: ``parameters`` a1..d1 and its poles ``p``, ``omega_n``
    [rad/s] and ``zeta``."""
    a2 = parameters["a2"]
    return np.array([
        math.log(p), math.log(omega_n), zeta, parameters["b2"] / a2, parameters["b1"] / a2, parameters["b0"] / a2,
        parameters["d0"] / a2, parameters["d1"] / a2,
    ])


def from_search(z: Sequence[float]) -> dict[str, float]:
    """Parameters a1..d1 of the search variables ``z`` (the first :data:`N_SEARCH` entries)."""
    p, wn, zeta = math.exp(z[0]), math.exp(z[1]), z[2]
    a1, a2, a3 = denominator(p, wn, zeta)
    return {"a1": a1, "a2": a2, "a3": a3, "b2": z[3] * a2, "b1": z[4] * a2, "b0": z[5] * a2, "d0": z[6] * a2,
            "d1": z[7] * a2}


def poles_of_search(z: Sequence[float]) -> dict[str, float]:
    """Poles (``p_hz``, ``omega_n_hz`` [Hz], ``zeta``) of the search variables ``z``."""
    return {"omega_n_hz": math.exp(z[1]) / TWO_PI, "zeta": float(z[2]), "p_hz": math.exp(z[0]) / TWO_PI}


def search_box(bounds: PoleBounds) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper bounds of the :data:`N_SEARCH` search variables: the pole box in
    (log p, log omega_n, zeta), the other variables free."""
    box = bounds.rad()
    lo = np.array([math.log(box[0][0]), math.log(box[1][0]), box[2][0]] + [-np.inf] * 5)
    hi = np.array([math.log(box[0][1]), math.log(box[1][1]), box[2][1]] + [np.inf] * 5)
    return lo, hi
