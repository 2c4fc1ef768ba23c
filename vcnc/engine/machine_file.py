"""Machine definition files (TOML): schema check with file and line in every message.

Layout::

    name = "my-mill"              # optional, defaults to the file name
    description = "..."
    sample_time = 0.001           # s

    [axes.x]
    feedback = "motor"            # or "table"
    measurement = "feedback"      # or "table": captures record a linear scale on the table
    substeps = 1
    wrap = false                  # a, b, c only: true for a rotary axis that wraps at 360 deg (modulo, roll-over)
    [axes.x.limits]               # velocity mm/s, acceleration mm/s^2, jerk mm/s^3, rapid mm/s
    [axes.x.drive]                # type = "ballscrew" | "linear" | "discrete", then its fields
    [axes.x.controller]           # type = "pid" | "ppi" | "smc" | "ppc" | "pdf", then its fields, and
                                  #   anti_windup = true (default) | false: the bare law, which winds up
    [axes.x.friction]             # optional non-idealities, one table each:
    [axes.x.backlash]             #   friction backlash encoder dac saturation noise delay
    ...                           #   resonance position_periodic load drift

    [program]                     # optional machine context of part programs (defaults change nothing)
    dialect = "linuxcnc"          # linuxcnc | fanuc | haas | grbl | fadal: unit of G04 P (s | ms)
    default_units = "mm"          # units of a program without G20/G21 (mm | inch)
    continuous_path = true        # path mode of a program without G61/G64
    tolerance = 0.01              # mm, path tolerance of that mode (optional)
    home = [0.0, 0.0, 0.0]        # mm, machine coordinates: program start and G28
    reference2 = [0.0, 0.0, 0.0]  # mm, machine coordinates: G30
    linear_units = "mm"           # mm | inch: the unit the stored offsets read in (#5221.., LinuxCNC's INI unit)
    decimal_point_input = "calculator"  # calculator | increment: Fanuc DPI (No. 3401#0) = 1 | 0, X10 = 10 | 0.010 mm
    tool_offset_memory = "C"      # A | B | C: Fanuc tool compensation memory (G10 L10-L13, #2001.., #10001..)
    tool_table = "tools.tbl"      # optional LinuxCNC tool table (T1 P1 D6.0 Z+12.5) or Heidenhain TOOL.T
    datum_table = "ZEROSHIFT.D"   # optional Heidenhain datum table (D X Y Z): the rows of CYCL DEF 7.1 #n
    subroutine_path = ["subs"]    # optional folders searched for o<name> subroutine files (LinuxCNC SUBROUTINE_PATH)
    user_m_path = ["mfiles"]      # optional folders holding the M100-M199 user programs (LinuxCNC USER_M_PATH)
    initial_feed = 500.0          # optional mm/min: feed of a feed move before any F (Fanuc No. 1411); unset: an error
    wrap_direction = "sign"       # optional: absolute moves of the wrap = true axes: sign (LinuxCNC; Fanuc RAB=1) |
                                  #   shortest (Fanuc RAB=0; TNC M126) | difference (TNC); unset: the control's own
    peck_tapping = "high-speed"   # optional, fanuc: M29 .. G84 Q (peck rigid tapping): high-speed (PCP=0, back by d)
    peck_tapping_d = 1.0          #   | standard (PCP=1, back to R, in to d above the cut); d [mm], No. 5213; unset:
                                  #   such a block is refused (set both or neither)
    [program.work_offsets]        # mm: G54 = [x, y, z], ... G59.3, "G54.1 P1" .. "G54.1 P300", Fadal E7 .. E48
                                  #   (Haas "G154 P1" .. "G154 P99", G110 .. G129: the same entries)
    [program.tools.1]             # mm: length = 12.5, radius = 3.0, offset_x/offset_y = 0 (per tool number),
                                  #   name = "MILL_D6" (Heidenhain TOOL CALL "MILL_D6"), point_angle = 118.0
                                  #   (deg, a drill's T-ANGLE: TNC cycles 200/203/205 Q395=1, 240 Q343=1)
    [program.touch_probe]         # optional Heidenhain touch probe table row (TCH PROBE cycles), its defaults:
    set_up = 2.0                  # mm, SET_UP safety clearance; feed = 100.0, fmax = 2000.0 mm/min (F, FMAX);
                                  #   dist = 20.0 mm (DIST); tip_radius [mm] (unset: the probe tool's radius)
    [program.kinematics]          # optional: the rotary axes that tilt the part (tilted plane, TCP)
    kind = "table"                # table (trunnion) | head (a tilted plane is then an error)
    [[program.kinematics.axes]]   # the outer (tilting) axis first, then the one it carries (the part's), or one
    name = "b"                    # a | b | c: one of this file's [axes.a] .. [axes.c]
    direction = "Y"               # X | Y | Z | -X | -Y | -Z: the machine axis it turns about
    pivot = [0.0, 0.0, -50.0]     # mm, a point of its axis of rotation (machine, every rotary axis at 0)
    limits = [-5.0, 110.0]        # deg, lowest and highest angle

or, for an axis simulated by an FMU: ``[axes.x] fmu = "drive.fmu"`` (with ``[axes.x.limits]``).
Field names and units are those of the ``drives`` and ``controllers`` records.
"""

from __future__ import annotations

import dataclasses
import math
import re
import tomllib
import typing
from pathlib import Path
from typing import Any

import controllers
import drives
from interpolators.context import (
    DIALECTS,
    PECK_TAPPING,
    TOOL_OFFSET_MEMORIES,
    Dialect,
    MachineContext,
    Tool,
    TouchProbe,
    read_datum_table,
    read_tool_table,
    work_offset_code,
)
from interpolators.limits import AxisLimits
from interpolators.rotary_wrap import ROTARY_AXES, WRAP_DIRECTIONS
from interpolators.tilted import Kinematics, RotaryAxis
from vcnc.core.axes import EXTRA_NAMES
from vcnc.core.errors import InputError, MachineError
from vcnc.core.setpoints import AXIS_NAMES
from vcnc.engine.axis import NONIDEALITY_FIELDS, AxisDefinition
from vcnc.engine.plausibility import plausibility_warnings

__all__ = ["parse_machine_text", "MachineSpec", "LineIndex"]

_TOP_KEYS = {"name": "", "description": "", "sample_time": "s", "axes": "", "program": ""}
_PROGRAM_KEYS = ("dialect", "default_units", "continuous_path", "tolerance", "home", "reference2", "tool_table",
                 "datum_table", "work_offsets", "tools", "linear_units", "decimal_point_input", "tool_offset_memory",
                 "kinematics", "subroutine_path", "user_m_path", "initial_feed", "touch_probe",
                 "wrap_direction", "length_offset_motion", "peck_tapping", "peck_tapping_d")
_AXIS_KEYS = {"feedback", "measurement", "substeps", "fmu", "limits", "drive", "controller", "wrap",
              *NONIDEALITY_FIELDS}
_LIMIT_UNITS = {"velocity": "mm/s", "acceleration": "mm/s^2", "jerk": "mm/s^3", "rapid": "mm/s"}


@dataclasses.dataclass(frozen=True, kw_only=True)
class MachineSpec:
    """What a machine file defines (axes in file order; FMU axes as their file path)."""

    name: str
    description: str
    sample_time: float
    axes: dict[str, Any]
    limits: dict[str, AxisLimits]
    context: MachineContext = dataclasses.field(default_factory=MachineContext)
    #: values legal but implausible for a real machine, one sentence each (:mod:`vcnc.engine.plausibility`)
    warnings: tuple[str, ...] = ()


class LineIndex:
    """Line numbers of the keys and tables of a TOML text (for error messages)."""

    _HEADER = re.compile(r"^\s*\[\[?\s*([^\]]+?)\s*\]\]?\s*(#.*)?$")
    _KEY = re.compile(r"^\s*([A-Za-z0-9_\-\.\"' ]+?)\s*=")

    def __init__(self, text: str) -> None:
        self.lines: dict[tuple[str, ...], int] = {}
        table: tuple[str, ...] = ()
        for i, line in enumerate(text.splitlines(), start=1):
            m = self._HEADER.match(line)
            if m:
                table = self._split(m.group(1))
                self.lines.setdefault(table, i)
                continue
            m = self._KEY.match(line)
            if m:
                self.lines.setdefault(table + self._split(m.group(1)), i)

    @staticmethod
    def _split(dotted: str) -> tuple[str, ...]:
        return tuple(p.strip().strip("\"'") for p in dotted.split("."))

    def line(self, *path: str) -> int | None:
        """Line of ``path`` (a key or table), else of its nearest enclosing table."""
        p = tuple(path)
        while p:
            if p in self.lines:
                return self.lines[p]
            p = p[:-1]
        return None


def _type_name(ann: str) -> str:
    ann = ann.replace(" | None", "")
    return {"float": "a number", "int": "an integer", "str": "a string", "bool": "true or false"}.get(
        ann, "a list of numbers" if ann.startswith("tuple") else ann
    )


def _annotation(t: Any) -> str:
    return t if isinstance(t, str) else getattr(t, "__name__", str(t))


def _coerce(value: Any, ann: str) -> Any:
    """Value converted to the field type ``ann`` or raise TypeError."""
    base = ann.replace(" | None", "").strip()
    if base == "float":
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise TypeError
        return float(value)
    if base == "int":
        if isinstance(value, bool) or not isinstance(value, int):
            raise TypeError
        return value
    if base == "bool":
        if not isinstance(value, bool):
            raise TypeError
        return value
    if base == "str":
        if not isinstance(value, str):
            raise TypeError
        return value
    if base.startswith("tuple"):
        if not isinstance(value, list) or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in value
        ):
            raise TypeError
        return tuple(float(v) for v in value)
    return value


def _build(
    cls: type, table: dict[str, Any], path: tuple[str, ...], where: _Where, *, skip: tuple[str, ...] = ()
) -> Any:
    """Instantiate a record class from a TOML table: unknown/missing keys, types, values."""
    fields = {f.name: f for f in dataclasses.fields(cls)}
    units = getattr(cls, "UNITS", {})
    hints = {n: _annotation(f.type) for n, f in fields.items()}
    kwargs: dict[str, Any] = {}
    for key, value in table.items():
        if key in skip:
            continue
        if key not in fields:
            allowed = ", ".join(f"{k} [{units.get(k, '')}]" if units.get(k) else k for k in fields)
            what = getattr(cls, "TABLE", "") or cls.__name__
            raise where.error(f"unknown key '{'.'.join(path + (key,))}' for {what}; expected one of: {allowed}",
                              path + (key,))
        try:
            kwargs[key] = _coerce(value, hints[key])
        except TypeError:
            unit = f" [{units[key]}]" if units.get(key) else ""
            raise where.error(
                f"'{'.'.join(path + (key,))}'{unit} must be {_type_name(hints[key])}, "
                f"got {type(value).__name__} {value!r}",
                path + (key,),
            ) from None
    missing = [
        n
        for n, f in fields.items()
        if n not in kwargs
        and n not in skip
        and f.default is dataclasses.MISSING
        and f.default_factory is dataclasses.MISSING
    ]
    if missing:
        k = missing[0]
        unit = f" [{units[k]}]" if units.get(k) else ""
        raise where.error(f"missing key '{'.'.join(path + (k,))}'{unit} ({_type_name(hints[k])})", path)
    try:
        return cls(**kwargs)
    except InputError as exc:
        key = getattr(exc, "key", None)
        raise where.error(exc.message if exc.text is None else f"{exc.message} (got {exc.text})",
                          path + ((key,) if key else ())) from None


class _Where:
    def __init__(self, file: str, index: LineIndex) -> None:
        self.file = file
        self.index = index

    def error(self, message: str, path: tuple[str, ...]) -> MachineError:
        return MachineError(message, file=self.file, line=self.index.line(*path))


def parse_machine_text(text: str, *, file: str, default_name: str) -> MachineSpec:
    """Parse and check a machine definition; MachineError names the key, unit, file and line."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)(?:, column (\d+))?", str(exc))
        raise MachineError(
            f"not valid TOML: {exc}", file=file, line=int(m.group(1)) if m else None,
            column=int(m.group(2)) if m and m.group(2) else None,
        ) from None
    where = _Where(file, LineIndex(text))
    for key in data:
        if key not in _TOP_KEYS:
            raise where.error(f"unknown key '{key}'; expected one of: {', '.join(_TOP_KEYS)}", (key,))
    name = data.get("name", default_name)
    if not isinstance(name, str) or not name:
        raise where.error("'name' must be a non-empty string", ("name",))
    description = data.get("description", "")
    if not isinstance(description, str):
        raise where.error("'description' must be a string", ("description",))
    if "sample_time" not in data:
        raise where.error("missing key 'sample_time' [s] (the servo and interpolation period)", ())
    ts = data["sample_time"]
    if isinstance(ts, bool) or not isinstance(ts, (int, float)) or not (math.isfinite(ts) and 1e-6 <= ts <= 1.0):
        raise where.error(f"'sample_time' [s] must be a number in [1e-6, 1], got {ts!r}", ("sample_time",))
    axes_tab = data.get("axes")
    if not isinstance(axes_tab, dict) or not axes_tab:
        raise where.error("missing table [axes.<name>]: a machine needs at least one axis", ("axes",))
    axes: dict[str, Any] = {}
    limits: dict[str, AxisLimits] = {}
    wrapped: list[str] = []
    for a, tab in axes_tab.items():
        path = ("axes", a)
        if a not in AXIS_NAMES:
            raise where.error(f"unknown axis name '{a}'; expected one of {', '.join(AXIS_NAMES)}", path)
        if not isinstance(tab, dict):
            raise where.error(f"'axes.{a}' must be a table", path)
        for key in tab:
            if key not in _AXIS_KEYS:
                raise where.error(f"unknown key 'axes.{a}.{key}'; expected one of: {', '.join(sorted(_AXIS_KEYS))}",
                                  path + (key,))
        if "limits" not in tab or not isinstance(tab["limits"], dict):
            raise where.error(f"missing table [axes.{a}.limits] (velocity mm/s, acceleration mm/s^2, jerk mm/s^3)",
                              path)
        limits[a] = _build_limits(tab["limits"], path + ("limits",), where)
        if _wraps(a, tab, where):
            wrapped.append(a)
        if "fmu" in tab:
            extra = [k for k in tab if k not in ("fmu", "limits", "wrap")]
            if extra:
                raise where.error(f"axes.{a}.{extra[0]} cannot be combined with 'fmu' (the FMU is the whole axis)",
                                  path + (extra[0],))
            if not isinstance(tab["fmu"], str):
                raise where.error(f"'axes.{a}.fmu' must be a file path string", path + ("fmu",))
            fmu = Path(tab["fmu"])
            if not fmu.is_absolute() and file and not file.startswith("<"):
                fmu = Path(file).parent / fmu
            axes[a] = ("fmu", str(fmu), where.index.line(*path, "fmu"))
            continue
        for req in ("drive", "controller"):
            if req not in tab or not isinstance(tab[req], dict):
                raise where.error(f"missing table [axes.{a}.{req}]", path)
        drive = _build_typed(tab["drive"], drives.PLANTS, path + ("drive",), where)
        ctrl = _build_typed(tab["controller"], controllers.CONTROLLERS, path + ("controller",), where)
        kwargs: dict[str, Any] = {}
        for f in NONIDEALITY_FIELDS:
            if f in tab:
                if not isinstance(tab[f], dict):
                    raise where.error(f"'axes.{a}.{f}' must be a table", path + (f,))
                kwargs[f] = _build(drives.NONIDEALITIES[f if f != "load" else "load"], tab[f], path + (f,), where)
        for key in ("feedback", "measurement", "substeps"):
            if key in tab:
                kwargs[key] = tab[key]
        try:
            axes[a] = AxisDefinition(name=a, drive=drive, controller=ctrl, limits=limits[a], **kwargs)
        except InputError as exc:
            key = getattr(exc, "key", None)
            raise where.error(exc.message, path + ((key,) if key else ())) from None
    context = _build_context(data.get("program", {}), where, file)
    # the program may move the axes beyond X, Y, Z the machine has (a, b, c in degrees, u, v, w in mm), no others
    context = dataclasses.replace(context, extra_axes=tuple(a for a in EXTRA_NAMES if a in axes),
                                  wrapped_axes=tuple(wrapped))
    if context.kinematics is not None:
        for ax in context.kinematics.axes:
            if ax.name not in axes:
                raise where.error(f"'program.kinematics.axes' names axis {ax.name!r}, which has no [axes.{ax.name}] "
                                  "table", ("program", "kinematics", "axes"))
    return MachineSpec(name=name, description=description, sample_time=float(ts), axes=axes, limits=limits,
                       context=context, warnings=tuple(plausibility_warnings(data, file=file, line=where.index.line)))


def _wraps(a: str, tab: dict, where: _Where) -> bool:
    """``[axes.a] wrap``: whether the rotary axis ``a`` wraps at 360 deg (:mod:`interpolators.rotary_wrap`)."""
    if "wrap" not in tab:
        return False
    wrap = tab["wrap"]
    if not isinstance(wrap, bool):
        raise where.error(f"'axes.{a}.wrap' must be true or false (a rotary axis that wraps at 360 deg), got {wrap!r}",
                          ("axes", a, "wrap"))
    if wrap and a not in ROTARY_AXES:
        raise where.error(f"'axes.{a}.wrap' = true: only a rotary axis (a, b, c) wraps at 360 deg", ("axes", a, "wrap"))
    return wrap


def _xyz_value(value: Any, path: tuple[str, ...], where: _Where) -> list[float]:
    if (not isinstance(value, list) or len(value) != 3
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in value)):
        raise where.error(f"'{'.'.join(path)}' [mm] must be three numbers [x, y, z], got {value!r}", path)
    return [float(v) for v in value]


def _build_dialect(tab: dict, path: tuple, where: _Where, file: str) -> Dialect:
    """The ``[program]`` table's dialect and the settings that change it (units, path mode and tolerance,
    initial feed, search paths)."""
    name = tab.get("dialect", "linuxcnc")
    if name not in DIALECTS or name == "heidenhain":
        raise where.error(f"'program.dialect' must be one of linuxcnc, fanuc, haas, grbl, fadal, got {name!r}",
                          path + ("dialect",))
    changes: dict[str, Any] = {}
    units = tab.get("default_units")
    if units is not None:
        if units not in ("mm", "inch"):
            raise where.error(f"'program.default_units' must be 'mm' or 'inch', got {units!r}",
                              path + ("default_units",))
        changes["default_units"] = units
    if "continuous_path" in tab:
        if not isinstance(tab["continuous_path"], bool):
            raise where.error("'program.continuous_path' must be true or false", path + ("continuous_path",))
        changes["continuous_path"] = tab["continuous_path"]
    if "tolerance" in tab:
        tol = tab["tolerance"]
        if isinstance(tol, bool) or not isinstance(tol, (int, float)) or not (math.isfinite(tol) and tol > 0):
            raise where.error(f"'program.tolerance' [mm] must be a number > 0, got {tol!r}", path + ("tolerance",))
        changes["tolerance"] = float(tol)
    if "initial_feed" in tab:
        feed = tab["initial_feed"]
        if isinstance(feed, bool) or not isinstance(feed, (int, float)) or not (math.isfinite(feed) and feed > 0):
            raise where.error(f"'program.initial_feed' [mm/min] must be a number > 0 (the feed of a feed move before "
                              f"any F word, Fanuc parameter No. 1411), got {feed!r}", path + ("initial_feed",))
        changes["initial_feed"] = float(feed)
    for key in ("subroutine_path", "user_m_path"):
        if key in tab:
            changes[key] = _search_path(tab[key], path + (key,), where, file)
    if "length_offset_motion" in tab:
        if not isinstance(tab["length_offset_motion"], bool):
            raise where.error("'program.length_offset_motion' must be true (a tool length change is an axis movement: "
                              "Fanuc TOS = 0, No. 5006#6) or false (a shift of the coordinate system: TOS = 1, "
                              f"LinuxCNC), got {tab['length_offset_motion']!r}", path + ("length_offset_motion",))
        changes["length_offset_motion"] = tab["length_offset_motion"]
    changes.update(_peck_tapping(tab, path, where))
    return dataclasses.replace(DIALECTS[name], **changes)


def _peck_tapping(tab: dict, path: tuple, where: _Where) -> dict[str, Any]:
    """``peck_tapping`` and ``peck_tapping_d`` of the ``[program]`` table: Fanuc's peck rigid tapping (PCP, No.
    5200#5; d, No. 5213; :attr:`interpolators.context.Dialect.peck_tapping`), set together."""
    if "peck_tapping" not in tab and "peck_tapping_d" not in tab:
        return {}
    kind, d = tab.get("peck_tapping"), tab.get("peck_tapping_d")
    if kind not in PECK_TAPPING:
        raise where.error("'program.peck_tapping' must be 'high-speed' (Fanuc PCP = 0: back by d after each cut) or "
                          "'standard' (PCP = 1: back to R after each cut, in again to d above the depth cut), set "
                          f"with peck_tapping_d; got {kind!r}", path + ("peck_tapping",))
    if isinstance(d, bool) or not isinstance(d, (int, float)) or not (math.isfinite(d) and d >= 0):
        raise where.error("'program.peck_tapping_d' [mm] must be a number >= 0 (d of Fanuc's peck rigid tapping, "
                          f"parameter No. 5213), set with peck_tapping; got {d!r}", path + ("peck_tapping_d",))
    return {"peck_tapping": kind, "peck_tapping_d": float(d)}


def _build_context(tab: Any, where: _Where, file: str) -> MachineContext:  # noqa: C901
    """The ``[program]`` table: dialect, home and reference positions, work offsets, tool table."""
    path = ("program",)
    if not isinstance(tab, dict):
        raise where.error("'program' must be a table", path)
    for key in tab:
        if key not in _PROGRAM_KEYS:
            raise where.error(f"unknown key 'program.{key}'; expected one of: {', '.join(_PROGRAM_KEYS)}",
                              path + (key,))
    dialect = _build_dialect(tab, path, where, file)
    kwargs: dict[str, Any] = {"dialect": dialect}
    for key in ("home", "reference2"):
        if key in tab:
            kwargs[key] = _xyz_value(tab[key], path + (key,), where)
    if tab.get("linear_units", "mm") not in ("mm", "inch"):
        raise where.error(f"'program.linear_units' must be 'mm' or 'inch', got {tab['linear_units']!r}",
                          path + ("linear_units",))
    kwargs["linear_units"] = tab.get("linear_units", "mm")
    if tab.get("decimal_point_input", "calculator") not in ("calculator", "increment"):
        raise where.error("'program.decimal_point_input' must be 'calculator' (Fanuc DPI=1: X10 is 10 mm) or "
                          f"'increment' (DPI=0: X10 is 0.010 mm), got {tab['decimal_point_input']!r}",
                          path + ("decimal_point_input",))
    kwargs["decimal_point_input"] = tab.get("decimal_point_input", "calculator")
    if tab.get("tool_offset_memory", "C") not in TOOL_OFFSET_MEMORIES:
        raise where.error("'program.tool_offset_memory' must be 'A', 'B' or 'C' (Fanuc tool compensation memory: one "
                          "value per offset; geometry and wear; geometry and wear apart for H and D), got "
                          f"{tab['tool_offset_memory']!r}", path + ("tool_offset_memory",))
    kwargs["tool_offset_memory"] = tab.get("tool_offset_memory", "C")
    if "wrap_direction" in tab:
        if tab["wrap_direction"] not in WRAP_DIRECTIONS:
            raise where.error("'program.wrap_direction' must be 'sign' (LinuxCNC WRAPPED_ROTARY, Fanuc RAB=1), "
                              "'shortest' (Fanuc RAB=0, TNC M126) or 'difference' (TNC without M126): the direction "
                              f"of an absolute move of a wrap = true axis; got {tab['wrap_direction']!r}",
                              path + ("wrap_direction",))
        kwargs["wrap_direction"] = tab["wrap_direction"]
    offsets = tab.get("work_offsets", {})
    if not isinstance(offsets, dict):
        raise where.error("'program.work_offsets' must be a table of G54 = [x, y, z] ...", path + ("work_offsets",))
    keys: dict[str, str] = {}
    for code in offsets:
        try:
            key = work_offset_code(code)
        except InputError as exc:
            raise where.error(f"'program.work_offsets.{code}': {exc}", path + ("work_offsets", code)) from None
        if key in keys:
            raise where.error(f"'program.work_offsets.{code}' and '{keys[key]}' are the same work offset ({key})",
                              path + ("work_offsets", code))
        keys[key] = code
    kwargs["work_offsets"] = {c: _xyz_value(v, path + ("work_offsets", c), where) for c, v in offsets.items()}
    tools: dict[int, Tool] = {}
    if "tool_table" in tab:
        tools.update(_table_file(tab, "tool_table", read_tool_table, path, where, file))
    if "datum_table" in tab:
        kwargs["datum_table"] = _table_file(tab, "datum_table", read_datum_table, path, where, file)
    tools_tab = tab.get("tools", {})
    if not isinstance(tools_tab, dict):
        raise where.error("'program.tools' must be tables [program.tools.<number>]", path + ("tools",))
    for number, entry in tools_tab.items():
        tpath = path + ("tools", number)
        if not number.isdigit() or not isinstance(entry, dict):
            raise where.error(f"'program.tools.{number}' must be a table named by a tool number", tpath)
        for key in entry:
            if key not in ("length", "radius", "offset_x", "offset_y", "comment", "name", "point_angle"):
                raise where.error(f"unknown key 'program.tools.{number}.{key}'; expected length [mm], radius [mm], "
                                  "offset_x [mm], offset_y [mm], comment, name, point_angle [deg]", tpath + (key,))
        try:
            tools[int(number)] = Tool(number=int(number), length=float(entry.get("length", 0.0)),
                                      radius=float(entry.get("radius", 0.0)),
                                      offset_x=float(entry.get("offset_x", 0.0)),
                                      offset_y=float(entry.get("offset_y", 0.0)), comment=str(entry.get("comment", "")),
                                      name=str(entry.get("name", "")),
                                      point_angle=float(entry.get("point_angle", 0.0)))
        except (InputError, TypeError, ValueError) as exc:
            raise where.error(f"program.tools.{number}: {getattr(exc, 'message', exc)}", tpath) from None
    kwargs["tools"] = tools
    if "kinematics" in tab:
        kwargs["kinematics"] = _build_kinematics(tab["kinematics"], path + ("kinematics",), where)
    if "touch_probe" in tab:
        if not isinstance(tab["touch_probe"], dict):
            raise where.error("'program.touch_probe' must be a table", path + ("touch_probe",))
        kwargs["touch_probe"] = _build(TouchProbe, tab["touch_probe"], path + ("touch_probe",), where)
    try:
        return MachineContext(**kwargs)
    except InputError as exc:
        raise where.error(exc.message, path) from None


_KINEMATICS_AXIS_KEYS = {"name": "", "direction": "", "pivot": "mm", "limits": "deg"}


def _table_file(tab: dict, key: str, reader, path: tuple[str, ...], where: _Where, file: str):
    """``program.tool_table`` or ``program.datum_table``: the file (a relative path starts at this machine file's
    folder) read by ``reader``, its errors named at the key."""
    value = tab[key]
    if not isinstance(value, str):
        raise where.error(f"'program.{key}' must be a file path string", path + (key,))
    table = Path(value)
    if not table.is_absolute() and file and not file.startswith("<"):
        table = Path(file).parent / table
    try:
        return reader(str(table))
    except InputError as exc:
        raise where.error(exc.message, path + (key,)) from None


def _search_path(value: Any, path: tuple[str, ...], where: _Where, file: str) -> tuple[str, ...]:
    """``program.subroutine_path`` (the folders searched for the file ``<name>.ngc`` of an ``o<name> call``
    after the program's own folder, LinuxCNC INI ``[RS274NGC] SUBROUTINE_PATH``) or ``program.user_m_path``
    (those holding the executables ``M100`` .. ``M199`` of user M codes, ``[RS274NGC] USER_M_PATH``;
    https://linuxcnc.org/docs/html/config/ini-config.html): a relative folder starts at this machine file's
    folder, as ``tool_table`` does and as the INI's relative entries start at the configuration's (LinuxCNC
    ngcgui documentation: ``SUBROUTINE_PATH = ../../../nc_files/ngcgui_lib``). A single string is one folder."""
    folders = [value] if isinstance(value, str) else value
    if not isinstance(folders, list) or not all(isinstance(f, str) and f for f in folders):
        raise where.error(f"'{'.'.join(path)}' must be a folder path string or a list of them", path)
    base = Path(file).parent if file and not file.startswith("<") else None
    return tuple(str(base / f) if base is not None and not Path(f).is_absolute() else f for f in folders)


def _build_kinematics(tab: Any, path: tuple[str, ...], where: _Where) -> Kinematics:
    """``[program.kinematics]``: ``kind`` and the two ``[[program.kinematics.axes]]`` (outer first)."""
    if not isinstance(tab, dict):
        raise where.error("'program.kinematics' must be a table", path)
    for key in tab:
        if key not in ("kind", "axes"):
            raise where.error(f"unknown key 'program.kinematics.{key}'; expected kind, axes", path + (key,))
    entries = tab.get("axes")
    if not isinstance(entries, list) or len(entries) not in (1, 2) or not all(isinstance(e, dict) for e in entries):
        raise where.error("'program.kinematics' needs two [[program.kinematics.axes]] tables (the outer, tilting "
                          "axis first, then the one it carries), or one (a 4-axis machine)", path)
    axes = []
    for entry in entries:
        for key in entry:
            if key not in _KINEMATICS_AXIS_KEYS:
                raise where.error(f"unknown key 'program.kinematics.axes.{key}'; expected one of: "
                                  + ", ".join(f"{k} [{u}]" if u else k for k, u in _KINEMATICS_AXIS_KEYS.items()),
                                  path + ("axes",))
        kwargs: dict[str, Any] = {"name": entry.get("name"), "direction": entry.get("direction", "")}
        if "pivot" in entry:
            kwargs["pivot"] = tuple(_xyz_value(entry["pivot"], path + ("axes", "pivot"), where))
        if "limits" in entry:
            lim = entry["limits"]
            if (not isinstance(lim, list) or len(lim) != 2
                    or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in lim)):
                raise where.error(f"'program.kinematics.axes.limits' [deg] must be two numbers [low, high], "
                                  f"got {lim!r}", path + ("axes",))
            kwargs["limits"] = (float(lim[0]), float(lim[1]))
        try:
            axes.append(RotaryAxis(**kwargs))
        except InputError as exc:
            raise where.error(exc.message, path + ("axes",)) from None
    try:
        return Kinematics(kind=tab.get("kind", "table"), axes=tuple(axes))
    except InputError as exc:
        raise where.error(exc.message, path) from None


def _build_typed(table: dict[str, Any], registry: dict[str, type], path: tuple[str, ...], where: _Where) -> Any:
    kind = table.get("type")
    if kind is None:
        raise where.error(f"missing key '{'.'.join(path)}.type'; expected one of: {', '.join(registry)}", path)
    if kind not in registry:
        raise where.error(f"'{'.'.join(path)}.type' must be one of: {', '.join(registry)}; got {kind!r}",
                          path + ("type",))
    return _build(registry[kind], table, path, where, skip=("type",))


def _build_limits(table: dict[str, Any], path: tuple[str, ...], where: _Where) -> AxisLimits:
    for key, value in table.items():
        if key not in _LIMIT_UNITS:
            raise where.error(
                f"unknown key '{'.'.join(path + (key,))}'; expected one of: "
                + ", ".join(f"{k} [{u}]" for k, u in _LIMIT_UNITS.items()),
                path + (key,),
            )
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (value > 0 and math.isfinite(value)):
            raise where.error(f"'{'.'.join(path + (key,))}' [{_LIMIT_UNITS[key]}] must be a finite number > 0, "
                              f"got {value!r}", path + (key,))
    for key in ("velocity", "acceleration"):
        if key not in table:
            raise where.error(f"missing key '{'.'.join(path + (key,))}' [{_LIMIT_UNITS[key]}]", path)
    return AxisLimits(**{k: float(v) for k, v in table.items()})


_ = typing  # annotations are read as strings
