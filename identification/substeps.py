"""A record sampled slower than the loop runs: the model predicted between its samples.

Controls log slower than their position loops run (a TNCscope trace at 3 ms of a loop closed every
0.2 ms or less; our reading of Heidenhain's TNCscope sampling choices, no manual found that states
the loop rate). Between two logged samples the loop's reference is not linear (the interpolator's
parabolic acceleration phases: up to a T^2/8 off the chord, 2.25 um at 2000 mm/s^2 and 3 ms) and the
friction switches when the velocity crosses zero, not at the next logged sample. Simulated at the
record's step (first-order hold on the reference, friction held over the sample: the simulation
contract of :mod:`identification.reduced_model`), the exact FADAL_PID_X model predicts its own
response logged at 3 ms with 1.71 um RMS and at 6 ms with 6.69 um; the output-error fit bent p by
30 and 47 % to imitate that (the traceid2 truth harness: ``benchmarks/recorded_traces.py``, cases
``dec3``/``dec6``).

The identification therefore predicts a record slower than :data:`FINE_STEP_S` at ``m`` sub-steps
per sample (``m = ceil(T / FINE_STEP_S)``): the reference between the logged samples a cubic spline
through them (not-a-knot), delayed on the sub-step grid, the model run at ``T / m`` (friction
switched at every sub-step) and its position taken at the logged samples. The exact model then
predicts the 3 and 6 ms records with 0.16 and 0.57 um. A record at ``FINE_STEP_S`` or faster is
simulated at its own step, exactly as :func:`identification.reduced_model.simulate` (``m = 1``).

The identified model keeps the record's sample time and its own contract:
``ReducedAxisModel.simulate`` at a coarse step is the first-order hold of the module above (what an
exported FMU reproduces), and predicts the coarse record worse than ``fit.rms_um``, which is this
module's prediction (``fit.substeps`` says how many). At the machine's own interpolation step
(1 ms or less) the two agree. The diagnosis predicts the record as the fit does
(:attr:`identification.searches.Data.held`; an element's split form with its law sampled at the
sub-steps), so that one report states one error for one model: camber linD
at 10 ms, 237.7 um in the fit against 275.2 um in the diagnosis' table before (the spline between
samples against their chord, 62 um apart at 5000 mm/s^2 over 10 ms).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np
import scipy.interpolate

from identification.dead_time import delay_reference
from identification.reduced_model import simulate
from identification.setpoint_filter import filter_reference

__all__ = ["FINE_STEP_S", "SubstepReference", "substep_count", "substep_reference", "simulate_record"]

#: Longest step the model is simulated at [s]: a slower record is predicted at sub-steps.
FINE_STEP_S = 0.001
#: Share of the record's span below which the spline's departure from a rest is ringing [-] (:func:`substep_reference`).
RING_SHARE = 1e-9


def substep_count(sample_time: float) -> int:
    """Sub-steps per sample of a record at ``sample_time`` [s] (1 up to :data:`FINE_STEP_S`)."""
    return max(1, math.ceil(sample_time / FINE_STEP_S - 1e-9))


@dataclasses.dataclass(frozen=True, eq=False)
class SubstepReference:
    """A recorded reference on the sub-step grid (:func:`substep_reference`).

    Attributes
    ----------
    fine : ndarray, shape ((N - 1) m + 1,)
        Reference at the sub-steps [mm]; every m-th is a recorded sample.
    substeps : int
        m, sub-steps per recorded sample.
    sample_time : float
        The record's T [s].
    """

    fine: np.ndarray
    substeps: int
    sample_time: float

    def delayed(self, samples: float) -> SubstepReference:
        """The reference delayed by ``samples`` of the record (linear between sub-steps,
        :func:`identification.dead_time.delay_reference`)."""
        if samples == 0.0:
            return self
        return dataclasses.replace(self, fine=delay_reference(self.fine, samples * self.substeps))

    def filtered(self, samples: float) -> SubstepReference:
        """The reference through the setpoint filter over ``samples`` of the record (on the
        sub-step grid, :func:`identification.setpoint_filter.filter_reference`)."""
        if samples == 0.0:
            return self
        return dataclasses.replace(self, fine=filter_reference(self.fine, samples * self.substeps))

    def at_samples(self, keep: slice | None = None) -> np.ndarray:
        """The reference at the recorded samples of ``keep`` (all by default) [mm]."""
        return self.fine[::self.substeps][keep or slice(None)]

    def simulate(self, parameters: Mapping[str, float], keep: slice | None = None) -> np.ndarray:
        """Predicted position [mm] at the recorded samples of ``keep`` (all by default), simulated
        from rest at ``keep.start``."""
        m = self.substeps
        n = (self.fine.size - 1) // m + 1
        start, stop, _ = (keep or slice(None)).indices(n)
        fine = self.fine[start * m:(stop - 1) * m + 1]
        if m == 1:
            return simulate(parameters, fine, self.sample_time)
        return simulate(parameters, fine, self.sample_time / m)[::m]


def substep_reference(reference: np.ndarray, sample_time: float) -> SubstepReference:
    """``reference`` [mm] logged every ``sample_time`` [s] on the sub-step grid (module docstring)."""
    xr = np.ascontiguousarray(reference, float)
    m = substep_count(sample_time)
    if m == 1 or xr.size < 4:
        return SubstepReference(xr, 1, float(sample_time))
    k = np.arange(xr.size, dtype=float)
    fine = scipy.interpolate.CubicSpline(k, xr)(np.arange((xr.size - 1) * m + 1) / m)
    fine[::m] = xr
    # a reference at rest stays at rest between its samples: the spline is global, and the moves ring into a rest
    # stretch, decaying about 3.7x a sample down to rounding level, which gives the model a velocity whose sign
    # switches the Coulomb levels (Eq. 3.2) and makes it chatter where the axis stands (a 3 ms record whose refitted
    # model moved 47 um in its first 2 s idle); the ringing below RING_SHARE of the record's span is taken out, the
    # spline next to the moves (their approach and settling) kept
    rest = np.flatnonzero(xr[1:] == xr[:-1])
    if rest.size:
        idx = (rest[:, None] * m + np.arange(1, m)).ravel()
        value = np.repeat(xr[rest], m - 1)
        ring = np.abs(fine[idx] - value) < RING_SHARE * max(float(np.ptp(xr)), 1e-300)
        fine[idx[ring]] = value[ring]
    return SubstepReference(np.ascontiguousarray(fine), m, float(sample_time))


def simulate_record(parameters: Mapping[str, float], reference: np.ndarray, sample_time: float, *,
                    delay_samples: float = 0.0, filter_samples: float = 0.0) -> np.ndarray:
    """Predicted position [mm] at the samples of a record (module docstring), the reference
    delayed by ``delay_samples`` of the record first, then through the setpoint filter over
    ``filter_samples`` (:mod:`identification.setpoint_filter`)."""
    ref = substep_reference(reference, sample_time).delayed(delay_samples).filtered(filter_samples)
    return ref.simulate(parameters)
