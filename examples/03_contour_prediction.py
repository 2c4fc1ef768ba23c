"""Virtual process planning: predict a part's contour error from a rapid identification.

1. Run a Table 3.2-style random-move test on the 'true' virtual Fadal (PID, all non-idealities).
2. Identify the reduced model of each axis from that capture (thesis Ch. 3).
3. Run the 40 mm circle and diamond at 200 mm/s on the true machine and on the models, and
   compare their contour errors (thesis Figs. 3.6 / 3.7): numbers, a JSON summary and an HTML
   report with the magnified contours.

Run: ``python examples/03_contour_prediction.py [OUT_DIR]`` (default ``contour_prediction``).
The same from the command line, once the models are saved::

    vcnc compare --truth fadal-pid --model x=model_x.json --model y=model_y.json \\
        --toolpath diamond --json diamond.json --report diamond_report
"""

from __future__ import annotations

import sys
from pathlib import Path

import interpolators
import toolpaths
from identification import identify
from vcnc.contour_compare import compare
from vcnc.engine.machine import load_machine


def main(out: Path) -> None:
    truth = load_machine("fadal-pid")
    program = interpolators.parse_program(toolpaths.random_moves(60, 10.0, 12000, seed=1, axes=truth.axes))
    setpoints = interpolators.interpolate(program, limits=truth.limits, sample_time=truth.sample_time)
    capture = truth.simulate(setpoints, seed=1)
    models = {a: identify(capture, axis=a, diagnose=False) for a in truth.axes}
    out.mkdir(parents=True, exist_ok=True)
    for a, m in models.items():
        m.to_json(out / f"model_{a}.json")
        print(f"axis {a}: omega_n {m.poles['omega_n_hz']:.3g} Hz, zeta {m.poles['zeta']:.3g}, "
              f"p {m.poles['p_hz']:.3g} Hz; fit rms {m.fit['rms_um']:.3g} um")
    for toolpath in ("circle", "diamond"):
        result = compare(truth, models, toolpath)
        d = result.to_dict()
        print(f"{toolpath:8s} true max {d['true']['contour_max_um']:.2f} um, predicted "
              f"{d['predicted']['contour_max_um']:.2f} um ({d['prediction_error_pct']['max']:+.2f} %); rms "
              f"{d['true']['contour_rms_um']:.2f} / {d['predicted']['contour_rms_um']:.2f} um")
        result.to_json(out / f"{toolpath}.json")
        result.report().write(out / f"{toolpath}_report")
    print(f"reports in {out}")


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "contour_prediction"))
