"""A setpoint filter between the recorded reference and the position loop: a moving average.

Controls smooth the interpolated setpoint after the point their trace taps it: Heidenhain's
jerk-limiting smoothing filters sit after the interpolator, and Siemens' setpoint filters
(jerk filter) act on the position setpoint of each axis (our reading of the controls'
descriptions; no manual found that fixes where the trace records). The loop then receives

    x_loop(t) = 1/L * integral_{t - L}^{t} x_ref(t' - delay_s) dt'

with ``L = setpoint_filter_s`` [s] (0: no filter) and ``delay_s`` the reference dead time
(:mod:`identification.dead_time`). The reduced model of Eq. (3.3) has no term for it: fitted
without one, its poles bend to imitate the filter's lag and smoothing (a 16 ms moving average
before the loop: zeta 23-314 % off on vcnc's machines, ``benchmarks/recorded_traces.py`` case
``jerkf``). A moving average resembles a dead time of ``L / 2`` at low frequency; the two are
fitted together (:mod:`identification.identify`).

Sampled (:func:`filter_reference`, also the rule of the FMU's filter): the reference is linear
between samples and holds its first value before the first one, as in
:func:`identification.dead_time.delay_reference`; the mean over ``L/T = n + f`` samples is the
trapezoid sum over the n whole intervals before sample k plus the fraction f of the interval
before them, divided by ``L/T``, in this order of floating-point operations::

    s = 0;  for i = k-n .. k-1:  s += (x_i + x_{i+1}) * 0.5
    if f > 0:  j = k-n-1;  m = (x_{j+1} - x_j) * (1 - f) + x_j;  s += f * (x_{j+1} + m) * 0.5
    y_k = s / (L/T)

with ``x_i`` the deviation of the reference from its first value (indices below 0 read 0) and
``y_k`` plus that first value the filtered reference: a reference at rest stays exactly where it
is, as the simulation from rest needs (:mod:`identification.reduced_model`). A discrete moving
average of N samples, as a control runs it in its interpolation cycle, has the group delay of
this filter with ``L = (N - 1) T`` and the low-frequency gain of one with ``L = N T``: fitted,
its length comes out between the two (the 16-sample average of the truth harness: 15.7-16.4 ms).
"""

from __future__ import annotations

import numpy as np

from identification.kernels import moving_average

__all__ = ["filter_reference"]


def filter_reference(reference: np.ndarray, samples: float) -> np.ndarray:
    """``reference`` through the moving average over ``samples`` (whole and fractional, >= 0; 0:
    unchanged) of the module docstring."""
    xr = np.ascontiguousarray(reference, dtype=float)
    if samples == 0.0:
        return xr.copy()
    if not samples > 0.0:
        raise ValueError(f"a moving average needs a length > 0 samples, got {samples!r}")
    out = np.empty_like(xr)
    moving_average(xr, float(samples), out)
    return out
