"""Sweep specification (TOML): parsing, strict validation and expansion into points.

Schema (also in ``docs/sweep.md``)::

    [sweep]
    mode = "grid"            # "grid": every combination; "random": n points drawn with seed
    n = 50                   # random mode only: number of points drawn
    seed = 0                 # random mode only: seed of the sampler
    axis = "x"               # axis that gets the effect and is identified
    profile = "trapezoid"    # feed profile: "trapezoid" or "scurve"

    [parameters]             # each: one value, a list of values, or a range table
    machine = ["fadal-pid"]  # built-in names or machine TOML files (relative to this file)
    toolpath = ["circle", "diamond"]   # circle | diamond | identification | a program file
    feed = {min = 3000, max = 12000, num = 4}   # [mm/min]; not used by program files
    gain = [0.8, 1.0, 1.25]  # scale of the controller's feedback gains [-]
    noise = [0, 1e-4]        # measurement noise std on every axis [mm] (0: none); absent: the machine's
    effect = ["none", "backlash"]      # diagnosis vocabulary (vcnc.engine.machine.EFFECTS) or "none"
    magnitude = [0.005, 0.02]          # size of the effect's main parameter (unit per effect)
    seed = {min = 0, max = 9, num = 10}  # seed of the simulated measurement noise

    [toolpath]               # geometry of the generated programs (not swept)
    radius = 10.0            # circle [mm]
    side = 20.0              # diamond [mm]
    moves = 200              # identification: number of random moves
    span = 10.0              # identification: targets within +/- span [mm]

    [outputs]
    identify = false         # identify the axis and record the identification error
    diagnose = false         # also run the residual diagnosis (needs identify)
    method = "exact"         # identification solver: exact | ga | kkt

A range table has ``min``, ``max``, optionally ``num`` (number of values, needed in grid mode)
and ``log`` (geometric spacing / log-uniform draws). In random mode a range without ``num`` is
drawn continuously (integers for ``seed``), with ``num`` from its ``num`` grid values; lists are
drawn from uniformly. Draws that repeat a point are merged, so a random sweep may have fewer than
``n`` points.

The main parameter that ``magnitude`` sets, per effect (:data:`MAGNITUDE_KEYS`): backlash width
[mm], friction_stribeck static/Coulomb ratio [-], friction_viscous_asymmetric asymmetry [-],
position_periodic and time_periodic force amplitude [N], resonance load fraction [-], delay
[samples], saturation voltage limit [V], drift rate [mm/s]. Without ``magnitude`` the effect gets
the realistic default of :func:`vcnc.engine.machine.realistic_effect`.

Each point has a stable id: a hash of everything that determines its result (parameters,
toolpath geometry, outputs, and the content of machine and program files). Points that come out
identical (e.g. ``magnitude`` with ``effect = "none"``, ``feed`` with a program file) are merged.
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import json
import math
import os
import re
import tomllib
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from drives.effects import EFFECTS as EFFECT_REGISTRY
from vcnc.core.errors import InputError
from vcnc.core.text import BinaryDataError, decode_text

__all__ = [
    "SweepSpec",
    "load_spec",
    "parse_spec",
    "MODES",
    "PARAMETERS",
    "BUILTIN_TOOLPATHS",
    "MAGNITUDE_KEYS",
    "point_id",
]

MODES: tuple[str, ...] = ("grid", "random")
BUILTIN_TOOLPATHS: tuple[str, ...] = ("circle", "diamond", "identification")
PROFILES: tuple[str, ...] = ("trapezoid", "scurve")
METHODS: tuple[str, ...] = ("exact", "ga", "kkt")

#: effect -> the parameter of :func:`vcnc.engine.machine.realistic_effect` that ``magnitude`` sets
#: (the registry :mod:`drives.effects`)
MAGNITUDE_KEYS: dict[str, str] = {name: info.magnitude for name, info in EFFECT_REGISTRY.items()}


@dataclasses.dataclass(frozen=True)
class _Param:
    kind: str  # "str", "float", "int"
    unit: str
    minimum: float | None = None  # inclusive lower bound
    positive: bool = False  # strictly > 0


#: swept parameter -> its type, unit and bounds; order is the column order of the results
PARAMETERS: dict[str, _Param] = {
    "machine": _Param("str", ""),
    "toolpath": _Param("str", ""),
    "feed": _Param("float", "mm/min", positive=True),
    "gain": _Param("float", "-", positive=True),
    "noise": _Param("float", "mm", minimum=0.0),
    "effect": _Param("str", ""),
    "magnitude": _Param("float", "unit of the effect", minimum=0.0),
    "seed": _Param("int", "-", minimum=0),
}
_DEFAULTS: dict[str, Any] = {
    "machine": "fadal-pid",
    "toolpath": "circle",
    "feed": 6000.0,
    "gain": 1.0,
    "noise": None,
    "effect": "none",
    "magnitude": None,
    "seed": 0,
}
_SWEEP_KEYS = {"mode", "n", "seed", "axis", "profile"}
_TOOLPATH_DEFAULTS: dict[str, float | int] = {"radius": 10.0, "side": 20.0, "moves": 200, "span": 10.0}
_OUTPUT_DEFAULTS: dict[str, Any] = {"identify": False, "diagnose": False, "method": "exact"}
_RANGE_KEYS = {"min", "max", "num", "log"}


@dataclasses.dataclass(frozen=True, kw_only=True)
class SweepSpec:
    """A validated sweep: how to sample, what to vary and what to measure.

    Attributes
    ----------
    mode : {"grid", "random"}
    n : int or None
        Random mode: points drawn.
    seed : int
        Random mode: seed of the sampler.
    axis : str
        Axis that gets the effect and is identified.
    profile : {"trapezoid", "scurve"}
    parameters : dict
        Parameter name -> list of values (grid/list) or a range dict (``min``, ``max``, ``num``,
        ``log``), already checked.
    toolpath : dict
        ``radius`` [mm], ``side`` [mm], ``moves``, ``span`` [mm].
    outputs : dict
        ``identify``, ``diagnose``, ``method``.
    source : str or None
        The spec file.
    base_dir : str
        Directory against which relative machine and program paths resolve.
    """

    mode: str = "grid"
    n: int | None = None
    seed: int = 0
    axis: str = "x"
    profile: str = "trapezoid"
    parameters: dict = dataclasses.field(default_factory=dict)
    toolpath: dict = dataclasses.field(default_factory=lambda: dict(_TOOLPATH_DEFAULTS))
    outputs: dict = dataclasses.field(default_factory=lambda: dict(_OUTPUT_DEFAULTS))
    source: str | None = None
    base_dir: str = "."

    def points(self) -> list[dict[str, Any]]:
        """The points of the sweep, each a task dict with a stable ``id`` (duplicates merged).

        Machine and program files are read here (so workers elsewhere need only the machine
        path and receive the program text); a missing file is an InputError naming the spec key.
        """
        combos = self._combinations()
        files = _FileCache(self)
        out: dict[str, dict[str, Any]] = {}
        for combo in combos:
            task = self._task(combo, files)
            out.setdefault(task["id"], task)
        self._check_machines({t["machine"]: t["machine_ref"] for t in out.values()}, files)
        return list(out.values())

    # ------------------------------------------------------------------ internals
    def _values(self, name: str) -> list[Any]:
        v = self.parameters.get(name, [_DEFAULTS[name]])
        if isinstance(v, dict):
            return _range_values(name, v)
        return list(v)

    def _combinations(self) -> list[dict[str, Any]]:
        names = list(PARAMETERS)
        if self.mode == "grid":
            grids = [self._values(n) for n in names]
            return [dict(zip(names, c)) for c in itertools.product(*grids)]
        rng = np.random.default_rng(self.seed)
        combos = []
        for _ in range(int(self.n or 0)):
            combo = {}
            for name in names:
                v = self.parameters.get(name, [_DEFAULTS[name]])
                if isinstance(v, dict) and v.get("num") is None:
                    combo[name] = _draw(name, v, rng)
                else:
                    vals = _range_values(name, v) if isinstance(v, dict) else v
                    combo[name] = vals[int(rng.integers(len(vals)))]
            combos.append(combo)
        return combos

    def _check_machines(self, machines: Mapping[str, str], files: _FileCache) -> None:
        # a bad machine is bad input of the whole sweep: found here, not once per point on a worker
        from vcnc.engine.machine import load_machine

        for name, ref in machines.items():
            try:
                m = load_machine(ref)
            except InputError as exc:
                raise files._fail("machine", f"{name!r}: {exc}") from None
            if self.axis not in m.axes:
                raise InputError(
                    f"[sweep] axis: machine {name!r} has no axis {self.axis!r} (axes: {', '.join(m.axes)})",
                    file=self.source, line=_find_line(self.source, "sweep", "axis"),
                )

    def _task(self, combo: dict[str, Any], files: _FileCache) -> dict[str, Any]:
        p = dict(combo)
        toolpath = p["toolpath"]
        program_text = None
        digests: dict[str, str] = {}
        if toolpath not in BUILTIN_TOOLPATHS:
            path, program_text = files.program(toolpath)
            digests["program"] = hashlib.sha256(program_text.encode()).hexdigest()
            p["feed"] = None  # the program's own F words apply
        machine = p["machine"]
        machine_ref = machine
        if _looks_like_path(machine):
            machine_ref, digest = files.machine(machine)
            digests["machine"] = digest
        if p["effect"] == "none":
            p["magnitude"] = None
        if p["feed"] is not None:
            p["feed"] = _canon(p["feed"])
        for k in ("gain", "noise", "magnitude"):
            if p[k] is not None:
                p[k] = _canon(p[k])
        p["seed"] = int(p["seed"])
        task = {
            **p,
            "axis": self.axis,
            "profile": self.profile,
            "geometry": dict(self.toolpath),
            "outputs": dict(self.outputs),
        }
        task["id"] = point_id(task, digests)
        task["machine_ref"] = machine_ref
        task["machine_digest"] = digests.get("machine")  # workers cache machines by path and content
        task["program_text"] = program_text
        return task


def point_id(task: Mapping[str, Any], digests: Mapping[str, str] | None = None) -> str:
    """Stable 16-hex-digit id of a point: a SHA-256 of what determines its result."""
    keys = [*PARAMETERS, "axis", "profile", "geometry", "outputs"]
    payload = {k: task.get(k) for k in keys}
    payload["files"] = dict(digests or {})
    payload["format"] = 1
    text = json.dumps(payload, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _canon(v: float) -> float:
    # 12 significant digits: ids do not change with the last bits of linspace/geomspace
    return float(f"{float(v):.12g}")


def _looks_like_path(s: str) -> bool:
    return s.lower().endswith(".toml") or os.sep in s or "/" in s


class _FileCache:
    """Reads machine and program files named in the spec once, with errors naming the key."""

    def __init__(self, spec: SweepSpec) -> None:
        self.spec = spec
        self._programs: dict[str, tuple[str, str]] = {}
        self._machines: dict[str, tuple[str, str]] = {}

    def _resolve(self, name: str) -> Path:
        p = Path(name).expanduser()
        return p if p.is_absolute() else Path(self.spec.base_dir) / p

    def _fail(self, key: str, message: str) -> InputError:
        return InputError(f"[parameters] {key}: {message}", file=self.spec.source,
                          line=_find_line(self.spec.source, "parameters", key))

    def program(self, name: str) -> tuple[str, str]:
        if name not in self._programs:
            p = self._resolve(name)
            try:
                raw = p.read_bytes()
            except OSError as exc:
                raise self._fail(
                    "toolpath",
                    f"{name!r} is neither one of {', '.join(BUILTIN_TOOLPATHS)} nor a readable program file "
                    f"({getattr(exc, 'strerror', None) or exc})",
                ) from None
            try:
                text = decode_text(raw)  # as interpolators.load_program decodes a program
            except BinaryDataError as exc:
                raise self._fail("toolpath", f"{name!r} is no program file: {exc}") from None
            self._programs[name] = (str(p.resolve()), text)
        return self._programs[name]

    def machine(self, name: str) -> tuple[str, str]:
        if name not in self._machines:
            p = self._resolve(name)
            try:
                data = p.read_bytes()
            except OSError as exc:
                raise self._fail("machine", f"cannot read machine file {name!r} ({exc.strerror or exc})") from None
            self._machines[name] = (str(p.resolve()), hashlib.sha256(data).hexdigest())
        return self._machines[name]


# ---------------------------------------------------------------------- parsing
def load_spec(path: str | os.PathLike[str]) -> SweepSpec:
    """Read and validate a sweep spec file; InputError naming the file, line and key at fault."""
    p = Path(path)
    try:
        text = p.read_text()
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read sweep spec ({getattr(exc, 'strerror', None) or exc})", file=str(p)) from None
    return parse_spec(text, file=str(p), base_dir=str(p.parent))


def parse_spec(text: str, *, file: str | None = None, base_dir: str = ".") -> SweepSpec:
    """Validate the TOML text of a sweep spec (schema in the module docstring).

    Raises
    ------
    InputError
        TOML syntax (with its line), unknown tables or keys, wrong types, values out of range,
        unknown effect or toolpath names, a grid range without ``num``, a random sweep without
        ``n``. The message names the file, the line and ``[table] key``.
    """
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        raise InputError(f"not valid TOML: {exc}", file=file, line=int(m.group(1)) if m else None) from None
    v = _Validator(text, file)
    v.only_keys("", doc, {"sweep", "parameters", "toolpath", "outputs"})
    sweep = v.table(doc, "sweep")
    params = v.table(doc, "parameters")
    tp = v.table(doc, "toolpath")
    outs = v.table(doc, "outputs")

    v.only_keys("sweep", sweep, _SWEEP_KEYS)
    mode = v.choice("sweep", "mode", sweep.get("mode", "grid"), MODES)
    n = sweep.get("n")
    if mode == "random":
        if n is None:
            raise v.fail("sweep", "n", "a random sweep needs n, the number of points to draw")
        v.integer("sweep", "n", n, minimum=1)
    elif n is not None:
        raise v.fail("sweep", "n", "n is only for mode = \"random\"; a grid takes every combination")
    seed = v.integer("sweep", "seed", sweep.get("seed", 0), minimum=0)
    axis = v.string("sweep", "axis", sweep.get("axis", "x"))
    from vcnc.core.setpoints import AXIS_NAMES

    v.choice("sweep", "axis", axis, tuple(AXIS_NAMES))
    profile = v.choice("sweep", "profile", sweep.get("profile", "trapezoid"), PROFILES)

    v.only_keys("parameters", params, set(PARAMETERS))
    checked: dict[str, Any] = {}
    for name, value in params.items():
        checked[name] = v.parameter(name, value, mode)

    v.only_keys("toolpath", tp, set(_TOOLPATH_DEFAULTS))
    geometry = dict(_TOOLPATH_DEFAULTS)
    for k, val in tp.items():
        if k == "moves":
            geometry[k] = v.integer("toolpath", k, val, minimum=1)
        else:
            geometry[k] = v.number("toolpath", k, val, positive=True)

    v.only_keys("outputs", outs, set(_OUTPUT_DEFAULTS))
    outputs = dict(_OUTPUT_DEFAULTS)
    for k in ("identify", "diagnose"):
        if k in outs:
            outputs[k] = v.boolean("outputs", k, outs[k])
    if "method" in outs:
        outputs["method"] = v.choice("outputs", "method", outs["method"], METHODS)
    if outputs["diagnose"] and not outputs["identify"]:
        raise v.fail("outputs", "diagnose", "diagnose = true needs identify = true")
    return SweepSpec(
        mode=mode,
        n=None if n is None else int(n),
        seed=seed,
        axis=axis,
        profile=profile,
        parameters=checked,
        toolpath=geometry,
        outputs=outputs,
        source=file,
        base_dir=base_dir,
    )


def _find_line(file: str | None, table: str, key: str | None, text: str | None = None) -> int | None:
    """1-based line of ``key`` inside ``[table]`` (or of the table header when key is None)."""
    if text is None:
        if file is None:
            return None
        try:
            text = Path(file).read_text()
        except (OSError, UnicodeDecodeError):
            return None
    current = ""
    header_line = None
    for i, raw in enumerate(text.splitlines(), start=1):
        s = raw.split("#", 1)[0].strip()
        m = re.fullmatch(r"\[\s*([A-Za-z0-9_.\-\"]+)\s*\]", s)
        if m:
            current = m.group(1).strip('"')
            if current == table and key is None:
                return i
            if not table and key is not None and current.split(".")[0] == key:
                return i  # a top-level key given as a table
            if current == table:
                header_line = i
            continue
        if key is not None and current == table and re.match(rf"\"?{re.escape(key)}\"?\s*=", s):
            return i
    return header_line


class _Validator:
    def __init__(self, text: str, file: str | None) -> None:
        self.text = text
        self.file = file

    def fail(self, table: str, key: str | None, message: str, value: Any = None) -> InputError:
        where = f"[{table}] {key}" if table and key else (f"[{table}]" if table else str(key))
        got = "" if value is None else f" (got {value!r})"
        return InputError(f"{where}: {message}{got}", file=self.file,
                          line=_find_line(None, table, key, self.text))

    def table(self, doc: dict, name: str) -> dict:
        t = doc.get(name, {})
        if not isinstance(t, dict):
            raise self.fail("", name, f"{name} must be a table [{name}]", t)
        return t

    def only_keys(self, table: str, t: dict, allowed: set[str]) -> None:
        for k in t:
            if k not in allowed:
                what = "table" if not table else "key"
                raise self.fail(table, k, f"unknown {what}; expected one of {', '.join(sorted(allowed))}")

    def choice(self, table: str, key: str, value: Any, allowed: Sequence[str]) -> str:
        if not isinstance(value, str) or value not in allowed:
            raise self.fail(table, key, f"expected one of {', '.join(allowed)}", value)
        return value

    def string(self, table: str, key: str, value: Any) -> str:
        if not isinstance(value, str) or not value:
            raise self.fail(table, key, "expected a non-empty string", value)
        return value

    def boolean(self, table: str, key: str, value: Any) -> bool:
        if not isinstance(value, bool):
            raise self.fail(table, key, "expected true or false", value)
        return value

    def integer(self, table: str, key: str, value: Any, *, minimum: int | None = None) -> int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(table, key, "expected an integer", value)
        if minimum is not None and value < minimum:
            raise self.fail(table, key, f"expected an integer >= {minimum}", value)
        return value

    def number(self, table: str, key: str, value: Any, *, positive: bool = False, minimum: float | None = None,
               unit: str = "") -> float:
        u = f" [{unit}]" if unit else ""
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise self.fail(table, key, f"expected a finite number{u}", value)
        if positive and not value > 0:
            raise self.fail(table, key, f"expected a number > 0{u}", value)
        if minimum is not None and value < minimum:
            raise self.fail(table, key, f"expected a number >= {minimum:g}{u}", value)
        return float(value)

    def _scalar(self, name: str, value: Any) -> Any:
        spec = PARAMETERS[name]
        if spec.kind == "str":
            s = self.string("parameters", name, value)
            if name == "effect":
                from vcnc.engine.machine import EFFECTS

                self.choice("parameters", name, s, ("none", *EFFECTS))
            return s
        if spec.kind == "int":
            return self.integer("parameters", name, value, minimum=int(spec.minimum or 0))
        return self.number("parameters", name, value, positive=spec.positive, minimum=spec.minimum, unit=spec.unit)

    def parameter(self, name: str, value: Any, mode: str) -> list[Any] | dict[str, Any]:
        if isinstance(value, dict):
            return self._range(name, value, mode)
        values = value if isinstance(value, list) else [value]
        if not values:
            raise self.fail("parameters", name, "expected at least one value")
        return [self._scalar(name, x) for x in values]

    def _range(self, name: str, r: dict, mode: str) -> dict[str, Any]:
        spec = PARAMETERS[name]
        if spec.kind == "str":
            raise self.fail("parameters", name, "a text parameter takes a value or a list, not a range table")
        for k in r:
            if k not in _RANGE_KEYS:
                raise self.fail("parameters", name, f"unknown range key {k!r}; expected min, max, num, log")
        if "min" not in r or "max" not in r:
            raise self.fail("parameters", name, "a range table needs min and max")
        lo, hi = self._scalar(name, r["min"]), self._scalar(name, r["max"])
        if hi < lo:
            raise self.fail("parameters", name, f"range max ({hi}) is below min ({lo})")
        num = r.get("num")
        if num is not None:
            self.integer("parameters", f"{name}.num", num, minimum=1)
        elif mode == "grid":
            raise self.fail("parameters", name, "a range in a grid sweep needs num (the number of values)")
        log = self.boolean("parameters", f"{name}.log", r.get("log", False))
        if log and not lo > 0:
            raise self.fail("parameters", name, "a log range needs min > 0", lo)
        return {"min": lo, "max": hi, "num": num, "log": log}


def _range_values(name: str, r: Mapping[str, Any]) -> list[Any]:
    lo, hi, num = r["min"], r["max"], int(r["num"])
    vals = np.geomspace(lo, hi, num) if r["log"] else np.linspace(lo, hi, num)
    if PARAMETERS[name].kind == "int":
        return sorted({int(round(x)) for x in vals})
    return [float(x) for x in vals]


def _draw(name: str, r: Mapping[str, Any], rng: np.random.Generator) -> Any:
    lo, hi = r["min"], r["max"]
    if PARAMETERS[name].kind == "int":
        return int(rng.integers(lo, hi + 1))
    if r["log"]:
        return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))
    return float(rng.uniform(lo, hi))
