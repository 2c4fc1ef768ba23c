"""The compiled loops of the identification models (numba), in one place: the reduced model's
exact sampled loop (Eq. 3.3 discretised, :mod:`identification.reduced_model`) with the diagnosis'
disturbance terms, and the split loop of an augmented model (a rigid or two-mass plant with
friction, backlash, delay and saturation, :mod:`identification.augmented`); and the moments of
the sinusoid columns a period search screens (:func:`sinusoid_moments`), and a Fourier series
evaluated without storing its basis (:func:`fourier_series`).

The helpers of the loops are inlined into them (``inline='always'``): numba otherwise compiles
them as calls, and on the long capture of ``benchmarks/diagnosis.py`` the split loop of a
two-mass plant with Stribeck friction took 1.94 ms instead of 1.49 ms (2026-11-23). Inlining
does not reorder any floating-point operation: the results are the same, bit for bit."""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["w_terms", "run_exact", "run_split", "sinusoid_moments", "fourier_series", "windowed_fourier_moments",
           "fourier_gram", "run_exact_tangent", "NO_STRIBECK", "NO_FOURIER",
           "SINCOS_MAX_PHASE"]


@numba.njit(cache=True, nogil=True, inline='always')
def w_terms(v, x, st, asym, pp_period, pp_coef):  # pragma: no cover - compiled
    """Disturbance terms of the diagnosis effects [mm/s^2] (identification.augmented) at model
    velocity v [mm/s] and position x [mm]: Stribeck ``st = (v_s, d+, d-)`` (v_s <= 0: none),
    asymmetric viscous ``asym |v|``, position-periodic Fourier series ``pp_coef[h] = (sin, cos)``
    of period ``pp_period`` (<= 0: none). All zero for the plain reduced model."""
    w = 0.0
    if st[0] > 0.0 and v != 0.0:
        # exp(-q) is exactly 0 from q = 746 on, where libm's underflow path costs 4x a normal exp
        r = v / st[0]
        q = r * r
        if q < 746.0:
            w += (st[1] if v > 0.0 else st[2]) * math.exp(-q)
    if asym != 0.0:
        w += asym * abs(v)
    if pp_period > 0.0:
        th = 2.0 * math.pi * x / pp_period
        for h in range(pp_coef.shape[0]):
            a = (h + 1) * th
            w += pp_coef[h, 0] * math.sin(a) + pp_coef[h, 1] * math.cos(a)
    return w


@numba.njit(cache=True, nogil=True)
def run_exact(phi, gamma, c, d, cv, dv, dvs, d0, d1, xr, wext, st, asym, pp_period, pp_coef,
              pos, vel):  # pragma: no cover - compiled
    """The exact sampled loop of the module docstring (deviations from xr[0]), with w_k extended
    by :func:`w_terms`. Fills ``pos`` and ``vel``; NaN from the sample where |x| exceeds 1e9 mm
    (a diverging candidate model) instead of overflowing."""
    r0 = xr[0]
    x0 = 0.0
    x1 = 0.0
    x2 = 0.0
    prev = 0.0
    for k in range(xr.shape[0]):
        r = xr[k] - r0
        p = (((c[0] * x0 + c[1] * x1) + c[2] * x2) + d * r) + r0
        pos[k] = p
        v = (((cv[0] * x0 + cv[1] * x1) + cv[2] * x2) + dv * r) + dvs * (r - prev)
        vel[k] = v
        if v > 0.0:
            f = d0
        elif v < 0.0:
            f = d1
        else:
            f = 0.0
        w = f + wext[k]
        w += w_terms(v, p, st, asym, pp_period, pp_coef)
        n0 = (((phi[0, 0] * x0 + phi[0, 1] * x1) + phi[0, 2] * x2) + gamma[0, 0] * r) + gamma[0, 1] * w
        n1 = (((phi[1, 0] * x0 + phi[1, 1] * x1) + phi[1, 2] * x2) + gamma[1, 0] * r) + gamma[1, 1] * w
        n2 = (((phi[2, 0] * x0 + phi[2, 1] * x1) + phi[2, 2] * x2) + gamma[2, 0] * r) + gamma[2, 1] * w
        x0, x1, x2 = n0, n1, n2
        prev = r
        if not abs(p) < 1e9:
            for j in range(k, xr.shape[0]):
                pos[j] = np.nan
                vel[j] = np.nan
            return


#: No Stribeck term (v_s <= 0) for the compiled friction terms.
NO_STRIBECK = np.zeros(3)
#: Empty position-periodic coefficient table (no Fourier terms) for the compiled friction terms.
NO_FOURIER = np.zeros((1, 2))


@numba.njit(cache=True, nogil=True)
def _rigid_coef(c, h):  # pragma: no cover - compiled
    """(e, p1, p2) of the exact step of x'' = acc - c x' over h: v' = e v + p1 acc, x' = x + p1 v + p2 acc."""
    ch = c * h
    if ch < 1e-6:
        return 1.0 - ch, h * (1.0 - 0.5 * ch), h * h * (0.5 - ch / 6.0)
    p1 = -math.expm1(-ch) / c
    return math.exp(-ch), p1, (h - p1) / c


@numba.njit(cache=True, nogil=True, inline='always')
def _rigid(x, v, acc, c, h):  # pragma: no cover - compiled
    """Exact step of x'' = acc - c x' over h (acc held)."""
    e, p1, p2 = _rigid_coef(c, h)
    return x + v * p1 + acc * p2, v * e + acc * p1


@numba.njit(cache=True, nogil=True, inline='always')
def _kinetic(v, d0, d1, st, asym):  # pragma: no cover - compiled
    """Friction while moving with velocity v != 0 [mm/s^2 of the whole mass]: Coulomb plus the
    velocity terms of :func:`w_terms` (Stribeck excess, asymmetric viscous)."""
    return (d0 if v > 0.0 else d1) + w_terms(v, 0.0, st, asym, 0.0, NO_FOURIER)


@numba.njit(cache=True, nogil=True, inline='always')
def _friction_step(x, v, force, mass, c, h, coef, d0, d1, st, asym, lo, hi):  # pragma: no cover - compiled
    """Step h of ``mass x'' = force - F - c x'`` with friction F that sticks (Karnopp).

    At rest the mass stays at rest while ``lo <= force <= hi`` (the static levels, Coulomb plus
    Stribeck excess); it breaks away against the static level; moving, F is the kinetic friction
    of its direction and a step that would reverse the velocity ends at rest. ``lo >= hi`` (no
    friction, or an identified friction without a stiction band) switches on sign(v) instead, 0
    at rest.
    ``coef`` is :func:`_rigid_coef` of (c / mass, h), computed once per run.
    """
    stick = lo < hi
    if v == 0.0:
        if not stick:
            f = 0.0
            dirn = 0.0
        elif force > hi:
            f = hi
            dirn = 1.0
        elif force < lo:
            f = lo
            dirn = -1.0
        else:
            return x, 0.0
    else:
        f = _kinetic(v, d0, d1, st, asym)
        dirn = 1.0 if v > 0.0 else -1.0
    a = (force - f) / mass
    x1 = x + v * coef[1] + a * coef[2]
    v1 = v * coef[0] + a * coef[1]
    if stick and v1 * dirn < 0.0 and v != 0.0:
        # the motion stops inside the step (at ts, linear estimate): stick there, or break away
        # against the static level for the rest of the step
        cm = c / mass
        ts = min(max(-v / (a - cm * v), 0.0), h)
        x1 = x + v * ts + 0.5 * (a - cm * v) * ts * ts
        if lo <= force <= hi:
            return x1, 0.0
        return _rigid(x1, 0.0, (force - (hi if force > hi else lo)) / mass, cm, h - ts)
    if stick and v1 * dirn < 0.0:
        v1 = 0.0
    return x1, v1


@numba.njit(cache=True, nogil=True, inline='always')
def _tm_slide(D, xm, vm, xt, vt, u, g):  # pragma: no cover - compiled
    """Exact step of the sliding two-mass plant: ``D = [Ad | Bd]`` (4 x 6), inputs (u, g)."""
    n0 = D[0, 0] * xm + D[0, 1] * vm + D[0, 2] * xt + D[0, 3] * vt + D[0, 4] * u + D[0, 5] * g
    n1 = D[1, 0] * xm + D[1, 1] * vm + D[1, 2] * xt + D[1, 3] * vt + D[1, 4] * u + D[1, 5] * g
    n2 = D[2, 0] * xm + D[2, 1] * vm + D[2, 2] * xt + D[2, 3] * vt + D[2, 4] * u + D[2, 5] * g
    n3 = D[3, 0] * xm + D[3, 1] * vm + D[3, 2] * xt + D[3, 3] * vt + D[3, 4] * u + D[3, 5] * g
    return n0, n1, n2, n3


@numba.njit(cache=True, nogil=True, inline='always')
def _tm_substep(D, S, kspr, cdmp, xm, vm, xt, vt, u, load, d0, d1, st, asym, lo, hi):  # pragma: no cover
    """One substep of the two-mass plant (exact linear steps ``D``, stuck table ``S``, both from
    :func:`identification.augmented.two_mass_matrices`) with the table's friction held over it:
    kinetic friction of its direction while it moves, stiction at rest (the table stays while the
    spring force less the load lies between the static levels ``lo`` and ``hi``, else breaks away
    against them); a step that would reverse a sticking table ends at rest."""
    stick = lo < hi
    if vt == 0.0:
        net = kspr * (xm - xt) + cdmp * vm - load
        if not stick:
            f = 0.0
            dirn = 0.0
        elif net > hi:
            f = hi
            dirn = 1.0
        elif net < lo:
            f = lo
            dirn = -1.0
        else:
            n0 = S[0, 0] * xm + S[0, 1] * vm + S[0, 2] * u + S[0, 3] * xt
            n1 = S[1, 0] * xm + S[1, 1] * vm + S[1, 2] * u + S[1, 3] * xt
            return n0, n1, xt, 0.0
    else:
        f = _kinetic(vt, d0, d1, st, asym)
        dirn = 1.0 if vt > 0.0 else -1.0
    xm, vm, xt, v1 = _tm_slide(D, xm, vm, xt, vt, u, f + load)
    if stick and v1 * dirn < 0.0:
        v1 = 0.0
    return xm, vm, xt, v1



@numba.njit(cache=True, nogil=True, inline='always')
def _play(mech, xb, half):  # pragma: no cover - compiled
    """Play operator: the load side ``xb`` follows the driven side ``mech`` within +/- ``half``."""
    if mech - xb > half:
        return mech - half
    if mech - xb < -half:
        return mech + half
    return xb


@numba.njit(cache=True, nogil=True, inline='always')
def _rest_start(x0, lo, hi, two_mass, meas_table, kspr):  # pragma: no cover - compiled
    """``(u0, xm, xt)``: the split form at rest at ``x0``. The law's output at the first sample holds the mass
    there, the level of the static band [lo, hi] nearest 0 (0 when the band holds it, as for Coulomb levels of
    opposite signs), and the delay line carries it; a u of 0 outside the band broke the mass away at the first
    sample by the band's offset, which the active samples do not see (a TNCscope trace at 3 ms: Coulomb levels
    480598 / 480487 mm/s^2, 850 um over the record). A two-mass plant's spring carries u0 from the motor to the
    stuck table, the measured mass at the reference (a spring unstretched moved the motor of a 60 Hz mode by
    85 um at the start under a load of 1 g)."""
    u0 = min(max(0.0, lo), hi) if lo < hi else 0.0
    xm = x0
    xt = x0
    if two_mass:
        if meas_table:
            xm += u0 / kspr
        else:
            xt -= u0 / kspr
    return u0, xm, xt


@numba.njit(cache=True, nogil=True)
def run_split(xr, T, m, a1, a2, a3, b0, b1, b2, cvis, d0, d1, wext, st, asym, pp_period, pp_coef,
              delay, umax, aw, lead, bl, res, tm, pos, vel):  # pragma: no cover - compiled
    """The sampled split form of the module docstring; the plant takes m steps per sample.

    ``aw`` (anti-windup of the saturation element, :class:`identification.effects.Saturation`):
    the law's accumulator ``a3 int(e) + a3 lead e + (b2 - a2) x_r`` does not take the step of a
    sample whose demand lies beyond ``umax`` when the step pushes it further out (conditional
    integration, as the machines' laws do: :class:`controllers.Controller`); the steps held back
    are summed in ``held`` and taken off the demand, so that a loop that never holds one back is
    the unclamped loop bit for bit. The demand is the law's own output, before the delay line, as
    in ``vcnc.engine.kernel``.

    The two-mass plant (``res[0] > 0``) steps exactly with the matrices ``tm`` of
    :func:`identification.augmented.two_mass_matrices` (a substep, the whole sample, the stuck
    table). A sample whose driven mass (the table of a two-mass plant, which must then have no play)
    slides on faster than the Stribeck range (``3 v_s``) at both its ends, with no asymmetric
    viscous or position-periodic term, is one exact step (friction is then constant over it and the
    motion monotone, so the m substeps would give the same result); any other sample takes the m
    substeps."""
    n = xr.shape[0]
    h = T / m
    kd = a1 - cvis
    ff = b2 - a2
    two_mass = res[0] > 0.0
    meas_table = res[3] > 0.5
    rr = res[2]
    kspr = 0.0
    cdmp = 0.0
    if two_mass:
        om = 2.0 * math.pi * res[0]
        kspr = om * om * rr * (1.0 - rr)
        cdmp = 2.0 * res[1] * om * rr * (1.0 - rr)
    # static friction levels (Coulomb plus the Stribeck excess at rest)
    lo = d1 + (st[2] if st[0] > 0.0 else 0.0)
    hi = d0 + (st[1] if st[0] > 0.0 else 0.0)
    no_st = np.zeros(3)
    coef = _rigid_coef(cvis, h)
    coef_whole = _rigid_coef(cvis, T)
    # whole-sample steps: only while friction is constant over the sample
    whole = asym == 0.0 and pp_period <= 0.0
    vguard = 3.0 * st[0] if st[0] > 0.0 else 0.0
    half = 0.5 * bl
    tm_sub, tm_whole, tm_stuck = tm[0], tm[1], tm[2]
    u0, xm, xt = _rest_start(xr[0], lo, hi, two_mass, meas_table, kspr)
    vm = 0.0
    vt = 0.0
    xb = xr[0]
    integ = (u0 - ff * xr[0]) / a3
    ubuf = np.full(delay + 1, u0)
    held = 0.0
    eprev = 0.0
    yprev = xr[0]
    rprev = xr[0]
    vrprev = 0.0
    for k in range(n):
        # ------------------------------------------------ measurement at the sample
        if two_mass and meas_table:
            y = xt
            vy = vt
        else:
            y = xm
            vy = vm
        if bl > 0.0:
            y = xb
            if abs((xm if not (two_mass and meas_table) else xt) - xb) < 0.5 * bl * (1.0 - 1e-12):
                vy = 0.0
        pos[k] = y
        vel[k] = vy
        # ------------------------------------------------ sampled controller (Eq. 3.3 split)
        e = xr[k] - y
        integ += T * e
        vr = (xr[k] - rprev) / T
        ar = (vr - vrprev) / T if k > 1 else 0.0
        u = b1 * vr - kd * (y - yprev) / T + a2 * e + a3 * integ + ff * xr[k] + b0 * ar - held
        if aw:
            step = a3 * (T * e + lead * (e - eprev)) + ff * (xr[k] - rprev)
            if (u > umax or u < -umax) and step * u > 0.0:
                held += step
                u -= step
            eprev = e
        yprev = y
        rprev = xr[k]
        vrprev = vr
        if delay > 0:
            ubuf[k % (delay + 1)] = u
            u = ubuf[(k + 1) % (delay + 1)] if k >= delay else u0
        if u > umax:
            u = umax
        elif u < -umax:
            u = -umax
        # ------------------------------------------------ plant over the sample (u held)
        steps = m
        if two_mass and whole and bl <= 0.0 and abs(vt) > vguard:
            n0, n1, n2, n3 = _tm_slide(tm_whole, xm, vm, xt, vt, u, _kinetic(vt, d0, d1, st, 0.0) + wext[k])
            if n3 * vt > 0.0 and abs(n3) > vguard:
                xm, vm, xt, vt = n0, n1, n2, n3
                steps = 0
        elif not two_mass and m > 1 and whole and abs(vm) > vguard:
            # the rigid mass slides on (its velocity is monotone over the step): the play operator
            # sees a monotone motion, so its end state is that of the m substeps
            x1, v1 = _friction_step(xm, vm, u - wext[k], 1.0, cvis, T, coef_whole, d0, d1, st, asym, lo, hi)
            if v1 * vm > 0.0 and abs(v1) > vguard:
                xm, vm = x1, v1
                steps = 0
                if bl > 0.0:
                    xb = _play(xm, xb, half)
        for _ in range(steps):
            # loads that are not friction: w_ext (held) and the position-periodic force
            load = wext[k]
            if pp_period > 0.0:
                load += w_terms(0.0, xt if two_mass else xm, no_st, 0.0, pp_period, pp_coef)
            if two_mass:
                xm, vm, xt, vt = _tm_substep(tm_sub, tm_stuck, kspr, cdmp, xm, vm, xt, vt, u, load, d0, d1, st, asym,
                                             lo, hi)
            else:
                xm, vm = _friction_step(xm, vm, u - load, 1.0, cvis, h, coef, d0, d1, st, asym, lo, hi)
            if bl > 0.0:
                xb = _play(xt if (two_mass and meas_table) else xm, xb, half)
        if not (abs(xm) < 1e9 and abs(vm) < 1e12):
            for q in range(k, n):
                pos[q] = np.nan
                vel[q] = np.nan
            return


# sin and cos of fdlibm (Sun Microsystems, 1993, freely distributable; netlib.org/fdlibm):
# Cody-Waite reduction by pi/2 in two parts (e_rem_pio2.c: PIO2_1 has 33 significant bits, so
# n * PIO2_1 is exact for |n| < 2^20) and the minimax polynomials of k_sin.c and k_cos.c on
# [-pi/4, pi/4]
_INVPIO2 = 6.36619772367581382433e-01
_PIO2_1 = 1.57079632673412561417e+00
_PIO2_1T = 6.07710050650619224932e-11
#: phases [rad] up to which the two-part reduction holds (|n| < 2^19, a margin of two)
SINCOS_MAX_PHASE = 8.0e5
_S1, _S2, _S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04
_S4, _S5, _S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10
_C1, _C2, _C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05
_C4, _C5, _C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11


@numba.njit(cache=True, nogil=True, inline='always')
def _sincos(v):  # pragma: no cover - compiled
    """(sin v, cos v) for |v| <= :data:`SINCOS_MAX_PHASE` without a libm call (module comment
    above): branch-free, so that a loop over samples vectorises; within 2.2e-16 of libm's values."""
    n = math.floor(v * _INVPIO2 + 0.5)
    r = (v - n * _PIO2_1) - n * _PIO2_1T
    z = r * r
    sp = r + r * z * (_S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6)))))
    cp = 1.0 - 0.5 * z + z * z * (_C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * _C6)))))
    q = int(n) & 3
    so = sp if (q & 1) == 0 else cp
    co = cp if (q & 1) == 0 else sp
    return (so if q < 2 else -so), (co if ((q + 1) & 2) == 0 else -co)


@numba.njit(cache=True, nogil=True)
def sinusoid_moments(scaled, periods, r, q_t):  # pragma: no cover - compiled
    """Moments of the columns ``sin(scaled / p)``, ``cos(scaled / p)`` for every period ``p``.

    ``scaled`` is ``2 pi`` times the coordinate (position [mm] or time [s]), ``r`` (n,) a residual,
    ``q_t`` (k, n) a basis, transposed and contiguous. Returns ``(m, qs, qc)``: ``m[j] = (s.s, s.c,
    c.c, r.s, r.c)`` of period j, ``qs[j] = q' s`` and ``qc[j] = q' c``. Per period the two columns
    are evaluated once into buffers and the moments taken by BLAS products: 400 periods over 16,000
    rows took 0.12 s, the batched products of stored columns 0.22 s; a single period 0.2 ms, where
    accumulating the ``q' s`` sums in the evaluation loop took 1.2 ms (2026-11-23). The sin and cos
    were most of it: libm's took 0.71 ms for 16,000 phases up to 12,000 rad, :func:`_sincos`
    (vectorised) 0.05 ms, within 1.1e-16 of them (2026-11-23, the 2-core development machine);
    phases beyond :data:`SINCOS_MAX_PHASE` take libm's.
    """
    n = scaled.shape[0]
    k = q_t.shape[0]
    npr = periods.shape[0]
    m = np.zeros((npr, 5))
    qs = np.zeros((npr, k))
    qc = np.zeros((npr, k))
    sv = np.empty(n)
    cv = np.empty(n)
    top = 0.0
    for i in range(n):
        top = max(top, abs(scaled[i]))
    for j in range(npr):
        p = periods[j]
        if top / abs(p) <= SINCOS_MAX_PHASE:
            for i in range(n):
                sv[i], cv[i] = _sincos(scaled[i] / p)
        else:
            for i in range(n):
                ph = scaled[i] / p
                sv[i] = math.sin(ph)
                cv[i] = math.cos(ph)
        m[j, 0] = np.dot(sv, sv)
        m[j, 1] = np.dot(sv, cv)
        m[j, 2] = np.dot(cv, cv)
        m[j, 3] = np.dot(r, sv)
        m[j, 4] = np.dot(r, cv)
        qs[j] = np.dot(q_t, sv)
        qc[j] = np.dot(q_t, cv)
    return m, qs, qc


@numba.njit(cache=True, nogil=True)
def fourier_series(s1, c1, coef):  # pragma: no cover - compiled
    """``sum_h coef[h, 0] sin(h p) + coef[h, 1] cos(h p)`` from ``s1 = sin(p)``, ``c1 = cos(p)``.

    The harmonics by the angle-addition recurrence of
    :func:`identification.effects._fourier.fourier_basis` (the same values, bit for bit), one
    harmonic at a time over all samples, never stored: a 64-harmonic load over 24,841 samples
    (EMPS) built a 25 MB basis and multiplied it for every simulation of a refit.
    """
    n = s1.shape[0]
    out = np.zeros(n)
    s = s1.copy()
    c = c1.copy()
    for h in range(coef.shape[0]):
        a = coef[h, 0]
        b = coef[h, 1]
        for k in range(n):
            out[k] += a * s[k] + b * c[k]
        if h + 1 < coef.shape[0]:
            for k in range(n):
                sk = s[k]
                ck = c[k]
                s[k] = sk * c1[k] + ck * s1[k]
                c[k] = ck * c1[k] - sk * s1[k]
    return out


@numba.njit(cache=True, nogil=True)
def windowed_fourier_moments(s1, c1, g, r, q_t, harmonics):  # pragma: no cover - compiled
    """Moments of the windowed Fourier columns ``g sin(h p)``, ``g cos(h p)``, h = 1..``harmonics``,
    without storing them (``s1 = sin p``, ``c1 = cos p``, ``g`` the window weight of each row).

    Returns ``(cs, ss, cr, qc)``: the trigonometric sums ``cs[k] = sum g^2 cos(k p)`` and
    ``ss[k] = sum g^2 sin(k p)`` for k = 0..2 ``harmonics`` (the Gram matrix of the columns follows
    from them by the product-to-sum identities: :func:`fourier_gram`), ``cr[j] = col_j . r`` and
    ``qc[:, j] = q_t col_j`` for the columns j in the order of
    :func:`identification.effects._fourier.fourier_basis` (sin, cos interleaved). The harmonics
    come from its angle-addition recurrence, started at h = 0 (so h = 1.. ``harmonics`` are the same
    values, bit for bit); O(n H) work instead of the O(n H^2) of the Gram of a stored basis.
    """
    n = s1.shape[0]
    k = q_t.shape[0]
    H = harmonics
    cs = np.zeros(2 * H + 1)
    ss = np.zeros(2 * H + 1)
    cr = np.zeros(2 * H)
    qc = np.zeros((k, 2 * H))
    s = np.zeros(n)
    c = np.ones(n)
    g2 = g * g
    gs = np.empty(n)
    gc = np.empty(n)
    for h in range(2 * H + 1):
        cs[h] = np.dot(g2, c)
        ss[h] = np.dot(g2, s)
        if 1 <= h <= H:
            for i in range(n):
                gs[i] = g[i] * s[i]
                gc[i] = g[i] * c[i]
            cr[2 * h - 2] = np.dot(gs, r)
            cr[2 * h - 1] = np.dot(gc, r)
            qc[:, 2 * h - 2] = np.dot(q_t, gs)
            qc[:, 2 * h - 1] = np.dot(q_t, gc)
        if h < 2 * H:
            for i in range(n):
                si = s[i]
                ci = c[i]
                s[i] = si * c1[i] + ci * s1[i]
                c[i] = ci * c1[i] - si * s1[i]
    return cs, ss, cr, qc


@numba.njit(cache=True, nogil=True)
def fourier_gram(cs, ss, harmonics):  # pragma: no cover - compiled
    """Gram matrix of the columns of :func:`windowed_fourier_moments` from its sums ``cs``, ``ss``:
    ``sin(a) sin(b) = (cos(a - b) - cos(a + b)) / 2``, ``cos(a) cos(b) = (cos(a - b) + cos(a + b)) / 2``,
    ``sin(a) cos(b) = (sin(a + b) + sin(a - b)) / 2``."""
    H = harmonics
    G = np.empty((2 * H, 2 * H))
    for h in range(1, H + 1):
        for m in range(1, H + 1):
            d = abs(h - m)
            sg = 1.0 if h >= m else -1.0
            G[2 * h - 2, 2 * m - 2] = 0.5 * (cs[d] - cs[h + m])
            G[2 * h - 1, 2 * m - 1] = 0.5 * (cs[d] + cs[h + m])
            G[2 * h - 2, 2 * m - 1] = 0.5 * (ss[h + m] + sg * ss[d])
            G[2 * h - 1, 2 * m - 2] = 0.5 * (ss[h + m] - sg * ss[d])
    return G


@numba.njit(cache=True, nogil=True, inline='always')
def _w_slopes(v, x, st, asym, pp_period, pp_coef):  # pragma: no cover - compiled
    """(dw/dv [1/s], dw/dx [1/s^2]) of :func:`w_terms` at (v, x); the Coulomb levels' jump at v = 0
    has no slope."""
    dv = 0.0
    dx = 0.0
    if st[0] > 0.0 and v != 0.0:
        r = v / st[0]
        q = r * r
        if q < 746.0:
            dv += (st[1] if v > 0.0 else st[2]) * math.exp(-q) * (-2.0 * r / st[0])
    if asym != 0.0:
        dv += asym if v > 0.0 else (-asym if v < 0.0 else 0.0)
    if pp_period > 0.0:
        k = 2.0 * math.pi / pp_period
        th = k * x
        for h in range(pp_coef.shape[0]):
            a = (h + 1) * th
            dx += (h + 1) * k * (pp_coef[h, 0] * math.cos(a) - pp_coef[h, 1] * math.sin(a))
    return dv, dx


@numba.njit(cache=True, nogil=True)
def run_exact_tangent(phi, gamma, c, cv, pos, vel, st, asym, pp_period, pp_coef, u):  # pragma: no cover
    """Sensitivities of :func:`run_exact`'s position to the disturbance inputs ``u`` added to
    ``wext``, along its trajectory ``pos``, ``vel`` (the tangent-linear loop: the state is linear in
    w, and w depends on the state through :func:`w_terms`, whose slopes :func:`_w_slopes` are taken
    at the trajectory; the Coulomb levels switch where the trajectory's velocity changes sign).
    ``u`` is (n, m), one input per column; returns (n, m): d pos[k] / d (scale of u[:, j]). All m
    inputs go through the loop together, the inner loop over them contiguous."""
    n = u.shape[0]
    m = u.shape[1]
    out = np.empty((n, m))
    s0 = np.zeros(m)
    s1 = np.zeros(m)
    s2 = np.zeros(m)
    for k in range(n):
        dv, dx = _w_slopes(vel[k], pos[k], st, asym, pp_period, pp_coef)
        for j in range(m):
            x0 = s0[j]
            x1 = s1[j]
            x2 = s2[j]
            p = (c[0] * x0 + c[1] * x1) + c[2] * x2
            out[k, j] = p
            w = u[k, j] + dv * ((cv[0] * x0 + cv[1] * x1) + cv[2] * x2) + dx * p
            s0[j] = ((phi[0, 0] * x0 + phi[0, 1] * x1) + phi[0, 2] * x2) + gamma[0, 1] * w
            s1[j] = ((phi[1, 0] * x0 + phi[1, 1] * x1) + phi[1, 2] * x2) + gamma[1, 1] * w
            s2[j] = ((phi[2, 0] * x0 + phi[2, 1] * x1) + phi[2, 2] * x2) + gamma[2, 1] * w
    return out


@numba.njit(cache=True, nogil=True)
def moving_average(xr, samples, out):  # pragma: no cover - compiled
    """The mean of ``xr`` (linear between samples, its first value held before it) over the
    ``samples`` (> 0, whole and fractional) before each sample, into ``out``, taken on the
    deviations from ``xr[0]`` (a reference at rest stays exactly there)
    (:mod:`identification.setpoint_filter`, whose order of operations the FMU repeats)."""
    n = int(math.floor(samples))
    f = samples - n
    x0 = xr[0]
    for k in range(xr.shape[0]):
        s = 0.0
        for i in range(k - n, k):
            lo = xr[i] - x0 if i > 0 else 0.0
            hi = xr[i + 1] - x0 if i + 1 > 0 else 0.0
            s += (lo + hi) * 0.5
        if f > 0.0:
            j = k - n - 1
            lo = xr[j] - x0 if j > 0 else 0.0
            hi = xr[j + 1] - x0 if j + 1 > 0 else 0.0
            mid = (hi - lo) * (1.0 - f) + lo
            s += f * (hi + mid) * 0.5
        out[k] = s / samples + x0
