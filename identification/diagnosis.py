"""Residual diagnosis: find what the reduced model fails to explain, name the effect, add it.

``diagnose(capture, model, axis=...)`` is called by :func:`identification.identify` and returns
the model augmented with the effects the data support (an
:class:`~identification.augmented.AugmentedAxisModel`; the plain model when none), with
``effects`` and ``validation`` filled in as the model-file contract asks.

Procedure (forward selection judged on held-out data)
-----------------------------------------------------
1. **Split.** The first ``train_fraction`` (70 %) of the samples identify, the last 30 %
   validate (a blocked split in time: the validation block is never seen by any fit, and a
   time-periodic load or a drift must extrapolate into it). The reduced model is refitted on the
   identification block (output error from the given model, pole bounds kept).
2. **Search.** Every effect not yet in the model proposes its best instance
   (:mod:`identification.effects.search`: equation-error partial regressions for disturbance
   terms with their nonlinear parameter searched - Stribeck velocity, position period, time
   period from the residual spectrum, harmonics by validation equation error - and simulations
   for the structured elements: delays 1..8 samples, saturation limits, backlash widths,
   resonance frequencies from the residual spectrum).
3. **Refit.** The ``top`` proposals with the lowest screening error are refitted jointly - all
   reduced parameters with the pole bounds of Eq. (3.8), the effect's parameters (including its
   nonlinear ones, except whole-sample delays) and the parameters of the effects already in - by
   output error (simulation error) on the identification block.
4. **Judge.** The proposal with the lowest held-out simulation RMS is added when it lowers the
   held-out RMS by at least ``min_gain`` (25 %) relative *and* by ``min_gain_um`` (0.05 um)
   absolute, and lowers the identification-block RMS too. Steps 2-4 repeat (at most
   ``max_effects`` times) until no proposal passes.
5. **Report.** Each stage (reduced model, then each effect in turn) is refitted on all samples
   for the identification-data error; the held-out error is that of the stage fitted on the
   identification block. Both go into ``effects[]`` and ``validation``.

The 25 % criterion: on clean captures of the project's virtual machines (different seeds and
programs) the best spurious proposal lowers the held-out RMS by at most about 10 % (the reduced
model's structural mismatch with a sampled, quantised machine); see
``tests/identification/test_diagnosis.py`` and ``benchmarks/diagnosis.py``.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import time
from typing import Any

import numpy as np
import scipy.optimize

from identification.augmented import AugmentedAxisModel, augment, simulate_augmented
from identification.bounds import as_bounds
from identification.effects import EFFECTS
from identification.effects.search import SEARCHES, Candidate, Data, SearchContext
from identification.poles import TWO_PI, denominator
from identification.reduced_model import ReducedAxisModel
from vcnc.capture import Capture
from vcnc.errors import IdentificationError

__all__ = [
    "report_figure",
    "DiagnosisOptions",
    "DiagnosisReport",
    "Stage",
    "diagnose",
    "diagnose_report",
    "refit",
    "before_after_rows",
    "format_before_after",
]

log = logging.getLogger(__name__)


@dataclasses.dataclass(frozen=True, kw_only=True)
class DiagnosisOptions:
    """Settings of the diagnosis (module docstring).

    Attributes
    ----------
    train_fraction : float
        Share of samples (from the start) that identify; the rest validates [-].
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

    train_fraction: float = 0.7
    min_gain: float = 0.25
    min_gain_um: float = 0.05
    max_effects: int = 3
    top: int = 3
    effects: tuple[str, ...] = tuple(EFFECTS)
    max_nfev: int = 40
    min_screen: float = 0.05

    def __post_init__(self) -> None:
        if not 0.3 <= self.train_fraction <= 0.9:
            raise IdentificationError(f"train_fraction must lie in [0.3, 0.9] (got {self.train_fraction!r})")
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


@dataclasses.dataclass(eq=False)
class DiagnosisReport:
    """Result of :func:`diagnose_report`: the stages, the rounds of candidates and the final model."""

    model: ReducedAxisModel
    reduced: ReducedAxisModel
    stages: list
    rounds: list
    data: Data
    time_s: float

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


def _theta_from(params: dict, poles: dict) -> np.ndarray:
    a2 = params["a2"]
    return np.array([
        math.log(poles["p_hz"] * TWO_PI), math.log(poles["omega_n_hz"] * TWO_PI), poles["zeta"],
        params["b2"] / a2, params["b1"] / a2, params["b0"] / a2, params["d0"] / a2, params["d1"] / a2,
    ])


def _params_from(z: np.ndarray) -> dict[str, float]:
    p, wn, zeta = math.exp(z[0]), math.exp(z[1]), z[2]
    a1, a2, a3 = denominator(p, wn, zeta)
    return {"a1": a1, "a2": a2, "a3": a3, "b2": z[3] * a2, "b1": z[4] * a2, "b0": z[5] * a2, "d0": z[6] * a2,
            "d1": z[7] * a2}


def refit(model: AugmentedAxisModel, data: Data, stop: int, *, max_nfev: int = 40) -> AugmentedAxisModel:
    """Joint output-error refit on samples ``[0, stop)`` of every continuous parameter.

    Reduced parameters as in :mod:`identification.output_error` (poles inside ``data.bounds``),
    the split form's plant viscous rate (as a share of a1) when an element is present, and every
    effect's :meth:`~identification.effects.Effect.free` parameters.
    """
    box = data.bounds.rad()
    poles = model.poles
    if not poles or not data.bounds.contains(poles, rtol=1e-6):
        poles = {"p_hz": min(max(poles.get("p_hz", 1.0), data.bounds.p_hz[0]), data.bounds.p_hz[1]),
                 "omega_n_hz": min(max(poles.get("omega_n_hz", 10.0), data.bounds.omega_n_hz[0]),
                                   data.bounds.omega_n_hz[1]),
                 "zeta": min(max(poles.get("zeta", 0.7), data.bounds.zeta[0]), data.bounds.zeta[1])}
    z0 = list(_theta_from(model.parameters, poles))
    lo: list[float] = [math.log(box[0][0]), math.log(box[1][0]), box[2][0]] + [-np.inf] * 5
    hi = [math.log(box[0][1]), math.log(box[1][1]), box[2][1]] + [np.inf] * 5
    structured = model.structured
    if structured:
        q = min(max(model.viscous_rate / model.parameters["a1"], 1e-5), 0.9)
        z0.append(math.log(q))
        lo.append(math.log(1e-5))
        hi.append(math.log(0.95))
    slices = []
    linear = [False] * len(z0)
    for e in model.elements:
        fr = e.free()
        slices.append((len(z0), len(fr)))
        for f in fr:
            z0.append(min(max(f.value, f.lo), f.hi))
            lo.append(f.lo)
            hi.append(f.hi)
            linear.append(f.linear)
    lo_a, hi_a = np.array(lo, float), np.array(hi, float)
    pad = 1e-9 * np.where(np.isfinite(hi_a - lo_a), hi_a - lo_a, 0.0)
    z0 = np.clip(np.array(z0, float), lo_a + pad, hi_a - pad)
    lin = np.array(linear, bool)
    xr, xm = data.xr, data.x[:stop]
    n = xr.size

    def build(z):
        params = _params_from(z)
        elements = [e.with_free(z[i:i + k]) if k else e for e, (i, k) in zip(model.elements, slices)]
        c = math.exp(z[8]) * params["a1"] if structured else 0.0
        return params, elements, c

    def fun(z):
        params, elements, c = build(z)
        m = AugmentedAxisModel(parameters=params, sample_time=data.T, elements=tuple(elements), viscous_rate=c,
                               poles={"p_hz": 1.0, "omega_n_hz": 1.0, "zeta": 1.0})
        y = simulate_augmented(params, xr, m.spec(n))[:stop]
        r = y - xm
        bad = ~np.isfinite(r)
        if bad.any():
            r[bad] = 10.0
        return r

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
                                               x_scale="jac", diff_step=1e-6, max_nfev=nfev, xtol=1e-10,
                                               ftol=1e-10)
        except ValueError:  # pragma: no cover - infeasible start after clipping
            return z
        if 2 * res.cost <= float(r0 @ r0):
            z = z.copy()
            z[idx] = res.x
        return z

    def linear_step(z):
        """Gauss-Newton step of the linear coefficients (forward-difference sensitivities, one
        simulation each), halved until it lowers the error."""
        idx = np.flatnonzero(lin)
        r0 = fun(z)
        cols = []
        for i in idx:
            step = 1e-3 * max(abs(z[i]), 1.0)
            zz = z.copy()
            zz[i] += step
            cols.append((fun(zz) - r0) / step)
        J = np.column_stack(cols)
        sc = np.linalg.norm(J, axis=0)
        sc[sc == 0] = 1.0
        delta = -np.linalg.lstsq(J / sc, r0, rcond=None)[0] / sc
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
    params, elements, c = build(z)
    return augment(model, elements, parameters=params, viscous_rate=c,
                   poles={"omega_n_hz": math.exp(z[1]) / TWO_PI, "zeta": float(z[2]), "p_hz": math.exp(z[0]) / TWO_PI})


# ------------------------------------------------------------------------------------ diagnose


def _errors(model: ReducedAxisModel, data: Data, start: int, stop: int) -> tuple[float, float]:
    y = model.simulate(data.xr)
    e = (data.x - y)[start:stop]
    if not np.all(np.isfinite(e)):
        return math.inf, math.inf
    return float(np.sqrt(np.mean(e * e)) * 1e3), float(np.max(np.abs(e)) * 1e3)


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
    """:func:`diagnose` with everything it found: stages, candidates per round, data split."""
    from identification.identify import check_capture

    t_start = time.perf_counter()
    opt = options or DiagnosisOptions()
    xr, x, T = check_capture(capture, axis)
    n = x.size
    ntr = int(round(opt.train_fraction * n))
    bounds = as_bounds(model.bounds or None, T)
    data = Data(xr=np.ascontiguousarray(xr, float), x=np.ascontiguousarray(x, float), T=T, ntr=ntr, bounds=bounds)
    base = augment(model, [])
    cur = refit(base, data, ntr, max_nfev=opt.max_nfev)
    vr, vm = _errors(cur, data, ntr, n)
    stages = [Stage(effect=None, train_model=cur, full_model=model, validation_rms_um=vr, validation_max_um=vm)]
    rounds: list[dict] = []
    for _ in range(opt.max_effects):
        present = {e.NAME for e in cur.elements}
        ctx = SearchContext(data, cur)
        cands: list[Candidate] = []
        for name in opt.effects:
            if name in present:
                continue
            try:
                cands.extend(SEARCHES[name](ctx))
            except (np.linalg.LinAlgError, ValueError, IdentificationError) as exc:
                log.info("search for %s failed: %s", name, exc)
        cands = [c for c in cands if math.isfinite(c.screen_rms_um)]
        cands.sort(key=lambda c: c.screen_rms_um)
        tried = []
        # only proposals whose screen shows evidence (a training-error drop of >= min_screen) are refitted
        cands_ev = [c for c in cands if c.screen_rms_um <= (1.0 - opt.min_screen) * ctx.train_rms_um]
        for c in cands_ev[: opt.top]:
            m = refit(c.start, data, ntr, max_nfev=opt.max_nfev)
            r_va, m_va = _errors(m, data, ntr, n)
            r_tr, _ = _errors(m, data, 0, ntr)
            tried.append((r_va, m_va, r_tr, m, c))
        log.info("round %d: %s", len(rounds) + 1, [(t[4].effect.NAME, round(t[0], 4)) for t in tried])
        rounds.append({
            "screened": {c.effect.NAME: round(c.screen_rms_um, 5) for c in cands},
            "equation_error_drop_pct": {c.effect.NAME: round(c.evidence["ee_rss_reduction_pct"], 3) for c in cands
                                        if "ee_rss_reduction_pct" in c.evidence},
            "refitted": {t[4].effect.NAME: {"validation_rms_um": round(t[0], 5),
                                            "identification_rms_um": round(t[2], 5)} for t in tried},
            "current_validation_rms_um": stages[-1].validation_rms_um,
            "current_identification_rms_um": ctx.train_rms_um,
        })
        if not tried:
            break
        prev = stages[-1].validation_rms_um
        chosen = None
        for r_va, m_va, r_tr, m, c in sorted(tried, key=lambda t: t[0]):
            gain = _gain(prev, r_va)
            ok = gain >= opt.min_gain and (prev - r_va) >= opt.min_gain_um and r_tr < ctx.train_rms_um
            nested = None
            if ok and c.effect.KIND == "element":
                # the element must beat its own null (the sampled split form without it), refitted
                null = refit(_null_of(m, c.effect.NAME), data, ntr, max_nfev=opt.max_nfev)
                r_null, _ = _errors(null, data, ntr, n)
                nested = _gain(r_null, r_va)
                ok = nested >= opt.min_gain and (r_null - r_va) >= opt.min_gain_um
                rounds[-1].setdefault("nested", {})[c.effect.NAME] = {"null_validation_rms_um": r_null,
                                                                     "gain_pct": 100.0 * nested}
            if ok:
                chosen = (r_va, m_va, m, c, gain, nested)
                break
        best_name = min(tried, key=lambda t: t[0])[4].effect.NAME
        rounds[-1]["best"] = best_name
        rounds[-1]["gain_pct"] = 100.0 * _gain(prev, min(t[0] for t in tried))
        rounds[-1]["accepted"] = chosen[3].effect.NAME if chosen else None
        if chosen is None:
            break
        r_va, m_va, m, c, gain, nested = chosen
        ev = dict(c.evidence)
        ev["validation_gain_pct"] = 100.0 * gain
        if nested is not None:
            ev["validation_gain_over_null_pct"] = 100.0 * nested
        ev["candidates_validation_rms_um"] = {t[4].effect.NAME: t[0] for t in sorted(tried, key=lambda t: t[0])}
        stages.append(Stage(effect=c.effect.NAME, train_model=m, full_model=None, validation_rms_um=r_va,
                            validation_max_um=m_va, evidence=ev))
        cur = m
    # identification-data errors: every stage refitted on all samples
    stages[0].identification_rms_um, stages[0].identification_max_um = _errors(model, data, 0, n)
    for s in stages[1:]:
        s.full_model = refit(s.train_model, data, n, max_nfev=opt.max_nfev)
        s.identification_rms_um, s.identification_max_um = _errors(s.full_model, data, 0, n)
    final = _final_model(model, stages, opt, data, rounds)
    return DiagnosisReport(model=final, reduced=model, stages=stages, rounds=rounds, data=data,
                           time_s=time.perf_counter() - t_start)


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
    if not any(e.KIND == "element" for e in rest):
        rest.append(Delay(samples=0, sample_time=model.sample_time))
    return augment(model, rest)


def _poles_on_bounds(model: ReducedAxisModel, data: Data) -> list[str]:
    out = []
    for k, (lo, hi) in data.bounds.as_dict().items():
        v = (model.poles or {}).get(k)
        if v is None:
            continue
        if v <= lo * (1 + 1e-6):
            out.append(f"{k} = {v:.4g} at its lower bound")
        elif v >= hi * (1 - 1e-6):
            out.append(f"{k} = {v:.4g} at its upper bound")
    return out


def _final_model(model: ReducedAxisModel, stages: list[Stage], opt: DiagnosisOptions, data: Data,
                 rounds: list[dict]) -> ReducedAxisModel:
    validation = {
        "rms_before_um": stages[0].validation_rms_um,
        "rms_after_um": stages[-1].validation_rms_um,
        "max_before_um": stages[0].validation_max_um,
        "max_after_um": stages[-1].validation_max_um,
        "split": f"first {opt.train_fraction:.0%} of the samples identify, the last {1 - opt.train_fraction:.0%} "
                 "validate (blocked in time)",
        "criterion": f"add the effect with the lowest held-out simulation RMS when it lowers it by >= "
                     f"{opt.min_gain:.0%} and >= {opt.min_gain_um} um and lowers the identification-block RMS",
        "samples": {"identification": data.ntr, "validation": data.n - data.ntr},
        "rounds": _jsonable(rounds),
    }
    # a reduced model whose poles sit on the search box is a structural warning (e.g. no integral
    # action, p -> 0, below the thesis' 0.2 Hz bound): effects found then may compensate for it
    on_bounds = _poles_on_bounds(model, data)
    if on_bounds:
        validation["warning"] = ("reduced-model poles on the bounds (" + ", ".join(on_bounds) + "): the reduced "
                                 "structure or the bounds do not fit these data; widen the bounds if the loop "
                                 "has no integral action (p -> 0)")
        log.warning("diagnosis: %s", validation["warning"])
    if len(stages) == 1:
        return dataclasses.replace(model, validation=validation, effects=[])
    last: AugmentedAxisModel = stages[-1].full_model  # type: ignore[assignment]
    records = []
    by_name = {e.NAME: e for e in last.elements}
    for prev, s in zip(stages[:-1], stages[1:]):
        e = by_name[s.effect]
        rec = e.record()
        if e.KIND == "element":
            rec["parameters"]["plant_viscous_rate_1_s"] = last.viscous_rate
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
            "evidence": _jsonable(s.evidence),
        })
        records.append(rec)
    fit = dict(model.fit)
    fit["reduced_model"] = {"rms_um": stages[0].identification_rms_um, "max_um": stages[0].identification_max_um,
                            "parameters": dict(model.parameters), "poles": dict(model.poles)}
    fit["rms_um"] = stages[-1].identification_rms_um
    fit["max_um"] = stages[-1].identification_max_um
    return augment(last, last.elements, axis=model.axis, method=model.method, fit=fit, effects=records,
                   validation=validation, bounds=dict(model.bounds))


def _jsonable(obj):
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, (np.floating, np.integer)):
        return obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def report_figure(capture: Capture, model: ReducedAxisModel, *, axis: str, ax=None):
    """Residual before (the reduced model) and after (``model``) vs time, velocity, position, spectrum.

    Works from a diagnosed model alone: the reduced model is rebuilt from
    ``model.fit["reduced_model"]`` (the model itself when nothing was added). Returns 4 Axes.
    """
    from identification.identify import check_capture
    from identification.residual import plot_before_after

    xr, x, T = check_capture(capture, axis)
    red = (model.fit or {}).get("reduced_model")
    before = model if not red else ReducedAxisModel(parameters=red["parameters"], sample_time=model.sample_time,
                                                    axis=model.axis)
    return plot_before_after(xr, x, T, before, model, ax=ax)


# ------------------------------------------------------------------------------ before/after table


def before_after_rows(model: ReducedAxisModel) -> list[dict[str, Any]]:
    """Rows of the before/after table from a diagnosed model's ``effects`` and ``validation``.

    One row for the reduced model, one per added effect (cumulative), the last being the final
    model; each with ``label``, ``identification_rms_um``, ``identification_max_um``,
    ``validation_rms_um``, ``validation_max_um``.
    """
    v = model.validation or {}
    effects = list(model.effects or [])
    if effects:
        first = effects[0]
        rows = [{"label": "reduced model", "identification_rms_um": first.get("rms_before_um"),
                 "identification_max_um": first.get("max_before_um"),
                 "validation_rms_um": first.get("validation_rms_before_um"),
                 "validation_max_um": first.get("validation_max_before_um")}]
    else:
        fit = model.fit or {}
        rows = [{"label": "reduced model", "identification_rms_um": fit.get("rms_um"),
                 "identification_max_um": fit.get("max_um"), "validation_rms_um": v.get("rms_before_um"),
                 "validation_max_um": v.get("max_before_um")}]
    for e in effects:
        rows.append({"label": f"+ {e['name']} ({e.get('summary', '')})",
                     "identification_rms_um": e.get("rms_after_um"), "identification_max_um": e.get("max_after_um"),
                     "validation_rms_um": e.get("validation_rms_after_um"),
                     "validation_max_um": e.get("validation_max_after_um")})
    rows.append(dict(rows[-1], label="final model"))
    return rows


def format_before_after(model: ReducedAxisModel) -> str:
    """Text table of :func:`before_after_rows` for the command line (errors in um)."""
    rows = before_after_rows(model)

    def f(x):
        return "      -" if x is None or not math.isfinite(float(x)) else f"{float(x):9.3f}"

    width = max(len(r["label"]) for r in rows)
    head = (f"{'model':<{width}}  {'ident RMS':>9}  {'ident max':>9}  {'valid RMS':>9}  {'valid max':>9}   [um]")
    lines = [head, "-" * len(head)]
    for r in rows:
        lines.append(f"{r['label']:<{width}}  {f(r['identification_rms_um'])}  {f(r['identification_max_um'])}  "
                     f"{f(r['validation_rms_um'])}  {f(r['validation_max_um'])}")
    v = model.validation or {}
    if v.get("split"):
        lines.append(f"validation: {v['split']}")
    if not model.effects:
        lines.append("diagnosis: no effect lowers the held-out error significantly; the reduced model stands")
    if v.get("warning"):
        lines.append(f"warning: {v['warning']}")
    return "\n".join(lines)
