"""FK free contour programming for the independent Heidenhain reference (:mod:`reference_heidenhain`).

Test code only, imports nothing of the readers. Written from the iTNC 530 user's manual, section 6.6
"Path Contours - FK Free Contour Programming" (the data of FL/FLT/FC/FCT, FPOL, relative data ``RX n``
etc., ``CLSD+``/``CLSD-``, ``PAR n``, auxiliary points ``P1X..`` and ``PDX PDY D``, ``FSELECT n``) and the
TNC 370 user's manual, section 5.6, as a different formulation from the reader's: every datum of an element is an
equation in the element's Cartesian unknowns (the end point E of a line; the centre C and end point E of an arc),
solved numerically (MINPACK's Levenberg-Marquardt, ``scipy.optimize.leastsq``, from a fixed list of starting
points: a Halton sequence and seeded random ones) instead of intersecting lines and circles in closed form (the reader's
single elements) or walking start directions, sizes and sweeps with Newton's method (the reader's open stretches).
An element with fewer equations than unknowns (a line without its length, an arc without its end) is solved
together with the FK elements after it, the unknowns of all in one system; the leading elements whose unknowns the
null space of the Jacobian at a solution leaves untouched are fixed, with one solution per distinct way (several:
FSELECT picks among them, the rest of the chain waits). Every such decision (the rank, the null space, a residual a
root, two roots one) is taken on a clear gap between two thresholds, never on one: a value between fails with an
error naming it (so a rounding difference, as of BLAS threads or memory alignment, cannot flip a result unseen).
Conventions shared with the reader (its docstring): the
solutions are numbered by the lengths of their elements in turn, equal lengths by the direction they leave the
start in (counter-clockwise from +X); ``DR+`` is counter-clockwise; ``AN`` of an arc is the tangent at its start;
``LEN`` of an arc its chord; ``CCA`` its centre angle; ``D`` the distance from the line's extension or from the
circle; an arc of a joined chain is no full circle unless its data name its end. The working plane is XY (the
reference runs tool axis Z only)."""

from __future__ import annotations

import math
import re
import warnings

import numpy as np
from scipy.optimize import least_squares, leastsq
from scipy.stats import norm, qmc

from tests.interpolators.reference_iso import ReferenceError

__all__ = ["FkReference"]

_TOKEN = re.compile(r"\s*(R[LR0](?![\d.])|[A-Z]+(?:[123][XY])?)\s*([-+]?\s*(?:Q\d+|\d+\.?\d*|\.\d+)|[-+])?")
_REFS = re.compile(r"R(CC)?(X|Y|PR|PA)|RAN|PAR")


def _unit(deg: float) -> np.ndarray:
    return np.array([math.cos(math.radians(deg)), math.sin(math.radians(deg))])


def _cross(a, b) -> float:
    return a[0] * b[1] - a[1] * b[0]


def _angle(v) -> float:
    return math.degrees(math.atan2(v[1], v[0]))


# relative singular values of a Jacobian: at most _ZERO is none (a degenerate direction: ~1e-10 or below, the central
# differences' own error), at least _NONZERO is one; between, the rank is ambiguous and the caller tries another
# solution or fails naming the value (never a silent flip on a rounding difference)
_ZERO, _NONZERO = 1e-9, 1e-6
_STARTS = 128  # every solve tries them all: 64 of a Halton sequence, 64 seeded random


def _starts(n: int, size: float, centre: np.ndarray) -> np.ndarray:
    """The starting points of a solve: normal about ``centre`` (scale ``size``), the first half from the (unscrambled)
    Halton sequence through the normal quantile, the second half seeded random: the same list on every run."""
    halton = qmc.Halton(d=n, scramble=False)
    halton.fast_forward(1)  # its first point is 0, the quantile of which is infinite
    grid = norm.ppf(halton.random(_STARTS // 2))
    rand = np.random.default_rng(7).normal(size=(_STARTS - _STARTS // 2, n))
    return centre + size * np.vstack([grid, rand])


def _residual_root(residual: float, size: float) -> bool | None:
    """A polished point is a root where its largest residual is at most 1e-8 ``size``, none where at least 1e-6
    ``size`` (a local minimum of the squares, or a start stopped short), None between: the caller fails naming it
    where it would be a new root (at a known root it is one more start reaching that root)."""
    if residual <= 1e-8 * size:
        return True
    return False if residual >= 1e-6 * size else None


def _distinct(x: np.ndarray, roots: list, size: float, line: int) -> bool:
    """``x`` is a new root: farther than 1e-4 ``size`` from every known root (at most 1e-6 ``size`` is a known one;
    between, an error naming the distance)."""
    d = min((float(np.max(np.abs(x - r))) for r in roots), default=math.inf)
    if d <= 1e-6 * size:
        return False
    if d >= 1e-4 * size:
        return True
    raise ReferenceError(f"FK element of line {line}: two roots {d:.1e} apart (size {size:g}), between one root "
                         "(1e-6 size) and two (1e-4 size)")


def _rank(jac: np.ndarray) -> tuple[int | None, np.ndarray]:
    """(rank, V^T) of ``jac`` by its singular values relative to the largest (or 1): those of at least _NONZERO
    count, those of at most _ZERO do not; rank None where one lies between."""
    _, sv, vt = np.linalg.svd(jac)
    rel = sv / max(1.0, sv.max(initial=0.0))
    if np.any((rel > _ZERO) & (rel < _NONZERO)):
        return None, vt
    return int(np.sum(rel >= _NONZERO)), vt


def _jacobian(fun, z) -> np.ndarray:
    """Central differences of ``fun`` at ``z`` (rows: residuals, columns: unknowns)."""
    cols = []
    for k in range(len(z)):
        dz = np.zeros(len(z))
        dz[k] = 1e-6
        cols.append((fun(z + dz) - fun(z - dz)) / 2e-6)
    return np.array(cols).T


class _Element:
    """An FK block's data: ``kw``, values ``v`` [mm, deg], block references ``refs``, ``dr`` (None, '+', '-')."""

    def __init__(self, kw: str, words: dict, refs: dict, line: int, number: int | None, closing: bool):
        self.kw, self.v, self.refs, self.line, self.number = kw, words, refs, line, number
        self.dr = words.get("DR")
        self.closing = closing
        self.closed_at = None  # where a closing element ends, set by the walk of its chain
        self.known: dict = {}  # the elements its relative data may name: resolved, or before it in its chain
        self.arc = kw in ("FC", "FCT")
        self.n = 4 if self.arc else 2  # unknowns: (C, E) of an arc, E of a line


class FkReference:
    """The FK state of the reference's run (all in program coordinates of XY [mm])."""

    def __init__(self) -> None:
        self.pole: np.ndarray | None = None
        self.ends: dict[int, tuple] = {}  # block number -> (start, end, centre or None, ccw)
        self.closed: np.ndarray | None = None
        self.waiting: tuple | None = None  # (element, S, T, solutions or None: open)
        self.last_direction: np.ndarray | None = None  # at the end of the last element emitted

    def parse(self, kw: str, rest: str, q: dict, scale: float, val) -> tuple[dict, dict]:
        words, refs, pos = {}, {}, 0
        rest = rest.strip()
        while pos < len(rest):
            m = _TOKEN.match(rest, pos)
            if m is None or m.end() == pos:
                raise ReferenceError(f"FK word at {rest[pos:]!r}")
            pos = m.end()
            key, value = m.group(1), (m.group(2) or "").replace(" ", "")
            if key in ("DR", "CLSD"):
                words[key] = value
            elif key in ("RL", "RR", "R0"):
                words[key] = ""
            elif key == "M":
                words.setdefault("M", []).append(int(value))
            elif _REFS.fullmatch(key):
                refs[key] = int(val(value, q))
            elif key in ("F",):
                words[key] = val(value, q)
            else:
                words[key] = val(value, q) * (1.0 if key in ("AN", "IAN", "PA", "IPA", "CCPA", "ICCPA", "CCA")
                                              else scale)
        return words, refs

    # --- equations ----------------------------------------------------------------------------------
    def _ref_end(self, el: _Element, key: str, start):
        return np.array(el.known[el.refs[key]][1]) if key in el.refs else start

    def equations(self, el: _Element, s, t, z) -> list:
        """The residuals of ``el``'s data with unknowns ``z`` (E, or C then E), start ``s``, tangent ``t``."""
        e = z[-2:]
        res = self._point_equations(el, s, e, "")
        if el.closing:
            res += [e[0] - el.closed_at[0], e[1] - el.closed_at[1]]
        res += self._arc_equations(el, s, t, z) if el.arc else self._line_equations(el, s, t, e)
        return res

    def _point_equations(self, el: _Element, s, point, prefix: str) -> list:
        """The residuals of the data fixing one point of ``el`` (``prefix`` "": its end X Y IX IY PR PA IPR IPA;
        "CC": its centre CCX .. ICCPA), start ``s``, incremental data from the block ``R..`` names (else ``s``)."""
        v, res = el.v, []
        for i, ax in enumerate("XY"):
            key = prefix + ax
            if key in v:
                res.append(point[i] - v[key])
            if "I" + key in v:
                res.append(point[i] - self._ref_end(el, "R" + key, s)[i] - v["I" + key])
        pr, pa = prefix + "PR", prefix + "PA"
        if pr in v or "I" + pr in v:
            base = self._ref_end(el, "R" + pr, s)
            r = v[pr] if pr in v else math.hypot(*(base - self.pole)) + v["I" + pr]
            res.append(math.hypot(*(point - self.pole)) - r)
        if pa in v or "I" + pa in v:
            res.append(_cross(_unit(self._polar_angle(el, s, prefix)), point - self.pole))
        return res

    def _line_equations(self, el: _Element, s, t, e) -> list:
        v, res = el.v, []
        if "LEN" in v:
            res.append(math.hypot(*(e - s)) - abs(v["LEN"]))
        res += [_cross(d, e - s) for d, _ in self._line_directions(el, s, t)]
        if "D" in v:  # the auxiliary point PDX PDY at the distance D from the line (its extension)
            p = np.array([v["PDX"], v["PDY"]])
            res.append((_cross(e - s, p - s) / math.hypot(*(e - s))) ** 2 - v["D"] ** 2)
        return res

    def _line_directions(self, el: _Element, s, t) -> list[tuple[np.ndarray, bool]]:
        """(direction, the end must lie ahead along it) of each datum naming the line's direction."""
        v, out = el.v, []
        if el.kw == "FLT":
            out.append((t, True))
        if "AN" in v:
            out.append((_unit(v["AN"]), True))
        if "IAN" in v:
            base = t if "RAN" not in el.refs else self._direction(el.known[el.refs["RAN"]])
            out.append((_unit(_angle(base) + v["IAN"]), True))
        if "PAR" in el.refs:
            out.append((self._direction(el.known[el.refs["PAR"]]), False))
        for p in ("P1", "P2"):
            if p + "X" in v:
                d = np.array([v[p + "X"], v[p + "Y"]]) - s
                out.append((d / math.hypot(*d), False))
        return out

    def _arc_equations(self, el: _Element, s, t, z) -> list:
        v, c, e = el.v, z[:2], z[2:]
        r = math.hypot(*(s - c))
        res = [math.hypot(*(e - c)) - r]
        if "R" in v:
            res.append(r - abs(v["R"]))
        res += self._point_equations(el, s, c, "CC")
        entry = self._entry(el, t)
        if entry is not None:
            res.append(float(np.dot(c - s, entry)))
        if "LEN" in v:
            res.append(math.hypot(*(e - s)) - abs(v["LEN"]))
        if "CCA" in v:
            a = math.radians(abs(v["CCA"])) * (1 if self._ccw(el, s, t, c) else -1)
            rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
            res += list(e - c - rot @ (s - c))
        for p in ("P1", "P2", "P3"):
            if p + "X" in v:
                res.append(math.hypot(*(np.array([v[p + "X"], v[p + "Y"]]) - c)) - r)
        if "D" in v:  # the auxiliary point PDX PDY at the distance D from the circle
            res.append((math.hypot(*(np.array([v["PDX"], v["PDY"]]) - c)) - r) ** 2 - v["D"] ** 2)
        return res

    def _polar_angle(self, el: _Element, s, cc: str) -> float:
        """PA (``cc`` "") or CCPA (``cc`` "CC") [deg] about FPOL; the I form from the start or block n's end."""
        key = cc + "PA"
        if key in el.v:
            return el.v[key]
        return _angle(self._ref_end(el, "R" + key, s) - self.pole) + el.v["I" + key]

    def _entry(self, el: _Element, t):
        if "AN" in el.v:
            return _unit(el.v["AN"])
        return t if el.kw == "FCT" else None

    def _ccw(self, el: _Element, s, t, c) -> bool:
        if el.dr:
            return el.dr == "+"
        entry = self._entry(el, t)
        if entry is None:
            raise ReferenceError("FC without DR")
        return _cross(entry, c - s) > 0

    @staticmethod
    def _direction(rec, *, at_end: bool = True) -> np.ndarray:
        s, e, c, ccw = rec
        if c is None:
            return (e - s) / math.hypot(*(e - s))
        r = (e if at_end else s) - c
        d = np.array([-r[1], r[0]]) if ccw else np.array([r[1], -r[0]])
        return d / math.hypot(*d)

    def admissible(self, el: _Element, s, t, z, tol: float) -> bool:
        """The inequalities the equations leave: directions ahead, the centre on the DR side, rays from FPOL."""
        v, e = el.v, z[-2:]
        if ("PA" in v or "IPA" in v) and np.dot(e - self.pole, _unit(self._polar_angle(el, s, ""))) < -tol:
            return False
        if not el.arc:
            if math.hypot(*(e - s)) <= tol:
                return False
            u = (e - s) / math.hypot(*(e - s))
            return all(abs(_cross(d, u)) < 1e-7 and (not ahead or np.dot(u, d) > 0)
                       for d, ahead in self._line_directions(el, s, t))
        c = z[:2]
        if math.hypot(*(s - c)) <= tol:
            return False
        if ("CCPA" in v or "ICCPA" in v) and np.dot(c - self.pole, _unit(self._polar_angle(el, s, "CC"))) < -tol:
            return False
        if math.hypot(*(e - s)) <= tol and not (el.closing or {"X", "Y", "IX", "IY", "PR", "PA", "IPR", "IPA", "CCA"}
                                                 & set(v)):
            return False  # a full circle only where the data name its end
        entry = self._entry(el, t)
        return entry is None or not el.dr or (_cross(entry, c - s) > 0) == (el.dr == "+")

    # --- solving ------------------------------------------------------------------------------------
    def _system(self, chain: list[_Element], s0, t0):
        """(walk, fun, n): the elements of ``chain`` joined (each starts where the one before ends, tangent to it
        for FLT/FCT/IAN): ``walk(z)`` their (element, start, tangent, unknowns), ``fun(z)`` all residuals."""
        n = sum(el.n for el in chain)

        def walk(z):
            s, t, out, k, closed = s0, t0, [], 0, self.closed
            known = dict(self.ends)
            for el in chain:
                zz = z[k:k + el.n]
                k += el.n
                out.append((el, s, t, zz))
                el.known = dict(known)
                if el.closing:
                    el.closed_at = closed  # the start of the CLSD+ element, resolved or in the chain
                elif "CLSD" in el.v:
                    closed = s
                if el.arc:
                    rec = (s, zz[2:], zz[:2], self._ccw(el, s, t, zz[:2]))
                else:
                    rec = (s, zz, None, True)
                if el.number is not None:
                    known[el.number] = rec
                s = zz[-2:]
                t = self._direction(rec) if math.hypot(*(rec[1] - rec[0])) > 1e-12 or rec[2] is not None else t
            return out

        def fun(z):
            return np.array([r for el, s, t, zz in walk(z) for r in self.equations(el, s, t, zz)], float)

        return walk, fun, n

    def solve(self, chain: list[_Element], s0, t0, tol: float, *, first: int = 0, head: int = 0) -> list[list[tuple]]:
        """The solutions of the elements ``chain`` (joined), each a list of (start, end, centre, ccw) per element;
        ``first``: only that many; ``head``: those differing in the first ``head`` elements (the rest left open).
        Every one of a fixed list of starts is tried (no stop that depends on which start found the last root), a new
        root told from a known one by a clear gap (:func:`_distinct`)."""
        walk, fun, n = self._system(chain, s0, t0)
        cut = sum(el.n for el in chain[:head]) if head else n
        size = 1.0 + max([abs(x) for el in chain for x in el.v.values() if isinstance(x, float)] + [*np.abs(s0)])
        roots: list[np.ndarray] = []

        def converged(x0, *, rough=False):
            """The root a start ``x0`` reaches (None if none): MINPACK's Levenberg-Marquardt with its own forward
            differences (``leastsq``) where the equations are at least as many as the unknowns, else trust-region
            reflective; ``rough``: a quick first pass whose root is then polished (:func:`_residual_root`; one
            of the band between is returned, for the caller to decide)."""
            x = minimise(x0, rough)
            if rough:
                return x if np.max(np.abs(fun(x))) <= 1e-6 * size else None
            return x if _residual_root(np.max(np.abs(fun(x))), size) is not False else None

        def minimise(x0, rough):
            tight = {"xtol": 1e-8, "ftol": 1e-8} if rough else {"xtol": 1e-15, "ftol": 1e-15, "gtol": 1e-15}
            if len(fun(x0)) >= n:
                with warnings.catch_warnings():  # its warning that a tolerance is not met: the residual decides
                    warnings.simplefilter("ignore", RuntimeWarning)
                    try:
                        return leastsq(fun, x0, maxfev=60 * (n + 1) if rough else 1000 * (n + 1), **tight)[0]
                    except ValueError:  # equations whose number changes with x, which leastsq refuses
                        pass
                    try:
                        return least_squares(fun, x0, method="lm", max_nfev=60 if rough else 1000, **tight).x
                    except ValueError:  # so also here (an element shrunk to nothing on the way): no root from x0
                        return x0
            return least_squares(fun, x0, method="trf", max_nfev=60 if rough else 1000, **tight).x

        def admissible(x):
            return all(self.admissible(el, s, t, zz, tol) for el, s, t, zz in walk(x))

        def good(x):  # admissible; with an open tail, at a point where the Jacobian clearly fixes the head
            return admissible(x) and (cut == n or (self._fixed_count(chain, fun, x) or 0) >= head)

        for i, start in enumerate(_starts(n, size, np.tile(s0, n // 2))):
            x = converged(start, rough=True)
            if x is None or any(np.max(np.abs(x[:cut] - r[:cut])) < 1e-5 * size for r in roots):
                continue
            x = converged(x)
            if x is None:
                continue
            tails = np.random.default_rng([7, i])  # the tail's own starts: the same whatever came before
            for _ in range(10 if cut < n else 0):  # the open tail the wrong way, or where it leaves the head ill-fixed
                if good(x):  # (an open line of almost no length or a huge one): the tail again, from a fresh start
                    break
                tail = converged(np.concatenate([x[:cut], np.tile(x[cut - 2:cut], (n - cut) // 2)
                                                 + tails.normal(scale=size, size=n - cut)]))
                x = tail if tail is not None and np.max(np.abs(tail[:cut] - x[:cut])) < 1e-4 * size else x
            if not good(x) or not _distinct(x[:cut], [r[:cut] for r in roots], size, chain[0].line):
                continue
            residual = np.max(np.abs(fun(x)))
            if _residual_root(residual, size) is None:
                raise ReferenceError(f"FK element of line {chain[0].line}: a new point of residual {residual:.1e} "
                                     f"(size {size:g}), between a root (1e-8 size) and none (1e-6 size)")
            if _residual_root(residual, size):
                roots.append(x)
                if len(roots) == first:
                    break
        out = []
        for z in roots:
            recs = []
            for el, s, t, zz in walk(z):
                recs.append((s, zz[2:], zz[:2], self._ccw(el, s, t, zz[:2])) if el.arc else (s, zz, None, True))
            out.append(recs)
        return out

    def _at_solutions(self, chain: list[_Element], s, t, tol: float, sols: list, decide):
        """``decide(z)`` (a value, or None where the singular values leave it ambiguous) at a solution of ``chain``
        where its Jacobian is well conditioned: the first solution if its smallest nonzero singular value is at least
        1e-2 (relative), else the best conditioned of up to six that decides (a solution on the edge of a degenerate
        case, as an open line of almost no length or a huge one, leaves the null space blurred); at a seeded random
        point when there is none; an error naming the margin if none decides. ``sols``: ``solve(.., first=1)``."""
        _, fun, n = self._system(chain, s, t)

        def flat(recs):
            return np.concatenate([np.concatenate([r[2], r[1]]) if r[2] is not None else r[1] for r in recs])

        def conditioning(z):
            sv = np.linalg.svd(_jacobian(fun, z), compute_uv=False)
            rel = sv / max(1.0, sv.max(initial=0.0))
            return rel[rel > _ZERO].min(initial=0.0)

        if not sols:
            points = [np.tile(s, n // 2) + np.random.default_rng(3).normal(scale=10.0, size=n)]
        else:
            points = [flat(sols[0])]
            if conditioning(points[0]) < 1e-2:
                points += [flat(recs) for recs in self.solve(chain, s, t, tol, first=6)[1:]]  # the same first
        for z in sorted(points, key=lambda z: -conditioning(z)) if len(points) > 1 else points:
            got = decide(z)
            if got is not None:
                return got
        raise ReferenceError(f"FK elements of lines {chain[0].line}..{chain[-1].line}: at every point tried a "
                             f"singular value of the Jacobian lies between {_ZERO:g} and {_NONZERO:g} (relative), "
                             "or a component of its null space between 1e-6 and 1e-3")

    def determined(self, chain: list[_Element], s, t, tol: float) -> bool:
        """The elements' data fix their unknowns: the Jacobian of the joined equations (central differences) has full
        rank at a solution, or at a seeded random point when there is none (two data naming the same direction, as
        FLT with AN, count once; a point at a distance D from a line of known direction fixes nothing of it, which
        only a solution shows). The rank by the gap in the singular values (:func:`_rank`)."""
        t = t if t is not None else np.array([1.0, 0.0])
        _, fun, n = self._system(chain, s, t)

        def full(z):
            jac = _jacobian(fun, z)
            rank = _rank(jac)[0] if jac.size else 0
            return None if rank is None else rank >= n

        return self._at_solutions(chain, s, t, tol, self.solve(chain, s, t, tol, first=1), full)

    @staticmethod
    def _fixed_count(chain: list[_Element], fun, z) -> int | None:
        """How many leading elements of ``chain`` (not its last) the equations fix at ``z``: their unknowns take
        no part in the null space of the Jacobian there (a component below 1e-6 is none, above 1e-3 is one; None
        where a component or a singular value lies between)."""
        jac = _jacobian(fun, z)
        n = len(z)
        if jac.size:
            rank, vt = _rank(jac)
            if rank is None:
                return None
            free = vt[rank:]
        else:
            free = np.eye(n)
        big = np.max(np.abs(free), axis=0) if len(free) else np.zeros(n)
        if np.any((big >= 1e-6) & (big <= 1e-3)):
            return None
        fixed = big < 1e-6
        k, at = 0, 0
        for el in chain[:-1]:
            if not fixed[at:at + el.n].all():
                break
            at += el.n
            k += 1
        return k

    def fixed_prefix(self, chain: list[_Element], s, t, tol: float) -> list[list[tuple]]:
        """The solutions (records per element, ordered for FSELECT) of the leading elements of ``chain`` (not its
        last) whose unknowns the joined data fix: at a solution, the unknowns the null space of the Jacobian leaves
        untouched; one list per distinct way they are fixed ([] when none is fixed)."""
        _, fun, n = self._system(chain, s, t)
        one = self.solve(chain, s, t, tol, first=1)
        if not one:
            return []
        k = self._at_solutions(chain, s, t, tol, one, lambda z: self._fixed_count(chain, fun, z))
        if k == 0:
            return []
        # the solve keeps one solution per head, told apart by a clear gap (no rounding of the heads here)
        return self.order_chains([recs[:k] for recs in self.solve(chain, s, t, tol, head=k)])

    @staticmethod
    def length(rec) -> float:
        s, e, c, ccw = rec
        if c is None:
            return math.hypot(*(e - s))
        a0, a1 = _angle(s - c), _angle(e - c)
        sweep = ((a1 - a0) if ccw else (a0 - a1)) % 360.0
        return math.hypot(*(s - c)) * math.radians(sweep if sweep > 1e-9 else 360.0)

    def order_chains(self, solutions: list[list[tuple]]) -> list[list[tuple]]:
        """By the elements in turn: shortest first; equal lengths by the direction they leave the start in,
        counter-clockwise from +X (rounded to 1e-6 degrees, and 360 is 0: a line along +X a rounding below it,
        at -1e-10 degrees, is the first, not the last)."""
        return sorted(solutions, key=lambda recs: [(round(self.length(rec), 6),
                                                    round(_angle(self._direction(rec, at_end=False)) % 360.0, 6)
                                                    % 360.0)
                                                   for rec in recs])

    def element(self, kw: str, words: dict, refs: dict, line: int, number, s, t, tol: float) -> list:
        """An FL/FLT/FC/FCT block: the (line, number, record) elements to emit now."""
        opened = self.closed is not None or any("CLSD" in e.v and not e.closing for e in
                                                (self.waiting[0] if self.waiting is not None else []))
        closing = words.get("CLSD") == "-" or (words.get("CLSD") == "" and opened)
        el = _Element(kw, words, refs, line, number, closing)
        chain = [el]
        if self.waiting is not None:
            before, s, t, sols = self.waiting
            if sols is not None:
                raise ReferenceError("an FK element with several solutions and no FSELECT")
            chain = before + [el]
            self.waiting = None
        return self._advance(chain, s, t, tol)

    def _advance(self, chain: list[_Element], s, t, tol: float) -> list:
        """Emit the leading elements of the open ``chain`` the data fix; several solutions wait for FSELECT (the
        rest of the chain after them), an undetermined rest waits for the next FK element."""
        out = []
        while chain:
            sols = self.fixed_prefix(chain, s, t, tol) if len(chain) > 1 else []
            if not sols and len(chain) == 1 and self.determined(chain, s, t, tol):
                sols = self.order_chains(self.solve(chain, s, t, tol))
                if not sols:
                    raise ReferenceError(f"FK element of line {chain[0].line}: no solution")
            if not sols:
                self.waiting = (chain, s, t, None)
                return out
            if len(sols) > 1:
                self.waiting = (chain, s, t, sols)
                return out
            out += [self._done(e, rec) for e, rec in zip(chain, sols[0])]
            chain = chain[len(sols[0]):]
            s, t = out[-1][1][1], self._direction(out[-1][1])
        return out

    def select(self, n: int) -> list:
        if self.waiting is None or self.waiting[3] is None:  # one solution and an arc back to its start (TNC)
            return []
        chain, _, _, sols = self.waiting
        self.waiting = None
        recs = sols[n - 1]
        out = [self._done(e, rec) for e, rec in zip(chain, recs)]
        return out + self._advance(chain[len(recs):], recs[-1][1], self._direction(recs[-1]), 1e-6)

    def _done(self, el: _Element, rec) -> tuple:
        if el.number is not None:
            self.ends[el.number] = rec
        self.last_direction = self._direction(rec)
        if el.closing:
            self.closed = None
        elif "CLSD" in el.v:
            self.closed = np.array(rec[0], float)
        return el, rec
