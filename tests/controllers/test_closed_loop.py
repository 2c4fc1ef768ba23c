"""Simulated linear loops against their transfer functions.

With every non-ideality off, the compiled simulation of each built-in machine must equal the
discrete equivalent of its sampled law (ZOH plant, python-control) to numerical precision; the
discrete equivalent of the continuous laws must stay close to the analytic Eq. (3.1) over the
command band; the ZPETC bench must track with zero phase (Eq. 3.25 of the thesis).
"""

from __future__ import annotations

import numpy as np
import pytest

from controllers import frequency_response
from vcnc.engine.machine import builtin_machines, load_machine
from vcnc.setpoints import Setpoints

FREQS = np.array([1.0, 3.0, 7.0, 13.0, 20.0, 30.0, 40.0, 50.0])
LINEAR = dict(friction=None, backlash=None, encoder=None, dac=None, saturation=None, noise=None, load=None)


def linear_machine(name: str):
    m = load_machine(name)
    for a in m.axes:
        ax = m.axis(a)
        opts = {k: None for k, v in LINEAR.items() if getattr(ax, k) is not None}
        if opts:
            m = m.with_axis_options(a, **opts)
    return m


def measured_response(m, axis: str, freqs: np.ndarray, *, settle: float = 4.0, window: float = 2.0) -> np.ndarray:
    """x/x_r at ``freqs`` from one multi-sine simulation (exact v_r, a_r), by least squares on a
    window of whole periods after the transients."""
    ts = m.sample_time
    n = int(round((settle + window) / ts)) + 20  # the last 20 samples (end of the preview) are not fitted
    t = np.arange(n) * ts
    amp = 0.01
    ph = np.linspace(0, 2 * np.pi, len(freqs), endpoint=False) ** 2  # spread phases (low crest)
    w = 2 * np.pi * freqs
    pos = amp * np.sin(np.outer(t, w) + ph).sum(1)
    vel = amp * (w * np.cos(np.outer(t, w) + ph)).sum(1)
    acc = -amp * (w**2 * np.sin(np.outer(t, w) + ph)).sum(1)
    sp = Setpoints(t=t, axes=(axis,), position=pos[:, None], velocity=vel[:, None], acceleration=acc[:, None],
                   block=np.full(n, -1), sample_time=ts)
    y = m.simulate(sp).measured[:, 0]
    k = (t >= settle) & (np.arange(n) < n - 20)
    basis = np.hstack([np.sin(np.outer(t[k], w) + ph), np.cos(np.outer(t[k], w) + ph), np.ones((k.sum(), 1))])
    coef, *_ = np.linalg.lstsq(basis, y[k], rcond=None)
    nf = len(freqs)
    return (coef[:nf] + 1j * coef[nf : 2 * nf]) / amp


@pytest.mark.parametrize("name", builtin_machines())
def test_simulation_equals_discrete_equivalent(name: str) -> None:
    m = linear_machine(name)
    ax = m.axis("x")
    freqs = FREQS[FREQS < 0.4 / m.sample_time]
    g_sim = measured_response(m, "x", freqs)
    delay = 0 if ax.delay is None else ax.delay.samples
    g_ref = frequency_response(ax.controller, ax.drive, m.sample_time, freqs, delay=delay)
    np.testing.assert_allclose(g_sim, g_ref, rtol=1e-6, atol=1e-8)


@pytest.mark.parametrize("name", ["fadal-pid", "fadal-ppi", "fadal-smc", "emps"])
def test_sampled_law_close_to_eq_3_1(name: str) -> None:
    """The 1 kHz implementation of a continuous law follows Eq. (3.1) over the command band:
    within 0.5 dB and 3 degrees up to 10 Hz (measured deviations grow to 1-3 dB, 7-10 degrees at
    50 Hz, from the zero-order hold and the sampled derivative)."""
    m = load_machine(name)
    ax = m.axis("x")
    f = np.array([0.5, 1, 2, 5, 10.0])
    g_d = frequency_response(ax.controller, ax.drive, m.sample_time, f)
    g_track, _ = ax.closed_loop(m.sample_time)
    g_c = np.array([complex(g_track(2j * np.pi * fi)) for fi in f])
    ratio = g_d / g_c
    assert np.max(np.abs(20 * np.log10(np.abs(ratio)))) < 0.5
    assert np.max(np.abs(np.degrees(np.angle(ratio)))) < 3.0


@pytest.mark.parametrize("name", ["ballscrew-ppc", "ballscrew-zpetc", "chevalier-pdf"])
def test_discrete_closed_loop_tf(name: str) -> None:
    """closed_loop() of a discrete law is the python-control TF of the simulated loop."""
    m = load_machine(name)
    ax = m.axis("x")
    g_track, g_dist = ax.closed_loop(m.sample_time)
    assert g_track.dt == m.sample_time and g_dist.dt == m.sample_time
    z = np.exp(2j * np.pi * FREQS[:4] * m.sample_time)
    pre = ax.controller.preview(ax.drive, m.sample_time)
    expect = frequency_response(ax.controller, ax.drive, m.sample_time, FREQS[:4])
    np.testing.assert_allclose(np.asarray(g_track(z)).ravel() * z**pre, expect, rtol=1e-6)


def test_zpetc_tracks_with_zero_phase() -> None:
    """Ball-screw bench with ZPETC (Sec. 3.4.2): overall tracking gain within 0.5 dB and phase
    within 2 degrees up to 50 Hz (Eq. 3.25), simulated."""
    m = linear_machine("ballscrew-zpetc")
    g = measured_response(m, "x", FREQS)
    assert np.max(np.abs(20 * np.log10(np.abs(g)))) < 0.5
    assert np.max(np.abs(np.degrees(np.angle(g)))) < 2.0
    ctrl = m.axis("x").controller
    design = ctrl.design(m.axis("x").drive, m.sample_time)
    np.testing.assert_allclose(design.poles[0], 0.86846 + 0.11762j, atol=1e-4)  # Table 4.2
    z = ctrl.zpetc_filter(m.axis("x").drive, m.sample_time)
    assert z.preview == 2
    np.testing.assert_allclose(z.kept_zeros, [-0.99937], atol=2e-5)  # z1 of Table 4.2


def test_without_zpetc_the_bench_lags() -> None:
    g = measured_response(linear_machine("ballscrew-ppc"), "x", np.array([20.0]))
    assert np.degrees(np.angle(g[0])) < -30.0
