"""Zero Phase Error Tracking Controller (Tomizuka 1987; Eqs. 3.23-3.25 of the thesis)."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # imported where used: python-control loads scipy.signal and matplotlib (seconds)
    import control

__all__ = ["ZPETC", "design_zpetc"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class ZPETC:
    """A designed ZPETC feedforward filter.

    Attributes
    ----------
    fir : ndarray
        Coefficients c_j of ``A(q^-1) B^-(q) / [B^-(1)]^2`` applied to r(k + d), ordered from the
        most future sample: r*(k) = sum_j c_j r(k + preview - j), then divided by B^+(q^-1).
    bplus : ndarray
        B^+(z^-1) coefficients (stable, well damped zeros, gain included).
    preview : int
        Future samples needed: relative degree d plus the number of zeros in B^-.
    cancelled_zeros, kept_zeros : ndarray
        Zeros of the closed loop put in B^+ (cancelled) and B^- (kept, phase compensated).
    """

    fir: np.ndarray
    bplus: np.ndarray
    preview: int
    cancelled_zeros: np.ndarray
    kept_zeros: np.ndarray

    def apply(self, reference: np.ndarray) -> np.ndarray:
        """r* for a whole reference [mm]; before the start and beyond the end the first and last
        values are held (the axis is at rest there)."""
        import scipy.signal
        r = np.asarray(reference, dtype=float)
        x = np.concatenate([r[self.preview :], np.full(min(self.preview, len(r)), r[-1])])[: len(r)]
        nb, na = len(self.fir), len(self.bplus)
        if nb == 1 and na == 1:
            return x * (self.fir[0] / self.bplus[0])
        zi = scipy.signal.lfiltic(self.fir, self.bplus, [r[0]] * max(na - 1, 0), [r[0]] * max(nb - 1, 0))
        # the history before k = 0 holds r[0] but x[k] for k < preview is still the future of r
        y, _ = scipy.signal.lfilter(self.fir, self.bplus, x, zi=zi)
        return y

    def causal_tf(self, sample_time: float) -> control.TransferFunction:
        """The filter delayed by ``preview`` samples, r*(k - preview) from r(k): causal [mm/mm]."""
        import control
        n = max(len(self.fir), len(self.bplus))
        num = np.concatenate([self.fir, np.zeros(n - len(self.fir))])
        den = np.concatenate([self.bplus, np.zeros(n - len(self.bplus))])
        return control.tf(num, den, sample_time)


def design_zpetc(loop: control.TransferFunction, *, kept_radius: float = 0.9) -> ZPETC:
    """ZPETC for a stable discrete closed loop G(z) = x/r* (Eq. 3.24).

    Zeros outside ``kept_radius`` or on the negative real side beyond -0.5 (unstable or poorly
    damped, e.g. the ZOH zero near -1 at z1 = -0.99937) go to B^-; their phase is cancelled by
    B^-(z^-1), the rest are cancelled exactly.
    """
    num = np.trim_zeros(np.atleast_1d(np.squeeze(loop.num[0][0])), "f")
    den = np.atleast_1d(np.squeeze(loop.den[0][0]))
    lead = den[0]
    den = den / lead
    num = num / lead
    d = len(den) - len(num)  # relative degree
    zeros = np.roots(num) if len(num) > 1 else np.array([])
    bad = (np.abs(zeros) >= kept_radius) | ((zeros.real < -0.5) & (np.abs(zeros.imag) < 1e-9))
    zminus = zeros[bad]
    zplus = zeros[~bad]
    # B^-(z^-1) = prod(1 - z_i z^-1); B^+(z^-1) = b0 prod(1 - z_j z^-1)
    bminus = np.real(np.poly(zminus)) if len(zminus) else np.array([1.0])
    bplus = num[0] * (np.real(np.poly(zplus)) if len(zplus) else np.array([1.0]))
    bm1 = np.sum(bminus)
    # A(q^-1) B^-(q): B^-(q) = prod(1 - z_i q) -> reversed coefficients, powers q^s ... q^0
    bminus_fwd = bminus[::-1]
    fir = np.convolve(bminus_fwd, den) / bm1**2
    return ZPETC(
        fir=fir,
        bplus=np.asarray(bplus, dtype=float),
        preview=d + len(zminus),
        cancelled_zeros=zplus,
        kept_zeros=zminus,
    )
