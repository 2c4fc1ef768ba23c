"""Residual diagnosis: find what the reduced model fails to explain, name the effect, add it.

``diagnose(capture, model, axis=...)`` is called by :func:`identification.identify` and returns
the model augmented with the effects the data support (an
:class:`~identification.augmented.AugmentedAxisModel`; the plain model when none), with
``effects`` and ``validation`` filled in as the model-file contract asks.

Procedure (forward selection judged on held-out data)
-----------------------------------------------------
1. **Trim and fold.** Idle stretches (the reference at rest and the axis settled, outside
   ``margin_s`` around every move) neither identify nor validate
   (:func:`identification.segments.active_mask`). The record is cut into ``folds`` contiguous
   folds at points where the reference rests or reverses, merged until each moves in both
   directions (:func:`identification.segments.folds`; what is still missing is a warning, a
   capture that never moves an error). The searches fit on the active samples outside the last
   fold and check their own choices (harmonic counts) on it.
2. **Search.** Every effect not yet in the model proposes its best instance
   (:mod:`identification.searches`: equation-error partial regressions for disturbance
   terms with their nonlinear parameter searched - Stribeck velocity, position period, time
   period from the residual spectrum, harmonics by validation equation error - and simulations
   for the structured elements: delays 1..8 samples, saturation limits, backlash widths,
   resonance frequencies from the residual spectrum).
3. **Refit.** The ``top`` proposals with the lowest screening error are refitted jointly - all
   reduced parameters with the pole bounds of Eq. (3.8), the effect's parameters (including its
   nonlinear ones, except whole-sample delays and a load's window) and the parameters of the
   effects already in - by output error (simulation error) on all active samples. A screen is a rough cost (a
   start with the loop moved by a Gauss-Newton step or two): when none of these proposals passes step 4, the
   round refits the others too, those screened above the current model included, by a few iterations, and refits
   in full and judges the ``top`` whose short refit lowers the active samples' error most, by at least half of
   ``min_gain`` (:func:`_second_chance`;
   the round's record lists them under ``second_chance``).
4. **Judge.** Each refitted proposal is judged on every fold held out in turn (the fit refitted
   on the other folds by a few Levenberg-Marquardt iterations from it, sensitivities shared by
   the folds: :func:`_judge`). The proposal with the lowest pooled held-out simulation RMS is added when it
   lowers it by at least ``min_gain`` (25 %) relative *and* by ``min_gain_um`` (0.05 um)
   absolute, lowers the error on all active samples, and no fold's held-out RMS rises by as much
   (a fold where a windowed load is off costs nothing and gains nothing; the folds where it acts
   must carry the gain), nor the error on the whole record, idle stretches included
   (:func:`_worse_on_the_record`: a model that moves where the axis rests; judged with the mean of its Coulomb
   levels, which no moving sample determines, where the whole record puts it: :func:`coulomb_mean_at_rest`, and
   kept so when accepted). An element must also beat its own null (the sampled split form without it; one that
   adds no fitted parameter to it, a whole-sample delay, by the folds as they stand:
   :func:`beats_the_model_without`); any other effect must itself carry the refit's gain (the refitted model
   without it predicts worse by as much: :func:`_idle_effect`). A mode must lie below the record's Nyquist
   frequency 1/(2T) (:func:`_unphysical_mode`). Steps 2-4 repeat (at most ``max_effects`` times) until no
   proposal passes.
5. **Check backward.** The final model faces every accepted effect again: one no longer physical (a mode above
   the Nyquist frequency, or below it by less than its decay rate (:func:`_unresolved_mode`), or damped beyond
   1/sqrt(2), a Stribeck term without its static excess) or no longer needed (the final model refitted without it
   predicts the held-out folds within ``min_gain``, a mode no longer coherent with the motion) is dropped, the
   model refitted without it, and the last round's record says so under ``dropped`` (:func:`_backward_check`; the
   report's ``dropped:`` lines). These refits too keep the
   Coulomb mean where the whole record puts it (:func:`_judged_at_rest`): the final model's mean is the rests'.
6. **Report.** ``validation`` gives the pooled and per-fold held-out errors before and after,
   the active stretches and the warnings; ``validation.unexplained`` the final residual's
   spectral peaks and its association with position, velocity, direction, acceleration and time
   (:func:`identification.residual.residual_evidence`), so that what no named effect explains is
   said with evidence instead of forced onto a name.

The 25 % criterion: on clean captures of the project's virtual machines (different seeds and
programs) the best spurious proposal lowers the held-out RMS by at most about 10 % (the reduced
model's structural mismatch with a sampled, quantised machine); see
``tests/identification/test_diagnosis.py`` and ``benchmarks/diagnosis.py``.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import textwrap
import time
from collections.abc import Callable
from typing import Any

import numpy as np
import scipy.optimize

from identification.augmented import AugmentedAxisModel, SimSpec, augment, simulate_augmented
from identification.bounds import WIDE_P_MIN_HZ, as_bounds
from identification.capture_checks import check_capture
from identification.dead_time import pure_delay_baseline
from identification.effects import EFFECTS, TimePeriodic
from identification.kernels import run_exact_tangent
from identification.least_squares import damped_steps, solve_scaled
from identification.measured_drift import drift_left_in
from identification.parallel import process_map, serial_blas, thread_map
from identification.parameters import from_search, search_box, to_search
from identification.poles import TWO_PI
from identification.reduced_model import ReducedAxisModel, discretize
from identification.residual import motion_coherence
from identification.searches import SEARCHES, Candidate, Data, SearchContext
from identification.segments import FoldPlan, active_mask, folds, motion_segments
from identification.substeps import substep_count, substep_reference
from vcnc.core.axes import axis_unit
from vcnc.core.capture import Capture
from vcnc.core.errors import IdentificationError
from vcnc.core.jsonsafe import plain
from vcnc.core.metrics import error_metrics

__all__ = [
    "report_figure",
    "DiagnosisOptions",
    "DiagnosisReport",
    "Stage",
    "diagnose",
    "diagnose_report",
    "refit",
    "coulomb_mean_at_rest",
    "after_table_lines",
    "wrapped_lines",
    "with_coulomb_mean",
    "stribeck_static_ratios",
    "no_stribeck_curve",
    "beats_the_model_without",
    "adds_no_parameter",
    "before_after_rows",
    "format_before_after",
    "samples_note",
    "refusal_lines",
    "dropped_lines",
]

log = logging.getLogger(__name__)


@dataclasses.dataclass(frozen=True, kw_only=True)
class DiagnosisOptions:
    """Settings of the diagnosis (module docstring).

    Attributes
    ----------
    folds : int
        Contiguous validation folds wanted (cut at idle points or reversals; fewer when a fold
        would lack motion in either direction) [-].
    margin_s : float
        Margin kept around every moving stretch when idle stretches are trimmed [s].
    min_gain : float
        Smallest relative drop of the held-out RMS for an effect to be added [-].
    min_gain_um : float
        Smallest absolute drop of the held-out RMS [um].
    max_effects : int
        Effects added at most.
    top : int
        Proposals refitted per round (by screening error).
    effects : tuple of str
        Effects considered (default all of :data:`identification.effects.EFFECTS`).
    max_nfev : int
        Iterations of each joint refit.
    min_screen : float
        Smallest relative drop of the identification-block error a proposal's screen must show
        to be refitted [-] (saves refits of proposals without evidence).
    """

    folds: int = 4
    margin_s: float = 0.2
    min_gain: float = 0.25
    min_gain_um: float = 0.05
    max_effects: int = 3
    top: int = 3
    effects: tuple[str, ...] = tuple(EFFECTS)
    max_nfev: int = 40
    min_screen: float = 0.05

    def __post_init__(self) -> None:
        if not 2 <= self.folds <= 20:
            raise IdentificationError(f"folds must lie in [2, 20] (got {self.folds!r})")
        if not 0.0 <= self.margin_s:
            raise IdentificationError(f"margin_s must be >= 0 s (got {self.margin_s!r})")
        unknown = [e for e in self.effects if e not in EFFECTS]
        if unknown:
            raise IdentificationError(f"unknown effect(s) {unknown}; expected some of {', '.join(EFFECTS)}")


@dataclasses.dataclass(eq=False)
class Stage:
    """One step of the forward selection: the model after adding ``effect`` (None: reduced)."""

    effect: str | None
    train_model: AugmentedAxisModel
    full_model: ReducedAxisModel | None
    validation_rms_um: float
    validation_max_um: float
    identification_rms_um: float = math.nan
    identification_max_um: float = math.nan
    evidence: dict = dataclasses.field(default_factory=dict)
    fold_rms_um: list = dataclasses.field(default_factory=list)
    fold_max_um: list = dataclasses.field(default_factory=list)
    in_sample_folds: list = dataclasses.field(default_factory=list)


@dataclasses.dataclass(eq=False)
class DiagnosisReport:
    """Result of :func:`diagnose_report`: the stages, the rounds of candidates and the final model."""

    model: ReducedAxisModel
    reduced: ReducedAxisModel
    stages: list
    rounds: list
    data: Data
    time_s: float
    plan: FoldPlan | None = None

    @property
    def effects(self) -> list[str]:
        return [s.effect for s in self.stages[1:]]

    def rows(self) -> list[dict[str, Any]]:
        return before_after_rows(self.model)

    def table(self) -> str:
        return format_before_after(self.model)

    def to_dict(self) -> dict[str, Any]:
        return {"effects": list(self.model.effects), "validation": dict(self.model.validation)}

    def plot(self, ax=None):
        """Residual before/after against time, velocity, position and its spectrum."""
        from identification.residual import plot_before_after

        return plot_before_after(self.data.xr, self.data.x, self.data.T, self.reduced, self.model, ax=ax)


# ------------------------------------------------------------------------------------ refit


class _Layout:
    """The refit's coordinates of a model: ``z`` (log poles, reduced parameters over a2, the
    split form's viscous share, the effects' free parameters), their bounds, and the model and
    simulated output of any ``z``."""

    def __init__(self, model: AugmentedAxisModel, data: Data) -> None:
        poles = model.poles
        if not poles or not data.bounds.contains(poles, rtol=1e-6):
            poles = {"p_hz": min(max(poles.get("p_hz", 1.0), data.bounds.p_hz[0]), data.bounds.p_hz[1]),
                     "omega_n_hz": min(max(poles.get("omega_n_hz", 10.0), data.bounds.omega_n_hz[0]),
                                       data.bounds.omega_n_hz[1]),
                     "zeta": min(max(poles.get("zeta", 0.7), data.bounds.zeta[0]), data.bounds.zeta[1])}
        z0 = list(to_search(model.parameters, poles["p_hz"] * TWO_PI, poles["omega_n_hz"] * TWO_PI, poles["zeta"]))
        lo, hi = (list(b) for b in search_box(data.bounds))
        self.structured = model.structured
        if self.structured:
            q = min(max(model.viscous_rate / model.parameters["a1"], 1e-5), 0.9)
            z0.append(math.log(q))
            lo.append(math.log(1e-5))
            hi.append(math.log(0.95))
        self.slices = []
        linear = [False] * len(z0)
        for e in model.elements:
            fr = e.free()
            self.slices.append((len(z0), len(fr)))
            for f in fr:
                z0.append(min(max(f.value, f.lo), f.hi))
                lo.append(f.lo)
                hi.append(f.hi)
                linear.append(f.linear)
        self.lo, self.hi = np.array(lo, float), np.array(hi, float)
        pad = 1e-9 * np.where(np.isfinite(self.hi - self.lo), self.hi - self.lo, 0.0)
        self.lo_pad, self.hi_pad = self.lo + pad, self.hi - pad
        self.z0 = np.clip(np.array(z0, float), self.lo_pad, self.hi_pad)
        self.lin = np.array(linear, bool)
        self.model = model
        self.data = data

    def build(self, z: np.ndarray) -> tuple[dict, list, float]:
        params = from_search(z)
        elements = [e.with_free(z[i:i + k]) if k else e for e, (i, k) in zip(self.model.elements, self.slices)]
        c = math.exp(z[8]) * params["a1"] if self.structured else 0.0
        return params, elements, c

    def spec(self, z: np.ndarray) -> tuple[dict, SimSpec]:
        """(reduced parameters, kernel specification) of ``z``."""
        params, elements, c = self.build(z)
        m = AugmentedAxisModel(parameters=params, sample_time=self.data.T, elements=tuple(elements), viscous_rate=c,
                               poles={"p_hz": 1.0, "omega_n_hz": 1.0, "zeta": 1.0})
        return params, m.spec(self.data.n)

    def simulate(self, z: np.ndarray) -> np.ndarray:
        """Simulated output [mm] over the whole record."""
        params, spec = self.spec(z)
        return simulate_augmented(params, self.data.xr, spec, held=self.data.held)

    def load_columns(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(indices in ``z`` of the linear coefficients of the time-periodic loads, (n, m) the load
        [mm/s^2] per unit of each at every sample): the columns of :meth:`TimePeriodic.window_basis`,
        ones for a mean. The load enters the kernels as the known disturbance ``wext``, linearly in
        these coefficients."""
        keys: list[int] = []
        blocks: list[np.ndarray] = []
        _, elements, _ = self.build(z)
        t = np.arange(self.data.n) * self.data.T
        for e, (i, k) in zip(elements, self.slices):
            if not (isinstance(e, TimePeriodic) and k):
                continue
            if e.with_mean:
                blocks.append(np.ones((self.data.n, 1)))
            blocks.append(e.window_basis(t))
            keys.extend(range(i + 1, i + k))  # after log_period (TimePeriodic.free)
        if not blocks:
            return np.zeros(0, int), np.zeros((self.data.n, 0))
        return np.array(keys, int), blocks[0] if len(blocks) == 1 else np.hstack(blocks)

    def model_of(self, z: np.ndarray) -> AugmentedAxisModel:
        params, elements, c = self.build(z)
        return augment(self.model, elements, parameters=params, viscous_rate=c,
                       poles={"omega_n_hz": math.exp(z[1]) / TWO_PI, "zeta": float(z[2]),
                              "p_hz": math.exp(z[0]) / TWO_PI})


def _load_sensitivities(params: dict, spec: SimSpec, data: Data, cols: np.ndarray) -> np.ndarray | None:
    """Sensitivities [mm per unit] of the simulated position to the time-periodic loads' linear
    coefficients (``cols``: the loads per unit, :meth:`_Layout.load_columns`), (n, m), all in one
    pass of the tangent-linear loop (:func:`identification.kernels.run_exact_tangent`), for a model
    simulated by the exact loop (no element) on the record's samples; None for the split form, for a
    record predicted at sub-steps (``data.held``), or when the simulation diverges: the forward
    differences then.

    They replace one forward-difference simulation per coefficient (128 on EMPS DATA_EMPS_PULSES,
    1.2 ms each; the tangent pass 2.4 ms for all, 2026-11-23, the 2-core development machine) and
    agree with them to 1e-5 (``python /tmp/pulses/tan_chk.py``), except where a perturbation moves
    a velocity sign change of the trajectory: the Coulomb levels' jump, which has no slope, makes a
    forward difference there a jump over the step (seen at the start of the first refit of PULSES).
    """
    if spec.structured or cols.shape[1] == 0 or data.held is not None:  # (the tangent pass runs on the samples)
        return None
    pos, vel = simulate_augmented(params, data.xr, spec, return_velocity=True)
    if spec.offset is not None:
        pos = pos - spec.offset
    if not (np.all(np.isfinite(pos)) and np.all(np.isfinite(vel))):
        return None
    dm = discretize(params, spec.sample_time)
    return run_exact_tangent(dm.phi, dm.gamma, dm.c, dm.cv, np.ascontiguousarray(pos), np.ascontiguousarray(vel),
                             np.ascontiguousarray(spec.stribeck, dtype=float), float(spec.asym),
                             float(spec.pp_period), np.ascontiguousarray(np.atleast_2d(spec.pp_coef), dtype=float),
                             np.ascontiguousarray(cols))


def _linear_jacobian(lay: _Layout, data: Data, z: np.ndarray, idx: np.ndarray, r0: np.ndarray, sel: np.ndarray,
                     fun: Callable[[np.ndarray], np.ndarray], residual: Callable[[np.ndarray], np.ndarray]
                     ) -> np.ndarray:
    """Sensitivities of the refit residual ``r0 = fun(z)`` to the linear coefficients ``z[idx]``
    (forward differences, one simulation each).

    A time-periodic coefficient's perturbed simulation takes the load of ``z`` plus the step
    times its column (:meth:`_Layout.load_columns`) instead of re-evaluating the whole Fourier
    series: on EMPS DATA_EMPS_PULSES (64 harmonics, 24,841 samples) the series took 1.6 ms of
    each 2.3 ms simulation (cProfile, 2026-11-23, the 2-core development machine). For a model
    without elements the time-periodic columns come from one tangent-linear pass instead
    (:func:`_load_sensitivities`). With these and the time-periodic search's moments, the
    diagnosis of EMPS DATA_EMPS_PULSES took 11.7 s CPU instead of 20.7 s (``VCNC_THREADS=1``,
    ``time.process_time``, the same effects found; 2026-11-23, the 2-core development machine).
    ``residual`` maps a simulated output to the residual on the refit's samples ``sel``.
    """
    params, spec0 = lay.spec(z)
    keys, cols = lay.load_columns(z)
    where = {int(k): j for j, k in enumerate(keys)}
    tangent = _load_sensitivities(params, spec0, data, cols)
    rest = [i for i in idx if i not in where] if tangent is not None else list(idx)

    def column(i):
        step = 1e-3 * max(abs(z[i]), 1.0)
        if i in where:
            y = simulate_augmented(params, data.xr,
                                   dataclasses.replace(spec0, wext=spec0.wext + step * cols[:, where[i]]),
                                   held=data.held)
            return (residual(y) - r0) / step
        zz = z.copy()
        zz[i] += step
        return (fun(zz) - r0) / step

    if tangent is None:
        return np.column_stack(thread_map(column, idx))
    where_j = {i: j for j, i in enumerate(idx)}
    J = np.empty((r0.size, idx.size))
    J[:, [where_j[int(k)] for k in keys]] = tangent[sel]
    for i, c in zip(rest, thread_map(column, rest)):
        J[:, where_j[i]] = c
    return J


def refit(model: AugmentedAxisModel, data: Data, samples: int | np.ndarray, *, max_nfev: int = 40
          ) -> AugmentedAxisModel:
    """Joint output-error refit of every continuous parameter on ``samples``.

    ``samples`` is a boolean mask over the record (or an int: the first ``samples``). The
    simulation always runs over the whole record (the model predicts from the reference alone);
    only the error on the chosen samples counts.

    Reduced parameters as in :mod:`identification.output_error` (poles inside ``data.bounds``),
    the split form's plant viscous rate (as a share of a1) when an element is present, and every
    effect's :meth:`~identification.effects.Effect.free` parameters.

    The trust-region solve stops at a relative step or cost change of 1e-8: with 1e-10 the
    captures of ``benchmarks/diagnosis.py`` took about 15 % more simulations, for effect
    parameters that moved by at most 2e-5 of their value (2026-11-23).
    """
    lay = _Layout(model, data)
    z0, lo_a, hi_a, lin = lay.z0, lay.lo, lay.hi, lay.lin
    n = data.n
    if isinstance(samples, (int, np.integer)):
        sel = np.arange(n) < int(samples)
    else:
        sel = np.asarray(samples, bool)
    xm = data.x[sel]

    def residual(y):
        r = y[sel] - xm
        bad = ~np.isfinite(r)
        if bad.any():
            r[bad] = 10.0
        return r

    def fun(z):
        return residual(lay.simulate(z))

    def solve(z, mask, nfev):
        """least squares over the entries ``mask`` of z (the others fixed)."""
        idx = np.flatnonzero(mask)

        def f(u):
            zz = z.copy()
            zz[idx] = u
            return fun(zz)

        r0 = f(z[idx])
        try:
            res = scipy.optimize.least_squares(f, z[idx], bounds=(lo_a[idx], hi_a[idx]), method="trf",
                                               x_scale="jac", diff_step=1e-6, max_nfev=nfev, xtol=1e-8,
                                               ftol=1e-8, workers=thread_map)
        except ValueError:  # pragma: no cover - infeasible start after clipping
            return z
        if 2 * res.cost <= float(r0 @ r0):
            z = z.copy()
            z[idx] = res.x
        return z

    def linear_step(z):
        """Gauss-Newton step of the linear coefficients (:func:`_linear_jacobian`), halved until it
        lowers the error."""
        idx = np.flatnonzero(lin)
        r0 = fun(z)
        J = _linear_jacobian(lay, data, z, idx, r0, sel, fun, residual)
        delta = -solve_scaled(J, r0)
        c0 = float(r0 @ r0)
        for alpha in (1.0, 0.5, 0.25):
            zz = z.copy()
            zz[idx] += alpha * delta
            r = fun(zz)
            if float(r @ r) < c0:
                return zz
        return z

    if lin.sum() <= 6:
        z = solve(z0, np.ones(z0.size, bool), max_nfev)
    else:
        # many linear coefficients (a Fourier series): alternate a linear solve of them with the
        # nonlinear refit of the rest - each finite-difference Jacobian stays small
        z = z0
        for _ in range(3):
            z = linear_step(z)
            z = solve(z, ~lin, max(10, max_nfev // 3))
        z = linear_step(z)
    return lay.model_of(z)


# ------------------------------------------------------------------------------------ diagnose


def _errors(model: ReducedAxisModel, data: Data, mask: np.ndarray) -> tuple[float, float]:
    """(RMS, max) [um] of the simulation error of ``model`` on the samples ``mask``."""
    return _rms_max_um((data.x - data.predict(model))[mask])


def _rms_max_um(error_mm: np.ndarray) -> tuple[float, float]:
    """(RMS, max) [um] of a simulation error [mm] (:func:`vcnc.core.metrics.error_metrics`): NaN when it
    is empty, inf when the simulation diverged (any value not finite), so that such a fit ranks last."""
    if error_mm.size and not np.all(np.isfinite(error_mm)):
        return math.inf, math.inf
    m = error_metrics(error_mm)
    return m["rms_um"], m["max_um"]


@dataclasses.dataclass(eq=False)
class _Judged:
    """A model fitted on all active samples and judged on every fold (fitted on the others)."""

    model: AugmentedAxisModel
    rms_um: float
    max_um: float
    fold_rms_um: list
    fold_max_um: list
    #: folds whose "held-out" error is the full fit's: no refit on the other folds lowered their error
    in_sample_folds: list = dataclasses.field(default_factory=list)

    @property
    def held_out_rms_um(self) -> float:
        """Pooled held-out RMS over the folds [um]."""
        return self._pooled[0]

    @property
    def held_out_max_um(self) -> float:
        return self._pooled[1]

    def pool(self, counts: list[int]) -> None:
        sse = sum(r * r * c for r, c in zip(self.fold_rms_um, counts) if math.isfinite(r) or r == math.inf)
        tot = sum(counts)
        rms = math.sqrt(sse / tot) if tot else math.nan
        self._pooled = (rms, max(self.fold_max_um) if self.fold_max_um else math.nan)


#: Relative step of the central differences of the held-out sensitivities (:func:`_held_out_sensitivities`).
HELD_OUT_DIFF_STEP = 1e-3
#: Levenberg-Marquardt iterations of a held-out fold's refit (:func:`_judge`).
HELD_OUT_ITERATIONS = 5
#: Damping tried in turn, lightest first, relative to the largest eigenvalue of the scaled Gram matrix
#: (:func:`identification.least_squares.damped_steps`; 0: the Gauss-Newton step).
HELD_OUT_DAMPING = (0.0, 1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0, 100.0)
#: Relative drop of the training error below which a held-out refit stops iterating [-].
HELD_OUT_TOL = 1e-4
#: Least share of the active record's sensitivity (norm along a direction) the training samples must carry for
#: a held-out refit to move along that direction [-] (:func:`_damped_refit`); with 4 folds an evenly
#: determined direction has sqrt(3/4) = 0.87.
HELD_OUT_SHARE = 0.1


def _held_out_sensitivities(lay: _Layout, z: np.ndarray, y0: np.ndarray) -> np.ndarray:
    """Sensitivities (n, len(z)) of the simulated position ``y0`` to ``z``, over the whole record: central
    differences of relative step :data:`HELD_OUT_DIFF_STEP` (one-sided on a bound); a time-periodic load's linear
    coefficients from one tangent-linear pass where the model has no element (:func:`_load_sensitivities`).

    The reduced model's Coulomb levels switch on the sign of the simulated velocity (Eq. 3.3;
    :mod:`identification.reduced_model`), so the simulation error is not smooth in the parameters that move the
    velocity where it crosses zero: where the simulated axis starts, stops or crawls, a change of 1e-9 of the
    parameters flips that sign at some sample and moves the position by micrometres from there on (camber linA,
    T = 10 ms: 1e-9 perturbations raise the fit's error by 0.19 % or leave it; a hydraulic rig's reference held
    over every second sample, the velocity alternating between -25 and ~1e-6 mm/s: by 12.5 um^2), and the fit ends
    on the edge of such a step. Forward differences of 1e-6 measure the steps, not the slope: in a synthetic record
    with a held reference the slope of the error in b0/a2 they give does not settle as the step shrinks (761, 364, 14
    for steps of 1e-6, 1e-5, 1e-4; central 1e-3: -1.06; ``tests/identification/test_identify_folds.py``), and no
    step along it lowered the training error of 4 of the 13 recorded traces' folds. Central differences of 1e-3
    take the secant over the switching; with them every fold of the 13 is refitted (2026-11-25). Our reading: the
    thesis does not simulate its friction in a refit.
    """
    params, spec = lay.spec(z)
    keys, cols = lay.load_columns(z)
    tangent = _load_sensitivities(params, spec, lay.data, cols)
    known = {int(k): j for j, k in enumerate(keys)} if tangent is not None else {}

    def column(i):
        h = HELD_OUT_DIFF_STEP * max(abs(z[i]), 1.0)
        lo, hi = max(z[i] - h, lay.lo_pad[i]), min(z[i] + h, lay.hi_pad[i])
        if hi <= lo:
            return np.zeros_like(y0)
        ends = []
        for v in (hi, lo):
            zz = z.copy()
            zz[i] = v
            ends.append(lay.simulate(zz) if v != z[i] else y0)
        return (ends[0] - ends[1]) / (hi - lo)

    J = np.empty((y0.size, z.size))
    rest = [i for i in range(z.size) if i not in known]
    for i, c in zip(rest, thread_map(column, rest)):
        J[:, i] = c
    for i, j in known.items():
        J[:, i] = tangent[:, j]
    J[~np.isfinite(J)] = 0.0
    return J


def _damped_refit(lay: _Layout, J: np.ndarray, z: np.ndarray, y: np.ndarray, train: np.ndarray, first: int,
                  G_all: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, int] | None:
    """One Levenberg-Marquardt iteration from ``z`` (simulated ``y`` over the record) on the samples ``train``
    (``J`` the sensitivities there): the lightest damping of :data:`HELD_OUT_DAMPING` from index ``first`` whose
    step lowers the error on them, as (z, its simulation, the damping's index), or None.

    A parameter on its bound that a step would push beyond it is held there and the step fitted on the others (the
    active set of a bounded least-squares solver): clipped afterwards, EMPS' step of |2-3| in the scaled parameters,
    nearly all beyond p's 1 mHz bound, raised the training error at every length; held, it lowers it.

    ``G_all``: the Gram matrix of the sensitivities on all active samples. A direction along which the training
    samples carry less than :data:`HELD_OUT_SHARE` of it (norm) is left at the full fit
    (:func:`identification.least_squares.damped_steps`' ``reference``): the held-out fold alone determines it.
    ident_fuzz seed 1 case 79 (fadal-ppi's y, a saturation, 0.82 s): the Coulomb levels' common mode (d0 and d1
    together, a constant load that the loop's integral action shows only while it builds up at the record's start)
    had a scaled singular value of 1.007e-3 on folds 2-4, just above the relative cut, which carry 0.6 % of the
    record's sensitivity along it; the refit moved d0/a2 and d1/a2 by -0.91 each and the first fold's held-out
    error was 311 um for 2.9 um on all samples. Our reading of approximate leave-a-block-out cross-validation
    (:func:`_judge`): a parameter the training samples do not determine cannot be re-estimated from them.
    """
    x = lay.data.x[train]
    r = x - y[train]
    c0 = float(r @ r)
    G, b = J.T @ J, J.T @ r
    share = HELD_OUT_SHARE * HELD_OUT_SHARE
    damping = HELD_OUT_DAMPING[first:]
    for k, delta in enumerate(damped_steps(G, b, damping, reference=G_all, share=share)):
        held = ((z <= lay.lo_pad) & (delta < 0)) | ((z >= lay.hi_pad) & (delta > 0))
        if held.any():
            free = ~held
            delta = np.zeros_like(delta)
            ref = None if G_all is None else G_all[np.ix_(free, free)]
            delta[free] = damped_steps(G[np.ix_(free, free)], b[free], (damping[k],), reference=ref, share=share)[0]
        zz = np.clip(z + delta, lay.lo_pad, lay.hi_pad)
        yy = lay.simulate(zz)
        e = x - yy[train]
        if np.all(np.isfinite(e)) and float(e @ e) < c0:
            return zz, yy, first + k
    return None


def _judge(model: AugmentedAxisModel, data: Data, plan: FoldPlan, opt: DiagnosisOptions, *,
           fitted: bool = False) -> _Judged:
    """Fit ``model`` on all active samples (unless ``fitted``), then hold out each fold in turn.

    Each fold's model is refitted on the other folds' samples from the fit on all active samples: up to
    :data:`HELD_OUT_ITERATIONS` Levenberg-Marquardt iterations (:func:`_damped_refit`), stopped when one lowers the
    training error by less than :data:`HELD_OUT_TOL`, with the sensitivities of the full fit
    (:func:`_held_out_sensitivities`, computed once and shared by the folds: a simplified Gauss-Newton, or chord,
    iteration). Its first iteration is the approximate leave-a-block-out refit of approximate leave-one-out
    cross-validation (Rad and Maleki, "A scalable estimate of the out-of-sample prediction error via approximate
    leave-one-out cross-validation", JRSS B 82, 2020); the others take it on towards the training fit where the
    error is not quadratic in the parameters (a position-periodic load's period: a TNCscope trace's folds needed a
    Gauss-Newton step shortened to 1/8 to 1/64). Directions whose singular value is below 1e-3 of the largest, or
    along which the other folds carry under :data:`HELD_OUT_SHARE` of the active samples' sensitivity, are left at
    the full fit (a parameter only the held-out fold determines, such as a constant load seen only at the start of
    the record, must not wander).

    A fold that no iteration helps keeps the full fit, which saw it, and is named (:func:`in_sample_warnings`).
    Cost: ``2 n_parameters`` simulations for the sensitivities and about 2 to 10 a fold.
    """
    full = model if fitted else refit(model, data, plan.active, max_nfev=opt.max_nfev)
    r, m = _errors(full, data, plan.active)
    lay = _Layout(full, data)
    z = lay.z0
    y0 = lay.simulate(z)
    J = _held_out_sensitivities(lay, z, y0)
    G_all = J[plan.active].T @ J[plan.active]

    def held_out(i):
        """(RMS, max) [um] on fold i of the model refitted on the other folds, and whether it moved (False: the
        full fit's own error, in sample)."""
        held = plan.mask(i)
        train = plan.active & ~held
        Jt = J[train]
        zi, yi, first = z, y0, 0
        c = float(np.sum((data.x - y0)[train] ** 2))
        for _ in range(HELD_OUT_ITERATIONS):
            got = _damped_refit(lay, Jt, zi, yi, train, first, G_all)
            if got is None:
                break
            zi, yi, k = got
            first = max(k - 1, 0)
            c_new = float(np.sum((data.x - yi)[train] ** 2))
            if c - c_new < HELD_OUT_TOL * c:
                break
            c = c_new
        return (*_rms_max_um((data.x - yi)[held]), yi is not y0)

    per_fold = thread_map(held_out, range(len(plan.folds)))
    fr = [f[0] for f in per_fold]
    fm = [f[1] for f in per_fold]
    j = _Judged(model=full, rms_um=r, max_um=m, fold_rms_um=fr, fold_max_um=fm,
                in_sample_folds=[i for i, f in enumerate(per_fold) if not f[2]])
    j.pool([f.active for f in plan.folds])
    return j


def _judged_at_rest(model: AugmentedAxisModel, before: ReducedAxisModel, data: Data, plan: FoldPlan,
                    opt: DiagnosisOptions) -> _Judged:
    """``model`` refitted on all active samples, its Coulomb levels' mean then set where the whole record puts it
    (:func:`coulomb_mean_at_rest`, about ``before``'s mean), and judged on the folds there (:func:`_judge`).

    The joint refits after a round's choice (the backward check's, whose model without a dropped effect becomes the
    final one) leave that mean where their steps end, as a round's refit does: coulomb35's scenario
    (test_whole_record_refusal.py) with a needless drift accepted before its load and dropped again ended at
    +4565 .. +20675 mm/s^2 for a load of +800 at the rest position (noise seeds 1-4, the load changed by +-1e-9, 1
    or 2 threads), 9.5 .. 42 um over all samples and 15 .. 66 um at rest, where the mean the rests put predicts
    1.15 and 0.33 um (tests/identification/test_coulomb_mean_joint.py)."""
    full = refit(model, data, plan.active, max_nfev=opt.max_nfev)
    return _judge(coulomb_mean_at_rest(full, before, data), data, plan, opt, fitted=True)


def _contradicting_folds(before: list[float], after: list[float], opt: DiagnosisOptions) -> list[int]:
    """Folds whose held-out RMS rises by >= min_gain and >= min_gain_um with the effect."""
    return [i for i, (b, a) in enumerate(zip(before, after)) if _raises(b, a, opt)]


def _raises(before: float, after: float, opt: DiagnosisOptions) -> bool:
    """Is ``after`` [um] above ``before`` by ``min_gain`` relative and ``min_gain_um`` (a fold or the whole record
    an effect makes worse)?"""
    return after - before >= opt.min_gain_um and (before <= 0 or (after - before) / before >= opt.min_gain)


def diagnose(capture: Capture, model: ReducedAxisModel, *, axis: str,
             options: DiagnosisOptions | None = None) -> ReducedAxisModel:
    """The model augmented with the effects the capture supports (module docstring).

    Parameters
    ----------
    capture : Capture
        The data the model was identified from.
    model : ReducedAxisModel
        The identified reduced model (Eq. 3.3).
    axis : str
        Axis of the capture.
    options : DiagnosisOptions, optional

    Returns
    -------
    ReducedAxisModel
        An :class:`~identification.augmented.AugmentedAxisModel` with ``effects`` (name, parameters,
        rms_before_um, rms_after_um, evidence) and ``validation`` filled; the given model (with
        ``validation`` filled and no effects) when nothing significant is found.
    """
    return diagnose_report(capture, model, axis=axis, options=options).model


def diagnose_report(capture: Capture, model: ReducedAxisModel, *, axis: str,
                    options: DiagnosisOptions | None = None) -> DiagnosisReport:
    """:func:`diagnose` with everything it found: stages, candidates per round, data split.

    The simulations run on the worker threads of :mod:`identification.parallel`, the linear algebra
    with one BLAS thread (tall, narrow matrices: :func:`~identification.parallel.serial_blas`).
    """
    t_start = time.perf_counter()
    with serial_blas():
        return _diagnose(capture, model, axis, options, t_start)


def _diagnose(capture: Capture, model: ReducedAxisModel, axis: str, options: DiagnosisOptions | None,
              t_start: float) -> DiagnosisReport:
    """The body of :func:`diagnose_report`."""
    opt = options or DiagnosisOptions()
    xr, x, T = check_capture(capture, axis)
    xr = np.ascontiguousarray(xr, float)
    x = np.ascontiguousarray(x, float)
    active = active_mask(xr, x, T, opt.margin_s)
    plan = folds(xr, active, opt.folds)
    for w in plan.warnings:  # kept in validation["warnings"], which the report and the summary's table print
        log.info("diagnosis: %s", w)
    # the searches fit on every active sample outside the last fold and check their own choices
    # (harmonic counts) on it; the folds judge
    last = plan.mask(len(plan.folds) - 1)
    bounds = as_bounds(model.bounds or None, T)
    held = substep_reference(xr, T) if substep_count(T) > 1 else None  # predicted as the fit predicted it
    data = Data(xr=xr, x=x, T=T, train=active & ~last, valid=last, bounds=bounds, active=active, held=held)
    counts = [f.active for f in plan.folds]
    base = _judge(augment(model, []), data, plan, opt)
    cur = base.model
    stages = [Stage(effect=None, train_model=cur, full_model=model, validation_rms_um=base.held_out_rms_um,
                    validation_max_um=base.held_out_max_um, fold_rms_um=base.fold_rms_um,
                    fold_max_um=base.fold_max_um, in_sample_folds=base.in_sample_folds)]
    cur_rms = base.rms_um
    rounds: list[dict] = []
    for _ in range(opt.max_effects):
        ctx = SearchContext(data, cur)
        cands = _proposals(ctx, cur, opt)
        tried = _refitted(cands, ctx, data, plan, active, cur_rms, opt)
        log.info("round %d: %s", len(rounds) + 1, [(t[1].effect.NAME, round(t[0].held_out_rms_um, 4)) for t in tried])
        rounds.append(_round_record(cands, tried, stages[-1], cur_rms))
        chosen = _choose(tried, ctx, data, plan, active, stages[-1], cur_rms, rounds[-1], opt) if tried else None
        if chosen is None:
            tried, chosen = _after_second_chance(cands, tried, ctx, data, plan, stages[-1], cur_rms, rounds[-1], opt)
        if chosen is None:
            rounds[-1]["accepted"] = None
            break
        stages.append(_accepted_stage(chosen, tried, stages[-1], rounds[-1]))
        cur, cur_rms = stages[-1].full_model, stages[-1].identification_rms_um
    stages = _backward_check(stages, data, plan, rounds, opt)
    # the reduced model's identification-data error, on the active samples
    stages[0].identification_rms_um, stages[0].identification_max_um = _errors(model, data, active)
    final = _final_model(model, stages, opt, data, rounds, plan, counts)
    return DiagnosisReport(model=final, reduced=model, stages=stages, rounds=rounds, data=data,
                           time_s=time.perf_counter() - t_start, plan=plan)


#: The searches, costliest first (measured on a 21,648-sample capture, one thread, 2026-11-23:
#: resonance 1.5 s, position_periodic 0.7 s, delay and backlash 0.55 s, time_periodic 0.45 s, the
#: others below 0.15 s): the order they are started in.
_SEARCH_COST = ("resonance", "position_periodic", "delay", "backlash", "time_periodic", "saturation",
                "friction_stribeck", "friction_viscous_asymmetric", "drift")


def _proposals(ctx: SearchContext, cur: AugmentedAxisModel, opt: DiagnosisOptions) -> list[Candidate]:
    """Every search's proposals for an effect the model does not have yet, best screen first."""
    present = {e.NAME for e in cur.elements}

    def search(name: str) -> list[Candidate]:
        try:
            return SEARCHES[name](ctx)
        except (np.linalg.LinAlgError, ValueError, IdentificationError) as exc:
            log.info("search for %s failed: %s", name, exc)
            return []

    # the searches are independent: side by side on the worker threads, the costly ones started first
    # (so that no worker is left with a long search at the end), their results in the options' order
    names = [name for name in opt.effects if name not in present]
    started = sorted(names, key=lambda n: _SEARCH_COST.index(n) if n in _SEARCH_COST else len(_SEARCH_COST))
    by_name = dict(zip(started, thread_map(search, started)))
    cands = [c for n in names for c in by_name[n] if math.isfinite(c.screen_rms_um)]
    cands.sort(key=lambda c: c.screen_rms_um)
    return cands


def _refitted(cands: list[Candidate], ctx: SearchContext, data: Data, plan, active: np.ndarray, cur_rms: float,
              opt: DiagnosisOptions) -> list[tuple]:
    """The proposals with evidence, refitted jointly and judged on the folds: ``(judged, candidate)``."""
    # only proposals whose screen shows evidence (a training-error drop of >= min_screen) are refitted
    cands_ev = [c for c in cands if c.screen_rms_um <= (1.0 - opt.min_screen) * ctx.train_rms_um]

    def refitted(c: Candidate) -> _Judged:
        return _judged_if_gaining(_refit_form(c, data, active, opt), data, plan, cur_rms, opt)

    # the refits are independent and mostly scipy's Python between the simulations: side by side
    # in worker processes (identification.parallel: threads would contend for the GIL)
    chosen = cands_ev[: opt.top]
    return list(zip(process_map(refitted, chosen), chosen))


def _refit_form(c: Candidate, data: Data, active: np.ndarray, opt: DiagnosisOptions
                ) -> tuple[AugmentedAxisModel, float, float]:
    """``(model, RMS, max)`` [um] of the proposal ``c`` refitted (:func:`refit_candidate`), in the better form of a
    saturation (:func:`_better_windup_form`) or a position-periodic force (:func:`_shorter_period_form`)."""
    m, r_fit, m_fit = refit_candidate(c, data, active, max_nfev=opt.max_nfev)
    if c.effect.NAME == "saturation":
        m, r_fit, m_fit = _better_windup_form(m, r_fit, m_fit, data, active, opt)
    if c.effect.NAME == "position_periodic":
        m, r_fit, m_fit = _shorter_period_form(m, r_fit, m_fit, data, active, opt)
    return m, r_fit, m_fit


def _judged_if_gaining(fit: tuple[AugmentedAxisModel, float, float], data: Data, plan, cur_rms: float,
                       opt: DiagnosisOptions) -> _Judged:
    """The refitted proposal ``fit`` (:func:`_refit_form`) judged on the folds (:func:`_judge`), or, when its error
    on the active samples falls below the current ``cur_rms`` [um] by less than half of ``min_gain``, not judged
    (held-out RMS inf): an in-sample drop below half the criterion cannot become a held-out drop that meets it."""
    m, r_fit, m_fit = fit
    if _gain(cur_rms, r_fit) >= 0.5 * opt.min_gain:
        return _judge(m, data, plan, opt, fitted=True)
    j = _Judged(model=m, rms_um=r_fit, max_um=m_fit, fold_rms_um=[], fold_max_um=[])
    j._pooled = (math.inf, math.inf)
    return j


#: Iterations (function evaluations of the trust-region solve) of the short refit that decides which proposals
#: left out by the screen a round's second chance refits in full (:func:`_second_chance`).
SECOND_CHANCE_NFEV = 6


def _second_chance(cands: list[Candidate], tried: list[tuple], data: Data, plan, active: np.ndarray,
                   cur_rms: float, opt: DiagnosisOptions) -> list[tuple]:
    """The proposals :func:`_refitted` left out, refitted when the round would name nothing: ``(judged,
    candidate)`` of the ``top`` whose refit lowers the current error ``cur_rms`` [um] on the active samples most,
    by at least half of ``min_gain``, judged on the folds (:func:`_judge`; the others are not returned).

    A screen is a rough cost: the start of an element's search, or a load's equation-error coefficients, with
    the loop's parameters moved by a Gauss-Newton step or two, may screen above the current model while the
    joint refit from it finds the effect. ident_fuzz seed 91 (identstart37, session 37): case 16 (fadal-pid/x,
    a 2-sample delay) screened the delay at 15.2 um against 4.02 um, its refit 0.71 um on the active samples
    against 3.71; case 27 (fadal-smc/y, an 88 Hz mode) the mode at 6.50 against 4.34, refitted 1.98 against
    4.22; case 3 (emps/x, saturation and Stribeck friction) the Stribeck term of round 2 at 1.75 against 1.67,
    refitted 0.77 against 1.91. A round's end costs a refit of every proposal left out, so each is first refitted
    by :data:`SECOND_CHANCE_NFEV` iterations only (every start of it, the lowest kept), and only the ``top`` that
    gain by then go on to the full refit from there (benchmarks/diagnosis.py's EMPS run, where nothing gains: full
    refits of the six others took as long as the round's own three refits and their judging; case 3's Stribeck
    term gains 0.50 after 6 iterations, case 16's delay only after more, and is not found so). The proposals
    refitted here meet every test of :func:`_choose`: the held-out gain, the folds, their null and the whole
    record."""
    done = {id(c) for _, c in tried}
    rest = [c for c in cands if id(c) not in done]
    if not rest:
        return []
    short = process_map(lambda c: refit_candidate(c, data, active, max_nfev=SECOND_CHANCE_NFEV), rest)
    gaining = sorted((i for i, f in enumerate(short) if _gain(cur_rms, f[1]) >= 0.5 * opt.min_gain),
                     key=lambda i: short[i][1])[: opt.top]

    def judged(i: int) -> _Judged:
        c = dataclasses.replace(rest[i], start=short[i][0], other_starts=())
        return _judged_if_gaining(_refit_form(c, data, active, opt), data, plan, cur_rms, opt)

    return list(zip(process_map(judged, gaining), [rest[i] for i in gaining]))


def refit_candidate(c: Candidate, data: Data, active: np.ndarray, *, max_nfev: int
                    ) -> tuple[AugmentedAxisModel, float, float]:
    """``(model, RMS, max)`` [um] on the ``active`` samples of the refit (:func:`refit`) from ``c.start`` and from each
    of ``c.other_starts``, the lowest RMS kept: the screen ranks the starts unrefitted, and the best-screened may
    refit into another basin of the loop's parameters (:func:`identification.searches._ee_candidate`)."""
    best = None
    for start in (c.start, *c.other_starts):
        m = refit(start, data, active, max_nfev=max_nfev)
        r_fit, m_fit = _errors(m, data, active)
        if best is None or r_fit < best[1]:
            best = (m, r_fit, m_fit)
    return best


def _better_windup_form(m: AugmentedAxisModel, r_fit: float, m_fit: float, data: Data, active: np.ndarray,
                        opt: DiagnosisOptions) -> tuple[AugmentedAxisModel, float, float]:
    """The refitted saturation ``m`` (errors ``r_fit``, ``m_fit`` [um] on the active samples) or its other
    form (anti-windup on/off, :class:`identification.effects.Saturation`) refitted from it, whichever
    has the lower error on the active samples.

    The error's valley in the limit is narrow (fadal-pid, a 2-sample delay ringing into its 7.5 V
    limit, the true loop: 0.20 um at the true limit, 0.78 um at 3 % above it), and the screen's
    starts, regressed on the unsaturated samples, are far enough from it that the form the screen
    prefers is not always the one whose refit finds it (there, the unclamped form refitted to 1.02 um
    on a machine with anti-windup; the clamped form from that fit: 0.20 um)."""
    sat = m.element("saturation")
    flipped = [dataclasses.replace(e, anti_windup=not e.anti_windup) if e is sat else e for e in m.elements]
    m2 = refit(augment(m, flipped), data, active, max_nfev=opt.max_nfev)
    r2, m2_max = _errors(m2, data, active)
    return (m2, r2, m2_max) if r2 < r_fit else (m, r_fit, m_fit)


def _shorter_period_form(m: AugmentedAxisModel, r_fit: float, m_fit: float, data: Data, active: np.ndarray,
                         opt: DiagnosisOptions) -> tuple[AugmentedAxisModel, float, float]:
    """The refitted position-periodic force ``m`` (errors ``r_fit``, ``m_fit`` [um] on the active samples), or the
    same force with the period of its largest harmonic refitted from it, when the travel covers the refitted period
    fewer than twice and a higher harmonic k carries more of the force than the fundamental.

    Such a fundamental also fits any smooth function of position, and the period the record shows is that of the
    harmonic: ident_fuzz seed 31 case 39 (ballscrew-ppc/x, a 10 mm screw-lead force, travel 19.6 mm, a saturation
    missed) refitted 18.8 mm with 3 harmonics (57, 173 and 10 mm/s^2) and named a period of 18.8 mm; from its second
    harmonic the refit ends at 9.94 mm with one, predicting the held-out folds as well (0.798 um). The shorter form is
    kept unless the longer one lowers its error by the gain an effect must bring (:func:`_lowers`; our reading of
    parsimony: the longer form's extra harmonics are terms of their own)."""
    pp = m.element("position_periodic")
    coef = np.array(pp.coefficients, float).reshape(-1, 2)
    k = int(np.argmax(np.hypot(coef[:, 0], coef[:, 1]))) + 1
    if k == 1 or pp.period <= 0.5 * data.span:
        return m, r_fit, m_fit
    # the harmonics that are multiples of k become the shorter period's own
    shorter = dataclasses.replace(pp, period=pp.period / k, coefficients=tuple(map(tuple, coef[k - 1::k])))
    m2 = refit(augment(m, [shorter if e is pp else e for e in m.elements]), data, active, max_nfev=opt.max_nfev)
    r2, m2_max = _errors(m2, data, active)
    return (m, r_fit, m_fit) if _lowers(r2, r_fit, opt) else (m2, r2, m2_max)


def _after_second_chance(cands: list[Candidate], tried: list[tuple], ctx: SearchContext, data: Data, plan,
                         stage: Stage, cur_rms: float, record: dict, opt: DiagnosisOptions
                         ) -> tuple[list, tuple | None]:
    """``(tried, chosen)`` of a round none of whose refitted proposals passed: the proposals of
    :func:`_second_chance` added to ``tried`` and judged by :func:`_choose`; ``record`` lists them under
    ``second_chance`` and its ``refitted``, ``best`` and ``gain_pct`` cover every refitted proposal."""
    more = _second_chance(cands, tried, data, plan, data.active, cur_rms, opt)
    record["second_chance"] = [c.effect.NAME for _, c in more]
    if not more:
        return tried, None
    chosen = _choose(more, ctx, data, plan, data.active, stage, cur_rms, record, opt)
    tried = tried + more
    record["refitted"] = _round_record(cands, tried, stage, cur_rms)["refitted"]
    best = min(tried, key=lambda t: t[0].held_out_rms_um)
    record["best"] = best[1].effect.NAME
    record["gain_pct"] = 100.0 * _gain(stage.validation_rms_um, best[0].held_out_rms_um)
    return tried, chosen


def _round_record(cands: list[Candidate], tried: list[tuple], stage: Stage, cur_rms: float) -> dict:
    """What a round saw: the screen, the refits, the current errors."""
    return {
        "screened": {c.effect.NAME: round(c.screen_rms_um, 5) for c in cands},
        "equation_error_drop_pct": {c.effect.NAME: round(c.evidence["ee_rss_reduction_pct"], 3) for c in cands
                                    if "ee_rss_reduction_pct" in c.evidence},
        "refitted": {t[1].effect.NAME: {"validation_rms_um": round(t[0].held_out_rms_um, 5),
                                        "identification_rms_um": round(t[0].rms_um, 5),
                                        "fold_rms_um": [round(v, 5) for v in t[0].fold_rms_um]}
                     for t in tried},
        "current_validation_rms_um": stage.validation_rms_um,
        "current_identification_rms_um": cur_rms,
    }


def _choose(tried: list[tuple], ctx: SearchContext, data: Data, plan, active: np.ndarray, stage: Stage,
            cur_rms: float, record: dict, opt: DiagnosisOptions) -> tuple | None:
    """The best refitted proposal that passes every test (held-out gain, no contradicting fold, a
    mode the motion excites and damped below 1/sqrt(2), beating its own null), or None; ``record`` notes why."""
    prev = stage.validation_rms_um
    chosen = None
    for j, c in sorted(tried, key=lambda t: t[0].held_out_rms_um):
        r_va = j.held_out_rms_um
        gain = _gain(prev, r_va)
        against = _contradicting_folds(stage.fold_rms_um, j.fold_rms_um, opt)
        ok = _lowers(prev, r_va, opt) and j.rms_um < cur_rms and not against
        if against:
            record.setdefault("contradicted_by_folds", {})[c.effect.NAME] = [i + 1 for i in against]
        if ok:
            settled = coulomb_mean_at_rest(j.model, stage.full_model, data)
            worse = _worse_on_the_record(stage.full_model, settled, data, opt)
            if worse is not None:
                record.setdefault("worse_on_the_record_um", {})[c.effect.NAME] = list(worse)
                ok = False
            elif settled is not j.model:
                # judged again at that mean: the stage reports the held-out errors of the model it keeps, and the
                # tests above hold for it
                j = _judge(settled, data, plan, opt, fitted=True)
                r_va, gain = j.held_out_rms_um, _gain(prev, j.held_out_rms_um)
                against = _contradicting_folds(stage.fold_rms_um, j.fold_rms_um, opt)
                ok = _lowers(prev, r_va, opt) and j.rms_um < cur_rms and not against
                if not ok:
                    record.setdefault("refused_at_the_mean_at_rest", {})[c.effect.NAME] = {
                        "validation_rms_um": r_va, "fold_rms_um": list(j.fold_rms_um)}
        if ok and not j.model.element(c.effect.NAME).in_loop:
            idle = _idle_effect(j, c.effect.NAME, data, opt)
            if idle is not None:
                record.setdefault("no_contribution_um", {})[c.effect.NAME] = list(idle)
                ok = False
        nested = None
        if ok and c.effect.NAME == "resonance":
            # a mode is claimed only when the axis' own motion excites it: the residual's line
            # must be coherent with a force of the commanded motion, its acceleration or its velocity's sign
            # (not an external line)
            e_new = j.model.element("resonance")
            coh = motion_coherence(ctx.r, data.xr, data.T, active, [e_new.frequency, e_new.antiresonance])
            record["resonance_motion_coherence"] = coh
            record["resonance_damping"] = e_new.damping
            record["resonance_frequency_hz"] = e_new.frequency
            why = _unphysical_mode(e_new, data.T)
            if why is not None:
                record.setdefault("unphysical", {})[c.effect.NAME] = why
            ok = coh >= _MIN_MODE_COHERENCE and why is None
        if ok and c.effect.NAME == "friction_stribeck":
            ratios = stribeck_static_ratios(j.model)
            record["stribeck_static_ratios"] = list(ratios)
            ok = no_stribeck_curve(ratios) is None
        if ok and j.model.element(c.effect.NAME).in_loop:
            # the element must beat its own null (the sampled split form without it), refitted
            null = _judge(_null_of(j.model, c.effect.NAME), data, plan, opt)
            r_null = null.held_out_rms_um
            nested = _gain(r_null, r_va)
            ok = beats_the_model_without(c.effect, (r_null, null.fold_rms_um), (r_va, j.fold_rms_um), opt)
            record.setdefault("nested", {})[c.effect.NAME] = {"null_validation_rms_um": r_null,
                                                              "gain_pct": 100.0 * nested}
        if ok:
            chosen = (j, c, gain, nested)
            break
    best = min(tried, key=lambda t: t[0].held_out_rms_um)
    record["best"] = best[1].effect.NAME
    record["gain_pct"] = 100.0 * _gain(prev, best[0].held_out_rms_um)
    record["accepted"] = chosen[1].effect.NAME if chosen else None
    return chosen


def _unphysical_mode(e, T: float) -> str | None:
    """Why the refitted mode ``e`` (:class:`identification.effects.Resonance`) is no resonance a record sampled
    every ``T`` [s] shows, or None.

    A second-order mode shows a resonant peak only for a damping below 1/sqrt(2) (:data:`_MAX_MODE_DAMPING`), and a
    record sampled every T shows no frequency above its Nyquist frequency 1/(2T): its samples determine a signal
    band-limited to 1/(2T), and anything above it aliases onto a lower frequency (Shannon, "Communication in the
    presence of noise", Proc. IRE 37(1), 1949, Theorem 1). A mode fitted above it is a lag the refit borrowed:
    ident_fuzz seed 21 case 52 with a one-sample delay only (fadal-pid/y, T = 1 ms) accepted a mode of damping 0.33
    in round 1, and the joint refit with the delay of round 2 moved it to 2744 Hz (damping 0.55), above the 500 Hz
    Nyquist frequency.

    Below it, the record must still tell the mode from the Nyquist alternation. Sampled every T, a mode of
    frequency f and decay rate sigma = 2 pi zeta f rings as x_n = e^(-sigma n T) cos(2 pi f n T + phi) =
    (-1)^n e^(-sigma n T) cos(2 pi (f_N - f) n T - phi), f_N = 1/(2T): the samples alternate under an envelope
    that beats at f_N - f. Without that beat they are a discrete pole on the negative real axis, z = -e^(-sigma T),
    which no continuous-time pole gives (e^(sT) is never negative for a real s): an artefact of the sampling, not a
    mode. A record resolves two frequencies only when it lasts at least the inverse of their distance (the
    resolution 1/duration of a Fourier analysis; Harris, "On the use of windows for harmonic analysis with the
    discrete Fourier transform", Proc. IEEE 66(1), 1978), and the ringing lasts 1/sigma: f is told
    from f_N only when f_N - f >= sigma, i.e. f <= f_N / (1 + 2 pi zeta) (:func:`resolved_below_nyquist`).
    ident_fuzz seed 61 case 27 (fadal-smc/x, Coulomb friction and no mode, T = 2 ms) named 225 Hz at damping 0.045
    (0.9 f_N; its beat period 40 ms against a 16 ms ringing), held out 0.58 -> 0.32 um; logged every 1 ms the same
    motion named 435 Hz (0.87 f_N), cut at its end 197 Hz at damping 0.18: a frequency that follows the sampling is
    the reduced model's friction at reversals, not a mode. The truth's modes of that benchmark (30-120 Hz, damping
    0.02-0.1) lie in this band in 4 cases of 85 below Nyquist (seeds 1-191 step 10): 2 missed before already, 2
    refused or skipped for other reasons."""
    nyquist = 0.5 / T
    if e.frequency >= nyquist:
        return (f"its frequency {e.frequency:.4g} Hz lies above the record's Nyquist frequency 1/(2T) = "
                f"{nyquist:.4g} Hz, which a sampled record cannot show")
    if e.damping >= _MAX_MODE_DAMPING:
        return f"its damping {e.damping:.3g} is >= 1/sqrt(2): a mode without a resonant peak"
    return None


def _unresolved_mode(e, T: float) -> str | None:
    """Why the mode ``e`` of a final model is one a record sampled every ``T`` [s] does not tell from its Nyquist
    frequency, or None (:func:`_unphysical_mode` has the reasoning; checked by the backward check only: a forward
    round may take such a mode as the lag of a delay it has not yet found, ident_fuzz seed 21 case 52 with a
    one-sample delay accepts a mode of damping 0.33 in round 1, the delay in round 2, and drops the mode)."""
    if not resolved_below_nyquist(e.frequency, e.damping, T):
        nyquist = 0.5 / T
        sigma = 2.0 * math.pi * e.damping * e.frequency
        return (f"its frequency {e.frequency:.4g} Hz (damping {e.damping:.3g}) lies {nyquist - e.frequency:.4g} Hz "
                f"below the record's Nyquist frequency {nyquist:.4g} Hz, less than its decay rate "
                f"{sigma:.4g} 1/s: its ringing dies before the record can tell it from the Nyquist alternation")
    return None


def resolved_below_nyquist(frequency: float, damping: float, T: float) -> bool:
    """Whether a record sampled every ``T`` [s] tells a mode of ``frequency`` [Hz] and ``damping`` [-] from its
    Nyquist frequency f_N = 1/(2T): f_N - f >= 2 pi zeta f, the distance at least the mode's decay rate (its ringing
    lasts a beat of the sampled alternation; :func:`_unphysical_mode`)."""
    return frequency < 0.5 / T and 0.5 / T - frequency >= 2.0 * math.pi * damping * frequency


def _unphysical(model: AugmentedAxisModel, name: str, data: Data) -> str | None:
    """Why the effect ``name`` of ``model`` is no longer the physical effect its name says (the tests of
    :func:`_choose` that need no refit), or None."""
    e = model.element(name)
    if name == "resonance":
        return _unphysical_mode(e, data.T) or _unresolved_mode(e, data.T)
    if name == "friction_stribeck":
        return no_stribeck_curve(stribeck_static_ratios(model))
    return None


def _without(model: AugmentedAxisModel, name: str) -> AugmentedAxisModel:
    """``model`` without the effect ``name`` as :func:`_choose` judged it: an element against its null
    (:func:`_null_of`), any other effect against the model without it."""
    in_loop = model.element(name).in_loop
    return _null_of(model, name) if in_loop else augment(model, [e for e in model.elements
                                                                 if e.NAME != name])


def _unneeded(final: Stage, without: _Judged, name: str, data: Data, plan: FoldPlan,
              opt: DiagnosisOptions) -> str | None:
    """Why the final model no longer needs ``name`` (``without``: the final model refitted without it and judged),
    or None: it must still lower the pooled held-out RMS by min_gain and min_gain_um (:func:`_lowers`), and a mode
    must still be coherent with a force of the commanded motion in the residual it explains
    (:data:`_MIN_MODE_COHERENCE`)."""
    w, f = without.held_out_rms_um, final.validation_rms_um
    if not beats_the_model_without(final.full_model.element(name), (w, without.fold_rms_um), (f, final.fold_rms_um),
                                   opt):
        return (f"the final model refitted without it predicts the held-out folds {w:.4g} um against {f:.4g} um "
                f"with it: it no longer lowers that error by {gain_required(final.full_model.element(name), opt)}")
    if name == "resonance":
        e = final.full_model.element(name)
        coh = motion_coherence(data.x - data.predict(without.model), data.xr, data.T, plan.active,
                               [e.frequency, e.antiresonance])
        if coh < _MIN_MODE_COHERENCE:
            return (f"the residual it explains is no longer coherent with the commanded motion (its acceleration "
                    f"or its velocity's sign) "
                    f"({coh:.3g} < {_MIN_MODE_COHERENCE})")
    return None


def _first_failing(stages: list[Stage], checked: set, data: Data, plan: FoldPlan,
                   opt: DiagnosisOptions) -> tuple[str, str, _Judged | None] | None:
    """The first accepted effect the final model (``stages[-1]``) no longer needs or that is no longer physical, as
    (name, why, the final model refitted without it and judged, when computed), or None. ``checked``: effects
    :func:`_choose` judged against this very model (their need is not tested again)."""
    final = stages[-1]
    for s in stages[1:]:
        why = _unphysical(final.full_model, s.effect, data)
        if why is not None:
            return s.effect, why, None
        if s.effect in checked:
            continue
        without = _judged_at_rest(_without(final.full_model, s.effect), final.full_model, data, plan, opt)
        why = _unneeded(final, without, s.effect, data, plan, opt)
        if why is not None:
            return s.effect, why, without
    return None


def _backward_check(stages: list[Stage], data: Data, plan: FoldPlan, rounds: list[dict],
                    opt: DiagnosisOptions) -> list[Stage]:
    """The stages with every accepted effect the final model no longer needs, or that is no longer physical, dropped
    (noted under ``dropped`` in the last round's record), the final model refitted without it; repeated until all
    pass.

    Forward selection judges each effect against the model of its round, and a later joint refit moves the earlier
    effects' parameters: ident_fuzz seed 21 case 52 (fadal-pid/y, a one-sample delay only) accepted a mode of damping
    0.33 that acted as the lag, then the delay, and the refit of both moved the mode to 2744 Hz, above the record's
    Nyquist frequency, where it explained nothing. So the final model faces every accepted effect again: the tests of
    :func:`_choose` that need no refit (:func:`_unphysical`) and, refitted and judged without it, the held-out gain
    and a mode's motion coherence (:func:`_unneeded`) - the backward elimination step of stepwise selection
    (Efroymson, "Multiple regression analysis", in Ralston and Wilf, Mathematical Methods for Digital Computers,
    Wiley, 1960; our reading: with the held-out gain of :func:`_choose` as the F test's stand-in). Each model
    refitted without an effect is judged with its Coulomb mean where the record puts it (:func:`_judged_at_rest`),
    as a round's accepted model is: the one that replaces the final model keeps a mean the rests pin."""
    checked = {stages[-1].effect}
    while len(stages) > 1:
        failing = _first_failing(stages, checked, data, plan, opt)
        if failing is None:
            break
        name, why, without = failing
        final = stages[-1]
        rest = [e for e in final.full_model.elements if e.NAME != name]
        if not rest:
            without = None
        elif without is None or len(without.model.elements) != len(rest):
            # the model that replaces the final one keeps no null delay of its own (a 0-sample delay is no effect):
            # judged against its null (_without), a dropped element left one where no other element remains
            without = _judged_at_rest(augment(final.full_model, rest), final.full_model, data, plan, opt)
        log.info("diagnosis: %s dropped: %s", name, why)
        w = without.held_out_rms_um if without is not None else stages[0].validation_rms_um
        rounds[-1].setdefault("dropped", {})[name] = {"reason": why, "validation_rms_with_um": final.validation_rms_um,
                                                      "validation_rms_without_um": w}
        stages = _dropped(stages, name, without)
        checked = set()
    return stages


def _dropped(stages: list[Stage], name: str, without: _Judged | None) -> list[Stage]:
    """``stages`` without the stage of ``name``, the last one's model replaced by ``without`` (the final model
    refitted without it and judged; None when no effect remains)."""
    kept = [s for s in stages if s.effect != name]
    if len(kept) == 1 or without is None:
        return kept[:1]
    kept[-1] = dataclasses.replace(
        kept[-1], **_judged_fields(without),
        evidence=dict(kept[-1].evidence, refitted_without=sorted({*kept[-1].evidence.get("refitted_without", []),
                                                                  name})))
    return kept


def _judged_fields(j: _Judged) -> dict:
    """The fields of a :class:`Stage` that the judged model ``j`` gives: its model and its errors."""
    return dict(train_model=j.model, full_model=j.model, validation_rms_um=j.held_out_rms_um,
                validation_max_um=j.held_out_max_um, identification_rms_um=j.rms_um, identification_max_um=j.max_um,
                fold_rms_um=j.fold_rms_um, fold_max_um=j.fold_max_um, in_sample_folds=j.in_sample_folds)


def stribeck_static_ratios(model: AugmentedAxisModel) -> tuple[float, float]:
    """Static over Coulomb friction, moving + and moving -, of ``model``'s Stribeck term: ``(d0 + s+) / d0`` and
    ``(d1 + s-) / d1`` (:class:`identification.effects.FrictionStribeck`).

    The Stribeck curve is friction that *falls* from its static level to the Coulomb level as the speed rises:
    static >= Coulomb, 1.3-2 times on lubricated guideways and ball screws (Armstrong-Helouvry, Dupont, Canudas de
    Wit, Automatica 30(7), 1994). A term whose excess opposes the Coulomb level says that friction vanishes
    near standstill, which is another effect imitated: on fadal-pid's x axis with its 3 um nut play and the loop
    closed on the motor encoder, the motor crosses the gap free of the table's friction at every reversal, and the
    refit found ``v_s`` 0.30 mm/s, excesses -562 / +558 mm/s^2 against Coulomb levels +538 / -359 (ratios -0.04 and
    -0.56; ``benchmarks/ident_fuzz.py`` seed 1 case 22). A direction without Coulomb friction in the model (d = 0)
    gives +inf when the excess resists motion there, -inf when it drives it."""
    st = model.element("friction_stribeck")
    p = model.parameters

    def ratio(coulomb: float, excess: float, resisting: float) -> float:
        if coulomb * resisting > 0:
            return (coulomb + excess) / coulomb
        return math.inf if excess * resisting >= 0 else -math.inf

    return ratio(p["d0"], st.excess_positive, 1.0), ratio(p["d1"], st.excess_negative, -1.0)


def no_stribeck_curve(ratios: tuple[float, float]) -> str | None:
    """Why a Stribeck term with static / Coulomb friction ``ratios`` (:func:`stribeck_static_ratios`, moving + and
    moving -) is no Stribeck curve, or None: either ratio below :data:`_MIN_STATIC_RATIO` (or not a number), or a
    finite one above :data:`_MAX_STATIC_RATIO`.

    A ratio far above the 1.3-2 of real guideways is a stick imitated: ballscrew-ppc's Coulomb friction holds the
    stopped mass for up to 12 ms at its reversals (its static level is its Coulomb level), which the reduced
    model's Coulomb term, switched on the sign of its velocity, cannot do, and the refit found ``v_s`` 0.035 mm/s
    with static / Coulomb 6.1 and inf (``benchmarks/ident_fuzz.py`` seed 21 case 30, no effect added). An infinite
    ratio (a direction whose Coulomb level does not resist motion, as under a load larger than the friction) is
    left to the lower bound."""
    if not min(ratios) >= _MIN_STATIC_RATIO:
        return (f"its static / Coulomb friction ratios {ratios[0]:.3g}, {ratios[1]:.3g} are below "
                f"{_MIN_STATIC_RATIO}: no Stribeck curve")
    if any(math.isfinite(r) and r > _MAX_STATIC_RATIO for r in ratios):
        return (f"its static / Coulomb friction ratios {ratios[0]:.3g}, {ratios[1]:.3g} exceed "
                f"{_MAX_STATIC_RATIO}: a stick at standstill, no Stribeck curve")
    return None


def _worse_on_the_record(before: ReducedAxisModel, after: AugmentedAxisModel, data: Data,
                         opt: DiagnosisOptions) -> tuple[float, float] | None:
    """(RMS before, after) [um] on all the record's samples when the effect raises it by >= min_gain and
    >= min_gain_um (as a contradicting fold), else None.

    The idle stretches neither identify nor validate, but a model that moves where the axis rests predicts no
    capture and no contour from rest (vcnc compare simulates from rest). Seen on a SINUMERIK trace: a
    position-periodic load of 1177 mm/s^2 at the starting position woke the reduced fit's Coulomb levels (d0, d1
    ~3e5 mm/s^2, switched on the sign of the simulated velocity: off while the reduced model rests exactly) and
    the final model chattered by 0.75 mm during the 4 s before the first move, 223 um RMS on all samples against
    the reduced model's 3.4 um, while its error on the active samples fell from 7.27 to 5.06 um. Our reading: the
    whole record, not its idle samples alone, is the test; a TNCscope trace's position-periodic load moves its
    idle samples from 0.0003 to 0.19 um, and lowers the error on all samples from 0.71 to 0.43 um.

    ``after`` comes with its Coulomb levels' mean set where the record puts it (:func:`coulomb_mean_at_rest`): the
    active samples do not determine that mean, and the joint refit left it wherever its finite-difference steps
    carried it (tests/identification/test_whole_record_refusal.py: -6731 or +18654 mm/s^2, 10.6 or 38.2 um over all
    samples, accepted or refused, for a 1e-9 change of the load)."""
    b = _errors(before, data, np.ones(data.n, bool))[0]
    a = _errors(after, data, np.ones(data.n, bool))[0]
    if not math.isfinite(a) or _raises(b, a, opt):
        return b, a
    return None


#: Means of the Coulomb levels tried across the bracket of :func:`coulomb_mean_at_rest` [-].
_MEAN_GRID = 17
#: Relative change of the whole-record RMS below which :func:`coulomb_mean_at_rest` leaves the mean where it was [-]:
#: a record that does not see the mean (a model that never rests exactly, its RMS flat to 1e-14 over the mean) must
#: not have it moved by rounding (fadal-pid with a 2-sample delay, test_diagnosis.py: a refitted delay's mean moved
#: 4611 -> 27761 mm/s^2 at the same RMS, and the saturation of the next round was no longer found).
_MEAN_TOL = 1e-3
#: Times the bracket of :func:`coulomb_mean_at_rest` is widened (x4 each) while its best mean lies on its edge [-].
_MEAN_WIDENINGS = 6


def with_coulomb_mean(model: ReducedAxisModel, mean: float) -> ReducedAxisModel:
    """``model`` with its Coulomb levels' mean (d0 + d1)/2 set to ``mean`` [mm/s^2], their difference kept."""
    p = dict(model.parameters)
    half = 0.5 * (p["d0"] - p["d1"])
    p["d0"], p["d1"] = mean + half, mean - half
    return dataclasses.replace(model, parameters=p)


def coulomb_mean_at_rest(after: ReducedAxisModel, before: ReducedAxisModel, data: Data) -> ReducedAxisModel:
    """``after`` with the mean of its Coulomb levels, (d0 + d1)/2 [mm/s^2], set where it predicts the whole record
    best (d0 - d1 and every other parameter kept).

    The moving samples do not determine that mean: the model's friction is d0 for v > 0, d1 for v < 0 and 0 only at
    exact rest, so once a model moves, the mean acts as a constant disturbance, which the loop's integral action
    passes as zero (G_dist = s/(s^3 + a1 s^2 + a2 s + a3)); it shows only where the model starts from exact rest.
    An effect that pushes the model at rest (a position-periodic load at the rest position) sets it chattering
    there, and then the mean is the force the chatter adds to the load: a model whose mean cancels the load at the
    rest position holds it, any other drifts until the integral action settles. So the one parameter the moving
    samples leave free is set by the samples that do show it, the idle stretches, and the whole-record rule
    (:func:`_worse_on_the_record`) judges the model at that mean: its verdict is the record's, not where the joint
    refit's steps happened to leave the mean (session 34: a 1e-9 change of the load moved it from -6731 to +18654
    mm/s^2, the whole record from 10.6 to 38.2 um, accepted then refused; at the fitted mean, -830 mm/s^2 against
    a load of 800 mm/s^2 at the rest position, 1.3 um, accepted, on every run).

    The whole-record RMS over the mean is a V about the mean that holds the model (test_whole_record_refusal.py):
    :data:`_MEAN_GRID` means across ``before``'s mean +- twice the largest Coulomb level of either model (the bracket
    widened x4 while the best lies on its edge, at most :data:`_MEAN_WIDENINGS` times), then a bounded Brent search
    between the best one's neighbours. The bracket depends on the refit's levels only through its width. The refit's
    own mean is kept unless another predicts the whole record better by :data:`_MEAN_TOL`: where the record does not
    see the mean (a model that never rests exactly), rounding must not move it.
    """
    everywhere = np.ones(data.n, bool)

    def cost(mean: float) -> float:
        return _errors(with_coulomb_mean(after, mean), data, everywhere)[0]

    own = 0.5 * (after.parameters["d0"] + after.parameters["d1"])
    centre = 0.5 * (before.parameters["d0"] + before.parameters["d1"])
    width = 2.0 * max(abs(before.parameters["d0"]), abs(before.parameters["d1"]), abs(after.parameters["d0"]),
                      abs(after.parameters["d1"]), 1.0)
    for _ in range(_MEAN_WIDENINGS + 1):
        means = np.linspace(centre - width, centre + width, _MEAN_GRID)
        costs = np.array([cost(m) for m in means])
        k = int(np.argmin(costs))
        if not np.max(costs) - costs[k] > _MEAN_TOL * costs[k]:
            return after  # the record does not see the mean (a model that never rests): it stays where it was
        if 0 < k < _MEAN_GRID - 1:
            break
        width *= 4.0
    lo, hi = means[max(k - 1, 0)], means[min(k + 1, _MEAN_GRID - 1)]
    res = scipy.optimize.minimize_scalar(cost, bounds=(lo, hi), method="bounded",
                                         options={"xatol": 1e-4 * (hi - lo)})
    best, best_cost = (float(res.x), float(res.fun)) if res.fun < costs[k] else (float(means[k]), float(costs[k]))
    if not best_cost < (1.0 - _MEAN_TOL) * cost(own):
        return after
    return with_coulomb_mean(after, best)


def _idle_effect(j: _Judged, name: str, data: Data, opt: DiagnosisOptions) -> tuple[float, float] | None:
    """(RMS with, without) [um] on the active samples when the refitted model ``j`` predicts as well without its
    effect ``name`` (the other parameters as refitted: the effect's share of the refit's gain is below min_gain or
    min_gain_um), else None.

    A joint refit moves the reduced parameters too; from a reduced fit caught in a local minimum it can find a
    better one whatever the effect, and the held-out gain is then the reduced model's, not the effect's (fuzz seed
    11 case 51, fadal-smc/y with a 25.5 um backlash: a drift of 8e-6 mm/s, 27 nm over the record, took the
    held-out RMS from 4.41 to 2.68 um). Elements face their refitted null instead (:func:`_null_of`)."""
    rest = [e for e in j.model.elements if e.NAME != name]
    without = augment(j.model, rest)
    b = _errors(without, data, data.active)[0]
    a = j.rms_um
    if math.isfinite(b) and not _lowers(b, a, opt):
        return a, b
    return None


def _accepted_stage(chosen: tuple, tried: list[tuple], stage: Stage, record: dict) -> Stage:
    """The stage of an accepted effect, with its evidence."""
    j, c, gain, nested = chosen
    ev = dict(c.evidence)
    ev["validation_gain_pct"] = 100.0 * gain
    if nested is not None:
        ev["validation_gain_over_null_pct"] = 100.0 * nested
    if "resonance_motion_coherence" in record and c.effect.NAME == "resonance":
        ev["motion_coherence"] = record["resonance_motion_coherence"]
    ev["candidates_validation_rms_um"] = {t[1].effect.NAME: t[0].held_out_rms_um
                                          for t in sorted(tried, key=lambda t: t[0].held_out_rms_um)}
    ev["fold_rms_before_um"] = list(stage.fold_rms_um)
    ev["fold_rms_after_um"] = list(j.fold_rms_um)
    return Stage(effect=c.effect.NAME, evidence=ev, **_judged_fields(j))


def adds_no_parameter(effect) -> bool:
    """Is ``effect`` an element that adds no fitted parameter to its null (a whole-sample delay: the refit moves the
    same parameters with and without it, :meth:`identification.effects.Effect.free` is empty)?"""
    return effect.KIND == "element" and not effect.free()


def beats_the_model_without(effect, without: tuple[float, list[float]], with_: tuple[float, list[float]],
                            opt: DiagnosisOptions) -> bool:
    """Does the model with ``effect`` beat the model refitted without it (an element's null, :func:`_null_of`), each
    judged on the same folds: ``with_`` and ``without`` are (pooled held-out RMS, held-out RMS per fold) [um]?

    An effect with parameters of its own must bring the gain an effect must bring (:func:`_lowers`). An element
    that adds none (:func:`adds_no_parameter`) is a choice between two models of one size, which the held-out folds
    decide as they stand: it must lower the pooled error by ``min_gain_um``, on more than half of the folds, and
    raise none by the gain (:func:`_contradicting_folds`). The relative gain would ask of it what the null's loop
    parameters leave: they imitate most of a short delay's lag (ident_fuzz seed 71 case 29, fadal-smc/x with a
    one-sample delay: held out 1.54 um with it, 1.73 um refitted without it, lower on 3 of 4 folds; the same
    program on the machine without the delay is predicted 2.30 um with one and 1.03 um without, worse on every
    fold).
    """
    (w, w_folds), (rms_um, folds_um) = without, with_
    if not adds_no_parameter(effect):
        return _lowers(w, rms_um, opt)
    lower = sum(a < b for a, b in zip(folds_um, w_folds))
    return (w - rms_um >= opt.min_gain_um and 2 * lower > len(folds_um)
            and not _contradicting_folds(w_folds, folds_um, opt))


def gain_required(effect, opt: DiagnosisOptions) -> str:
    """What :func:`beats_the_model_without` asks of ``effect``, in words."""
    if adds_no_parameter(effect):
        return f">= {opt.min_gain_um} um pooled and on more than half of the folds"
    return f">= {opt.min_gain:.0%} and >= {opt.min_gain_um} um"


def _lowers(before: float, after: float, opt: DiagnosisOptions) -> bool:
    """Is ``after`` [um] below ``before`` by ``min_gain`` relative and ``min_gain_um``: the gain an effect must
    bring (on the held-out error, over its null, or of its own share of a refit)?"""
    return before - after >= opt.min_gain_um and _gain(before, after) >= opt.min_gain


def _gain(before: float, after: float) -> float:
    """Relative drop from ``before`` to ``after`` (1 when an infinite error becomes finite)."""
    if not math.isfinite(after):
        return -math.inf
    if not math.isfinite(before):
        return 1.0
    return (before - after) / before if before > 0 else 0.0


def _null_of(model: AugmentedAxisModel, name: str) -> AugmentedAxisModel:
    """``model`` without the effect ``name``, keeping the sampled split form (a 0-sample delay)."""
    from identification.effects import Delay

    rest = [e for e in model.elements if e.NAME != name]
    if not any(e.in_loop for e in rest):
        rest.append(Delay(samples=0, sample_time=model.sample_time))
    return augment(model, rest)


def _poles_on_bounds(model: ReducedAxisModel, data: Data) -> list[str]:
    out = []
    for k, (lo, hi) in data.bounds.as_dict().items():
        v = (model.poles or {}).get(k)
        if v is None:
            continue
        if v <= lo * (1 + 1e-6) and not (k == "p_hz" and lo <= WIDE_P_MIN_HZ):
            # p on the widened 1 mHz bound is a loop without integral action (p -> 0), as identify decided
            out.append(f"{k} = {v:.4g} at its lower bound")
        elif v >= hi * (1 - 1e-6):
            out.append(f"{k} = {v:.4g} at its upper bound")
    return out


#: Ratio of a fold's held-out RMS to the largest of the other folds' above which the record is said not to behave as
#: one loop throughout [-] (:func:`outlier_fold_warnings`). On 10 real traces the ratio stays below 5.4 (a TNCscope
#: trace with a shaker on in two of its folds: 3.08 um against 0.576), and a record whose gains switch mid-record
#: reaches 85 (an ODrive joint motor, Kp 1 -> 500 at 0.5 s: 2055 mdeg against 24.3).
OUTLIER_FOLD_RATIO = 10.0


def outlier_fold_warnings(fold_rms_um: list[float], windows_s: list, unit: str = "um") -> list[str]:
    """Name a fold whose held-out RMS is over :data:`OUTLIER_FOLD_RATIO` times every other fold's: the loop the other
    folds show does not predict that stretch, so the record does not behave as one loop throughout (gains switched,
    a loop opened or saturated there, a measured channel that is not the loop's in that stretch), and the model is a
    compromise that a user must not read as the loop's. Our reading; a model predicts its folds alike when one loop
    runs throughout."""
    out = []
    finite = [r for r in fold_rms_um if math.isfinite(r)]
    if len(finite) < 3:
        return out
    for i, r in enumerate(fold_rms_um):
        others = [v for j, v in enumerate(fold_rms_um) if j != i and math.isfinite(v)]
        if not (math.isfinite(r) and others and r > OUTLIER_FOLD_RATIO * max(others)):
            continue
        w = windows_s[i] if i < len(windows_s) else (math.nan, math.nan)
        out.append(f"fold {i + 1} ({w[0]:.4g}..{w[1]:.4g} s) is predicted {r / max(others):.3g} times worse held out "
                   f"({r:.4g} {unit}) than any other fold (at most {max(others):.4g} {unit}): the record does not "
                   "behave as one loop throughout (gains switched or a loop opened mid-record, an axis held off its "
                   "reference, a measured channel that is not the loop's in that stretch); the model is a compromise "
                   "between them, not the loop's: identify the stretches apart (crop the record)")
    return out


def in_sample_warnings(reduced: list[int], final: list[int] | None) -> list[str]:
    """Say which folds' "held-out" errors are in sample (:func:`_judge`: no iteration of the refit on the other
    folds lowered their error, so the fold keeps the full fit, which saw it). Our reading: such a number is no
    out-of-sample check, and a table that pools it as "valid" claims more than it shows (before the sensitivities
    of :func:`_held_out_sensitivities`, 4 of 13 recorded traces had such a fold)."""
    out = []
    for which, idx in (("reduced model", reduced), ("final model", final)):
        if idx:
            names = ", ".join(str(i + 1) for i in idx)
            out.append(f"the {which}'s held-out error on fold{'s' if len(idx) > 1 else ''} {names} is its "
                       "identification error there: no refit on the other folds lowered their error, so it "
                       "is no out-of-sample check")
    return out


def bound_advice(on_bounds: list[str]) -> str:
    """What to do about poles on the box (:func:`_poles_on_bounds`): widening helps a slow pole p of a loop
    without integral action; a damping or frequency on its bound is not cured by p -> 0 (our reading: a 100 ms
    CNC log put zeta on 0.2 and was advised to widen p), so the advice names the bound that binds."""
    advice = []
    if any(b.startswith("p_hz") for b in on_bounds):
        advice.append("widen the bounds if the loop has no integral action (p -> 0)")
    if any(not b.startswith("p_hz") for b in on_bounds):
        advice.append("move a zeta or omega_n bound only where the loop is known to lie beyond it; otherwise the "
                      "record does not show the loop's dynamics the reduced model needs (too slow a sample time, "
                      "too little excitation) and its poles are not the loop's")
    return "; ".join(advice)


def _final_model(model: ReducedAxisModel, stages: list[Stage], opt: DiagnosisOptions, data: Data,
                 rounds: list[dict], plan: FoldPlan, counts: list[int]) -> ReducedAxisModel:
    T = data.T
    everywhere = np.ones(data.n, bool)
    fold_rows = []
    for i, f in enumerate(plan.folds):
        fold_rows.append({"window_s": f.window_s(T), "active_samples": f.active,
                          "positive_samples": f.positive, "negative_samples": f.negative,
                          "rms_before_um": stages[0].fold_rms_um[i], "rms_after_um": stages[-1].fold_rms_um[i],
                          "max_before_um": stages[0].fold_max_um[i], "max_after_um": stages[-1].fold_max_um[i]})
    segs = motion_segments(plan.active)
    validation = {
        "rms_before_um": stages[0].validation_rms_um,
        "rms_after_um": stages[-1].validation_rms_um,
        "max_before_um": stages[0].validation_max_um,
        "max_after_um": stages[-1].validation_max_um,
        "identification_rms_before_um": stages[0].identification_rms_um,
        "identification_max_before_um": stages[0].identification_max_um,
        "split": f"{len(plan.folds)} contiguous folds cut where the reference stands still or reverses; each is "
                 "held out in turn (the fit on all active samples refitted on the other folds by up to "
                 f"{HELD_OUT_ITERATIONS} Levenberg-Marquardt iterations) and the held-out errors pooled; "
                 f"idle stretches trimmed with a {opt.margin_s:g} s margin",
        "criterion": f"add the effect with the lowest pooled held-out simulation RMS when it lowers it by >= "
                     f"{opt.min_gain:.0%} and >= {opt.min_gain_um} um, lowers the error on all active samples, and "
                     f"neither a fold's held-out RMS nor the RMS on the whole record rises by >= {opt.min_gain:.0%} "
                     f"and >= {opt.min_gain_um} um",
        "folds": fold_rows,
        "active": {"margin_s": opt.margin_s, "active_samples": int(plan.active.sum()),
                   "idle_samples": int(plan.active.size - plan.active.sum()),
                   "segments_s": [[a * T, b * T] for a, b in segs[:50]], "segments": len(segs)},
        "samples": {"identification": int(plan.active.sum()), "validation": int(sum(counts)), "record": data.n},
        "record_rms_um": [_errors(model, data, everywhere)[0]] + [_errors(s.full_model, data, everywhere)[0]
                                                                 for s in stages[1:]],
        "rounds": plain(rounds),
    }
    validation["naive_active"] = pure_delay_baseline(data.xr, data.x, T, mask=plan.active)
    warnings = list(plan.warnings) + in_sample_warnings(stages[0].in_sample_folds,
                                                        stages[-1].in_sample_folds if len(stages) > 1 else None)
    warnings += outlier_fold_warnings(stages[-1].fold_rms_um, [r["window_s"] for r in fold_rows],
                                      axis_unit(model.axis or "x", small=True))
    if warnings:
        validation["warnings"] = warnings
    final_model = stages[-1].full_model if len(stages) > 1 else model
    stopped = not rounds or rounds[-1].get("accepted") is None
    validation["unexplained"] = _unexplained(final_model, data, plan, stopped)
    # a reduced model whose poles sit on the search box is a structural warning (e.g. no integral
    # action, p -> 0, below the thesis' 0.2 Hz bound): effects found then may compensate for it
    on_bounds = _poles_on_bounds(model, data)
    if on_bounds:
        drift = drift_left_in(model.fit)
        advice = (f"a drift of the measured channel against the commanded one ({drift['rate_um_min']:.4g} "
                  "um/min, fit.drift) holds them there: remove it (identify(..., drift='remove'), vcnc identify "
                  "--drift remove)" if drift else bound_advice(on_bounds))
        validation["warning"] = ("reduced-model poles on the bounds (" + ", ".join(on_bounds) + "): the reduced "
                                 "structure or the bounds do not fit these data; " + advice)
        log.info("diagnosis: %s", validation["warning"])  # printed from validation["warning"]: once
    if len(stages) == 1:
        return dataclasses.replace(model, validation=validation, effects=[])
    last: AugmentedAxisModel = stages[-1].full_model  # type: ignore[assignment]
    records = []
    by_name = {e.NAME: e for e in last.elements}
    base = {r["name"]: r for r in last.effect_records()}
    for prev, s in zip(stages[:-1], stages[1:]):
        e = by_name[s.effect]
        rec = base[s.effect]
        rec.update({
            "rms_before_um": prev.identification_rms_um,
            "rms_after_um": s.identification_rms_um,
            "max_before_um": prev.identification_max_um,
            "max_after_um": s.identification_max_um,
            "validation_rms_before_um": prev.validation_rms_um,
            "validation_rms_after_um": s.validation_rms_um,
            "validation_max_before_um": prev.validation_max_um,
            "validation_max_after_um": s.validation_max_um,
            "description": e.DESCRIPTION,
            "summary": e.summary(),
            "evidence": plain(s.evidence),
        })
        # a parameter the record does not pin (a period the travel covers once) is kept for the simulation and
        # reported as such, never as a measured number
        if unpinned := e.unpinned(travel=data.span, duration=data.n * T):
            rec["unpinned"] = unpinned
            rec["summary"] = f"{e.summary()}; not pinned by the record: {', '.join(unpinned)}"
        records.append(rec)
    fit = dict(model.fit)
    fit["reduced_model"] = {"rms_um": stages[0].identification_rms_um, "max_um": stages[0].identification_max_um,
                            "parameters": dict(model.parameters), "poles": dict(model.poles)}
    # the prediction of the capture stays one of all its samples (before_after_rows: which samples each number covers)
    fit["rms_um"], fit["max_um"] = _errors(last, data, everywhere)
    return augment(last, last.elements, axis=model.axis, method=model.method, fit=fit, effects=records,
                   validation=validation, bounds=dict(model.bounds))


#: smallest coherence of the residual with the commanded acceleration or velocity sign near a claimed mode [-]
#: (0.9 for a mode the motion excites, 0.09 for an external 55 Hz line: residual.motion_coherence)
_MIN_MODE_COHERENCE = 0.5
#: damping ratio below which a refitted two-mass mode is a resonance [-]: a second-order mode shows a resonant
#: peak only for zeta < 1/sqrt(2) (Ogata, Modern Control Engineering, 5th ed., Sec. 7-2, resonant peak M_r). Above
#: it the element is a lag the refit borrowed: ident_fuzz seed 12 case 45, ballscrew-zpetc with a one-sample delay
#: and no mode, refitted a 2994 Hz "mode" of damping 1.0 (the bound), table share 0.993, held out 2.85 -> 0.48 um.
_MAX_MODE_DAMPING = 1.0 / math.sqrt(2.0)

#: static / Coulomb friction below which a Stribeck term is no Stribeck curve [-] (:func:`stribeck_static_ratios`)
_MIN_STATIC_RATIO = 0.9
#: static / Coulomb friction above which a Stribeck term is no Stribeck curve [-]: twice the 1.3-2 of lubricated
#: guideways and ball screws (Armstrong-Helouvry, Dupont, Canudas de Wit, Automatica 30(7), 1994)
_MAX_STATIC_RATIO = 4.0

#: explained share of the residual's variance above which a state "explains" it [-] (time: slow
#: trends and the residual's own correlation explain some of any residual, hence the higher bar)
_STRUCTURE_SHARE = {"position": 0.2, "velocity": 0.2, "direction": 0.2, "acceleration": 0.2, "time": 0.35}


#: What a residual explained by time says (a drift the ``drift`` effect did not take: the reduced model's slow
#: pole p imitates a drift of the measured channel, fadal-pid with 100 um/min: p 0.02 Hz for 1.14, and the
#: effect then lowers the held-out error too little to be kept)
_DRIFT_ADVICE = ("; a trend in time is a drift of the measured channel against the commanded one (thermal growth) "
                 "that the fit's slow pole imitates: vcnc identify --drift remove takes it out before the fit")


def drift_advice(fit: dict) -> str:
    """:data:`_DRIFT_ADVICE`, unless the fit already took the drift out or tried to (``fit['drift']``,
    :func:`identification.measured_drift.fit_with_drift`): advising ``--drift remove`` after it predicted worse
    sends the user in a circle (our reading; a hydraulic rig's record: drift out predicts 474 -> 527 um)."""
    rec = fit.get("drift") or {}
    if rec.get("removed"):
        return ("; a trend in time remains after the measured channel's drift was taken out before the fit: the "
                "model does not explain it")
    if "rms_removed_um" in rec:
        return (f"; the measured channel's drift was tried out of the fit and predicts {rec['rms_kept_um']:.4g} -> "
                f"{rec['rms_removed_um']:.4g} um, not twice better: this trend in time is not a drift the fit can be "
                "freed of, and the model does not explain it")
    return _DRIFT_ADVICE


def _unexplained(model: ReducedAxisModel, data: Data, plan: FoldPlan, stopped: bool) -> dict[str, Any]:
    """Evidence on the final residual (:func:`identification.residual.residual_evidence`) and a statement."""
    from identification.residual import residual_evidence

    y = data.predict(model)
    ev = residual_evidence(data.x - y, data.xr, data.T, plan.active)
    hits = [k for k, lim in _STRUCTURE_SHARE.items() if ev["explained_share"].get(k, 0.0) >= lim]
    ev["structured"] = bool(hits)
    u = axis_unit(model.axis or "x", small=True)  # um, or mdeg on a rotary axis
    peaks = ", ".join(f"{p['frequency_hz']:.4g} Hz ({p['amplitude_um']:.3g} {u})" for p in ev["spectral_peaks"][:3])
    if hits:
        what = ", ".join(f"{k} ({100 * ev['explained_share'][k]:.0f} % of its variance)" for k in hits)
        head = ("no effect of the vocabulary explains the remaining residual" if stopped
                else "the remaining residual (effects stopped at max_effects)")
        ev["statement"] = f"{head}: RMS {ev['rms_um']:.3g} {u}, explained by {what}; spectral peaks {peaks}" + (
            drift_advice(model.fit) if "time" in hits else "")
    else:
        ev["statement"] = (f"the remaining residual (RMS {ev['rms_um']:.3g} {u}) shows no dependence on position, "
                           f"velocity, direction, acceleration or time; spectral peaks {peaks}")
    return ev


def report_figure(capture: Capture, model: ReducedAxisModel, *, axis: str, ax=None):
    """Residual before (the reduced model) and after (``model``) vs time, velocity, position, spectrum.

    Works from a diagnosed model alone: the reduced model is rebuilt from
    ``model.fit["reduced_model"]`` (the model itself when nothing was added). Returns 4 Axes.
    """
    from identification.residual import plot_before_after

    xr, x, T = check_capture(capture, axis)
    red = (model.fit or {}).get("reduced_model")
    # the reduced model with the final model's dead time and setpoint filter: it predicts the same recorded reference
    before = model if not red else ReducedAxisModel(parameters=red["parameters"], sample_time=model.sample_time,
                                                    axis=model.axis, delay_s=model.delay_s,
                                                    setpoint_filter_s=model.setpoint_filter_s)
    return plot_before_after(xr, x, T, before, model, ax=ax)


# ------------------------------------------------------------------------------ before/after table


def before_after_rows(model: ReducedAxisModel) -> list[dict[str, Any]]:
    """Rows of the before/after table from a diagnosed model's ``effects`` and ``validation``.

    One row for the reduced model, one per added effect (cumulative), the last being the final
    model; each with ``label``, ``record_rms_um`` (all the record's samples), ``identification_rms_um``,
    ``identification_max_um`` (its active samples, which the diagnosis fits on), ``validation_rms_um``,
    ``validation_max_um`` (the same active samples, each fold predicted by the model refitted on the others).
    """
    v = model.validation or {}
    effects = list(model.effects or [])
    record = list(v.get("record_rms_um") or [])
    if effects:
        first = effects[0]
        rows = [{"label": "reduced model", "identification_rms_um": first.get("rms_before_um"),
                 "identification_max_um": first.get("max_before_um"),
                 "validation_rms_um": first.get("validation_rms_before_um"),
                 "validation_max_um": first.get("validation_max_before_um")}]
    else:
        rows = [{"label": "reduced model", "identification_rms_um": v.get("identification_rms_before_um"),
                 "identification_max_um": v.get("identification_max_before_um"),
                 "validation_rms_um": v.get("rms_before_um"), "validation_max_um": v.get("max_before_um")}]
    for e in effects:
        rows.append({"label": f"+ {e['name']} ({e.get('summary', '')})", "name": e["name"], "summary": e.get("summary"),
                     "identification_rms_um": e.get("rms_after_um"), "identification_max_um": e.get("max_after_um"),
                     "validation_rms_um": e.get("validation_rms_after_um"),
                     "validation_max_um": e.get("validation_max_after_um")})
    for row, r in zip(rows, record):
        row["record_rms_um"] = r
    final = {k: v for k, v in rows[-1].items() if k not in ("name", "summary")}  # the model, not its last effect
    rows.append(dict(final, label="final model"))
    return rows


def samples_note(model: ReducedAxisModel) -> str:
    """Which samples each column of :func:`format_before_after` covers, and how they were simulated.

    Our reading: a table whose rows mix sample sets misleads (a TNCscope trace: the reduced model's 1.08 um on
    its 2955 active samples against the fit's 0.68 um on all 6848, idle ones included, simulated between the
    samples), so every number says what it is over. A record slower than 1 ms is predicted as the fit predicted it
    (:attr:`identification.searches.Data.held`), so that the fit's error and the table's agree for one model
    (camber linD at 10 ms: 237.7 um in the fit, 275.2 on the record's grid before)."""
    v = model.validation or {}
    n = v.get("samples") or {}
    if not n:
        return ""
    margin = (v.get("active") or {}).get("margin_s")
    record = f"'all' the record's {n['record']}; " if "record" in n else ""  # (a model file written before 'all')
    substeps = (model.fit or {}).get("substeps") or 1
    how = ("on the record's sample grid" if substeps == 1 else
           f"as the fit predicts the record, on {substeps} sub-steps a sample (the reference between its samples a "
           "cubic spline; an element's sampled controller at the sub-steps)")
    return (f"samples: {record}'ident' and 'valid' its {n.get('identification')} "
            f"active ones (idle stretches, where an axis at rest is predicted for free, trimmed"
            + (f" with a {margin:g} s margin" if margin is not None else "") + "), 'valid' each fold's predicted by "
            f"the model refitted on the others; all simulated {how}")


def refusal_lines(validation: dict, unit: str = "um") -> list[str]:
    """One line per effect that lowered the pooled held-out error and was refused, from ``validation['rounds']``:
    by a fold whose held-out error it raises (:func:`_contradicting_folds`; a TNCscope trace's 55 Hz time-periodic
    load, 2.13 -> 1.13 um pooled, fold 4 0.60 -> 0.79 um, while it was refitted from one start only: from the
    current loop's, :func:`refit_candidate`, it is kept, 2.12 -> 0.68 um, fold 4 0.58 -> 0.56 um) or by the
    whole record (:func:`_worse_on_the_record`; a
    SINUMERIK trace's position-periodic load, held out 7.27 -> 5.06 um, 3.4 -> 223 um over all samples), or as no
    physical effect of its name (the round's ``unphysical`` reasons: a mode above the Nyquist frequency or damped
    beyond 1/sqrt(2), :func:`_unphysical_mode`). A report
    that said no effect lowers the held-out error hid that one did, and why it is not in the model (our reading)."""
    lines = []
    for r in validation.get("rounds") or []:
        was = r.get("current_validation_rms_um")
        for name, against in (r.get("contradicted_by_folds") or {}).items():
            cand = (r.get("refitted") or {}).get(name, {})
            held, per_fold = cand.get("validation_rms_um"), cand.get("fold_rms_um") or []
            if held is None or not was or not held < was or not all(0 < f <= len(per_fold) for f in against):
                continue
            which = ", ".join(f"{f} to {per_fold[f - 1]:.4g} {unit}" for f in against)
            lines.append(f"refused: {name} lowers the held-out error {was:.4g} -> {held:.4g} {unit}, but raises that "
                         f"of fold {which}, by as much as a gain must lower it: what it fits does not hold over the "
                         "whole record (an effect present in part of it, or fitted to something else)")
        for name, (before, after) in (r.get("worse_on_the_record_um") or {}).items():
            held = (r.get("refitted") or {}).get(name, {}).get("validation_rms_um")
            was = r.get("current_validation_rms_um")
            gain = (f"lowers the held-out error {was:.4g} -> {held:.4g} {unit}, but " if held is not None and was
                    else "")
            lines.append(f"refused: {name} {gain}raises the RMS over all the record's samples {before:.4g} -> "
                         f"{after:.4g} {unit}: it moves the model where the axis rests (the idle stretches the "
                         "held-out folds trim)")
        for name, why in (r.get("unphysical") or {}).items():
            held = (r.get("refitted") or {}).get(name, {}).get("validation_rms_um")
            if held is not None and was and held < was:
                lines.append(f"refused: {name} lowers the held-out error {was:.4g} -> {held:.4g} {unit}, but {why}")
    return lines


def dropped_lines(validation: dict, unit: str = "um") -> list[str]:
    """One line per accepted effect the final model dropped again, from the ``dropped`` notes of
    ``validation['rounds']`` (:func:`_backward_check`): which, why, and the held-out error with and without it."""
    lines = []
    for r in validation.get("rounds") or []:
        for name, d in (r.get("dropped") or {}).items():
            lines.append(f"dropped: {name}, accepted in an earlier round, because {d.get('reason')}; the final model "
                         f"without it: held-out RMS {d.get('validation_rms_with_um', math.nan):.4g} -> "
                         f"{d.get('validation_rms_without_um', math.nan):.4g} {unit}")
    return lines


def unpinned_lines(model: ReducedAxisModel) -> list[str]:
    """One line per parameter of a named effect that the record does not pin (the effect record's ``unpinned``,
    :meth:`identification.effects.Effect.unpinned`): which, its fitted value, and why."""
    lines = []
    for e in model.effects or []:
        for key, why in (e.get("unpinned") or {}).items():
            value = (e.get("parameters") or {}).get(key)
            shown = f" {value:.4g}" if isinstance(value, (int, float)) else ""
            lines.append(f"not pinned: {e['name']} {key}{shown} is one of many values that fit: {why}")
    return lines


#: Width the command line's table of :func:`format_before_after` and an effect's description under it keep to
#: [characters].
TABLE_COLUMNS = 100


def wrapped_lines(text: str, width: int = TABLE_COLUMNS) -> list[str]:
    """``text`` as the command line prints it: each of its lines kept when it fits in ``width`` columns, else
    wrapped at word boundaries, continued 4 columns in (a word longer than the width, a path, stays whole). The
    words are the text's own: the HTML report prints the same text unwrapped (a summary's sample note, split and
    naive-prediction lines ran to 275, 282 and 321 columns)."""
    out = []
    for line in text.split("\n"):
        if len(line) <= width:
            out.append(line)
            continue
        indent = line[:len(line) - len(line.lstrip())]
        out += textwrap.wrap(line, width, initial_indent="", subsequent_indent=indent + "    ",
                             break_long_words=False, break_on_hyphens=False)
    return out


def format_before_after(model: ReducedAxisModel) -> str:
    """Text table of :func:`before_after_rows` for the command line (errors in um, mdeg on a rotary axis)."""
    rows = before_after_rows(model)
    u = axis_unit(model.axis, small=True)
    # an effect's row is named by the effect; what was fitted follows the table, wrapped (a time-periodic load's
    # summary made a 130-character label and the table 190 columns wide)
    labels = [f"+ {r['name']}" if r.get("name") else r["label"] for r in rows]
    width = max(len(label) for label in labels)
    head = (f"{'model':<{width}}  {'all RMS':>9}  {'ident RMS':>9}  {'ident max':>9}  {'valid RMS':>9}  "
            f"{'valid max':>9}   [{u}]")
    lines = [head, "-" * len(head)]
    for label, r in zip(labels, rows, strict=True):
        lines.append(f"{label:<{width}}  {_cell(r.get('record_rms_um'))}  {_cell(r['identification_rms_um'])}  "
                     f"{_cell(r['identification_max_um'])}  {_cell(r['validation_rms_um'])}  "
                     f"{_cell(r['validation_max_um'])}")
    return "\n".join(lines + after_table_lines(model))


def _cell(x) -> str:  # noqa: ANN001 - a number, None or NaN
    """A table cell [um or mdeg]: ``-`` where there is no finite value."""
    return "      -" if x is None or not math.isfinite(float(x)) else f"{float(x):9.3f}"


def after_table_lines(model: ReducedAxisModel) -> list[str]:
    """The lines :func:`format_before_after` prints after its table, each a paragraph (what each effect fitted,
    wrapped at :data:`TABLE_COLUMNS`; which samples; the split; refusals; parameters not pinned; the folds; warnings;
    the residual): the command line's summary and the HTML report say the same."""
    rows = before_after_rows(model)
    u = axis_unit(model.axis, small=True)
    f = _cell
    lines = []
    for r in rows:
        if r.get("name") and r.get("summary"):
            lines.append(textwrap.fill(f"+ {r['name']}: {r['summary']}", TABLE_COLUMNS, subsequent_indent="    "))
    note = samples_note(model)
    if note:
        lines.append(note)
    v = model.validation or {}
    if v.get("split"):
        lines.append(f"validation: {v['split']}")
    refused = refusal_lines(v, u) + dropped_lines(v, u)
    if not model.effects:
        lines.append("diagnosis: no effect is kept; the reduced model stands" if refused else
                     "diagnosis: no effect lowers the held-out error significantly; the reduced model stands")
    lines.extend(refused)
    lines.extend(unpinned_lines(model))
    for fo in v.get("folds") or []:
        w = fo.get("window_s") or [math.nan, math.nan]
        lines.append(f"  fold {w[0]:8.3f}..{w[1]:8.3f} s ({fo.get('active_samples')} active samples): held-out RMS "
                     f"{f(fo.get('rms_before_um'))} -> {f(fo.get('rms_after_um'))} {u}")
    if v.get("warning"):
        lines.append(f"warning: {v['warning']}")
    for w in v.get("warnings") or []:
        lines.append(f"warning: {w}")
    if (v.get("unexplained") or {}).get("statement"):
        lines.append(f"residual: {v['unexplained']['statement']}")
    return lines
