"""The settling tail of a simulated capture: the record runs on after the last setpoint until the axes have settled.

A control's trace (TNCscope, halscope, a SINUMERIK trace) runs on after the interpolator stops: the axis still
moves, the following error decays to its standstill value (or hunts around it, a Coulomb-friction limit cycle).
A capture that ends with the reference cuts that decay off, and with it the part of the record that shows the
loop's slowest pole most plainly. ``vcnc simulate`` therefore holds the last commanded position for up to
:data:`BOUND_S` seconds (``--settle S``) and keeps the capture up to the point where every axis has settled, plus
:data:`WINDOW_S` at rest (:func:`settling_tail`).

Settled means: from that sample on, the following error ``reference - measured`` of every axis, averaged over
:data:`SMOOTH_S` (a noise sample or an encoder count's flicker is no motion), stays within a band around its final
value (the median of the last :data:`WINDOW_S` of the hold). The band is the largest of :data:`RELATIVE` (0.1 %) of
the error's largest deviation from that value in the tail (an exponential decay settles there in 6.9 time
constants), three standard
deviations of the error about its trend over that last window (measurement noise, encoder counts, a limit cycle)
and :data:`FLOOR_MM`. The control signal, where the capture has it, must have settled in the same sense (an axis
held by static friction while its integrator winds up has a steady error and a ramping control signal: it will
move again). An axis that has not stayed in its band for :data:`WINDOW_S` before the bound (a drift of the
measured channel, a loop without integral action creeping on) is reported as not settled, and the whole bound is
kept.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from vcnc.core.axes import ROTARY_AXES
from vcnc.core.capture import Capture

__all__ = ["BOUND_S", "WINDOW_S", "RELATIVE", "SMOOTH_S", "FLOOR_MM", "FLOOR_V", "SettlingTail", "settling_tail"]

#: Longest settling tail ``vcnc simulate`` runs [s] (``--settle S``): several time constants of the slowest loop
#: of the built-in machines (fadal-pid's integral pole at 1.17 Hz: 0.14 s; EMPS's slowest pole about 0.2 Hz)
BOUND_S = 2.0
#: Time at rest recorded after the axes settled, and the window of the final value [s]
WINDOW_S = 0.1
#: Part of the largest deviation from the final value in the tail that counts as settled: 0.1 % (an exponential
#: decay settles there in 6.9 time constants; 1 % left fadal-ppi's P loop 15 um from rest, its error 1.5 mm at the
#: last setpoint)
RELATIVE = 0.001
#: Averaging time of the error's deviation before it is compared with the band [s]
SMOOTH_S = 0.02
#: Smallest settling band [mm] (deg on a rotary axis): 1 nm, below any machine's measurement
FLOOR_MM = 1e-6
#: Smallest settling band of the control signal [V]: 1 uV, below a 16-bit DAC's step over +/-10 V (0.3 mV)
FLOOR_V = 1e-6


@dataclasses.dataclass(frozen=True, kw_only=True)
class SettlingTail:
    """Where a capture's settling tail ends.

    Attributes
    ----------
    samples : int
        Samples of the capture to keep (those of the setpoints and of the tail).
    seconds : float
        Length of the kept tail after the last setpoint [s].
    settled : bool
        Every axis settled within the bound (False: the whole bound is kept).
    band : dict
        Axis -> the settling band [mm] (deg on a rotary axis).
    unsettled : tuple of str
        The axes that had not settled at the bound.
    """

    samples: int
    seconds: float
    settled: bool
    band: dict[str, float]
    unsettled: tuple[str, ...] = ()

    def note(self, bound_s: float) -> str:
        """The tail in words, for the command line and the capture's header."""
        if self.settled:
            return (f"the capture runs on {self.seconds:.4g} s after the last setpoint, the command held, until "
                    f"every axis settled (following error within {self._worst_band()} of its final value, control "
                    f"signal steady; then {WINDOW_S:g} s at rest; --settle S bounds the tail, --settle 0 ends the "
                    "capture with the reference)")
        return (f"axis {', '.join(self.unsettled)} had not settled {bound_s:g} s after the last setpoint (the "
                "command held; following error or control signal still moving): the capture runs on to that bound "
                "(--settle S to change it)")

    def _worst_band(self) -> str:
        """The widest band in words: um on the linear axes, mdeg on the rotary ones (the band is in deg there)."""
        linear = [b for a, b in self.band.items() if a.lower() not in ROTARY_AXES]
        rotary = [b for a, b in self.band.items() if a.lower() in ROTARY_AXES]
        turns = f"{max(rotary) * 1000.0:.3g} mdeg" if rotary else ""
        if not linear:
            return turns or "0 um"
        return f"{max(linear) * 1000.0:.3g} um" + (f" ({turns} on a rotary axis)" if turns else "")


def _scatter(window: np.ndarray) -> np.ndarray:
    """Standard deviation of each column about its straight-line fit: the noise of a window, not its trend (a
    measured channel creeping on would widen its own band by its slope)."""
    x = np.arange(len(window), dtype=float)
    x -= x.mean()
    slope = (x @ (window - window.mean(axis=0))) / max(float(x @ x), 1.0)
    return (window - window.mean(axis=0) - np.outer(x, slope)).std(axis=0)


def _settled_from(tail: np.ndarray, w: int, k: int, floor: float) -> tuple[np.ndarray, np.ndarray, int]:
    """Per column of ``tail`` (samples from the last setpoint on): the first sample from which its mean over ``k``
    samples stays within the band around its final value, the band, and the number of such means."""
    final = np.median(tail[-w:], axis=0)
    # the deviation from the final value averaged over SMOOTH_S: single samples of noise or an encoder count's
    # flicker beyond the band are no motion (a raw sample beyond three deviations would keep the tail to the bound)
    cums = np.cumsum(np.vstack([np.zeros((1, tail.shape[1])), tail - final]), axis=0)
    dev = np.abs(cums[k:] - cums[:-k]) / k  # sample j: the mean over j .. j + k - 1
    band = np.maximum.reduce([RELATIVE * np.abs(tail - final).max(axis=0), 3.0 * _scatter(tail[-w:]),
                              np.full(tail.shape[1], floor)])
    settle_at = np.zeros(tail.shape[1], dtype=int)
    for i in range(tail.shape[1]):
        out = np.flatnonzero(dev[:, i] > band[i])
        settle_at[i] = out[-1] + 1 if len(out) else 0
    return settle_at, band, len(dev)


def settling_tail(capture: Capture, start: int) -> SettlingTail:
    """The end of the settling tail of ``capture``, whose samples from ``start`` on hold the last commanded
    position (the setpoints followed by a hold, :meth:`vcnc.core.setpoints.Setpoints.held`).

    Parameters
    ----------
    capture : Capture
        The simulated run, setpoints and hold.
    start : int
        Number of samples of the setpoints (the hold begins at sample ``start``).

    Returns
    -------
    SettlingTail
    """
    n = len(capture)
    ts = capture.sample_time
    w = max(1, int(round(WINDOW_S / ts)))
    if n - start + 1 <= w:
        return SettlingTail(samples=n, seconds=(n - start) * ts, settled=False, band={},
                            unsettled=tuple(capture.axes))
    k = max(1, min(int(round(SMOOTH_S / ts)), w))
    tail = capture.reference[start - 1:] - capture.measured[start - 1:]  # from the last setpoint on
    settle_at, band, m = _settled_from(tail, w, k, FLOOR_MM)
    if capture.control is not None:  # an axis stuck by friction while its integrator winds up has not settled
        settle_u, _, _ = _settled_from(capture.control[start - 1:], w, k, FLOOR_V)
        settle_at = np.maximum(settle_at, settle_u)
    unsettled = tuple(a for a, at in zip(capture.axes, settle_at) if at > m - w)
    bands = {a: float(b) for a, b in zip(capture.axes, band)}
    if unsettled:
        return SettlingTail(samples=n, seconds=(n - start) * ts, settled=False, band=bands, unsettled=unsettled)
    keep = min(n, start - 1 + int(settle_at.max()) + w)
    return SettlingTail(samples=keep, seconds=(keep - start) * ts, settled=True, band=bands)
