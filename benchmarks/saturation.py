"""Saturated drives with and without the laws' anti-windup: one line per built-in machine and case.

Run: ``.venv/bin/python benchmarks/saturation.py [--machine NAME ...]``

Cases on each built-in machine's X axis (hand-written programs):

- ``G0 x10``, ``G0 x25``: ``G0 X100``, a 3 s dwell, ``G0 X0``, a 3 s dwell, with the axis'
  acceleration and jerk limits raised 10 and 25 times (a machine file whose limits ask more than
  the drive delivers; the wild run's fadal-smc and ballscrew-zpetc cases);
- ``tight``: ``G1 X100`` at the velocity limit and back, with 3 s dwells, at the machine's own limits
  but with an amplifier limit of 60 % of the largest control the program asks without one (a machine
  file with a tight current limit).

Each case runs the bare law (``anti_windup = false``, the laws before anti-windup) and the law with
anti-windup (the default). Columns: share of the samples at the limit (``Capture.aux["saturated"]``),
largest tracking error [mm], largest overshoot past the end of a move [mm], time after the reference
stops until the error stays within 20 um [s] (the dwell: 2.9 s means not settled), error at the end
[um]; ``diverged`` when the kernel stopped the run. Prints figures only.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this tree's packages, not the installed ones

import numpy as np  # noqa: E402

import drives  # noqa: E402
import interpolators  # noqa: E402
from vcnc.core.errors import VcncError  # noqa: E402
from vcnc.engine.machine import Machine, builtin_machines, load_machine  # noqa: E402
from vcnc.facade import interpolate  # noqa: E402

RAPID = "G21 G90\nG0 X0\nG0 X100\nG4 P3\nG0 X0\nG4 P3\nM30\n"
FEED = "G21 G90\nG1 X0 F{feed}\nG1 X100\nG4 P3\nG1 X0\nG4 P3\nM30\n"
SETTLED_MM = 0.02
WINDOW_S = 2.9


def with_law(machine: Machine, anti_windup: bool) -> Machine:
    law = dataclasses.replace(machine.axis("x").controller, anti_windup=anti_windup)
    return machine.with_axis_options("x", controller=law)


def cases(m: Machine) -> dict[str, tuple[Machine, str]]:
    ax = m.axis("x")
    out = {}
    for k in (10, 25):
        lim = dataclasses.replace(ax.limits, acceleration=k * ax.limits.acceleration,
                                  jerk=k * (ax.limits.jerk or 20.0 * ax.limits.acceleration))
        out[f"G0 x{k}"] = (m.with_axis("x", dataclasses.replace(ax, limits=lim)), RAPID)
    feed = FEED.format(feed=60.0 * ax.limits.velocity)
    free = m.with_axis_options("x", saturation=None, dac=None)
    peak = float(np.abs(free.simulate(setpoints(free, feed)).control).max())
    tight = drives.Saturation(voltage_limit=0.6 * peak)
    out[f"tight {0.6 * peak:.2g} V"] = (m.with_axis_options("x", saturation=tight), feed)
    return out


def setpoints(m: Machine, text: str):
    return interpolate(interpolators.parse_program(text), m).select_axes(("x",))


def measure(m: Machine, text: str) -> str:
    try:
        c = m.simulate(setpoints(m, text))
    except VcncError:
        return f"{'diverged':>44}"
    ts = m.sample_time
    r, y = c.reference[:, 0], c.measured[:, 0]
    moving = np.abs(np.diff(r, prepend=r[0])) > 0.0
    ends = np.flatnonzero(moving[:-1] & ~moving[1:]) + 1
    starts = np.flatnonzero(moving & ~np.r_[False, moving[:-1]])
    over, settle = 0.0, 0.0
    for st, en in zip(starts, ends):
        seg = slice(en, min(len(r), en + int(WINDOW_S / ts)))
        over = max(over, float(np.max(np.sign(r[en] - r[st - 1]) * (y[seg] - r[en]))))
        late = np.flatnonzero(np.abs(r[seg] - y[seg]) > SETTLED_MM)
        settle = max(settle, (late[-1] + 1) * ts if len(late) else 0.0)
    e = np.abs(r - y)
    return (f"{100 * c.aux['saturated'][:, 0].mean():6.1f} % {e.max():9.2f} {over:9.3f} {settle:6.3f}"
            f" {1e3 * e[-1]:10.2f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--machine", action="append", choices=builtin_machines(), help="these machines only")
    args = ap.parse_args()
    head = f"{'sat':>8} {'max mm':>9} {'over mm':>9} {'settle':>6} {'end um':>10}"
    print(f"{'machine':16} {'case':14} | bare law: {head} | anti-windup: {head}")
    for name in args.machine or builtin_machines():
        m = load_machine(name)
        for case, (mc, text) in cases(m).items():
            print(f"{name:16} {case:14} | {measure(with_law(mc, False), text):>{len(head) + 10}} "
                  f"| {measure(with_law(mc, True), text):>{len(head) + 13}}", flush=True)


if __name__ == "__main__":
    main()
