"""The linear regression of Eqs. (3.9)-(3.11): regressor rows from a capture, in chunks.

Row k of Phi and Y (Eq. 3.11), column order fixed (:data:`COLUMNS`)::

    Phi_k = [e_i,k, -v_k, -a_k, x_r,k, v_r,k, a_r,k, -PV(v_k), -NV(v_k)],   Y_k = x_k
    theta = [alpha_i, alpha_1, alpha_2, beta_0, beta_1, beta_2, delta+, delta-]   (Eq. 3.10)

with x_r the commanded and x the measured position [mm], v, a the measured velocity [mm/s] and
acceleration [mm/s^2], v_r, a_r those of the reference, e_i the integrated tracking error
[mm s]. By default (Sec. 3.2 of the thesis) derivatives are central differences,
``v_k = (x_{k+1} - x_{k-1}) / 2T`` and ``a_k = (v_{k+1} - v_{k-1}) / 2T``, and
``e_i,k = T sum_{m<=k} (x_r,m - x_m)``; rows whose differences would need samples outside the
capture (two at each end) are dropped.

Options a real encoder needs (:class:`RegressorOptions`):

* ``smoothing_window``: Savitzky-Golay derivatives (polynomial of ``smoothing_order`` over an odd
  window of samples) instead of central differences: on quantised encoder data the central
  second difference amplifies the count noise by 1/T^2;
* ``velocity_deadband`` [mm/s]: PV = 1 only when v > deadband and NV = 1 only when v < -deadband,
  so that quantisation chatter at standstill does not toggle the friction columns;
* ``integration``: ``"rectangle"`` (the thesis' sum) or ``"trapezoid"``.

Rows are produced in chunks (:func:`iter_regressor`) so that :class:`SufficientStatistics` can
accumulate captures of any length; the statistics keep the triangular factor of the column-scaled
[Phi, Y] (a streaming QR), from which P = Phi^T Phi, R = Phi^T Y and gamma = Y^T Y (Eq. 3.19)
follow, without squaring the condition number on the way.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterator, Sequence

import numpy as np
import scipy.linalg
import scipy.signal

from vcnc.core.errors import IdentificationError

__all__ = [
    "COLUMNS",
    "COLUMN_DESCRIPTIONS",
    "THETA_NAMES",
    "RegressorOptions",
    "FRICTION_DIRECTIONS",
    "regressor",
    "iter_regressor",
    "SufficientStatistics",
    "statistics",
]

#: Regressor columns in the order of Eq. (3.11).
COLUMNS: tuple[str, ...] = ("e_i", "-v", "-a", "x_r", "v_r", "a_r", "-PV", "-NV")

#: What each column is, for messages.
COLUMN_DESCRIPTIONS: dict[str, str] = {
    "e_i": "integrated tracking error [mm s]",
    "-v": "measured velocity [mm/s]",
    "-a": "measured acceleration [mm/s^2]",
    "x_r": "commanded position [mm]",
    "v_r": "commanded velocity [mm/s]",
    "a_r": "commanded acceleration [mm/s^2]",
    "-PV": "friction switch for positive velocity",
    "-NV": "friction switch for negative velocity",
}

#: What :attr:`RegressorOptions.friction` may say: both Coulomb levels identified, or only that of the
#: direction named (the record moves that way only; the other level mirrors it).
FRICTION_DIRECTIONS: tuple[str, ...] = ("two-way", "positive", "negative")

#: Normalised parameters of Eq. (3.10), in column order.
THETA_NAMES: tuple[str, ...] = ("alpha_i", "alpha_1", "alpha_2", "beta_0", "beta_1", "beta_2", "delta+", "delta-")


@dataclasses.dataclass(frozen=True, kw_only=True)
class RegressorOptions:
    """How the regressor is built from sampled positions.

    Attributes
    ----------
    smoothing_window : int
        0 (default): central differences as in Sec. 3.2. Otherwise an odd number of samples
        (>= smoothing_order + 2) for Savitzky-Golay derivative filters.
    smoothing_order : int
        Polynomial order of the Savitzky-Golay filters (>= 2).
    velocity_deadband : float
        [mm/s]; |v| <= deadband gives PV = NV = 0. Default 0 (the thesis' PV/NV).
    integration : str
        ``"rectangle"`` (thesis: e_i,k = T sum_{m<=k} e_m) or ``"trapezoid"``.
    friction : str
        ``"two-way"`` (default): a Coulomb level for each direction, delta+ and delta- (Eq. 3.10).
        ``"positive"`` or ``"negative"``: the record moves that way only, so only that direction's
        level is identified and the other is taken as its mirror (d1 = -d0, Coulomb friction of the
        same size both ways): the column of that level is -sign(v) (-(PV - NV) for ``"positive"``,
        -(NV - PV) for ``"negative"``), the other column zero, which
        :class:`identification.problem.ReducedProblem` leaves out.
    chunk : int
        Rows per chunk when streaming [samples].
    """

    smoothing_window: int = 0
    smoothing_order: int = 3
    velocity_deadband: float = 0.0
    integration: str = "rectangle"
    friction: str = "two-way"
    chunk: int = 8192

    def __post_init__(self) -> None:
        w = self.smoothing_window
        if w != 0 and (w < self.smoothing_order + 2 or w % 2 == 0):
            raise IdentificationError(
                f"smoothing_window must be 0 or an odd number of samples >= smoothing_order + 2 "
                f"(= {self.smoothing_order + 2}); got {w}"
            )
        if self.smoothing_order < 2:
            raise IdentificationError(f"smoothing_order must be >= 2 (got {self.smoothing_order})")
        if not (math.isfinite(self.velocity_deadband) and self.velocity_deadband >= 0):
            raise IdentificationError(f"velocity_deadband [mm/s] must be >= 0 (got {self.velocity_deadband!r})")
        if self.integration not in ("rectangle", "trapezoid"):
            raise IdentificationError(
                f"integration must be 'rectangle' or 'trapezoid' (got {self.integration!r})"
            )
        if self.friction not in FRICTION_DIRECTIONS:
            raise IdentificationError(
                f"friction must be one of {', '.join(FRICTION_DIRECTIONS)} (got {self.friction!r})"
            )
        if self.chunk < 16:
            raise IdentificationError(f"chunk must be >= 16 rows (got {self.chunk})")

    @property
    def half_width(self) -> int:
        """Samples dropped at each end of the capture."""
        return 2 if self.smoothing_window == 0 else self.smoothing_window // 2

    def kernels(self, sample_time: float) -> tuple[np.ndarray, np.ndarray]:
        """FIR kernels (first, second derivative), length 2 h + 1, for correlation."""
        T = sample_time
        h = self.half_width
        if self.smoothing_window == 0:
            k1 = np.array([0.0, -1.0, 0.0, 1.0, 0.0]) / (2 * T)
            k2 = np.array([1.0, 0.0, -2.0, 0.0, 1.0]) / (4 * T * T)
        else:
            w, o = self.smoothing_window, self.smoothing_order
            # savgol_coeffs(use="dot") gives correlation weights for the centre sample
            k1 = scipy.signal.savgol_coeffs(w, o, deriv=1, delta=T, use="dot")
            k2 = scipy.signal.savgol_coeffs(w, o, deriv=2, delta=T, use="dot")
        assert k1.size == 2 * h + 1
        return k1, k2


def _correlate_valid(x: np.ndarray, k: np.ndarray) -> np.ndarray:
    return np.correlate(x, k, mode="valid")


def iter_regressor(
    reference: np.ndarray,
    measured: np.ndarray,
    sample_time: float,
    *,
    options: RegressorOptions | None = None,
) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """Yield ``(Phi, Y)`` blocks of the regression of Eq. (3.11), ``options.chunk`` rows each.

    Parameters
    ----------
    reference, measured : array_like, shape (N,)
        Commanded and measured position [mm], sampled every ``sample_time``.
    sample_time : float
        T [s].
    options : RegressorOptions, optional

    Yields
    ------
    Phi : ndarray, shape (n, 8)
        Columns :data:`COLUMNS`.
    Y : ndarray, shape (n,)
        Measured position [mm].
    """
    opt = options or RegressorOptions()
    xr = np.asarray(reference, dtype=float)
    x = np.asarray(measured, dtype=float)
    n = xr.size
    h = opt.half_width
    if n < 2 * h + 3:
        raise IdentificationError(f"only {n} samples; the regressor needs at least {2 * h + 3}")
    k1, k2 = opt.kernels(sample_time)
    T = sample_time
    carry = 0.0  # sum of tracking errors before the chunk
    first_err = xr[0] - x[0]
    # e_i at rows h..: sum over samples 0..k; start the running sum with samples 0..h-1
    if h > 0:
        carry = float(np.sum(xr[:h] - x[:h]))
    db = opt.velocity_deadband
    for start in range(h, n - h, opt.chunk):
        stop = min(start + opt.chunk, n - h)
        lo, hi = start - h, stop + h
        seg_x, seg_r = x[lo:hi], xr[lo:hi]
        v = _correlate_valid(seg_x, k1)
        a = _correlate_valid(seg_x, k2)
        vr = _correlate_valid(seg_r, k1)
        ar = _correlate_valid(seg_r, k2)
        err = xr[start:stop] - x[start:stop]
        csum = carry + np.cumsum(err)
        carry = float(csum[-1])
        if opt.integration == "trapezoid":
            ei = T * (csum - 0.5 * (first_err + err))
        else:
            ei = T * csum
        phi = np.empty((stop - start, 8))
        phi[:, 0] = ei
        phi[:, 1] = -v
        phi[:, 2] = -a
        phi[:, 3] = xr[start:stop]
        phi[:, 4] = vr
        phi[:, 5] = ar
        pv, nv = (v > db).astype(float), (v < -db).astype(float)
        phi[:, 6] = -pv
        phi[:, 7] = -nv
        if opt.friction != "two-way":  # one level, the other its mirror: a sign column in the level's place
            j = 6 if opt.friction == "positive" else 7
            phi[:, j] = -(pv - nv) if j == 6 else -(nv - pv)
            phi[:, 13 - j] = 0.0
        yield phi, x[start:stop].copy()


def regressor(
    reference: np.ndarray,
    measured: np.ndarray,
    sample_time: float,
    *,
    options: RegressorOptions | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The whole regression ``(Phi, Y)`` of Eq. (3.11) at once (see :func:`iter_regressor`).

    Returns
    -------
    Phi : ndarray, shape (N - 2h, 8)
        Columns :data:`COLUMNS` (h = 2 for central differences).
    Y : ndarray, shape (N - 2h,)
        Measured position [mm].
    """
    blocks = list(iter_regressor(reference, measured, sample_time, options=options))
    return np.vstack([b[0] for b in blocks]), np.concatenate([b[1] for b in blocks])


class SufficientStatistics:
    """Streaming accumulator of P = Phi^T Phi, R = Phi^T Y, gamma = Y^T Y (Eq. 3.19).

    Internally the upper-triangular factor U of the column-scaled matrix [Phi D, Y d_y] is
    updated chunk by chunk (``U <- qr([U; block])``), so the statistics of a capture of any
    length take O(n^2) memory and keep their accuracy (the normal equations are never formed
    unless asked for).

    Parameters
    ----------
    n_columns : int
        Columns of Phi: 8 for Eq. (3.11); more when further linear effects are appended (their
        coefficients are solved jointly with theta_2, see :func:`identification.solve`).
    names : sequence of str, optional
        Column names, for messages (default :data:`COLUMNS` plus ``extra1``, ...).
    """

    def __init__(self, n_columns: int = 8, *, names: Sequence[str] | None = None) -> None:
        if n_columns < 8:
            raise IdentificationError(f"the regression needs at least the 8 columns of Eq. (3.11), got {n_columns}")
        self.n_columns = n_columns
        self.names = tuple(names) if names is not None else COLUMNS + tuple(
            f"extra{i + 1}" for i in range(n_columns - 8)
        )
        self.n_samples = 0
        self.scale: np.ndarray | None = None  # column multipliers D (Phi columns, then Y)
        self._U = np.zeros((0, n_columns + 1))
        self.absmax = np.zeros(n_columns)  # largest |value| seen per column

    def update(self, phi: np.ndarray, y: np.ndarray) -> SufficientStatistics:
        """Add rows; returns self."""
        phi = np.asarray(phi, dtype=float)
        y = np.asarray(y, dtype=float).reshape(-1, 1)
        if phi.ndim != 2 or phi.shape[1] != self.n_columns or phi.shape[0] != y.shape[0]:
            raise IdentificationError(
                f"regressor block has shape {phi.shape} with {y.shape[0]} outputs; "
                f"expected (n, {self.n_columns}) and n outputs"
            )
        if phi.shape[0] == 0:
            return self
        block = np.hstack([phi, y])
        if not np.all(np.isfinite(block)):
            raise IdentificationError("regressor holds NaN or inf (check the capture for non-finite values)")
        if self.scale is None:
            rms = np.sqrt(np.mean(block * block, axis=0))
            self.scale = np.where(rms > 0, 1.0 / np.where(rms > 0, rms, 1.0), 1.0)
        self.absmax = np.maximum(self.absmax, np.max(np.abs(phi), axis=0))
        stacked = np.vstack([self._U, block * self.scale])
        self._U = scipy.linalg.qr(stacked, mode="r", check_finite=False)[0][: self.n_columns + 1]
        self.n_samples += phi.shape[0]
        return self

    @classmethod
    def from_normal_equations(
        cls, P: np.ndarray, R: np.ndarray, gamma: float, *, names: Sequence[str] | None = None
    ) -> SufficientStatistics:
        """Statistics from given P, R, gamma (Eq. 3.19), e.g. from another program."""
        P = np.asarray(P, dtype=float)
        R = np.asarray(R, dtype=float).ravel()
        n = P.shape[0]
        if P.shape != (n, n) or R.shape != (n,):
            raise IdentificationError(f"P must be square (got {P.shape}) and R of matching length (got {R.shape})")
        if not (np.all(np.isfinite(P)) and np.all(np.isfinite(R)) and math.isfinite(float(gamma))):
            raise IdentificationError("P, R and gamma must be finite")
        if not np.allclose(P, P.T, rtol=1e-10, atol=0):
            raise IdentificationError("P = Phi^T Phi must be symmetric")
        M = np.zeros((n + 1, n + 1))
        M[:n, :n] = P
        M[:n, n] = M[n, :n] = R
        M[n, n] = float(gamma)
        diag = np.diag(M)
        if np.any(diag < 0):
            raise IdentificationError("P and gamma must have a non-negative diagonal (sums of squares)")
        d = np.where(diag > 0, 1.0 / np.sqrt(np.where(diag > 0, diag, 1.0)), 1.0)
        Ms = M * d[:, None] * d[None, :]
        try:
            L = np.linalg.cholesky(Ms)
            U = L.T
        except np.linalg.LinAlgError:
            w, V = np.linalg.eigh(Ms)
            U = scipy.linalg.qr(np.sqrt(np.clip(w, 0, None))[:, None] * V.T, mode="r")[0]
        st = cls(n, names=names)
        st.scale = d
        st._U = U
        st.n_samples = -1  # unknown
        st.absmax = np.sqrt(np.clip(np.diag(P), 0, None))
        return st

    # -------------------------------------------------------------- statistics
    @property
    def factor(self) -> np.ndarray:
        """Upper-triangular U with U^T U = D [Phi Y]^T [Phi Y] D (D = diag(:attr:`scale`))."""
        return self._U

    def _gram(self) -> np.ndarray:
        if self.scale is None:
            raise IdentificationError("no data accumulated")
        G = self._U.T @ self._U
        inv = 1.0 / self.scale
        return G * inv[:, None] * inv[None, :]

    @property
    def P(self) -> np.ndarray:
        """Phi^T Phi (Eq. 3.19)."""
        return self._gram()[:-1, :-1]

    @property
    def R(self) -> np.ndarray:
        """Phi^T Y (Eq. 3.19)."""
        return self._gram()[:-1, -1]

    @property
    def gamma(self) -> float:
        """Y^T Y."""
        return float(self._gram()[-1, -1])


def statistics(
    reference: np.ndarray,
    measured: np.ndarray,
    sample_time: float,
    *,
    options: RegressorOptions | None = None,
) -> SufficientStatistics:
    """Sufficient statistics of the regression of Eq. (3.11), streamed in chunks."""
    st = SufficientStatistics(8)
    for phi, y in iter_regressor(reference, measured, sample_time, options=options):
        st.update(phi, y)
    return st
