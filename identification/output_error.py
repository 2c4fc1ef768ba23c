"""Output-error refinement (not in the thesis): fit the simulated, not the regressed, position.

The equation-error problem of Eq. (3.12) regresses x_k on measured derivatives, so differentiation
noise, the central-difference smearing of the acceleration steps at reversals and the friction
switching on *measured* velocity bias it. The refinement starts from that solution and minimises

    g = 1/2 sum_k (x_k - x_hat_k)^2,    x_hat = ReducedAxisModel.simulate(x_r)

(friction switching on the *predicted* velocity, as the model is used) over the eight parameters,
with the poles kept in the same bounds: variables (log p, log omega_n, zeta) in the box and
(beta_0, beta_1, beta_2, delta+, delta-) free, as in Eq. (3.10). Solved by a bounded trust-region
least squares (``scipy.optimize.least_squares``, ``trf``) with finite-difference Jacobians; each
residual is one compiled simulation of the capture (for a record logged slower than 1 ms, at sub-steps
between its samples: :mod:`identification.substeps`).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.optimize

from identification.bounds import PoleBounds
from identification.initial_state import fit_initial_state
from identification.parameters import from_search, search_box, to_search
from identification.poles import TWO_PI, canonical
from identification.substeps import substep_reference

__all__ = ["refine_output_error"]

#: Relative finite-difference steps of the descent (:func:`_descend`): the fine one first, then the
#: coarse one from its end, for a residual that the friction switching makes rough at the fine step.
FINE_STEP = 1e-7
COARSE_STEP = 1e-3
#: The fine descent counts as stalled where it started when it lowers the cost by less than this share [-].
STALLED = 1e-3


def refine_output_error(
    parameters: dict[str, float],
    poles: dict[str, float],
    reference: np.ndarray,
    measured: np.ndarray,
    sample_time: float,
    *,
    bounds: PoleBounds,
    max_nfev: int = 400,
    offset: bool = False,
    delay: tuple[float, float, float] | float | None = None,
    keep: slice | None = None,
    initial_state: bool = False,
    setpoint_filter: tuple[float, float, float] | None = None,
    coarse: bool = False,
) -> dict:
    """Refine a reduced model by output error (module docstring).

    Parameters
    ----------
    parameters, poles : dict
        Starting point (a1..d1; p_hz, omega_n_hz, zeta), e.g. the equation-error solution.
    reference, measured : ndarray
        x_r and x [mm].
    sample_time : float
        T [s].
    bounds : PoleBounds
        Pole box kept during the refinement.
    max_nfev : int
        Residual evaluations (simulations) allowed, Jacobian included.
    offset : bool
        Also fit a constant added to the prediction (a datum offset between the channels,
        :mod:`identification.datum_offset`), starting from 0.
    delay : (start, low, high) or float, optional
        Also fit the reference dead time [samples] within [low, high] (``reference`` is then the
        recorded one, delayed at each step on the sub-step grid of :mod:`identification.substeps`):
        the equation error's estimate trades the loop's own lag for a shift (fadal-ppi: 13.7
        samples), the simulated position does not. A number: the recorded reference delayed by
        that many samples, fixed.
    keep : slice, optional
        The samples the residual is taken on (all by default): the simulation starts at
        ``keep.start`` from rest.
    initial_state : bool
        Also fit the model's state at the first kept sample (a record that starts in motion,
        :mod:`identification.initial_state`), eliminated by linear least squares in each residual.
    setpoint_filter : (start, low, high), optional
        Also fit the length of a moving average on the (delayed) reference [samples] within
        [low, high] (:mod:`identification.setpoint_filter`).
    coarse : bool
        Always continue the descent with the coarse finite-difference step, not only when the fine one
        stalled where it started (:func:`_descend`).

    Returns
    -------
    dict
        ``parameters``, ``poles``, ``cost`` [mm^2], ``start_cost`` [mm^2], ``nfev``, ``message``,
        and ``offset_mm`` [mm] (0 unless ``offset``), ``delay_samples`` (the start unless ``delay``),
        ``filter_samples`` (0 unless ``setpoint_filter``).

    Notes
    -----
    With ``initial_state`` the result also has ``initial_state`` (the causal state [mm]) and
    ``start_response`` [mm] (its free response on the kept samples, to add to the simulation).
    """
    xr = np.ascontiguousarray(reference, float)
    xm = np.ascontiguousarray(measured, float)
    held = substep_reference(xr, sample_time)  # a slow record: predicted between its samples
    if delay is not None and not isinstance(delay, tuple):
        held, delay = held.delayed(float(delay)), None
    x0, typ, lo, hi = _search_start(parameters, poles, bounds, span=float(np.ptp(xr)), offset=offset, delay=delay,
                                    setpoint_filter=setpoint_filter)
    nv = x0.size - (1 if offset else 0) - (1 if delay is not None else 0) - (1 if setpoint_filter is not None else 0)
    i_delay = nv + (1 if offset else 0)
    i_filter = x0.size - 1
    fun = _Residual(held, xm, keep, sample_time, nv=nv, offset=offset, initial_state=initial_state,
                    i_delay=i_delay if delay is not None else None,
                    i_filter=i_filter if setpoint_filter is not None else None)
    r0 = fun(x0)
    start_cost = 0.5 * float(r0 @ r0)
    x, cost, nfev, message = _descend(fun, x0, start_cost, lo, hi, typ, max_nfev, coarse=coarse)
    params = from_search(x[:nv])
    start = {}
    if initial_state:
        r = fun.reference(x).simulate(params, fun.cut) - fun.measured + (x[nv] if offset else 0.0)
        state, response = fit_initial_state(params, sample_time, r)
        start = {"initial_state": state, "start_response": response}
    p, wn, z = canonical(math.exp(x[0]), math.exp(x[1]), float(x[2]), bounds)
    return {
        "parameters": params,
        "poles": {"omega_n_hz": wn / TWO_PI, "zeta": z, "p_hz": p / TWO_PI},
        "cost": cost,
        "start_cost": start_cost,
        "nfev": nfev,
        "message": message,
        "offset_mm": float(x[nv]) if offset else 0.0,
        "delay_samples": float(x[i_delay]) if delay is not None else 0.0,
        "filter_samples": float(x[i_filter]) if setpoint_filter is not None else 0.0,
        **start,
    }



def _descend(fun, x0: np.ndarray, start_cost: float, lo: np.ndarray, hi: np.ndarray, typ: np.ndarray,
             max_nfev: int, *, coarse: bool = False) -> tuple[np.ndarray, float, int, str]:
    """``(x, cost, residual evaluations, message)``: the trust-region descent from ``x0`` with the
    fine finite-difference step :data:`FINE_STEP`, then, when it stalled where it started (the cost
    lowered by less than :data:`STALLED`) within the ``max_nfev`` residual evaluations, again from its
    end with the coarse step :data:`COARSE_STEP` on what is left of them; the lower cost kept (``x0``
    when neither lowers it); with ``coarse`` the coarse descent follows whenever evaluations are left.
    A fine descent that moved is otherwise left as it was: on a hydraulic axis' record (eha 1_1)
    continued coarsely it ended in another basin, and the diagnosis then named a 32 Hz resonance it had
    not named before.

    The residual is not smooth at the fine step: the model's friction switches on the sign of its
    predicted velocity, and a step of 1e-7 moves switching instants by a sample here and there,
    jumps that swamp the gradient where the axis often stands still. On fadal-ppi running CAM
    program 0136 (160k samples) a change of a1 by 1e-7 of itself moves the RMS by 0.004 um, by
    1e-5 by 0.003 um: the fine descent stopped at once wherever it started (equation error 9.6 Hz /
    1.26 with p on 500 Hz at 3.55 um; the truth 36.3 Hz / 0.75, p 4.68 Hz at 3.48 um); with
    differences taken over 1e-3 of each variable it went on to 0.56 um from the first and 0.42 um
    from the second (38.9 Hz / 0.75, p 4.61 Hz).
    """
    best, cost, nfev, message = x0, start_cost, 0, ""
    for step in (FINE_STEP, COARSE_STEP):
        if nfev >= max_nfev or (not coarse and cost < (1.0 - STALLED) * start_cost):
            break
        res = scipy.optimize.least_squares(
            fun, best, bounds=(lo, hi), method="trf", x_scale=typ, diff_step=step, max_nfev=max_nfev - nfev,
            xtol=1e-12, ftol=1e-12,
        )
        nfev += int(res.nfev)
        message = message or str(res.message)
        if res.cost < cost:
            best, cost, message = res.x, float(res.cost), str(res.message)
    return best, cost, nfev, message


class _Residual:
    """The output-error residual of a search vector: the model's simulation on the (delayed, filtered)
    reference minus the measured position on the kept samples, plus the offset and the free response
    of the fitted initial state when those are searched."""

    def __init__(self, held, measured: np.ndarray, keep: slice | None, sample_time: float, *, nv: int,
                 offset: bool, initial_state: bool, i_delay: int | None, i_filter: int | None) -> None:
        self.held, self.sample_time, self.nv = held, sample_time, nv
        self.offset, self.initial_state, self.i_delay, self.i_filter = offset, initial_state, i_delay, i_filter
        self.cut = keep if keep is not None else slice(None)
        self.measured = measured[self.cut]

    def reference(self, x: np.ndarray):
        """The reference the loop receives at ``x``: delayed by its dead time, then filtered."""
        ref = self.held.delayed(x[self.i_delay]) if self.i_delay is not None else self.held
        return ref.filtered(max(x[self.i_filter], 0.0)) if self.i_filter is not None else ref

    def __call__(self, x: np.ndarray) -> np.ndarray:
        params = from_search(x[:self.nv])
        r = self.reference(x).simulate(params, self.cut) - self.measured
        if self.offset:
            r = r + x[self.nv]
        if self.initial_state and np.all(np.isfinite(r)):
            r = r + fit_initial_state(params, self.sample_time, r)[1]
        return r

def _search_start(parameters: dict[str, float], poles: dict[str, float], bounds: PoleBounds, *, span: float,
                  offset: bool, delay: tuple[float, float, float] | None,
                  setpoint_filter: tuple[float, float, float] | None = None):
    """``(x0, typical sizes, lower, upper)`` of :func:`refine_output_error`'s search: the model's variables
    (:func:`identification.parameters.to_search`), then the offset [mm] with ``offset``, then the dead time
    [samples] with ``delay``, then the setpoint filter's length [samples] with ``setpoint_filter``."""
    # start from the canonical labelling: with p the slowest of three real poles, the fast pair can
    # turn complex through zeta = 1; labelled otherwise, a fast real pole shares nothing with the
    # pair, and the search stalls where the two fast poles meet (31 % off on fadal-ppi's GA start)
    p0, w0, z0 = canonical(poles["p_hz"] * TWO_PI, poles["omega_n_hz"] * TWO_PI, poles["zeta"], bounds)
    x0 = to_search(parameters, p0, w0, z0)
    lo, hi = search_box(bounds)
    x0 = np.clip(x0, lo, hi)
    # typical sizes, so that finite-difference steps are meaningful for every variable
    typ = np.maximum(np.abs(x0), 1e-3 * np.max(np.abs(x0[3:6])) + 1e-12)
    typ[:3] = 1.0
    if offset:  # the constant [mm], scaled by the record's span
        x0 = np.append(x0, 0.0)
        typ = np.append(typ, 1e-3 * max(span, 1e-6))
        lo, hi = np.append(lo, -np.inf), np.append(hi, np.inf)
    if delay is not None:
        x0 = np.append(x0, float(np.clip(delay[0], delay[1], delay[2])))
        typ = np.append(typ, 1.0)
        lo, hi = np.append(lo, delay[1]), np.append(hi, delay[2])
    if setpoint_filter is not None:
        x0 = np.append(x0, float(np.clip(setpoint_filter[0], setpoint_filter[1], setpoint_filter[2])))
        typ = np.append(typ, 1.0)
        lo, hi = np.append(lo, setpoint_filter[1]), np.append(hi, setpoint_filter[2])
    return x0, typ, lo, hi
