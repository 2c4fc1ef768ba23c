"""The reduced closed-loop axis model of the thesis and its exact sampled-time simulation.

Model (Eq. 3.3 of the thesis multiplied by s)::

    (s^3 + a1 s^2 + a2 s + a3) x = (b0 s^3 + b1 s^2 + b2 s + a3) x_r - s w
    w = PV(v) d0 + NV(v) d1 + w_ext                                   [mm/s^2]

x is the axis position [mm], x_r the commanded position [mm], v = dx/dt [mm/s], w the
disturbance in acceleration units (Coulomb friction d0 for v > 0 and d1 for v < 0, plus an
optional external input w_ext, default 0). Units: a1 [1/s], a2 [1/s^2], a3 [1/s^3], b0 [-],
b1 [1/s], b2 [1/s^2], d0 and d1 [mm/s^2]. The transfer functions are
``G_track = (b0 s^3 + b1 s^2 + b2 s + a3)/(s^3 + a1 s^2 + a2 s + a3)`` and
``G_dist = s/(s^3 + a1 s^2 + a2 s + a3)`` with ``x = G_track x_r - G_dist w`` (Eq. 3.1; here the
friction is in mm/s^2, i.e. the thesis' K/J is inside d0 and d1).

Simulation contract (the FMU export implements exactly this in C)
------------------------------------------------------------------
**Continuous realisation.** With the time scale ``W = a3**(1/3)`` [rad/s] (requires a3 > 0), the
numerator split ``n2 = b1 - a1 b0``, ``n1 = b2 - a2 b0``, ``n0 = a3 (1 - b0)`` and the scaled
observer-canonical state z (3 states, all in mm)::

    dz/dt = A z + B [x_r, w]^T,   x = C z + D [x_r, w]^T,   v = Cv z + Dv [x_r, w]^T + b0 dx_r/dt

    A = [[-a1,      W, 0],          B = [[n2,       0   ],
         [-a2/W,    0, W],               [n1/W,   -1/W  ],
         [-a3/W^2,  0, 0]]               [n0/W^2,  0    ]]
    C  = [1, 0, 0],   D  = [b0, 0]
    Cv = [-a1, W, 0], Dv = [n2, 0]

(the plain companion form has entries up to a3 ~ 3e5; scaling state i by W^(i-1) makes A's
entries of order W).

**Discretisation** at the sample time T [s]: x_r by first-order hold (exact for a reference that
is linear between samples), w by zero-order hold. With ``E = expm([[A T, B_r T, 0, B_w T],
[0, 0, 1, 0], [0, 0, 0, 0], [0, 0, 0, 0]])`` (6 x 6; B_r, B_w the columns of B)::

    Phi = E[:3, :3]          G0 = E[:3, 3]    (response to a constant x_r)
    N   = E[:3, 4]           (response to the ramp x_r = t/T over one step)
    Gw  = E[:3, 5]

so ``z_{k+1} = Phi z_k + (G0 - N) x_r,k + N x_r,k+1 + Gw w_k``. The causal state
``xi_k = z_k - N x_r,k`` removes x_r,k+1::

    xi_{k+1} = Phi xi_k + Gamma[:, 0] x_r,k + Gamma[:, 1] w_k,  Gamma[:, 0] = G0 - N + Phi N,
                                                               Gamma[:, 1] = Gw
    x_k = C xi_k + d x_r,k,                                       d  = b0 + C N
    v_k = Cv xi_k + dv x_r,k + dvs (x_r,k - x_r,k-1),             dv = n2 + Cv N,  dvs = b0 / T

v_k is the model velocity just before sample k (left limit; the b0 dx_r/dt part uses the slope
of the reference segment that ends at k, so nothing depends on x_r,k+1). x_r,-1 = x_r,0.

**Friction switching.** At sample k: ``f_k = d0`` if v_k > 0, ``d1`` if v_k < 0, ``0`` if v_k == 0;
``w_k = f_k + w_ext,k`` held over [k, k+1).

Coulomb friction switched on sign(v) has no stiction band, so a model at standstill is not
at rest in floating point: rounding leaves |v| ~ 1e-13 mm/s, the friction switches and the
position chatters by about a micrometre (|d| T^2 scale). Implementations that must agree bit for
bit therefore need the same operation order (below) and no fused multiply-add (C:
``-ffp-contract=off``).

**Initial state**: at rest at x_r,0, the steady state of a constant reference (x = x_r).
The loop runs on deviations from the first reference sample, ``r_k = x_r,k - x_r,0`` (the
model is linear in the reference and G_track(0) = 1), so the state at rest is exactly zero,
v_0 == 0 and the friction stays off until the reference moves; the position is
``x_k = (... + d r_k) + x_r,0``. (In absolute coordinates the rest state
``z_0 = x_r,0 [1 - b0, (a1 - b1)/W, (a2 - b2)/W^2]`` leaves rounding noise of ~1e-13 mm/s in
v_0, enough to switch the friction on at sample 0.)

**Order of floating-point operations** per sample (sums left to right)::

    r_k  = xr_k - xr_0
    x_k  = (((C0 xi0 + C1 xi1) + C2 xi2) + d r_k) + xr_0
    v_k  = (((Cv0 xi0 + Cv1 xi1) + Cv2 xi2) + dv r_k) + dvs (r_k - r_{k-1})
    w_k  = f_k + wext_k
    xi'_i = (((Phi_i0 xi0 + Phi_i1 xi1) + Phi_i2 xi2) + Gamma_i0 r_k) + Gamma_i1 w_k

:func:`discretize` returns these matrices (:class:`DiscreteModel`); :func:`simulate` runs the
loop compiled with numba.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import scipy.linalg

from identification.dead_time import delay_reference
from identification.effect_record import EffectRecord
from identification.kernels import NO_FOURIER, NO_STRIBECK, run_exact
from identification.model_format import model_to_dict, write_model
from identification.parameters import PARAMETER_NAMES, PARAMETER_UNITS
from identification.poles import pole_splits, pole_table, zero_table
from identification.setpoint_filter import filter_reference
from vcnc.core.errors import InputError

__all__ = [
    "PARAMETER_NAMES",
    "PARAMETER_UNITS",
    "DiscreteModel",
    "continuous_state_space",
    "discretize",
    "simulate",
    "ReducedAxisModel",
]


def _params(parameters: Mapping[str, float]) -> dict[str, float]:
    """Validated parameter dict (all eight names, finite floats, a3 > 0)."""
    if hasattr(parameters, "parameters") and not isinstance(parameters, Mapping):
        parameters = parameters.parameters  # a ReducedAxisModel
    missing = [k for k in PARAMETER_NAMES if k not in parameters]
    if missing:
        raise InputError(f"reduced-model parameters {missing} missing; expected {', '.join(PARAMETER_NAMES)}")
    out = {}
    for k in PARAMETER_NAMES:
        v = float(parameters[k])
        if not math.isfinite(v):
            raise InputError(f"reduced-model parameter {k} [{PARAMETER_UNITS[k]}] is not finite (got {v!r})")
        out[k] = v
    if not out["a3"] > 0.0:
        raise InputError(
            f"reduced-model parameter a3 [1/s^3] must be > 0 for a stable closed loop (got {out['a3']!r})"
        )
    return out


def continuous_state_space(parameters: Mapping[str, float]) -> dict[str, Any]:
    """The scaled continuous realisation of the module docstring.

    Parameters
    ----------
    parameters : mapping
        a1..d1 of Eq. (3.3) (units in :data:`PARAMETER_UNITS`).

    Returns
    -------
    dict
        ``A`` (3x3), ``B`` (3x2, columns x_r and w), ``C`` (3,), ``D`` (2,), ``Cv`` (3,), ``Dv``
        (2,), ``b0`` (coefficient of dx_r/dt in v) and the time scale ``W`` [rad/s].
    """
    p = _params(parameters)
    a1, a2, a3, b0, b1, b2 = (p[k] for k in ("a1", "a2", "a3", "b0", "b1", "b2"))
    W = a3 ** (1.0 / 3.0)
    n2, n1, n0 = b1 - a1 * b0, b2 - a2 * b0, a3 * (1.0 - b0)
    A = np.array([[-a1, W, 0.0], [-a2 / W, 0.0, W], [-a3 / W**2, 0.0, 0.0]])
    B = np.array([[n2, 0.0], [n1 / W, -1.0 / W], [n0 / W**2, 0.0]])
    return {
        "A": A,
        "B": B,
        "C": np.array([1.0, 0.0, 0.0]),
        "D": np.array([b0, 0.0]),
        "Cv": np.array([-a1, W, 0.0]),
        "Dv": np.array([n2, 0.0]),
        "b0": b0,
        "W": W,
    }


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class DiscreteModel:
    """Sampled reduced model in the causal FOH/ZOH form of the module docstring.

    Attributes
    ----------
    phi : ndarray (3, 3)
        State transition over one sample.
    gamma : ndarray (3, 2)
        Input matrix; column 0 multiplies x_r,k [mm], column 1 multiplies w_k [mm/s^2].
    c : ndarray (3,)
        Position output row.
    d : float
        Position feedthrough of x_r,k [-].
    cv : ndarray (3,)
        Velocity output row [1/s].
    dv : float
        Velocity feedthrough of x_r,k [1/s].
    dvs : float
        Velocity coefficient of the last reference step x_r,k - x_r,k-1 (= b0/T) [1/s].
    xi0 : ndarray (3,)
        Initial causal state for x_r,0 = 1 mm (scale by x_r,0).
    d0, d1 : float
        Friction levels [mm/s^2].
    sample_time : float
        T [s].
    """

    phi: np.ndarray
    gamma: np.ndarray
    c: np.ndarray
    d: float
    cv: np.ndarray
    dv: float
    dvs: float
    xi0: np.ndarray
    d0: float
    d1: float
    sample_time: float

    def __iter__(self):
        """Unpacks as ``Phi, Gamma, C, D`` (position output, x_r and w feedthrough)."""
        return iter((self.phi, self.gamma, self.c, np.array([self.d, 0.0])))


def discretize(parameters: Mapping[str, float], sample_time: float) -> DiscreteModel:
    """Sample the reduced model at ``sample_time`` (FOH on x_r, ZOH on w), causal form.

    Parameters
    ----------
    parameters : mapping or ReducedAxisModel
        a1..d1 of Eq. (3.3).
    sample_time : float
        T [s], > 0.

    Returns
    -------
    DiscreteModel
        Unpacks as ``(Phi, Gamma, C, D)``; see the module docstring for every matrix.
    """
    T = float(sample_time)
    if not (math.isfinite(T) and T > 0.0):
        raise InputError(f"sample_time [s] must be a positive number (got {sample_time!r})")
    p = _params(parameters)
    return _discretize_cached(tuple(p[k] for k in PARAMETER_NAMES), T)


@functools.lru_cache(maxsize=256)
def _discretize_cached(values: tuple[float, ...], T: float) -> DiscreteModel:
    p = dict(zip(PARAMETER_NAMES, values))
    ss = continuous_state_space(p)
    A, B = ss["A"], ss["B"]
    M = np.zeros((6, 6))
    M[:3, :3] = A * T
    M[:3, 3] = B[:, 0] * T
    M[:3, 5] = B[:, 1] * T
    M[3, 4] = 1.0
    E = scipy.linalg.expm(M)
    phi = E[:3, :3]
    g0, n_ramp, gw = E[:3, 3], E[:3, 4], E[:3, 5]
    gamma = np.column_stack([g0 - n_ramp + phi @ n_ramp, gw])
    c, cv = ss["C"], ss["Cv"]
    b0, W = p["b0"], ss["W"]
    z0 = np.array([1.0 - b0, (p["a1"] - p["b1"]) / W, (p["a2"] - p["b2"]) / W**2])
    return DiscreteModel(
        phi=phi,
        gamma=gamma,
        c=c,
        d=float(b0 + c @ n_ramp),
        cv=cv,
        dv=float(ss["Dv"][0] + cv @ n_ramp),
        dvs=b0 / T,
        xi0=z0 - n_ramp,
        d0=p["d0"],
        d1=p["d1"],
        sample_time=T,
    )


def simulate(
    parameters: Mapping[str, float],
    reference: np.ndarray,
    sample_time: float,
    *,
    disturbance: np.ndarray | None = None,
    return_velocity: bool = False,
) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
    """Predicted axis position for a sampled reference (contract of the module docstring).

    Parameters
    ----------
    parameters : mapping or ReducedAxisModel
        a1..d1 of Eq. (3.3).
    reference : array_like, shape (N,)
        Commanded position x_r,k [mm].
    sample_time : float
        T [s].
    disturbance : array_like, shape (N,), optional
        External disturbance w_ext,k [mm/s^2] (held over each sample), default 0.
    return_velocity : bool
        Also return the model velocity v_k [mm/s] that switched the friction.

    Returns
    -------
    ndarray, shape (N,)
        Position x_k [mm] (and velocity v_k [mm/s] when asked).
    """
    xr = np.ascontiguousarray(reference, dtype=float)
    if xr.ndim != 1:
        raise InputError(f"reference must be one-dimensional (got shape {xr.shape})")
    if xr.size == 0:
        raise InputError("reference is empty; expected at least one sample [mm]")
    if not np.all(np.isfinite(xr)):
        raise InputError(f"reference [mm] holds NaN or inf at sample {int(np.argmin(np.isfinite(xr)))}")
    if disturbance is None:
        wext = np.zeros_like(xr)
    else:
        wext = np.ascontiguousarray(disturbance, dtype=float)
        if wext.shape != xr.shape:
            raise InputError(f"disturbance has shape {wext.shape}, expected {xr.shape} (one value per sample)")
        if not np.all(np.isfinite(wext)):
            raise InputError("disturbance [mm/s^2] holds NaN or inf")
    m = discretize(parameters, sample_time)
    pos = np.empty_like(xr)
    vel = np.empty_like(xr)
    # The loop runs on deviations from the first reference sample: the state at rest is then
    # exactly zero, so v_0 == 0 and the friction stays off until the reference moves.
    run_exact(m.phi, m.gamma, m.c, m.d, m.cv, m.dv, m.dvs, m.d0, m.d1, xr, wext, NO_STRIBECK, 0.0, 0.0,
              NO_FOURIER, pos, vel)
    return (pos, vel) if return_velocity else pos


# ---------------------------------------------------------------------------------------- model


@dataclasses.dataclass(frozen=True, kw_only=True, eq=False)
class ReducedAxisModel:
    """An identified (or given) reduced closed-loop axis model, Eq. (3.3) of the thesis.

    Attributes
    ----------
    parameters : dict
        a1..d1 (units in :data:`PARAMETER_UNITS`).
    sample_time : float
        Sample time T [s] of the data it was identified from (the default for :meth:`simulate`).
    axis : str
        Axis name.
    method : str
        Solver that produced it (``exact``, ``ga``, ``kkt``; ``+oe`` when refined by output error;
        ``given`` for a model built from known parameters).
    poles : dict
        ``omega_n_hz`` [Hz], ``zeta`` [-], ``p_hz`` [Hz] of Eq. (3.7).
    bounds : dict
        Search box used: ``{"p_hz": (lo, hi), "omega_n_hz": (lo, hi), "zeta": (lo, hi)}``.
    fit : dict
        Prediction of the identification data: ``rms_um``, ``max_um`` and solver details.
    effects : list of EffectRecord
        Effects added by the residual diagnosis (:class:`identification.effect_record.EffectRecord`,
        typed records that read as the model file's mappings); empty for a plain reduced model.
    validation : dict
        ``rms_before_um``/``rms_after_um`` of the diagnosis; empty when not run.
    delay_s : float
        Dead time between the recorded reference and the loop [s] (:mod:`identification.dead_time`):
        every simulation delays the reference it is given by this much first (> 0: the recorded
        reference leads).
    setpoint_filter_s : float
        Length of a moving-average setpoint filter between the (delayed) reference and the loop
        [s] (:mod:`identification.setpoint_filter`; 0: none): every simulation filters the
        delayed reference by it.
    """

    parameters: dict
    sample_time: float
    axis: str = "x"
    method: str = "given"
    poles: dict = dataclasses.field(default_factory=dict)
    bounds: dict = dataclasses.field(default_factory=dict)
    fit: dict = dataclasses.field(default_factory=dict)
    effects: list[EffectRecord] = dataclasses.field(default_factory=list)
    validation: dict = dataclasses.field(default_factory=dict)
    delay_s: float = 0.0
    setpoint_filter_s: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "parameters", _params(self.parameters))
        object.__setattr__(self, "effects", [EffectRecord(e) for e in self.effects])
        if not math.isfinite(self.delay_s):
            raise InputError(f"delay_s [s] must be finite (got {self.delay_s!r})")
        if not (math.isfinite(self.setpoint_filter_s) and self.setpoint_filter_s >= 0.0):
            raise InputError(f"setpoint_filter_s [s] must be finite and >= 0 (got {self.setpoint_filter_s!r})")
        if not (math.isfinite(self.sample_time) and self.sample_time > 0):
            raise InputError(f"sample_time [s] must be positive (got {self.sample_time!r})")
        if not self.poles:
            p = self.parameters
            splits = pole_splits(p["a1"], p["a2"], p["a3"])
            if splits:
                object.__setattr__(self, "poles", dict(splits[0]))

    # ----------------------------------------------------------------- simulation
    def simulate(
        self,
        reference: np.ndarray,
        *,
        sample_time: float | None = None,
        disturbance: np.ndarray | None = None,
    ) -> np.ndarray:
        """Predicted position [mm] for a reference [mm] sampled at ``sample_time`` [s].

        ``sample_time`` defaults to the model's. See the module docstring for the exact
        discretisation and friction switching.
        """
        T = self.sample_time if sample_time is None else sample_time
        return simulate(self.parameters, self.loop_reference(reference, T), T, disturbance=disturbance)

    def loop_reference(self, reference: np.ndarray, sample_time: float | None = None) -> np.ndarray:
        """The reference the loop receives: ``reference`` [mm] delayed by :attr:`delay_s`, then
        through the setpoint filter of :attr:`setpoint_filter_s`."""
        xr = np.asarray(reference, dtype=float)
        T = self.sample_time if sample_time is None else sample_time
        if self.delay_s != 0.0:
            xr = delay_reference(xr, self.delay_s / T)
        if self.setpoint_filter_s != 0.0:
            xr = filter_reference(xr, self.setpoint_filter_s / T)
        return xr

    def simulate_reference(self, reference: np.ndarray, sample_time: float) -> np.ndarray:
        """Machine-axis protocol: predicted position [mm] for a sampled reference [mm]."""
        return self.simulate(reference, sample_time=sample_time)

    def velocity(self, reference: np.ndarray, *, sample_time: float | None = None) -> np.ndarray:
        """Model velocity v_k [mm/s] (the signal that switches the friction)."""
        T = self.sample_time if sample_time is None else sample_time
        return simulate(self.parameters, self.loop_reference(reference, T), T, return_velocity=True)[1]

    def discretize(self, sample_time: float | None = None) -> DiscreteModel:
        """The sampled model at ``sample_time`` [s] (default the model's)."""
        return discretize(self.parameters, self.sample_time if sample_time is None else sample_time)

    # ------------------------------------------------------------- transfer functions
    @property
    def G_track(self):
        """Tracking transfer function x/x_r (python-control ``TransferFunction``), Eq. (3.1)."""
        import control

        p = self.parameters
        return control.tf([p["b0"], p["b1"], p["b2"], p["a3"]], [1.0, p["a1"], p["a2"], p["a3"]])

    def tracking_response(self, s: complex | np.ndarray) -> complex | np.ndarray:
        """:attr:`G_track` evaluated at ``s`` [rad/s] (complex), without python-control: its numerator and
        denominator by Horner's rule, as ``TransferFunction.__call__`` evaluates them (the same numbers). Importing
        python-control took 1 s of a ``vcnc identify`` run (11 s on two loaded cores), for the one frequency the
        setpoint filter's signature needs (:func:`identification.filter_signature.notch_ratio`)."""
        p = self.parameters
        return np.polyval([p["b0"], p["b1"], p["b2"], p["a3"]], s) / np.polyval([1.0, p["a1"], p["a2"], p["a3"]], s)

    @property
    def G_dist(self):
        """Disturbance transfer function [mm per mm/s^2]: x = G_track x_r - G_dist w, Eq. (3.1)."""
        import control

        p = self.parameters
        return control.tf([1.0, 0.0], [1.0, p["a1"], p["a2"], p["a3"]])

    def pole_table(self) -> list[dict[str, float]]:
        """Closed-loop poles as frequency [Hz] and damping [-] (Tables 3.3-3.5)."""
        p = self.parameters
        return pole_table(p["a1"], p["a2"], p["a3"])

    def zero_table(self) -> list[dict[str, float]]:
        """Zeros of G_track as frequency [Hz] and damping [-] (Tables 3.3-3.5)."""
        p = self.parameters
        return zero_table(p["b0"], p["b1"], p["b2"], p["a3"])

    def is_stable(self) -> bool:
        """True when all three poles are in the open left half plane."""
        return all(r["real"] < 0.0 for r in self.pole_table())

    def poles_on_bounds(self, *, tolerance: float = 1e-3) -> list[tuple[str, int, bool]]:
        """The pole variables the fit left on a bound of its box (``bounds``): ``(key, side, at_nyquist)`` with
        ``side`` 0 (lower) or 1 (upper) and ``at_nyquist`` when that bound is the record's Nyquist frequency
        (the box of thesis Sec. 4.3 ends there: the loop may be faster than the record resolves). On a bound:
        within ``tolerance`` of it, relative."""
        nyquist = 0.5 / self.sample_time
        out = []
        for key in ("omega_n_hz", "zeta", "p_hz"):
            value, box = self.poles.get(key), (self.bounds or {}).get(key)
            if value is None or box is None:
                continue
            for side, bound in enumerate(box):
                if abs(value - bound) <= tolerance * max(abs(bound), 1e-12):
                    at_nyquist = side == 1 and key != "zeta" and abs(bound - nyquist) <= tolerance * nyquist
                    out.append((key, side, at_nyquist))
        return out

    # ------------------------------------------------------------------- plots
    def plot(self, ax=None, *, truth: Mapping[str, float] | ReducedAxisModel | None = None, f_max_hz=None):
        """Bode plots of G_track and G_dist, like Fig. 3.5 of the thesis.

        Parameters
        ----------
        ax : array of 4 matplotlib Axes, optional
            (|G_track|, phase G_track, |G_dist|, phase G_dist); a new 2x2 figure when omitted.
        truth : mapping or ReducedAxisModel, optional
            True parameters, drawn dashed for comparison.
        f_max_hz : float, optional
            Upper frequency [Hz]; default the Nyquist frequency.

        Returns
        -------
        ndarray of Axes
        """
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(2, 2, figsize=(10, 6), sharex=True)
        axes = np.asarray(ax).ravel()
        fmax = f_max_hz or 0.5 / self.sample_time
        f = np.logspace(-1, math.log10(fmax), 400)
        models = [("identified", self, "-")]
        if truth is not None:
            tm = truth if isinstance(truth, ReducedAxisModel) else ReducedAxisModel(
                parameters=dict(truth), sample_time=self.sample_time
            )
            models.append(("true", tm, "--"))
        for label, m, style in models:
            for col, g in enumerate((m.G_track, m.G_dist)):
                resp = g(2j * np.pi * f)
                axes[col * 2].loglog(f, np.abs(resp), style, label=label)
                axes[col * 2 + 1].semilogx(f, np.degrees(np.unwrap(np.angle(resp))), style, label=label)
        axes[0].set_ylabel("|G_track| [-]")
        axes[1].set_ylabel("phase G_track [deg]")
        axes[2].set_ylabel("|G_dist| [mm/(mm/s^2)]")
        axes[3].set_ylabel("phase G_dist [deg]")
        for a in axes:
            a.grid(True, which="both", alpha=0.3)
        for a in axes[-2:]:
            a.set_xlabel("frequency [Hz]")
        axes[0].legend()
        return axes

    # --------------------------------------------------------------------- files
    def to_dict(self) -> dict[str, Any]:
        """The model as a ``vcnc.axis-model/1`` dictionary (ARCHITECTURE.md, "Model file")."""
        return model_to_dict(self)

    def to_json(self, path) -> None:
        """Write the model file (atomic: nothing half-written on failure)."""
        write_model(self, path)
