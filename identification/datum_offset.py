"""A constant offset between the recorded commanded and measured positions (a datum offset).

The reduced model of Eq. (3.3) settles at the reference (``G_track(0) = 1``, ``G_dist(0) = 0``):
it has no term for a measured position that rests a constant distance away from the commanded
one. Traces have such offsets whenever the two channels are not in the same frame: the commanded
position in workpiece coordinates and the actual one in machine coordinates (a datum shift or a
work offset), a linear scale or a laser logged beside the control's setpoint, a homing offset
between a drive's motor-side position and the control's axis position. Fitted as it is, an offset
of 10 um on the virtual fadal-pid drove the integrator pole to the bound of the box and tripled
the prediction error; one of 0.5 mm hid a 0.1 s reference dead time altogether (the truth harness
of the traceid audit).

:func:`estimate_offset` takes the offset from the regression of Eq. (3.11) with two more columns:
a measured position ``x + c`` turns the integrated tracking error ``e_i`` into ``e_i - c t``, so
``Y = theta^T Phi + alpha_i c t + c`` holds exactly with a constant and a ramp beside the eight
columns of Eq. (3.11). It needs no rest in the record (an identification test of exact stops has
none long enough) and does not depend on the pole box. :func:`identification.identify.fit_reduced_model`
removes a large offset (over :data:`COARSE_SHARE` of the RMS tracking error) before the fit when
the model fitted without it predicts at least twice better (:data:`MIN_GAIN`), as it does for the
reference dead time: the regression's estimate is biased by a few um, the equation error's misfit.
The output-error refinement then fits what remains exactly (and the model is fitted again without
it: a residual offset of 0.4 um still held the slow pole on its bound), and a small offset only
there, again when it at least halves the prediction error: so a loop that rests a little off its reference (no
integral action, friction) keeps its identification as it was.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from identification.regressor import RegressorOptions, regressor

__all__ = ["OffsetEstimate", "estimate_offset", "MIN_GAIN", "COARSE_SHARE"]

#: Least ratio of prediction RMS (without removing the offset / with) for the offset to be removed.
MIN_GAIN = 2.0
#: Share of the RMS tracking error above which the regression's estimate is removed before the
#: fit [-]; below it, only the output-error refinement (which fits the offset exactly) may remove one.
COARSE_SHARE = 0.05


@dataclasses.dataclass(frozen=True)
class OffsetEstimate:
    """A datum offset and whether it was removed.

    Attributes
    ----------
    offset_mm : float
        Measured minus commanded position that was removed [mm] (0 when not applied).
    estimated_mm : float
        The regression's estimate, applied or not [mm].
    applied : bool
        Whether the offset was removed before identification.
    rms_without_um, rms_with_um : float
        Prediction RMS of the model fitted without and with the removal [um] (NaN when not judged).
    """

    offset_mm: float
    estimated_mm: float
    applied: bool
    rms_without_um: float = float("nan")
    rms_with_um: float = float("nan")

    def to_dict(self) -> dict:
        return {k: (None if v != v else v) for k, v in dataclasses.asdict(self).items()}


def estimate_offset(reference: np.ndarray, measured: np.ndarray, sample_time: float, *,
                    options: RegressorOptions | None = None) -> float:
    """The datum offset [mm] of ``measured`` against ``reference`` (module docstring).

    Parameters
    ----------
    reference, measured : ndarray
        Commanded and measured position [mm].
    sample_time : float
        [s].
    options : RegressorOptions, optional
        As for the identification.

    Returns
    -------
    float
        The offset c from the unconstrained least squares [mm], NaN when the record cannot tell it.

    Notes
    -----
    Row k of the regression (sample k + h, h = ``options.half_width``) integrates the error from sample 0:
    the offset lowers e_i by ``c T (k + h + 1)`` (``c T (k + h)`` for the trapezoid), so the constant column's
    coefficient is ``c (1 + alpha_i T (h + 1))`` and the ramp's (``k / n``) ``alpha_i c T n``; the constant's
    less the ramp's share at row 0 is c. Taken alone the constant was 2.4 % (fadal-pid) to 21 % (ballscrew-ppc)
    off. On a record moving at every row (-PV - NV = -1 throughout: no encoder count at rest) the constant column
    is the friction switches' sum, the Coulomb levels take up any part of it, and the least squares returned
    0.57 c on fadal-smc and 0.51 c on chevalier-pdf (ident_fuzz seed 21 case 59, ballscrew-zpetc: 1.127 mm of
    2.109, not removed, and the slow pole imitating the rest predicted 70 um held out); the ramp, which no other
    column carries, gives c then, where the loop integrates (alpha_i > 0).
    """
    opt = options or RegressorOptions()
    phi, y = regressor(reference, measured, sample_time, options=opt)
    n = max(y.size, 1)
    ramp = np.arange(y.size, dtype=float) / n
    a = np.column_stack([phi, np.ones_like(y), ramp])
    scale = np.linalg.norm(a, axis=0)
    scale[scale == 0.0] = 1.0
    coef = np.linalg.lstsq(a / scale, y, rcond=None)[0] / scale
    if np.any((phi[:, 6] == 0.0) & (phi[:, 7] == 0.0)):  # rows at rest: the constant is the offset's own
        first = opt.half_width + (1 if opt.integration == "rectangle" else 0)
        return float(coef[8] - coef[9] * first / n)
    if not coef[0] > 0.0:
        return float("nan")
    return float(coef[9] / (coef[0] * sample_time * n))
