"""Residual analysis of a capture against an identified model: what the model fails to explain.

Two residuals (thesis Sec. 3.2-3.3):

* **simulation (output) error** ``x_k - x_hat_k``: the measured position minus the model's
  free-run prediction from the reference alone (``model.simulate``) - what a user of the model
  sees;
* **equation error** ``Y_k - Phi_k theta``: the residual of the regression of Eq. (3.11) at the
  model's parameters (theta from a1..d1 by Eq. 3.10), computed from measured derivatives. It is
  not filtered by the closed loop, so an unmodelled force shows in it with its own waveform
  (a square-wave load stays square), and it points at *when* and *at which state* the model's
  force balance fails.

Views (:class:`ResidualAnalysis`): against time, velocity (where friction effects and reversals
show), position (position-periodic forces, lead error), acceleration (saturation, inertia), and the
amplitude spectrum (periodic loads, resonances).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from identification.augmented import predict_record
from identification.reduced_model import ReducedAxisModel
from identification.regressor import RegressorOptions, regressor
from vcnc.core.metrics import error_metrics

__all__ = ["ResidualAnalysis", "analyse", "equation_error", "spectrum", "binned", "plot_before_after",
           "residual_evidence", "motion_coherence"]


def equation_error(model: ReducedAxisModel, reference: np.ndarray, measured: np.ndarray,
                   sample_time: float, *, options: RegressorOptions | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Equation error of Eq. (3.11) at the model's parameters.

    Returns
    -------
    rows : ndarray of int
        Sample index of each regressor row.
    residual : ndarray
        ``Y - Phi theta`` [mm] (disturbance effects of an augmented model included in the
        prediction).
    """
    opt = options or RegressorOptions()
    phi, y = regressor(reference, measured, sample_time, options=opt)
    p = model.parameters
    a2 = p["a2"]
    theta = np.array([p["a3"], p["a1"], 1.0, p["b2"], p["b1"], p["b0"], p["d0"], p["d1"]]) / a2
    pred = phi @ theta
    rows = np.arange(opt.half_width, opt.half_width + y.size)
    if getattr(model, "elements", ()):
        from identification.searches import disturbance_offset

        pred = pred + disturbance_offset(model, -phi[:, 1], y, rows * sample_time)
    return rows, y - pred


def spectrum(residual: np.ndarray, sample_time: float) -> tuple[np.ndarray, np.ndarray]:
    """One-sided amplitude spectrum (Hann window, mean removed): (frequency [Hz], amplitude [unit of input])."""
    r = np.asarray(residual, float)
    r = r - r.mean()
    w = np.hanning(r.size)
    amp = np.abs(np.fft.rfft(r * w)) * 2.0 / max(np.sum(w), 1e-300)
    return np.fft.rfftfreq(r.size, sample_time), amp


def binned(x: np.ndarray, r: np.ndarray, bins: int = 40) -> dict[str, np.ndarray]:
    """Mean and RMS of ``r`` in equal-count bins of ``x`` (``center``, ``mean``, ``rms``, ``count``)."""
    x = np.asarray(x, float)
    r = np.asarray(r, float)
    edges = np.unique(np.quantile(x, np.linspace(0, 1, bins + 1)))
    idx = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, max(edges.size - 2, 0))
    k = max(edges.size - 1, 1)
    count = np.bincount(idx, minlength=k).astype(float)
    s = np.bincount(idx, weights=r, minlength=k)
    s2 = np.bincount(idx, weights=r * r, minlength=k)
    cx = np.bincount(idx, weights=x, minlength=k)
    with np.errstate(invalid="ignore", divide="ignore"):
        return {"center": cx / count, "mean": s / count, "rms": np.sqrt(s2 / count), "count": count}


def residual_evidence(residual: np.ndarray, reference: np.ndarray, sample_time: float,
                      active: np.ndarray | None = None, *, peaks: int = 5) -> dict[str, Any]:
    """What a residual correlates with, for a person to act on when no named effect explains it.

    Parameters
    ----------
    residual : ndarray, shape (N,)
        Simulation error x - x_hat [mm].
    reference : ndarray, shape (N,)
        Commanded position [mm] (its derivatives are the states the residual is set against: free
        of measurement noise).
    sample_time : float
        T [s].
    active : ndarray of bool, optional
        Samples to analyse (default all).
    peaks : int
        Spectral peaks listed.

    Returns
    -------
    dict
        ``rms_um``; ``spectral_peaks`` (``frequency_hz``, ``amplitude_um``, largest first; the
        Hann-windowed amplitude spectrum of the residual over the analysed samples);
        ``correlation`` (Pearson coefficient [-] with ``position``, ``velocity``, ``direction``
        (sign of the velocity), ``acceleration`` and ``time``); ``explained_share`` (share of the
        residual's variance explained by its mean in 20 equal-count bins of each, which also
        catches a dependence that is not linear [-]); ``strongest`` (the largest of those).
    """
    r = np.asarray(residual, float)
    xr = np.asarray(reference, float)
    m = np.ones(r.size, bool) if active is None else np.asarray(active, bool)
    v = np.gradient(xr, sample_time)
    a = np.gradient(v, sample_time)
    t = np.arange(r.size) * sample_time
    signals = {"position": xr, "velocity": v, "direction": np.sign(v), "acceleration": a, "time": t}
    rr = r[m]
    out: dict[str, Any] = {"rms_um": float(np.sqrt(np.mean(rr * rr)) * 1e3) if rr.size else float("nan")}
    f, amp = spectrum(rr, sample_time)
    ok = f > 0
    f, amp = f[ok], amp[ok]
    interior = np.flatnonzero((amp[1:-1] > amp[:-2]) & (amp[1:-1] >= amp[2:])) + 1 if amp.size > 2 else np.array([])
    top = interior[np.argsort(amp[interior])[::-1][:peaks]] if interior.size else np.array([], int)
    out["spectral_peaks"] = [{"frequency_hz": float(f[i]), "amplitude_um": float(amp[i] * 1e3)} for i in top]
    corr, share = {}, {}
    var = float(np.var(rr)) if rr.size else 0.0
    for name, s in signals.items():
        sm = s[m]
        if rr.size < 3 or np.ptp(sm) == 0 or var == 0:
            corr[name], share[name] = 0.0, 0.0
            continue
        corr[name] = float(np.corrcoef(sm, rr)[0, 1])
        if name == "direction":
            groups = [rr[sm == k] for k in (-1.0, 0.0, 1.0) if np.any(sm == k)]
            between = sum(g.size * (g.mean() - rr.mean()) ** 2 for g in groups) / rr.size
        else:
            b = binned(sm, rr, 20)
            c = np.nan_to_num(b["count"])
            between = float(np.sum(c * (np.nan_to_num(b["mean"]) - rr.mean()) ** 2) / max(c.sum(), 1.0))
        share[name] = float(between / var)
    out["correlation"] = corr
    out["explained_share"] = share
    best = max(share, key=share.get)
    out["strongest"] = {"with": best, "explained_share": share[best], "correlation": corr[best]}
    return out


def motion_coherence(residual: np.ndarray, reference: np.ndarray, sample_time: float, active: np.ndarray,
                     frequencies: list[float], *, band: float = 0.2) -> float:
    """Largest magnitude-squared coherence [-] of the residual with a force of the commanded motion (the
    commanded acceleration, or the sign of the commanded velocity) within +/- ``band`` of any of ``frequencies`` [Hz].

    A mode the axis' own motion excites answers the reference: its line in the residual is coherent
    with a force the motion puts on the axis - the inertial force (the commanded acceleration: 0.9 for
    the fadal-pid 60 Hz mode) or the Coulomb friction that flips with the commanded velocity's sign at
    every reversal; an external line (a shaker) is coherent with neither (0.17 and 0.09 for a 55 Hz
    shaker; ``tests/identification/test_residual.py``, ``tests/identification/test_diagnosis_folds.py``).
    The friction's step is the larger drive of a mode on short, fast moves: ident_fuzz seed 21 case 24
    (ballscrew-ppc/x, a 48 Hz mode of damping 0.07, 86 moves of +/-3 mm) has coherence 0.34 with the
    acceleration and 0.93 with the velocity's sign. Each is an ordinary coherence, not the multiple
    coherence of both (Bendat and Piersol, Random Data, 4th ed., Sec. 7.3): with two inputs the latter's
    estimate of an unrelated line is about twice as high on the same segments (0.35-0.39 for the test's
    shaker), close to the diagnosis' 0.5; a mode driven by both forces alike keeps 0.6 and 0.74.
    Welch estimates (``scipy.signal.coherence``, segments of about 0.5 s) over the active samples.
    """
    import scipy.signal

    r = np.asarray(residual, float)[active]
    v = np.gradient(np.asarray(reference, float), sample_time)
    a = np.gradient(v, sample_time)[active]
    # the velocity's sign with a dead band: the commanded velocity at rest is rounding noise
    s = np.where(np.abs(v) > 1e-6 * max(float(np.max(np.abs(v))), 1e-300), np.sign(v), 0.0)[active]
    nper = int(2 ** np.ceil(np.log2(0.5 / sample_time)))
    if r.size < 2 * nper:
        nper = max(16, int(2 ** np.floor(np.log2(max(r.size // 4, 16)))))
    best = 0.0
    for force in (a, s):
        f, c = scipy.signal.coherence(r, force, fs=1.0 / sample_time, nperseg=nper)
        for f0 in frequencies:
            sel = (f >= (1 - band) * f0) & (f <= (1 + band) * f0)
            if sel.any():
                best = max(best, float(np.nanmax(np.nan_to_num(c[sel]))))
    return best


@dataclasses.dataclass(eq=False)
class ResidualAnalysis:
    """Residuals of one capture axis against a model, with the views of the module docstring.

    Attributes
    ----------
    t : ndarray
        Time [s].
    reference, measured, predicted : ndarray
        x_r, x and the model's prediction x_hat [mm].
    simulation_error : ndarray
        x - x_hat [mm].
    velocity, acceleration : ndarray
        Commanded velocity [mm/s] and acceleration [mm/s^2] (central differences of x_r: the
        state the residual is plotted against, free of measurement noise).
    eq_rows, equation_error : ndarray
        Regressor row sample indices and the equation error [mm].
    """

    t: np.ndarray
    reference: np.ndarray
    measured: np.ndarray
    predicted: np.ndarray
    simulation_error: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    eq_rows: np.ndarray
    equation_error: np.ndarray
    sample_time: float

    def metrics(self) -> dict[str, Any]:
        """RMS and max of both residuals [um]."""
        e, q = self.simulation_error, self.equation_error
        return {"simulation": error_metrics(e), "equation": error_metrics(q)}

    def spectrum(self, which: str = "simulation") -> tuple[np.ndarray, np.ndarray]:
        """Amplitude spectrum [um] of the ``simulation`` or ``equation`` error."""
        r = self.simulation_error if which == "simulation" else self.equation_error
        f, a = spectrum(r, self.sample_time)
        return f, a * 1e3

    def against(self, what: str, *, bins: int = 40) -> dict[str, np.ndarray]:
        """Binned simulation error [um] against ``velocity``, ``position`` or ``acceleration``."""
        x = {"velocity": self.velocity, "position": self.reference, "acceleration": self.acceleration}[what]
        return binned(x, self.simulation_error * 1e3, bins)

    def reversal_profile(self, half_window: int = 50) -> tuple[np.ndarray, np.ndarray]:
        """Mean simulation error [um] around commanded velocity reversals (+ to - and - to +, signed)."""
        v = self.velocity
        s = np.sign(v)
        nz = np.flatnonzero(s != 0)
        idx = nz[1:][s[nz[1:]] != s[nz[:-1]]]
        idx = idx[(idx > half_window) & (idx < v.size - half_window)]
        if idx.size == 0:
            return np.arange(-half_window, half_window + 1) * self.sample_time, np.zeros(2 * half_window + 1)
        segs = np.array([self.simulation_error[i - half_window:i + half_window + 1] * -s[i] for i in idx])
        return np.arange(-half_window, half_window + 1) * self.sample_time, segs.mean(axis=0) * 1e3

    def plot(self, ax=None, *, label: str = "", color=None):
        """Residual vs time, velocity, position and its spectrum (4 axes)."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(2, 2, figsize=(11, 7))
        a = np.asarray(ax).ravel()
        a[0].plot(self.t, self.simulation_error * 1e3, lw=0.6, label=label, color=color)
        a[0].set_xlabel("time [s]")
        a[0].set_ylabel("simulation error [um]")
        for k, what, unit in ((1, "velocity", "mm/s"), (2, "position", "mm")):
            b = self.against(what)
            a[k].plot(b["center"], b["mean"], ".-", lw=0.8, label=label, color=color)
            a[k].set_xlabel(f"commanded {what} [{unit}]")
            a[k].set_ylabel("mean error per bin [um]")
        f, amp = self.spectrum()
        # log-log up to the Nyquist frequency: a structural mode above 100 Hz shows beside the loop's band
        a[3].loglog(f[1:], amp[1:] + 1e-12, lw=0.7, label=label, color=color)
        a[3].set_xlabel("frequency [Hz]")
        a[3].set_ylabel("amplitude [um]")
        a[3].set_xlim(f[1], 0.5 / self.sample_time)
        for x in a:
            x.grid(True, alpha=0.3)
        return a


def analyse(model: ReducedAxisModel, reference: np.ndarray, measured: np.ndarray,
            sample_time: float) -> ResidualAnalysis:
    """Residual analysis of ``measured`` [mm] against ``model`` driven by ``reference`` [mm]."""
    xr = np.asarray(reference, float)
    x = np.asarray(measured, float)
    # at the model's own sample time, as the fit and the diagnosis predict the record (sub-steps below 1 ms)
    pred = (predict_record(model, xr) if sample_time == model.sample_time
            else model.simulate(xr, sample_time=sample_time))
    rows, eq = equation_error(model, xr, x, sample_time)
    v = np.gradient(xr, sample_time)
    a = np.gradient(v, sample_time)
    return ResidualAnalysis(t=np.arange(x.size) * sample_time, reference=xr, measured=x, predicted=pred,
                            simulation_error=x - pred, velocity=v, acceleration=a, eq_rows=rows,
                            equation_error=eq, sample_time=sample_time)


def _rms(a: np.ndarray) -> float:
    return float(np.sqrt(np.mean(np.square(a))))


def plot_before_after(reference: np.ndarray, measured: np.ndarray, sample_time: float,
                      before: ReducedAxisModel, after: ReducedAxisModel, ax=None):
    """The report figure: residual before (reduced model) and after (augmented) against time,
    velocity and position, and their spectra.

    Returns
    -------
    ndarray of 4 Axes (a new 2 x 2 figure when ``ax`` is None).
    """
    rb = analyse(before, reference, measured, sample_time)
    ra = analyse(after, reference, measured, sample_time)
    mb, ma = rb.metrics()["simulation"], ra.metrics()["simulation"]
    # the records of a diagnosed model, else the elements of one augmented by hand
    names = [e.get("name") for e in (after.effects or [])] or [e.NAME for e in getattr(after, "elements", ())]
    axes = rb.plot(ax, label=f"reduced model (RMS {mb['rms_um']:.3g} um)", color="tab:red")
    final = f"+ {', '.join(names)}" if names else "final model: no effect added"
    ra.plot(axes, label=f"{final} (RMS {ma['rms_um']:.3g} um)", color="tab:blue")
    axes[0].legend(fontsize=8)
    fig = axes[0].figure
    fig.suptitle("residual of the measured position over the whole record, before and after the diagnosis\n"
                 "(RMS: the whole record predicted by the model fitted on it; the held-out validation RMS is in the "
                 "report's table)", fontsize=10)
    fig.tight_layout()
    return axes
