"""Feed profiles along one segment: trapezoidal (closed form) and S-curve (ruckig).

A profile is a list of phases of constant path jerk; each phase has a duration and its state at
the start (path position, speed, acceleration), so the path position inside a phase is the
cubic ``p0 + v0 t + a0 t^2/2 + j t^3/6``. Both profiles share this form, which lets the sampler
evaluate any mix of them at once.
"""

from __future__ import annotations

import math

import numba
import numpy as np
import ruckig

from vcnc.core.errors import VcncError

__all__ = [
    "PROFILES",
    "trapezoid_phases",
    "scurve_phases",
    "trapezoid_reach",
    "scurve_reach",
    "reach_many",
    "reach_passes",
    "phase_states",
    "phase_clock",
    "trapezoid_duration",
]

#: Names accepted by ``interpolate(profile=...)``.
PROFILES: tuple[str, ...] = ("trapezoid", "scurve")

#: Relative amount by which the velocity, acceleration and jerk limits of a segment shrink when
#: ruckig raises on it at first (see ``_Ruckig.profile``) [-].
RUCKIG_RETRY_SHRINK: float = 1e-9


def trapezoid_duration(length: np.ndarray, v_max: np.ndarray, a_max: np.ndarray) -> np.ndarray:
    """Duration of rest-to-rest trapezoidal moves [s].

    ``T = L/V + V/A`` when the cruise speed is reached (``L >= V^2/A``), else ``2 sqrt(L/A)``.
    """
    L, V, A = np.asarray(length, float), np.asarray(v_max, float), np.asarray(a_max, float)
    return np.where(L >= V * V / A, L / V + V / A, 2.0 * np.sqrt(L / A))


def trapezoid_phases(
    length: np.ndarray, v0: np.ndarray, v1: np.ndarray, v_max: np.ndarray, a_max: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Time-optimal trapezoidal profiles, vectorised over segments.

    Parameters
    ----------
    length : ndarray, shape (n,)
        Segment length [mm] (> 0).
    v0, v1 : ndarray, shape (n,)
        Entry and exit speed [mm/s]; must satisfy ``|v1^2 - v0^2| <= 2 a_max L`` and
        ``v0, v1 <= v_max``.
    v_max, a_max : ndarray, shape (n,)
        Speed [mm/s] and acceleration [mm/s^2] bounds.

    Returns
    -------
    duration, p0, v0, a0, jerk : ndarray, shape (n, 3)
        Phases accelerate / cruise / decelerate: durations [s] and start states [mm, mm/s,
        mm/s^2]; jerk is zero.
    """
    L = np.asarray(length, float)
    v0 = np.asarray(v0, float)
    v1 = np.asarray(v1, float)
    V = np.asarray(v_max, float)
    A = np.asarray(a_max, float)
    vp = np.minimum(V, np.sqrt(np.maximum(A * L + 0.5 * (v0 * v0 + v1 * v1), 0.0)))
    vp = np.maximum(vp, np.maximum(v0, v1))
    t1 = (vp - v0) / A
    t3 = (vp - v1) / A
    s1 = 0.5 * (vp + v0) * t1
    s3 = 0.5 * (vp + v1) * t3
    with np.errstate(divide="ignore", invalid="ignore"):
        t2 = np.where(vp > 0, np.maximum(L - s1 - s3, 0.0) / vp, 0.0)
    n = len(L)
    dur = np.stack([t1, t2, t3], axis=1)
    p0 = np.stack([np.zeros(n), s1, s1 + vp * t2], axis=1)
    pv = np.stack([v0, vp, vp], axis=1)
    pa = np.stack([A, np.zeros(n), -A], axis=1)
    return dur, p0, pv, pa, np.zeros((n, 3))


def trapezoid_reach(v: float, length: float, a_max: float) -> float:
    """Largest speed reachable from ``v`` [mm/s] over ``length`` [mm] at ``a_max`` [mm/s^2]."""
    return math.sqrt(v * v + 2.0 * a_max * length)


def scurve_reach(v: float, length: float, a_max: float, j_max: float) -> float:
    """Largest speed reachable from ``v`` over ``length`` with zero acceleration at both ends.

    A jerk-limited speed change ``dv`` with zero end accelerations takes ``T = dv/A + A/J`` when
    ``dv >= A^2/J`` and ``T = 2 sqrt(dv/J)`` otherwise; its acceleration is symmetric in time,
    so it covers ``(v0 + v1) T / 2``. Solving for ``dv`` is a cubic (short change) or a quadratic
    (long change) in closed form.

    Parameters
    ----------
    v : float
        Start speed [mm/s] (>= 0).
    length : float
        [mm]
    a_max, j_max : float
        [mm/s^2], [mm/s^3]

    Returns
    -------
    float
        [mm/s]

    Notes
    -----
    Evaluated by the compiled kernel the look-ahead's passes run (:func:`reach_passes`), so that a speed
    computed here and one computed there agree to the bit.
    """
    return float(_reach(float(v), float(length), float(a_max), float(j_max), True, _POWERS))


@numba.njit(cache=True, nogil=True)
def _reach(v, length, a_max, j_max, jerk_limited, powers):  # pragma: no cover - compiled
    """:func:`scurve_reach` (``jerk_limited``; its closed form: the cubic of a short change ``x^3 + 2 v x - L
    sqrt(J) = 0`` with ``x = sqrt(dv)``, Cardano's root polished by two Newton steps, and the quadratic ``J dv^2 +
    (2 v J + A^2) dv + 2 v A^2 - 2 L A J = 0`` of a long change ``dv > A^2/J``) or :func:`trapezoid_reach`,
    compiled: the operations of the Python form it replaced, in its order (tests/interpolators/test_fast_kernels.py
    keeps that form). ``powers`` holds the exponents ``2, 3, 1/3`` as data, so that each power is the C library's
    ``pow`` as in Python (a constant exponent 2 would be compiled to ``x * x``)."""
    if not jerk_limited:
        return math.sqrt(v * v + 2.0 * a_max * length)
    if length <= 0:
        return v
    A, J = a_max, j_max
    dv_lim = A * A / J
    p, q = 2.0 * v, -length * math.sqrt(J)
    disc = (q / 2.0) ** powers[0] + (p / 3.0) ** powers[1]
    sd = math.sqrt(disc)
    x = math.copysign(abs(-q / 2.0 + sd) ** powers[2], -q / 2.0 + sd) + math.copysign(
        abs(-q / 2.0 - sd) ** powers[2], -q / 2.0 - sd
    )
    for _ in range(2):
        x -= (x * x * x + p * x + q) / (3.0 * x * x + p)
    dv = x * x
    if dv > dv_lim:
        b = 2.0 * v * J + A * A
        c = 2.0 * v * A * A - 2.0 * length * A * J
        dv = (-b + math.sqrt(b * b - 4.0 * J * c)) / (2.0 * J)
    return v + (0.0 if 0.0 > dv else dv)  # Python's max(dv, 0.0)


_POWERS = np.array([2.0, 3.0, 1.0 / 3.0])


@numba.njit(cache=True, nogil=True)
def _reach_many(v, length, a_max, j_max, jerk_limited, powers, out):  # pragma: no cover - compiled
    for i in range(v.shape[0]):
        out[i] = _reach(v[i], length[i], a_max[i], j_max[i], jerk_limited, powers)


def reach_many(v: np.ndarray, length: np.ndarray, a_max: np.ndarray, j_max: np.ndarray, *,
               jerk_limited: bool) -> np.ndarray:
    """:func:`scurve_reach` (``jerk_limited``) or :func:`trapezoid_reach` of each row, bit for bit (compiled)."""
    v, length, a_max, j_max = (np.ascontiguousarray(np.broadcast_to(np.asarray(x, dtype=float), np.shape(v)))
                               for x in (v, length, a_max, j_max))
    out = np.empty(len(v))
    _reach_many(v, length, a_max, j_max, bool(jerk_limited), _POWERS, out)
    return out


@numba.njit(cache=True, nogil=True)
def _passes(v, length, a_max, j_max, jerk_limited, powers):  # pragma: no cover - compiled
    n = length.shape[0]
    for k in range(n - 1, 0, -1):
        r = _reach(v[k + 1], length[k], a_max[k], j_max[k], jerk_limited, powers)
        if r < v[k]:  # Python's min(v, r)
            v[k] = r
    for k in range(1, n):
        r = _reach(v[k - 1], length[k - 1], a_max[k - 1], j_max[k - 1], jerk_limited, powers)
        if r < v[k]:
            v[k] = r


def reach_passes(v: np.ndarray, length: np.ndarray, a_max: np.ndarray, j_max: np.ndarray, *,
                 jerk_limited: bool) -> np.ndarray:
    """The speeds ``v`` (shape ``(n + 1,)``, at the ends of ``n`` segments) lowered, backwards then forwards, to
    what each segment can reach from the next (previous) one: ``v[k] = min(v[k], reach(v[k + 1], length[k],
    ...))`` for ``k = n - 1 .. 1``, then ``v[k] = min(v[k], reach(v[k - 1], length[k - 1], ...))`` for
    ``k = 1 .. n - 1``, ``reach`` being :func:`scurve_reach` (``jerk_limited``) or :func:`trapezoid_reach`; bit for
    bit the Python loops (compiled). Returns a new array."""
    out = np.array(v, dtype=float)
    _passes(out, np.ascontiguousarray(length, dtype=float), np.ascontiguousarray(a_max, dtype=float),
            np.ascontiguousarray(j_max, dtype=float), bool(jerk_limited), _POWERS)
    return out


@numba.njit(cache=True, nogil=True)
def _phase_states(t, phase, start, duration, p0, v0, a0, jerk, end_at, s, v, a):  # pragma: no cover - compiled
    for i in range(t.shape[0]):
        k = phase[i]
        d = duration[k]
        tau = t[i] - start[k]
        tau = tau if tau > 0.0 else 0.0  # np.clip(tau, 0, d): maximum, then minimum
        tau = tau if tau < d else d
        jj = jerk[k]
        aa = a0[k]
        vv = v0[k]
        s[i] = p0[k] + tau * (vv + tau * (0.5 * aa + tau * (jj / 6.0)))
        v[i] = vv + tau * (aa + 0.5 * jj * tau)
        a[i] = aa + jj * tau
        if tau >= d and end_at[k] == end_at[k]:
            s[i] = end_at[k]


def phase_states(t: np.ndarray, phase: np.ndarray, start: np.ndarray, duration: np.ndarray, p0: np.ndarray,
                 v0: np.ndarray, a0: np.ndarray, jerk: np.ndarray, end_at: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Path position, speed and acceleration at the times ``t`` inside their phases (index ``phase``), compiled.

    Each phase has a ``start`` time, a ``duration``, its start state (``p0``, ``v0``, ``a0``) and its ``jerk``;
    the time into the phase is clipped to ``0 .. duration``. A phase whose ``end_at`` is not NaN ends its segment:
    at (or past) its end the position is exactly ``end_at`` (the segment's length, no rounding residue).

    Returns
    -------
    s, v, a : ndarray, shape (n,)
        ``p0 + tau (v0 + tau (a0/2 + tau j/6))``, ``v0 + tau (a0 + j tau / 2)``, ``a0 + j tau`` [mm, mm/s, mm/s^2],
        operation by operation the array expressions of these formulas.
    """
    n = len(t)
    s, v, a = np.empty(n), np.empty(n), np.empty(n)
    start, duration, p0, v0, a0, jerk, end_at = (np.ascontiguousarray(x, dtype=float)
                                                 for x in (start, duration, p0, v0, a0, jerk, end_at))
    _phase_states(np.ascontiguousarray(t, dtype=float), np.ascontiguousarray(phase, dtype=np.int64), start, duration,
                  p0, v0, a0, jerk, end_at, s, v, a)
    return s, v, a


@numba.njit(cache=True, nogil=True)
def _phase_clock(chain, duration, chain_n0, Ts, n0, rel):  # pragma: no cover - compiled
    whole, frac, current = 0, 0.0, -1
    for i in range(chain.shape[0]):
        if chain[i] != current:  # a chain starts on its own whole sample
            current, whole, frac = chain[i], chain_n0[chain[i]], 0.0
        n0[i] = whole
        rel[i] = frac
        frac += duration[i]
        w = math.floor(frac / Ts)
        whole += w
        frac -= w * Ts
        if frac >= Ts:  # the floor's own rounding
            frac -= Ts
            whole += 1
        elif frac < 0.0:
            frac += Ts
            whole -= 1


def phase_clock(chain: np.ndarray, duration: np.ndarray, chain_n0: np.ndarray, Ts: float
                ) -> tuple[np.ndarray, np.ndarray]:
    """The start of each phase as a whole sample and a fraction of a sample after it, counted phase by phase.

    Parameters
    ----------
    chain : ndarray of int, shape (n,)
        The chain of each phase; the phases of a chain are consecutive, in time order.
    duration : ndarray, shape (n,)
        Phase durations [s].
    chain_n0 : ndarray of int
        The sample each chain starts on.
    Ts : float
        Sample time [s].

    Returns
    -------
    n0, rel : ndarray, shape (n,)
        Phase ``i`` starts ``rel[i]`` (``0 <= rel < Ts``) [s] after sample ``n0[i]``.

    Notes
    -----
    Each start is the one before plus that phase's duration, carried in whole samples (integers) and a fraction
    below ``Ts``: the rounding of a start is that of ``rel + duration`` (at most an ulp of the phase's own duration
    plus ``Ts``), whatever the time into the program or the chain. A sum of the durations from the program's start
    rounded each start by an ulp of the time into the program: 534 s into corpus program 0284 at Ts = 0.25 ms a
    phase started 5e-14 s off the end of the one before, 1.7e-11 deg of B at 360 deg/s, and the jerk by finite
    differences read 36002.4 for 36000 deg/s^3.
    """
    n = len(duration)
    n0, rel = np.empty(n, dtype=np.int64), np.empty(n)
    _phase_clock(np.ascontiguousarray(chain, dtype=np.int64), np.ascontiguousarray(duration, dtype=float),
                 np.ascontiguousarray(chain_n0, dtype=np.int64), float(Ts), n0, rel)
    return n0, rel


class _Ruckig:
    """One reusable 1-DoF ruckig instance (offline calculation)."""

    def __init__(self) -> None:
        self.otg = ruckig.Ruckig(1)
        self.inp = ruckig.InputParameter(1)
        self.traj = ruckig.Trajectory(1)
        self.inp.current_position = [0.0]
        self.inp.current_acceleration = [0.0]
        self.inp.target_acceleration = [0.0]
        self.inp.min_velocity = [0.0]

    def profile(self, L: float, v0: float, v1: float, V: float, A: float, J: float):
        """Duration [s] and ruckig profile of one segment.

        Ruckig 0.19 raises ``RuckigError`` ("error in step 1") on some inputs exactly at the border
        of two profile types (found by fuzzing: ``V = 2 A^2/J`` and ``L = 2 A^3/J^2`` at once, from
        limits scaled by a rotary axis); the segment is then planned once more with the limits
        :data:`RUCKIG_RETRY_SHRINK` smaller, which moves it off that border and keeps every limit. It raises too on
        a segment of some nm whose end speeds differ by their rounding (27 nm at 21.7 mm/s, the end speed a few
        1e-15 mm/s lower: found by fuzzing dense chords under the S-curve); such a segment is then planned at its
        start speed throughout (speeds within :data:`RUCKIG_RETRY_SHRINK` of each other).
        """
        try:
            res = self._calculate(L, v0, v1, V, A, J)
        except ruckig.RuckigError:
            k = 1.0 - RUCKIG_RETRY_SHRINK
            try:
                res = self._calculate(L, v0, v1, max(V * k, v0, v1), A * k, J * k)
            except ruckig.RuckigError:
                res = None
            if res is None and v0 != v1 and abs(v0 - v1) <= RUCKIG_RETRY_SHRINK * max(v0, v1):
                try:
                    res = self._calculate(L, v0, v0, V, A, J)
                except ruckig.RuckigError:
                    res = None
        if res not in (ruckig.Result.Working, ruckig.Result.Finished):
            raise VcncError(
                f"ruckig found no S-curve profile (result {res}) for length {L!r} mm, speeds {v0!r} -> {v1!r} mm/s, "
                f"limits v {V!r} mm/s, a {A!r} mm/s^2, j {J!r} mm/s^3"
            )
        prof = self.traj.profiles[0][0]
        if prof.brake.duration > 0 or prof.accel.duration > 0:  # pragma: no cover - states are within limits
            raise VcncError("ruckig returned a profile with a pre-phase; start state outside the limits")
        return self.traj.duration, prof

    def _calculate(self, L: float, v0: float, v1: float, V: float, A: float, J: float):
        inp = self.inp
        inp.current_velocity = [v0]
        inp.target_position = [L]
        inp.target_velocity = [v1]
        inp.max_velocity = [V]
        inp.max_acceleration = [A]
        inp.max_jerk = [J]
        return self.otg.calculate(inp, self.traj)


_RUCKIG: _Ruckig | None = None


def scurve_phases(
    length: np.ndarray, v0: np.ndarray, v1: np.ndarray, v_max: np.ndarray, a_max: np.ndarray, j_max: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Time-optimal jerk-limited profiles computed by ruckig, one per segment.

    Each segment is planned as a 1-DoF ruckig problem on its arc length: from position 0,
    speed ``v0``, acceleration 0 to position ``length``, speed ``v1``, acceleration 0, with
    ``0 <= v <= v_max``, ``|a| <= a_max``, ``|j| <= j_max``. The seven phases of ruckig's profile
    (``Trajectory.profiles``) are returned as they are.

    Returns
    -------
    duration, p0, v0, a0, jerk : ndarray, shape (n, 7)
        Phase durations [s], start states [mm, mm/s, mm/s^2] and jerks [mm/s^3].
    """
    global _RUCKIG
    if _RUCKIG is None:
        _RUCKIG = _Ruckig()
    rk = _RUCKIG
    n = len(length)
    dur = np.zeros((n, 7))
    p0 = np.zeros((n, 7))
    pv = np.zeros((n, 7))
    pa = np.zeros((n, 7))
    pj = np.zeros((n, 7))
    for i in range(n):
        _, prof = rk.profile(float(length[i]), float(v0[i]), float(v1[i]), float(v_max[i]), float(a_max[i]),
                             float(j_max[i]))
        dur[i] = prof.t
        pj[i] = prof.j
        p0[i] = prof.p[:7]
        pv[i] = prof.v[:7]
        pa[i] = prof.a[:7]
    return dur, p0, pv, pa, pj


def ruckig_duration(length: float, v0: float, v1: float, v_max: float, a_max: float, j_max: float) -> float:
    """Duration [s] ruckig computes for one segment (reference for tests)."""
    global _RUCKIG
    if _RUCKIG is None:
        _RUCKIG = _Ruckig()
    return _RUCKIG.profile(length, v0, v1, v_max, a_max, j_max)[0]
