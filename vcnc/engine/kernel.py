"""The compiled per-sample closed loop: one numba kernel for every controller, plant and option.

One call simulates one axis over all samples. Options are switched by entries of the parameter
vector (layout in :mod:`vcnc.engine.layout`), so a new machine never triggers a recompilation; the
compiled code is cached on disk (``cache=True``).

Per sample k (period Ts): the feedback y_k is formed (motor or table position, lead error,
drift, seeded Gaussian noise, encoder rounding) and recorded as the measured position, unless an
independent table scale is recorded instead (table position, its own noise draw, the same
rounding, no drift), the control law computes u_k, the computational
delay, DAC quantisation/range and amplifier limit act on it, and the plant advances over
[k Ts, (k+1) Ts) with u held (zero-order hold). The rigid plant is integrated exactly
(exponential solution between friction events, with the instants where the velocity reaches zero
located analytically and stiction decided there); the two-mass plant uses fine symplectic steps.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from vcnc.engine.layout import (
    BACKLASH,
    BETA_NEG,
    BETA_POS,
    CTRL_KIND,
    DAC_LSB,
    DAC_RANGE,
    DELAY,
    DPLANT_A,
    DPLANT_B,
    DPLANT_ORDER,
    DPLANT_SCALE,
    DRIFT_RATE,
    DRIFT_TAU,
    ENC_RES,
    FC_NEG,
    FC_POS,
    FEEDBACK_TABLE,
    FS_NEG,
    FS_POS,
    GAIN,
    LAW_LIMIT,
    LOAD_AMP,
    LOAD_CONST,
    LOAD_PERIOD,
    LOAD_PHASE,
    MEASURE_TABLE,
    NOISE_STD,
    PLANT_KIND,
    PP_FORCE,
    PP_PERIOD,
    PP_PHASE,
    PP_POS,
    RES_FRACTION,
    RES_OMEGA,
    RES_ZETA,
    SAMPLE_TIME,
    SAT,
    SUBSTEPS,
    V_STRIBECK,
)

__all__ = ["simulate_axis"]

_TWO_PI = 2.0 * math.pi


@numba.njit(cache=True)
def _phi(beta: float, t: float) -> tuple[float, float, float]:
    """exp(-beta t), (1 - exp(-beta t))/beta, (t - phi1)/beta with their beta -> 0 limits."""
    bt = beta * t
    if bt < 1e-4:
        e = 1.0 - bt + bt * bt / 2.0 - bt * bt * bt / 6.0
        p1 = t * (1.0 - bt / 2.0 + bt * bt / 6.0 - bt * bt * bt / 24.0)
        p2 = t * t * (0.5 - bt / 6.0 + bt * bt / 24.0 - bt * bt * bt / 120.0)
        return e, p1, p2
    e = math.exp(-bt)
    p1 = -math.expm1(-bt) / beta
    return e, p1, (t - p1) / beta


_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_MIX1 = np.uint64(0xBF58476D1CE4E5B9)
_MIX2 = np.uint64(0x94D049BB133111EB)
_S30 = np.uint64(30)
_S27 = np.uint64(27)
_S31 = np.uint64(31)
_S11 = np.uint64(11)
_TWO53 = 1.0 / 9007199254740992.0


@numba.njit(cache=True)
def _uniform(state: np.ndarray) -> float:
    """SplitMix64 step on ``state[0]``: a uniform number in (-1, 1)."""
    z = state[0] + _GOLDEN
    state[0] = z
    z = (z ^ (z >> _S30)) * _MIX1
    z = (z ^ (z >> _S27)) * _MIX2
    z = z ^ (z >> _S31)
    return float(z >> _S11) * _TWO53 * 2.0 - 1.0


@numba.njit(cache=True)
def _normal_pair(state: np.ndarray) -> tuple[float, float]:
    """Two independent standard normal numbers (Marsaglia's polar method)."""
    while True:
        a = _uniform(state)
        b = _uniform(state)
        q = a * a + b * b
        if 0.0 < q < 1.0:
            f = math.sqrt(-2.0 * math.log(q) / q)
            return a * f, b * f


@numba.njit(cache=True)
def _dry_friction(dirn, v, fcp, fcn, fsp, fsn, bp, bn, vs):
    """(dry friction level [V], viscous rate beta [1/s]) of a mass moving in direction ``dirn`` (+1/-1) at
    velocity ``v`` [mm/s]: the Coulomb level, raised towards the static one below the Stribeck velocity
    ``vs`` (``fc + (fs - fc) exp(-(v/vs)^2)``), and beta, both of that direction."""
    if dirn > 0.0:
        fc, fs, beta = fcp, fsp, bp
    else:
        fc, fs, beta = fcn, fsn, bn
    level = fc
    if vs > 0.0:
        r = v / vs
        level = fc + (fs - fc) * math.exp(-r * r)
    return level, beta


@numba.njit(cache=True)
def _load(t, xm, load_c, load_a, load_w, load_phase, pp_f, pp_period, pp_phase):
    """The load [V] on the motor at time ``t`` [s] and motor position ``xm`` [mm]: constant, time-periodic
    and position-periodic parts."""
    d = load_c
    if load_a != 0.0:
        d += load_a * math.sin(load_w * t + load_phase)
    if pp_f != 0.0:
        d += pp_f * math.sin(_TWO_PI * xm / pp_period + pp_phase)
    return d


@numba.njit(cache=True)
def _rigid_step(x, v, force, h, g, bp, bn, fcp, fcn, fsp, fsn, vs, ep, p1p, p2p, en, p1n, p2n):
    """Advance x' = v, v' = g (F - friction) - beta v over h; returns (x, v, dry friction [V])."""
    if v == 0.0:
        if force > fsp:
            dirn = 1.0
        elif force < -fsn:
            dirn = -1.0
        else:
            return x, 0.0, force  # stiction holds the applied force
    else:
        dirn = 1.0 if v > 0.0 else -1.0
    remaining = h
    fric = 0.0
    for seg in range(3):
        level, beta = _dry_friction(dirn, v, fcp, fcn, fsp, fsn, bp, bn, vs)
        a = g * (force - dirn * level)
        if seg == 0:
            fric = dirn * level
        if remaining == h:
            if dirn > 0.0:
                e, p1, p2 = ep, p1p, p2p
            else:
                e, p1, p2 = en, p1n, p2n
        else:
            e, p1, p2 = _phi(beta, remaining)
        v_end = v * e + a * p1
        if v_end * dirn > 0.0:
            return x + v * p1 + a * p2, v_end, fric
        # the velocity reaches zero inside the segment: locate the instant
        if a == 0.0:
            return x, 0.0, fric
        if beta > 0.0:
            arg = -beta * v / a
            tstar = math.log1p(arg) / beta if arg > -1.0 else remaining
        else:
            tstar = -v / a
        if tstar < 0.0:
            tstar = 0.0
        if tstar > remaining:
            tstar = remaining
        e2, q1, q2 = _phi(beta, tstar)
        x = x + v * q1 + a * q2
        v = 0.0
        remaining -= tstar
        if force > fsp and dirn < 0.0:
            dirn = 1.0
        elif force < -fsn and dirn > 0.0:
            dirn = -1.0
        else:
            return x, 0.0, fric
        if remaining <= 0.0:
            return x, 0.0, fric
    return x, v, fric


@numba.njit(cache=True, nogil=True)
def simulate_axis(
    ref: np.ndarray,
    vel: np.ndarray,
    acc: np.ndarray,
    P: np.ndarray,  # noqa: N803
    C: np.ndarray,  # noqa: N803
    x0: float,
    seed: int,
    out: np.ndarray,
) -> int:
    """Simulate one axis; fills ``out`` (N, 6) and returns -1, or the sample index of divergence.

    ``ref``, ``vel``, ``acc``: reference fed to the law [mm] (already pre-filtered), commanded
    velocity [mm/s] and acceleration [mm/s^2]. ``P``: plant/option vector, ``C``: law vector.
    ``x0``: initial position [mm] (at rest). Output columns: measured, table [mm], velocity [mm/s],
    applied control [V], dry friction [V], true position of the measured point [mm] (the measured
    signal without sensor noise, encoder quantisation and drift), and 1.0 where the control was at
    its limit (the actuator passed its limit value, or the law's anti-windup held a step back), else 0.
    """
    rng = np.empty(1, dtype=np.uint64)
    rng[0] = np.uint64(seed) * _GOLDEN
    spare = 0.0
    have_spare = False
    n = ref.shape[0]
    ts = P[SAMPLE_TIME]
    kind = int(P[CTRL_KIND])
    plant = int(P[PLANT_KIND])
    g = P[GAIN]
    bp = P[BETA_POS]
    bn = P[BETA_NEG]
    fcp = P[FC_POS]
    fcn = P[FC_NEG]
    fsp = P[FS_POS]
    fsn = P[FS_NEG]
    vs = P[V_STRIBECK]
    nsub = max(1, int(P[SUBSTEPS]))
    if plant == 1:
        nsub = max(nsub, int(math.ceil(ts * P[RES_OMEGA] / _TWO_PI * 40.0)))
    h = ts / nsub
    ep, p1p, p2p = _phi(bp, h)
    en, p1n, p2n = _phi(bn, h)
    backlash = P[BACKLASH]
    fb_table = P[FEEDBACK_TABLE] > 0.5
    meas_table = P[MEASURE_TABLE] > 0.5
    enc = P[ENC_RES]
    inv_enc = 1.0 / enc if enc > 0.0 else 0.0
    noise = P[NOISE_STD]
    drift_rate = P[DRIFT_RATE]
    drift_tau = P[DRIFT_TAU]
    lsb = P[DAC_LSB]
    inv_lsb = 1.0 / lsb if lsb > 0.0 else 0.0
    dac_range = P[DAC_RANGE]
    sat = P[SAT]
    # the actuator's limit (amplifier or DAC range), and the one the law's anti-windup knows
    act_limit = min(sat, dac_range) if dac_range > 0.0 else sat
    law_limit = P[LAW_LIMIT]
    delay = int(P[DELAY])
    pp_f = P[PP_FORCE]
    pp_x = P[PP_POS]
    pp_period = P[PP_PERIOD]
    pp_phase = P[PP_PHASE]
    load_c = P[LOAD_CONST]
    load_a = P[LOAD_AMP]
    load_w = _TWO_PI / P[LOAD_PERIOD] if P[LOAD_PERIOD] > 0.0 else 0.0
    load_phase = P[LOAD_PHASE]
    # two-mass constants (masses in V s^2/mm)
    m1 = 1.0
    m2 = 1.0
    kspring = 0.0
    cdamp = 0.0
    if plant == 1:
        mtot = 1.0 / g
        m1 = (1.0 - P[RES_FRACTION]) * mtot
        m2 = P[RES_FRACTION] * mtot
        mred = m1 * m2 / mtot
        kspring = P[RES_OMEGA] ** 2 * mred
        cdamp = 2.0 * P[RES_ZETA] * P[RES_OMEGA] * mred
    # discrete plant history (plant units)
    order = int(P[DPLANT_ORDER])
    dscale = P[DPLANT_SCALE]
    uh = np.zeros(9)
    yh = np.zeros(9)
    if plant == 2:
        for i in range(9):
            yh[i] = x0 / dscale

    # mechanical state
    xm = x0  # motor side (rigid body / motor mass)
    vm = 0.0
    xt2 = x0  # table mass (two-mass)
    vt2 = 0.0
    xplay = x0  # table after backlash
    # controller state
    y1 = 0.0
    y2 = 0.0
    e1 = 0.0
    e2 = 0.0
    integ = 0.0
    xh0 = x0
    xh1 = 0.0
    xh2 = 0.0
    uprev = 0.0
    buf = np.zeros(delay + 1)
    vfilt = C[7]

    for k in range(n):
        t = k * ts
        # ---------------------------------------------------------------- measurement
        if plant == 1:
            mech_table = xt2
            vel_table = vt2
        else:
            mech_table = xm
            vel_table = vm
        if backlash > 0.0:
            half = 0.5 * backlash
            if mech_table - xplay > half:
                xplay = mech_table - half
            elif mech_table - xplay < -half:
                xplay = mech_table + half
        else:
            xplay = mech_table
        table = xplay
        if pp_period > 0.0 and pp_x != 0.0:
            table += pp_x * math.sin(_TWO_PI * xm / pp_period + pp_phase)
        y = table if fb_table else xm
        if drift_rate != 0.0:
            if drift_tau > 0.0:
                y += drift_rate * drift_tau * (-math.expm1(-t / drift_tau))
            else:
                y += drift_rate * t
        ym = table
        if noise > 0.0:
            if meas_table:
                # two sensors: one pair per sample (feedback, scale)
                g1, g2 = _normal_pair(rng)
                y += noise * g1
                ym += noise * g2
            elif have_spare:
                y += noise * spare
                have_spare = False
            else:
                g1, spare = _normal_pair(rng)
                have_spare = True
                y += noise * g1
        if enc > 0.0:
            y = enc * math.floor(y * inv_enc + 0.5)
            ym = enc * math.floor(ym * inv_enc + 0.5)
        if not meas_table:
            ym = y
        if k == 0:
            y1 = y
            y2 = y
            e1 = ref[0] - y
            e2 = e1
        # ---------------------------------------------------------------- control law
        r = ref[k]
        vr = vel[k]
        ar = acc[k]
        e = r - y
        if vfilt > 0.5:
            vhat = (y - y2) / (2.0 * ts)
        else:
            vhat = (y - y1) / ts
        u = 0.0
        # the law's accumulator (integral, adapted disturbance, PDF sum) moves by step this sample;
        # its share of u is step_gain * step
        step = 0.0
        step_gain = 0.0
        if kind == 0:  # PID
            if vfilt > 0.5:
                de = (e - e2) / (2.0 * ts)
            else:
                de = (e - e1) / ts
            step = ts * e
            step_gain = C[1]
            u = C[0] * e + C[1] * (integ + step) + C[2] * de + C[3] * vr + C[4] * ar
        elif kind == 1:  # P-PI
            ev = C[0] * (e + C[3] * vr + C[4] * ar) - vhat
            step = ts * ev
            step_gain = C[1]
            u = C[2] * ev + C[1] * (integ + step)
        elif kind == 2:  # adaptive sliding mode (integ is the adapted disturbance d_hat)
            edot = vr - vhat
            s = C[0] * e + edot
            step = C[2] * ts * s
            step_gain = 1.0
            u = C[3] * (ar + C[0] * edot) + C[4] * vhat + C[1] * s + (integ + step)
        elif kind == 3:  # pole placement + Kalman filter
            b0 = C[3] * xh0 + C[4] * xh1 + C[5] * xh2 + C[12] * uprev
            b1 = C[6] * xh0 + C[7] * xh1 + C[8] * xh2 + C[13] * uprev
            b2 = C[9] * xh0 + C[10] * xh1 + C[11] * xh2 + C[14] * uprev
            innov = y - b0
            xh0 = b0 + C[15] * innov
            xh1 = b1 + C[16] * innov
            xh2 = b2 + C[17] * innov
            u = C[0] * (r - xh0) - C[1] * xh1 - C[2] * xh2
            # the observer is fed the control the actuator will pass (anti-windup: the law's
            # limit, inf without), not the demand beyond it
            uprev = min(max(u, -law_limit), law_limit)
        elif kind == 4:  # PDF
            step = C[0] * e
            step_gain = 1.0
            u = (integ + step) - C[1] * y
        if kind <= 2:
            if vr > 0.0:
                u += C[5]
            elif vr < 0.0:
                u -= C[6]
        # conditional integration (anti-windup): no step that drives a demand beyond the law's limit
        # further out; inf (no anti-windup) never holds a step back
        limited = 0.0
        if (u > law_limit or u < -law_limit) and step * u > 0.0:
            u -= step_gain * step
            limited = 1.0
        else:
            integ += step
        y2 = y1
        y1 = y
        e2 = e1
        e1 = e
        # ---------------------------------------------------------------- actuator
        if delay > 0:
            buf[k % (delay + 1)] = u
            u = buf[(k + 1) % (delay + 1)] if k >= delay else 0.0
        if lsb > 0.0:
            u = lsb * math.floor(u * inv_lsb + 0.5)
        if dac_range > 0.0:
            if u > dac_range:
                u = dac_range
            elif u < -dac_range:
                u = -dac_range
        if u > sat:
            u = sat
        elif u < -sat:
            u = -sat
        if u >= act_limit or u <= -act_limit:
            limited = 1.0
        out[k, 0] = ym
        out[k, 1] = table
        out[k, 2] = vel_table
        out[k, 3] = u
        out[k, 5] = table if (fb_table or meas_table) else xm
        # ---------------------------------------------------------------- plant
        fric_out = 0.0
        if plant == 0:
            for j in range(nsub):
                d = _load(t + j * h, xm, load_c, load_a, load_w, load_phase, pp_f, pp_period, pp_phase)
                xm, vm, fr = _rigid_step(
                    xm, vm, u - d, h, g, bp, bn, fcp, fcn, fsp, fsn, vs, ep, p1p, p2p, en, p1n, p2n
                )
                if j == 0:
                    fric_out = fr
        elif plant == 1:
            for j in range(nsub):
                d = _load(t + j * h, xm, load_c, load_a, load_w, load_phase, pp_f, pp_period, pp_phase)
                fsp_ = kspring * (xm - xt2) + cdamp * (vm - vt2)
                vm += h * (u - fsp_) / m1
                xm += h * vm
                net = fsp_ - d
                fr = 0.0
                if vt2 == 0.0:
                    if net > fsp:
                        dirn = 1.0
                    elif net < -fsn:
                        dirn = -1.0
                    else:
                        dirn = 0.0
                        fr = net
                else:
                    dirn = 1.0 if vt2 > 0.0 else -1.0
                if dirn != 0.0:
                    level, beta = _dry_friction(dirn, vt2, fcp, fcn, fsp, fsn, bp, bn, vs)
                    fr = dirn * level
                    vnew = vt2 + h * ((net - fr) / m2 - beta * vt2)
                    if vt2 != 0.0 and vnew * vt2 < 0.0:
                        vnew = 0.0
                    if vt2 == 0.0 and vnew * dirn < 0.0:
                        vnew = 0.0
                    vt2 = vnew
                xt2 += h * vt2
                if j == 0:
                    fric_out = fr
        else:
            # y_{k+1} = sum b_i u_{k+1-i} - sum a_i y_{k+1-i}; uh[0] = u_k, yh[0] = y_k
            for i in range(order - 1, 0, -1):
                uh[i] = uh[i - 1]
            uh[0] = u
            ynew = 0.0
            for i in range(order):
                ynew += P[DPLANT_B + i] * uh[i] - P[DPLANT_A + i] * yh[i]
            for i in range(order - 1, 0, -1):
                yh[i] = yh[i - 1]
            yh[0] = ynew
            xnew = ynew * dscale
            vm = (xnew - xm) / ts
            xm = xnew
        out[k, 4] = fric_out
        out[k, 6] = limited
        if not (abs(xm) < 1e9 and abs(vm) < 1e12):
            return k
    return -1
