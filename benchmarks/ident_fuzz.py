"""Seeded random captures for ``identify`` and the residual diagnosis, unlike the tests' captures.

Each case draws a built-in machine and axis, a program (random moves with random count, span and
feed, or full circles on a two-axis machine), zero, one or two effects at realistic sizes (the
ranges of :func:`vcnc.engine.machine.realistic_effect`'s sources), the measurement noise and
encoder resolution, and the record's conditions (decimated to 0.25-8 ms, a constant offset, the
reference logged a few samples late or early, cut mid-move). It identifies the axis from the
commanded and measured positions only and checks:

- ``identify`` returns, or refuses with an :class:`IdentificationError` (``refused``, its message listed; any other
  exception is a ``traceback``);
- every number of the model is finite (``nonfinite``), its poles are inside the bounds it reports (``pole``);
- with no effect added: no effect named (``false_positive``; a ``delay`` on a record whose reference was logged
  early is the dead time identify leaves to the diagnosis below 5 samples, ``identification/dead_time.py``), and
  the final model's held-out RMS within 3 times the record's noise floor plus 1 um (``high_residual``; the machines' own
  non-idealities, e.g. fadal's 3 um nut play behind the motor encoder, are the margin);
- with effects added, those the diagnosis must name (``shown``, marked ``*``): each changes the noise-free
  measured position by more than 3 times the noise floor (+0.2 um), and together they leave the reduced model
  an error 1.5 times (+0.3 um) that of the same record identified without them (what the reduced model absorbs
  of an effect, e.g. most of a one-sample delay, is no failure; nor is a mode at or above the record's Nyquist
  frequency, or below it by less than its decay rate). Each shown effect is named (``missed``), first
  when it is twice the other's size (``not_first``), the held-out error falls (``no_gain``), and a parameter
  with a known truth is within its tolerance (``parameter``: periods 5 %, backlash width 30 %, drift rate 25 %)
  unless the model reports it as not pinned by the record (``EffectRecord.unpinned``: a period the travel covers
  fewer than 1.5 times), which the case's line notes (``unpinned``).

The CPU time of a case covers the simulations, the identification with its diagnosis, and the reduced fit of the
record without the effects.

Outcomes other than ``ok``, ``refused`` and ``skip`` (an effect the machine cannot take, e.g. a friction on
chevalier-pdf's discrete plant, a truth that diverges, or a delay that takes the truth's sampled linear loop past
the unit circle, :func:`unstable_delay`) are failures.

Run: ``PYTHONPATH=$PWD .venv/bin/python benchmarks/ident_fuzz.py --cases 40 --seed 1 [--start 0] [--only 7]``
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import traceback
from pathlib import Path

import numpy as np

# this checkout first; benchmarks/identification.py is named like the package: keep this folder off the path
sys.path[:] = [str(Path(__file__).resolve().parents[1])] + [
    p for p in sys.path if Path(p or ".").resolve() != Path(__file__).resolve().parent]

import control  # noqa: E402

import toolpaths  # noqa: E402
import vcnc  # noqa: E402
from drives.effects import EFFECT_NAMES  # noqa: E402
from identification import identify  # noqa: E402
from identification.diagnosis import resolved_below_nyquist  # noqa: E402
from vcnc.core.errors import IdentificationError, MachineError, SimulationError  # noqa: E402

MACHINES = ("fadal-pid", "fadal-ppi", "fadal-smc", "ballscrew-ppc", "ballscrew-zpetc", "chevalier-pdf", "emps")


def draw_effect(rng: np.random.Generator, name: str) -> dict:
    """Parameters of ``name`` drawn in its realistic range (realistic_effect's docstring and sources)."""
    u = rng.uniform
    return {
        "friction_stribeck": lambda: {"static_ratio": u(1.3, 2.0), "stribeck_velocity_mm_s": u(2.0, 10.0)},
        "friction_viscous_asymmetric": lambda: {"asymmetry": u(0.1, 0.4) * rng.choice([-1, 1])},
        "backlash": lambda: {"width_mm": u(0.005, 0.03)},
        "position_periodic": lambda: {"period_mm": rng.choice([5.0, 10.0, 20.0])},
        "time_periodic": lambda: {"period_s": u(0.1, 1.5)},
        "resonance": lambda: {"frequency_hz": u(30.0, 120.0), "damping": u(0.02, 0.1),
                              "load_fraction": u(0.2, 0.6)},
        "delay": lambda: {"samples": int(rng.integers(1, 3))},  # 3 samples make fadal-pid and the ballscrews ring
        "saturation": lambda: {"saturated_fraction": u(0.02, 0.06)},
        "drift": lambda: {"rate_mm_s": u(1e-4, 5e-4) * rng.choice([-1, 1])},
    }[name]()


def draw_case(seed: int, index: int) -> dict:
    rng = np.random.default_rng([seed, index])
    name = str(rng.choice(MACHINES))
    m = vcnc.machine(name)
    axis = str(rng.choice(list(m.axes)))
    lim = m.axis(axis).limits
    feed = float(rng.uniform(0.2, 1.0) * 60.0 * lim.velocity)
    if len(m.axes) > 1 and rng.random() < 0.2:
        r = float(rng.uniform(2.0, 20.0))
        laps = int(rng.integers(2, 5))
        text = (f"G21 G61 G17\nG0 X0 Y0\nG1 X{r:.3f} F{feed:.0f}\n" + f"G2 X{r:.3f} Y0 I{-r:.3f} J0\n" * laps
                + "M30\n")
        program = f"{laps} circles r {r:.1f} F{feed:.0f}"
    else:
        n, span = int(rng.integers(12, 50)), float(rng.choice([1.0, 3.0, 10.0, 30.0]))
        n *= 1 + int(rng.random() < 0.3)
        text = toolpaths.random_moves(n, span, round(feed), seed=int(rng.integers(1 << 30)), axes=(axis,))
        program = f"{n} moves +/-{span:g} F{feed:.0f}"
    k = int(rng.choice([0, 1, 1, 2]))
    effects = {}
    for e in rng.permutation(list(EFFECT_NAMES))[:k]:
        effects[str(e)] = draw_effect(rng, str(e))
    st = m.sample_time
    steps = [s for s in (1, 2, 4, 8, 16, 32) if 0.25e-3 - 1e-12 <= s * st <= 8e-3 + 1e-12]
    return {
        "index": index, "machine": name, "axis": axis, "text": text, "program": program, "effects": effects,
        "noise_um": float(rng.choice([0.0, 0.1, 0.3, 1.0])),
        "encoder_um": float(rng.choice([0.0, 0.05, 0.25, 1.0, 2.0])),
        "step": int(rng.choice(steps)) if rng.random() < 0.5 else 1,
        "offset_mm": float(rng.uniform(-5, 5)) if rng.random() < 0.3 else 0.0,
        "shift": int(rng.integers(-3, 4)) if rng.random() < 0.3 else 0,
        "cut": float(rng.uniform(0.5, 0.95)) if rng.random() < 0.3 else 1.0,
        "sim_seed": int(rng.integers(1 << 20)),
    }


def _record(case: dict, cap) -> vcnc.Capture:
    """The axis' commanded and measured positions under the case's record conditions."""
    i = cap.axis_index(case["axis"])
    ref, meas, t = cap.reference[:, i], cap.measured[:, i], cap.t
    sh, s = case["shift"], case["step"]
    if sh > 0:  # the reference logged sh samples late
        ref = np.concatenate([np.full(sh, ref[0]), ref[:-sh]])
    elif sh < 0:
        ref = np.concatenate([ref[-sh:], np.full(-sh, ref[-1])])
    ref, meas, t = ref[::s], meas[::s] + case["offset_mm"], t[::s]
    n = max(int(case["cut"] * t.size), 2)
    return vcnc.Capture(t=t[:n], axes=(case["axis"],), reference=ref[:n, None], measured=meas[:n, None])


def unstable_delay(case: dict) -> str | None:
    """Why the case's ``delay`` makes the truth's sampled linear loop unstable, else None.

    Two samples take fadal-ppi and fadal-smc (|z| = 1.008 and 1.004 at 65 Hz) and chevalier-pdf (1.017 at
    160 Hz) past the unit circle: the truth then limit-cycles at that frequency, held only by its current
    limit (seed 12 case 70: 31 um at 65.6 Hz, 3 % of the samples saturated, none without the delay). That is
    an unstable machine, not a loop delay a linear model with a delay element can reproduce. A case's
    ``resonance`` is in the loop checked (:meth:`vcnc.engine.axis.AxisDefinition.sampled_loop`, as
    :meth:`vcnc.Machine.unstable_axes` checks it): seed 31 case 42 (ballscrew-zpetc, 2 samples and an 84.7 Hz
    mode) limit-cycled at 1.6 mm peak to peak where the rigid loop with the delay alone is stable (|z| = 0.962).
    """
    if "delay" not in case["effects"]:
        return None
    m = vcnc.machine(case["machine"]).with_effect(case["axis"], "delay", case["effects"]["delay"])
    if "resonance" in case["effects"]:
        m = m.with_effect(case["axis"], "resonance", case["effects"]["resonance"])
    a = m.axis(case["axis"])
    g, _ = a.sampled_loop(m.sample_time)
    z = control.poles(g)
    k = int(np.argmax(np.abs(z)))
    if abs(z[k]) < 1.0:
        return None
    mode_note = " and its structural mode" if a.resonance is not None else ""
    return (f"the sampled loop with a {a.delay.samples}-sample delay{mode_note} is unstable (pole |z| = "
            f"{abs(z[k]):.4f} at {abs(np.angle(z[k])) / (2 * np.pi * m.sample_time):.0f} Hz): a limit cycle its "
            "current limit holds")


def build(case: dict):
    """(record with the effects, the same record without them, each effect's change of the noise-free
    measured position alone [um RMS], the noise floor: RMS of measured minus its noise-free value [um])."""
    ax = case["axis"]
    base = vcnc.machine(case["machine"]).with_axis_options(ax, noise=case["noise_um"] * 1e-3 or None,
                                                          encoder=case["encoder_um"] * 1e-3 or None)
    sp = vcnc.interpolate(vcnc.parse_program(case["text"]), base)
    m = base
    for e, p in case["effects"].items():
        m = m.with_effect(ax, e, p)
    cap = m.simulate(sp, seed=case["sim_seed"])
    clean = base.simulate(sp, seed=case["sim_seed"])
    i = cap.axis_index(ax)
    visible = {}
    for e, p in case["effects"].items():
        alone = base.with_effect(ax, e, p).simulate(sp, seed=case["sim_seed"])
        d = alone.measured[:, i] - clean.measured[:, i] if e == "drift" else (
            alone.aux["measured_true"][:, i] - clean.aux["measured_true"][:, i])
        visible[e] = float(np.sqrt(np.mean(d ** 2))) * 1e3
    floor = float(np.sqrt(np.mean((cap.measured[:, i] - cap.aux["measured_true"][:, i]) ** 2))) * 1e3
    return _record(case, cap), _record(case, clean), visible, floor


def _finite(obj) -> bool:
    if isinstance(obj, dict):
        return all(_finite(v) for v in obj.values())
    if isinstance(obj, (list, tuple)):
        return all(_finite(v) for v in obj)
    if isinstance(obj, (float, np.floating)):
        return math.isfinite(obj)
    return True


TRUTH = {  # effect -> (model parameter, its truth from the drawn parameters, relative tolerance)
    # backlash: the width trades off with the loop's own lag at reversals (test_diagnosis: 20 % on one capture)
    "backlash": ("width_mm", lambda p: p["width_mm"], 0.3),
    "position_periodic": ("period_mm", lambda p: p["period_mm"], 0.05),
    "time_periodic": ("period_s", lambda p: p["period_s"], 0.05),
    "drift": ("rate_mm_s", lambda p: -p["rate_mm_s"], 0.25),  # the table lags the drifting feedback
}


#: A named mode's frequency the record pins (:func:`mode_parameter_fails`) within this share of the truth's [-]: half a
#: step of the resonance search's log grid (12 frequencies over 20 Hz .. 0.45/T, a step of 1.33 at 1 ms,
#: ``identification.searches.search_resonance``), so that a refit which moved off its grid start toward the truth
#: passes and one left at a neighbouring grid frequency does not.
MODE_FREQUENCY_TOL = 0.15
#: A named mode's damping ratio within this factor of the truth's (either way) [-]: half a step, in log, of the
#: search's damping starts 0.04, 0.12, 0.3 (steps of 2.5 and 3) rounded up; a mode's damping is pinned by the
#: width of its peak, which a few seconds of motion resolve coarsely.
MODE_DAMPING_FACTOR = 2.0


def mode_parameter_fails(case: dict, record) -> list[str]:
    """The ``parameter`` failures of a named ``resonance`` (``record``, an ``EffectRecord``) against the case's mode.

    The frequency checked is the one the record pins (``identification.effects.Resonance``): measured at the motor,
    the anti-resonance f sqrt(1 - r) (the free-free f and the table share r trade off: seed 81 case 4,
    ballscrew-zpetc/x, truth 81.6 Hz with r 0.345, anti-resonance 66.0 Hz, was named 115.9 Hz with r 0.707,
    anti-resonance 62.7 Hz); measured at the table, f itself. The truth's side is the axis' feedback or its
    measurement at the table (``vcnc.engine.axis.AxisDefinition``)."""
    truth = case["effects"]["resonance"]
    m = vcnc.machine(case["machine"])
    for e, p in case["effects"].items():
        m = m.with_effect(case["axis"], e, p)
    a = m.axis(case["axis"])
    at_table = a.feedback == "table" or a.measurement == "table"
    f_true = truth["frequency_hz"] * (1.0 if at_table else math.sqrt(1.0 - truth["load_fraction"]))
    got = record.parameters
    f_got = got["frequency_hz"] if got["measured_at"] == "table" else got["antiresonance_hz"]
    kind = "frequency_hz" if at_table else "antiresonance_hz"
    out = []
    if abs(f_got - f_true) > MODE_FREQUENCY_TOL * f_true:
        out.append(f"parameter resonance.{kind} {f_got:.4g} vs {f_true:.4g} (named {got['frequency_hz']:.4g} Hz "
                   f"at the {got['measured_at']}, truth {truth['frequency_hz']:.4g} Hz at the "
                   f"{'table' if at_table else 'motor'})")
    ratio = got["damping"] / truth["damping"]
    if not 1.0 / MODE_DAMPING_FACTOR <= ratio <= MODE_DAMPING_FACTOR:
        out.append(f"parameter resonance.damping {got['damping']:.3g} vs {truth['damping']:.3g}")
    return out


def named_effects(model) -> list[str]:
    """Effects the model names, and ``drift`` when identify took a drift off before the fit (fit.drift)."""
    out = [e.name for e in model.effects]
    if (model.fit.get("drift") or {}).get("removed") and "drift" not in out:
        out.append("drift")
    return out


def shown_effects(case: dict, model, visible: dict, floor: float, clean_rms: float | None) -> dict:
    """The effects a diagnosis must name: each changes the noise-free measured position by more than 3 times
    the noise floor (+0.2 um), and together they leave the reduced model an error 1.5 times (+0.3 um) that of
    the same record without them (what the reduced model absorbs of an effect, e.g. of a delay, is no effect).
    A mode at or above the record's Nyquist frequency 1/(2T) is none: the record cannot show its frequency
    (Shannon 1949; the diagnosis refuses such a mode, ``diagnosis._unphysical_mode``), e.g. seed 31 case 28, a 90 Hz
    mode logged every 8 ms (62.5 Hz); nor is one below it by less than its decay rate 2 pi zeta f, whose ringing dies
    before the record tells it from the Nyquist alternation (``diagnosis.resolved_below_nyquist``; ident39), e.g.
    seed 51 case 6, 94.1 Hz at damping 0.093 logged every 4 ms (125 Hz)."""
    if clean_rms is None:
        return {}
    reduced = model.validation.get("identification_rms_before_um", model.fit.get("rms_um"))
    if not reduced > 1.5 * clean_rms + 0.3:
        return {}
    mode = case["effects"].get("resonance")
    aliased = mode is not None and not resolved_below_nyquist(mode["frequency_hz"], mode["damping"], model.sample_time)
    return {e: v for e, v in visible.items() if v > 3.0 * floor + 0.2 and not (e == "resonance" and aliased)}


def check(case: dict, model, shown: dict, floor: float) -> list[str]:
    out = []
    if not (_finite({**model.parameters, **model.poles}) and _finite(model.validation) and _finite(model.fit)):
        out.append("nonfinite")
    for k, (lo, hi) in model.bounds.items():
        v = model.poles.get(k)
        if v is None or not (lo * (1 - 1e-9) <= v <= hi * (1 + 1e-9)):
            out.append(f"pole {k}={v} outside ({lo}, {hi})")
    named = named_effects(model)
    val = model.validation
    before, after = val.get("rms_before_um", math.nan), val.get("rms_after_um", math.nan)
    if case["shift"] < 0 and named[:1] == ["delay"]:
        # a reference logged early is a dead time; below MIN_DELAY_SAMPLES (dead_time.py) identify leaves it to
        # the diagnosis' delay, as it cannot be told from an in-loop delay there
        named = named[1:]
    if not case["effects"]:
        if named:
            out.append(f"false_positive {named}")
        if after > 3.0 * floor + 1.0:
            out.append(f"high_residual {after:.2f} um (floor {floor:.2f})")
    for e in shown:
        if e not in named:
            out.append(f"missed {e} ({shown[e]:.1f} um)")
    top = max(shown, key=shown.get) if shown else None
    dominant = len(shown) == 1 or (len(shown) == 2 and max(shown.values()) > 2 * min(shown.values()))
    if top and dominant and top in named and named[0] != top:
        out.append(f"not_first {top}")
    if shown and model.effects and not after < before:
        out.append("no_gain")
    for e, p in case["effects"].items():
        if e in TRUTH and e in [r.name for r in model.effects]:
            key, f, tol = TRUTH[e]
            rec = next(r for r in model.effects if r.name == e)
            got = rec.parameters[key]
            if abs(got - f(p)) > tol * abs(f(p)) and key not in rec.unpinned:
                out.append(f"parameter {e}.{key} {got:.4g} vs {f(p):.4g}")
    mode = next((r for r in model.effects if r.name == "resonance"), None)
    if mode is not None and "resonance" in case["effects"]:
        out += mode_parameter_fails(case, mode)
    return out


def unpinned_notes(case: dict, model) -> list[str]:
    """The truth-checked parameters the model reports as not pinned by the record (``EffectRecord.unpinned``, e.g. a
    period the travel covers once): no failure, the report does not state them as measured."""
    return [f"unpinned {r.name}.{TRUTH[r.name][0]} {r.parameters[TRUTH[r.name][0]]:.4g} vs "
            f"{TRUTH[r.name][1](case['effects'][r.name]):.4g}" for r in model.effects
            if r.name in TRUTH and r.name in case["effects"] and TRUTH[r.name][0] in r.unpinned]


def run(case: dict) -> dict:
    t0 = time.process_time()
    row = {"case": case, "outcome": "ok", "detail": "", "cpu_s": 0.0, "named": []}
    try:
        unstable = unstable_delay(case)
        if unstable:  # known before the two simulations of build
            row.update(outcome="skip", detail=unstable)
            return row
        rec, clean, visible, floor = build(case)
    except (MachineError, SimulationError) as exc:  # an effect the machine cannot take, or an unstable truth
        row.update(outcome="skip", detail=str(exc))
        return row
    row["visible"], row["floor"] = visible, floor
    try:
        model = identify(rec, axis=case["axis"])
    except IdentificationError as exc:
        row.update(outcome="refused", detail=str(exc).splitlines()[0][:160])
    except Exception:  # noqa: BLE001 - the runner reports every other exception as a failure
        row.update(outcome="traceback", detail=traceback.format_exc().strip().splitlines()[-1][:160])
    else:
        clean_rms = None
        if case["effects"]:
            try:
                clean_rms = identify(clean, axis=case["axis"], diagnose=False).fit["rms_um"]
            except IdentificationError:
                pass
        row["named"] = named_effects(model)
        row["rms"] = (model.validation.get("rms_before_um"), model.validation.get("rms_after_um"))
        row["shown"] = shown_effects(case, model, visible, floor, clean_rms)
        fails = check(case, model, row["shown"], floor)
        if fails:
            row.update(outcome=fails[0].split()[0], detail="; ".join(fails))
        row["detail"] = "; ".join(filter(None, [row["detail"], *unpinned_notes(case, model)]))
    row["cpu_s"] = time.process_time() - t0
    return row


def describe(case: dict) -> str:
    cond = [f"T x{case['step']}" if case["step"] > 1 else "",
            f"off {case['offset_mm']:.2f}" if case["offset_mm"] else "",
            f"shift {case['shift']}" if case["shift"] else "", f"cut {case['cut']:.2f}" if case["cut"] < 1 else ""]
    eff = ",".join(f"{e}({', '.join(f'{k}={v:.3g}' if isinstance(v, float) else f'{k}={v}' for k, v in p.items())})"
                   for e, p in case["effects"].items()) or "-"
    return (f"{case['machine']}/{case['axis']} {case['program']}; noise {case['noise_um']} um enc "
            f"{case['encoder_um']} um; {' '.join(c for c in cond if c) or 'plain'}; {eff}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=40)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--start", type=int, default=0)
    ap.add_argument("--only", type=int, nargs="*", help="run these case indices only")
    args = ap.parse_args()
    indices = args.only if args.only else range(args.start, args.start + args.cases)
    counts: dict[str, int] = {}
    total = 0.0
    for i in indices:
        row = run(draw_case(args.seed, i))
        counts[row["outcome"]] = counts.get(row["outcome"], 0) + 1
        total += row["cpu_s"]
        shown = row.get("shown", {})
        vis = " ".join(f"{e}:{v:.1f}{'*' if e in shown else ''}" for e, v in row.get("visible", {}).items())
        rms = row.get("rms")
        rms_s = f"{rms[0]:.2f}->{rms[1]:.2f}" if rms else "-"
        print(f"{i:4d} {row['outcome']:<14} {row['cpu_s']:6.1f}s floor {row.get('floor', math.nan):.2f} "
              f"held-out {rms_s} named {row['named'] or '-'} visible[{vis}] | {describe(row['case'])}"
              + (f"\n       {row['detail']}" if row["detail"] else ""), flush=True)
    n = sum(counts.values())
    print(f"\n{n} cases, {total:.0f} s CPU ({total / max(n, 1):.1f} s/case): "
          + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))


if __name__ == "__main__":
    main()
