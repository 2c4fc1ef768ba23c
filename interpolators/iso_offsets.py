"""Additional work offsets of Fanuc and Haas mills, and ``G10`` as those controls set offsets.

Fanuc (0i-MD B-64304EN "Adding workpiece coordinate systems (G54.1 or G54)", "Changing workpiece
coordinate system (G10 L2, G10 L20)"; the GSK 980MDc manual, a Fanuc-compatible control, words them the same):

- ``G54.1 P<n>`` selects additional workpiece coordinate system n, P1-P48 (P1-P300 with the 300-set
  option); without P, P1 is selected. It is modal in the group of G54-G59 and stays until another of them.
  ``G54 P<n>`` is the same ("G54.1 Pn or G54 Pn"), unless the block's P belongs to another word
  (G04, G10, G64, a cycle; an ``M98 P`` is the subprogram's).
- ``G10 L20 P<n> X.. Y.. Z..`` sets its offset, as ``G10 L2 P<p>`` sets G54-G59 (P1-P6): under G90 the
  values are the offset, under G91 they are added to it; an axis not named keeps its offset.
  ``G10 L2 P0`` sets the external workpiece zero offset, which shifts every workpiece system (Fanuc
  "External workpiece zero point offset", ``#5201``-``#5206``; Haas: "P0 G52 references work coordinate",
  the G52 entry of its offset table, ``#5201``-``#5205``). The external offset is one per axis (Fanuc 0i-MD
  B-64304EN "Changing workpiece coordinate system": ``G10 L2 Pp IP_``, "p=0: External workpiece zero point
  offset value", IP_ "for each axis"), so an A-W word sets that axis' external offset as X Y Z do theirs (a
  Mastercam post writes ``G10 L2 P0 X0. Y0. Z0. B0.`` for a B-axis machine).
- G92 and G52 act in these systems as in G54-G59: G92 shifts every workpiece coordinate system and
  G52 sets the local system in every one (in vcnc both offsets are kept apart from the table, see
  :mod:`interpolators.iso`).

Haas (mill operator's manual "G154 Select Work Coordinates P1-P99", "G10 Set Offsets"): ``G154 P<n>``,
n = 1-99, and ``G110``-``G129`` = ``G154 P1``-``P20``; ``G10 L20 P<n>`` sets them ("L20 auxiliary work
coordinate origin for G110-G129", "P1-P99 G154 P1-P99"), G90 the value, G91 added ("G10 L2 P1 G91 X60.
moves offset G54 X 60 mm").

System variables (read): Fanuc ``#7001``-``#7960`` (P1-P48, 20 per system: ``#7001`` the first axis
of P1, ``#7021`` of P2 ...) and ``#14001``-``#19988`` (P1-P300, the same layout); Haas ``#7001``-``#7386``
(G110-G129) and ``#14001``-``#15966`` (G154 P1-P99) (Haas "Macros", "Offsets"; the variable list of
the NGC control). vcnc reads the first three (X Y Z) and the A B C of each system; the others read 0.
The modal ``#4014`` reads 54.1 (Fanuc) / 154 (Haas) and ``#4130`` the P number (0 under G54-G59).

Tool offsets (Fanuc 0i-MD "Changing of tool compensation value (G10)"; Haas "G10 Set Offsets": "L10 length
offset amount (for H code), L1 or L11 tool wear offset amount (for H code), L12 diameter offset amount (for D
code), L13 diameter wear offset amount"): ``G10 L<n> P<offset> R<value>``, P the offset number (the tool table's
entry: H/D numbers are tool numbers in vcnc), R the value, under G90 set, under G91 added. What L sets depends
on Fanuc's tool compensation memory (:attr:`interpolators.context.MachineContext.tool_offset_memory`; Fanuc
0i-MD "Tool compensation values"; Fanuc Series 0i-MODEL B connection manual B-63833EN-1 "Tool compensation
memory"):

- memory C (the default here, and Haas's): geometry and wear apart, and apart for H and D: ``L10`` H geometry,
  ``L11`` (``L1``, "to provide compatibility with the format of older CNC programs") H wear, ``L12`` D geometry,
  ``L13`` D wear;
- memory B: one geometry and one wear per offset number, which H and D both use: ``L10`` geometry, ``L11``
  wear; the tool's length and radius both take the value;
- memory A: one value per offset number, for H and D: ``L11`` (``L1``) sets it; no wear.

An L word the memory does not have is an error naming it. The control applies geometry + wear
(:attr:`interpolators.context.Tool.length_wear`). Haas's D values are diameters (as its manual words them),
Fanuc's radii (its default; a parameter can make them diameters, not modelled). A change applies at the next
G43 / G41 / G42, as a table change.

The same registers are system variables (:func:`tool_offset_variable`, read and written by
:mod:`interpolators.iso_system`). Fanuc 0i-MD B-64304EN "System variables", "Tool compensation values", offset
number n = 1-999 (the 0i-MD has 400; the #2001.. aliases reach 200): memory A ``#10000+n`` (``#2000+n``) the
value; memory B ``#11000+n`` (``#2200+n``) geometry, ``#10000+n`` (``#2000+n``) wear; memory C ``#11000+n``
(``#2200+n``) H geometry, ``#10000+n`` (``#2000+n``) H wear, ``#13000+n`` D geometry, ``#12000+n`` D wear.
Haas ("Macros", "Tool Offsets", tools 1-200): ``#2000+n`` length geometry, ``#2200+n`` length wear, ``#2400+n``
diameter geometry, ``#2600+n`` diameter wear (its #10000.. are general-purpose variables).

The table is :attr:`interpolators.context.MachineContext.work_offsets` (keys ``"G54.1 P<n>"``). LinuxCNC
has none of these codes: under ``--dialect linuxcnc`` G54.1 and G154 stay errors naming them.

The ISO reader's offset blocks in every dialect live here too, on its state (:class:`interpolators.iso.State`):
:func:`g10` (LinuxCNC G10 L1/L10/L11/L2/L20, the Fanuc/Haas forms above), :func:`local_offset` (G52),
:func:`reference_p` (a P word on G28, G30, G52, G53, G92) and :func:`length_compensation` (G43, G43.1, G44, G49,
LinuxCNC G43.2).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING, Protocol

import numpy as np

from interpolators._words import Where
from interpolators.context import WORK_OFFSETS, MachineContext, Tool, extended_offset
from interpolators.iso_axes import EXTRA_LETTERS, refuse_wrapped_offset, word_values
from interpolators.iso_cycles import CYCLE_AXES
from interpolators.iso_words import Word, WordError, fail_words, offset_number

if TYPE_CHECKING:
    from interpolators.iso import Notes, State

__all__ = ["EXTENDED_CODES", "P_SELECT_CODES", "MAX_EXTENDED", "selected_offset", "set_work_offset", "extended_number",
           "offset_parameter", "g54_takes_p", "set_tool_offset", "TOOL_LEVELS", "ToolRegister", "tool_offset_variable",
           "fanuc_tool_variable", "tool_offset", "with_tool_offset", "length_compensation", "h_alone", "length_travel",
           "length_moves_now", "length_cancelled", "length_in_cycle", "reference_p", "local_offset", "g10",
           "set_external_axis"]

#: G10 L words that write the tool offsets under the ``fanuc`` and ``haas`` dialects.
TOOL_LEVELS = frozenset({1, 10, 11, 12, 13})

#: Highest additional offset number per dialect: Fanuc P300 (the option; P48 standard), Haas P99.
MAX_EXTENDED: Mapping[str, int] = MappingProxyType({"fanuc": 300, "haas": 99})

#: The codes that select an additional offset, per dialect: round(10 * G) -> (modal group, name).
EXTENDED_CODES: Mapping[str, Mapping[int, tuple[str, str]]] = MappingProxyType({
    "fanuc": MappingProxyType({541: ("coordinate system", "G54.1")}),
    "haas": MappingProxyType({1540: ("coordinate system", "G154"),
                              **{1100 + 10 * i: ("coordinate system", f"G{110 + i}") for i in range(20)}}),
})

#: Codes whose P word is the offset number (the block's P is theirs).
P_SELECT_CODES = frozenset({541, 1540})

#: First system variable of each block of 20 (one per system) and the systems it covers, per dialect.
_VARIABLES: Mapping[str, tuple[tuple[int, int], ...]] = MappingProxyType({
    "fanuc": ((7001, 48), (14001, 300)),
    "haas": ((7001, 20), (14001, 99)),
})


def g54_takes_p(groups: Mapping[str, object], has_p: bool, dialect: str, cycle: bool) -> bool:
    """Whether a Fanuc block's ``G54 P<n>`` selects additional system n (as G54.1 P<n>): the block has G54
    (``groups["coordinate system"][0] == 540``) and a P no other code of it reads (G04 dwell, G10,
    G64 tolerance, a drilling cycle: ``cycle``)."""
    code = groups.get("coordinate system")
    return (dialect == "fanuc" and has_p and not cycle and isinstance(code, tuple) and code[0] == 540
            and not any(g in groups for g in ("dwell", "path", "nonmodal")))


def extended_number(code: str) -> int:
    """The P number of an additional offset's code (``"G54.1 P7"`` -> 7); 0 for G54-G59.3."""
    return int(code.rsplit("P", 1)[1]) if code.startswith("G54.1 P") else 0


def selected_offset(key: int, p: float | None, dialect: str) -> tuple[str, bool]:
    """The work-offset table key a selection code picks, and whether P1 was assumed (no P word).

    Parameters
    ----------
    key : int
        round(10 * G): 541 (G54.1), 1540 (G154), 1100-1290 (G110-G129).
    p : float or None
        The block's P word (G54.1, G154 only).
    dialect : str
        ``"fanuc"`` or ``"haas"``.

    Raises
    ------
    WordError
        P not a whole number in the dialect's range (letter ``"P"``).
    """
    if key not in P_SELECT_CODES:
        return extended_offset(key // 10 - 109), False
    name = "G54.1" if key == 541 else "G154"
    last = MAX_EXTENDED[dialect]
    if p is None:
        return extended_offset(1), True
    if p != int(p) or not 1 <= p <= last:
        raise WordError(f"P{p:g} is not an additional work offset number", letter="P",
                        expected=f"{name} P1 .. P{last}")
    return extended_offset(int(p)), False


class OffsetState(Protocol):
    """What :func:`set_work_offset` reads and writes of the ISO executor's state."""

    context: MachineContext
    offsets: dict[str, np.ndarray]  # work offsets the program set [mm]
    extra_offsets: dict[str, np.ndarray]  # their a, b, c [deg], u, v, w [mm]
    incremental: bool

    @property
    def scale(self) -> float: ...

    g92: np.ndarray  # the offset shared by every system [mm]: G92 shift + G52 local + external (P0)
    external: np.ndarray  # the external workpiece zero offset (G10 L2 P0) [mm]
    g92_extra: np.ndarray  # the a, b, c [deg], u, v, w [mm] part of g92
    external_extra: np.ndarray  # the a, b, c [deg], u, v, w [mm] part of external


def set_work_offset(level: int, p: float | None, words: dict[str, float], st: OffsetState, dialect: str) -> str:
    """Fanuc/Haas ``G10 L2 P<p>`` (G54-G59, P1-P6) and ``G10 L20 P<n>`` (an additional offset): the named
    axes' offset becomes the value (G90) or moves by it (G91); returns the table key set.

    Parameters
    ----------
    level : int
        The L word: 2 or 20.
    p : float or None
        The P word.
    words : dict of str to float
        The block's words by letter (X Y Z [program units], A B C [deg], U V W, R).
    st : OffsetState
        The reader's state; ``st.offsets``/``st.extra_offsets`` are updated.
    dialect : str
        ``"fanuc"`` or ``"haas"``.

    Raises
    ------
    WordError
        P missing or out of range, or a word G10 does not take here.
    """
    if "R" in words:
        raise WordError("R (a rotation of the coordinate system) is LinuxCNC's G10 L2 R, not Fanuc/Haas",
                        letter="R", expected="G68 to rotate the program")
    last = 6 if level == 2 else MAX_EXTENDED[dialect]
    if level == 2 and p == 0:
        _set_external(words, st)
        return "external"
    if p is None or p != int(p) or not 1 <= p <= last:
        what = "G54-G59" if level == 2 else ("G54.1 P" if dialect == "fanuc" else "G154 P") + "<n>"
        raise WordError(f"G10 L{level} needs P{0 if level == 2 else 1} .. P{last} ({what})",
                        letter="P" if p is not None else None, expected=f"G10 L{level} P1 .. P{last} X.. Y.. Z..")
    code = WORK_OFFSETS[int(p) - 1] if level == 2 else extended_offset(int(p))
    current = st.offsets.get(code)
    linear = (st.context.offset(code) if current is None else current).copy()
    for i, a in enumerate("XYZ"):
        if a in words:
            linear[i] = (linear[i] if st.incremental else 0.0) + words[a] * st.scale
    st.offsets[code] = linear
    v = word_values({a: words[a] for a in EXTRA_LETTERS if a in words}, scale=st.scale)
    given = ~np.isnan(v)
    if np.any(given):
        extra = st.extra_offsets.get(code, np.zeros(6)).copy()
        extra[given] = (extra if st.incremental else np.zeros(6))[given] + v[given]
        st.extra_offsets[code] = extra
    return code


def set_external_axis(st: OffsetState, axis: int, value: float) -> None:
    """Axis ``axis`` (0-5: X Y Z A B C) of the external workpiece zero offset becomes ``value`` [mm, deg]; the shift
    every system shares (``g92``) moves with it. G10 L2 P0 and the Fanuc/Haas variables ``#5201``-``#5206``
    (:func:`interpolators.iso_system.set_system_parameter`) set it."""
    if axis < 3:
        st.g92[axis] += value - st.external[axis]
        st.external[axis] = value
    else:
        st.g92_extra[axis - 3] += value - st.external_extra[axis - 3]
        st.external_extra[axis - 3] = value


def _set_external(words: dict[str, float], st: OffsetState) -> None:
    """G10 L2 P0: the external offset of the named axes (X Y Z and A-W alike, module docstring) becomes the
    value (G90) or moves by it (G91); the shift every system shares moves with it."""
    for i, a in enumerate("XYZ"):
        if a in words:
            set_external_axis(st, i, (st.external[i] if st.incremental else 0.0) + words[a] * st.scale)
    v = word_values({a: words[a] for a in EXTRA_LETTERS if a in words}, scale=st.scale)
    given = ~np.isnan(v)
    value = (st.external_extra if st.incremental else np.zeros(6)) + np.where(given, v, 0.0)
    st.g92_extra[given] += (value - st.external_extra)[given]
    st.external_extra[given] = value[given]


def offset_parameter(n: int, dialect: str) -> tuple[str, int] | None:
    """The additional offset and axis index (0 .. 19) system variable ``#n`` reads under ``dialect``, or
    None when ``#n`` is none of them."""
    for first, count in _VARIABLES.get(dialect, ()):
        k, j = divmod(n - first, 20)
        if 0 <= k < count:
            return extended_offset(k + 1), j
    return None


_LENGTH, _RADIUS, _BOTH = ("length",), ("radius",), ("length", "radius")

#: What ``G10 L<level>`` sets under each Fanuc tool compensation memory: the parts of the tool (H: length,
#: D: radius) and the kind ("geometry", "wear", or memory A's "value": the whole offset, no wear).
_G10_REGISTERS: Mapping[str, Mapping[int, tuple[tuple[str, ...], str]]] = MappingProxyType({
    "A": {1: (_BOTH, "value"), 11: (_BOTH, "value")},
    "B": {10: (_BOTH, "geometry"), 1: (_BOTH, "wear"), 11: (_BOTH, "wear")},
    "C": {10: (_LENGTH, "geometry"), 1: (_LENGTH, "wear"), 11: (_LENGTH, "wear"), 12: (_RADIUS, "geometry"),
          13: (_RADIUS, "wear")},
})

#: The Fanuc tool offset variables per memory: block k of ``#10001 + 1000 k`` .. (k = 0 also ``#2001``.., k = 1
#: ``#2201``..) -> (parts, kind).
_FANUC_VARIABLES: Mapping[str, Mapping[int, tuple[tuple[str, ...], str]]] = MappingProxyType({
    "A": {0: (_BOTH, "value")},
    "B": {0: (_BOTH, "wear"), 1: (_BOTH, "geometry")},
    "C": {0: (_LENGTH, "wear"), 1: (_LENGTH, "geometry"), 2: (_RADIUS, "wear"), 3: (_RADIUS, "geometry")},
})

#: Haas #2001-#2800 by block of 200: length geometry, length wear, diameter geometry, diameter wear.
_HAAS_VARIABLES = ((_LENGTH, "geometry"), (_LENGTH, "wear"), (_RADIUS, "geometry"), (_RADIUS, "wear"))


@dataclasses.dataclass(frozen=True, kw_only=True)
class ToolRegister:
    """One tool offset register: tool ``number``'s ``parts`` (``"length"``, ``"radius"``), their ``kind``
    (``"geometry"``, ``"wear"``, ``"value"``: geometry + wear), a value of the register being ``per_mm`` times the
    offset in mm (2 for Haas's diameters)."""

    number: int
    parts: tuple[str, ...]
    kind: str
    per_mm: float = 1.0


def tool_offset_variable(n: int, dialect: str, memory: str) -> ToolRegister | None:
    """The register system variable ``#n`` names under ``dialect`` (``"fanuc"``, ``"haas"``) and the Fanuc tool
    compensation ``memory`` (``"A"``, ``"B"``, ``"C"``), or None (module docstring)."""
    if dialect == "haas":
        if not 2001 <= n <= 2800:
            return None
        block, number = divmod(n - 2001, 200)
        parts, kind = _HAAS_VARIABLES[block]
        return ToolRegister(number=number + 1, parts=parts, kind=kind, per_mm=2.0 if parts == _RADIUS else 1.0)
    if 2001 <= n <= 2400:
        block, number = divmod(n - 2001, 200)
        number += 1
    elif 10001 <= n <= 13999 and n % 1000:
        block, number = divmod(n - 10000, 1000)
    else:
        return None
    found = _FANUC_VARIABLES[memory].get(block)
    return None if found is None else ToolRegister(number=number, parts=found[0], kind=found[1])


def fanuc_tool_variable(n: int) -> bool:
    """Whether ``#n`` is a Fanuc tool offset variable of some memory type (``#2001``-``#2400``,
    ``#10001``-``#13999``): memory C, which has every block of them, names it."""
    return tool_offset_variable(n, "fanuc", "C") is not None


def _parts(tool: Tool, part: str) -> tuple[float, float]:
    """Geometry and wear of ``part`` (``"length"``, ``"radius"``) of ``tool`` [mm]."""
    total, wear = (tool.length, tool.length_wear) if part == "length" else (tool.radius, tool.radius_wear)
    return total - wear, wear


def tool_offset(tool: Tool | None, register: ToolRegister) -> float | None:
    """The value ``register`` holds for ``tool`` (None: not in the table, 0), in mm times ``per_mm``; None when it
    serves H and D (memory A, B) and the table's length and radius differ, neither being 0."""
    if tool is None:
        return 0.0
    values = []
    for part in register.parts:
        geometry, wear = _parts(tool, part)
        values.append({"geometry": geometry, "wear": wear, "value": geometry + wear}[register.kind])
    found = {v for v in values if v != 0.0} or {0.0}
    return found.pop() * register.per_mm if len(found) == 1 else None


def with_tool_offset(tool: Tool, register: ToolRegister, value: float, *, add: bool = False) -> Tool:
    """``tool`` with ``register`` set to ``value`` (in mm times ``per_mm``), or moved by it (``add``)."""
    changes: dict[str, float] = {}
    for part in register.parts:
        geometry, wear = _parts(tool, part)
        amount = value / register.per_mm
        if register.kind == "value":
            geometry, wear = (geometry + wear if add else 0.0) + amount, 0.0
        elif register.kind == "geometry":
            geometry = (geometry if add else 0.0) + amount
        else:
            wear = (wear if add else 0.0) + amount
        changes[part], changes[f"{part}_wear"] = geometry + wear, wear
    return dataclasses.replace(tool, **changes)


class ToolState(Protocol):
    """What :func:`set_tool_offset` reads and writes of the ISO executor's state."""

    context: MachineContext
    tools: dict[int, Tool]  # tool table entries the program wrote
    incremental: bool

    @property
    def scale(self) -> float: ...

    def tool(self, number: int) -> Tool | None: ...


def set_tool_offset(level: int, p: float | None, words: dict[str, float], st: ToolState, dialect: str) -> Tool:
    """Fanuc/Haas ``G10 L10/L11/L1/L12/L13 P<n> R<value>``: the register of offset ``n`` that L names under the
    tool compensation memory (module docstring; Haas: memory C, D in diameters) set to R (G90) or moved by R
    (G91); returns the new table entry.

    Raises
    ------
    WordError
        P missing or not a whole number >= 0, R missing, axis words (those are LinuxCNC's G10 L1/L10), or an L
        the memory does not have.
    """
    if p is None or p != int(p) or p < 0:
        raise WordError(f"G10 L{level} needs the offset number P (a whole number >= 0)", letter="P" if p else None,
                        expected=f"G10 L{level} P<offset> R<value>")
    axes = [a for a in "XYZ" if a in words]
    if axes or "R" not in words:
        raise WordError(f"G10 L{level} sets offset P{int(p)} from R (Fanuc/Haas tool offsets)",
                        letter=axes[0] if axes else None, expected=f"G10 L{level} P{int(p)} R<value>")
    memory = "C" if dialect == "haas" else st.context.tool_offset_memory
    found = _G10_REGISTERS[memory].get(level)
    if found is None:
        levels = " ".join(f"L{n}" for n in sorted(_G10_REGISTERS[memory]))
        raise WordError(f"G10 L{level}: tool compensation memory {memory} has no such offset (its G10: {levels}; "
                        "the machine's [program] tool_offset_memory)", letter="L",
                        expected=f"G10 {levels.split()[-1]} P{int(p)} R<value>")
    number = int(p)
    register = ToolRegister(number=number, parts=found[0], kind=found[1],
                            per_mm=2.0 if dialect == "haas" and found[0] == _RADIUS else 1.0)
    new = with_tool_offset(st.tool(number) or Tool(number=number), register, words["R"] * st.scale,
                           add=st.incremental)
    st.tools[number] = new
    return new


def length_compensation(entry, seen, st: State, where: Where, notes: Notes) -> None:
    """G43, G43.1, G43.2, G44, G49: the tool length offset set (:func:`_set_length`); where the control moves the
    axis by its change (:attr:`interpolators.context.Dialect.length_offset_motion`: Fanuc, Haas, Fadal), the change
    is kept for :func:`length_travel`."""
    before = st.tool_length
    _set_length(entry, seen, st, where, notes)
    if st.context.dialect.length_offset_motion:
        st.length_pending += st.tool_length - before


def h_alone(gcodes, seen, st: State) -> tuple[int, Word] | None:
    """The group 08 entry an H word alone stands for under ``fanuc`` and ``haas``: in G43 or G44 mode a block with an
    H word and no group 08 code changes the offset to H's, as ``G43 H..`` / ``G44 H..`` would, the direction staying;
    H0 makes it 0; under tool centre point control (G43.4, G43.5, G234) it is that code's ``H..``, the new length
    travelled by the next TCP block (:func:`interpolators.iso_tcp.tip_point`; our reading, no Fanuc text on a new H in
    G43.4 mode being at hand). None for any other block (a G45-G48 block reads its H itself).

    No Fanuc text is at hand; Fanuc-compatible controls word it: "When the tool length offset value is changed due
    to a change of offset number, the offset value changes to the new tool length offset value, the new tool length
    offset value is not added to the old tool length offset value. To cancel tool length offset, specify G49 or H0"
    (SZGH-CNC1000MDb manual, "G43, G44"); "G43 H10; 1st offset / H14; 2nd offset ... The H offsets can be changed
    throughout the program without canceling the previous offset with a G49 or H00. The new H offset will
    automatically take effect in either the G43 or G44 mode, whichever is active at the time" (Milltronics
    PL-551 system information, "Tool length offset (G43, G44, G49)"). Fanuc and Haas read so is our reading; the
    change then moves as a G43's does (:func:`length_moves_now`, :func:`length_travel`, :func:`length_in_cycle`)."""
    if st.context.dialect.name not in ("fanuc", "haas") or "H" not in seen or "length compensation" in gcodes \
            or "position offset" in gcodes or not st.tcp and st.length_code not in (43.0, 44.0):
        return None
    return (st.tcp or (430 if st.length_code == 43.0 else 440)), seen["H"]


def length_travel(target: np.ndarray, axis_words: list[str], st: State, *, now: bool = False) -> np.ndarray:
    """The end point [mm, machine] ``target`` of a G00-G03 block with the tool length change not yet travelled
    added to an incremental Z word (Fanuc, tool length compensation by an axis movement, parameter TOS = 0: the
    change of the offset is added to the block's travel, B-63943EN-1/02 12.5.2; LinuxCNC and grbl never set it).
    An absolute Z word ends at the programmed Z plus the offset, as ``target`` has it; either takes the change up.
    ``now`` (:func:`length_moves_now`): the block made the change itself and has no Z word: Z moves by it in this
    block."""
    if not st.length_pending or "Z" not in axis_words and not now:
        return target
    if st.incremental or "Z" not in axis_words:
        target = target.copy()
        target[2] += st.length_pending
    st.length_pending = 0.0
    return target


def length_cancelled(st: State) -> None:
    """Z has reached its reference (G28, G30) or a machine coordinate (G53): under compensation by an axis movement
    the tool length offset vector is cancelled there and restored by the next Z move, the modal G43/G44 and H
    staying (FANUC Series 0i-MB operator's manual B-63844EN/02, 14.1.2 "G53, G28, and G30 Commands in Tool Length
    Offset Mode": the vector of the tool length offset axis is "canceled upon movement to a reference position being
    performed", G53's and ``G49 G53``'s "upon movement being performed according to a specified value", a G49 in a
    G53 block without a Z word moving no Z; "the previously specified modal
    G code remains displayed"): the whole offset is left to travel (:func:`length_travel`), so a ``G49`` after
    ``G91 G28 Z0`` (Fusion 360's Fanuc post) moves nothing, and an incremental Z after it travels the offset again.
    Under a coordinate shift nothing is left to travel."""
    st.length_pending = st.tool_length if st.context.dialect.length_offset_motion else 0.0


def length_in_cycle(st: State) -> None:
    """A canned-cycle block: the series' initial level (:class:`interpolators.iso_cycles.CycleWords`, a machine
    position along the drilling axis) follows a shift of the program zero along that axis made since the series' last
    block -- a work offset (G54-G59, G54.1 P, G154 P), G92 / G52, a G10 that rewrote the offset in force, a tool length
    change -- and in G17 a length change not yet travelled (Fanuc TOS = 0, :func:`length_travel`) is taken up at the
    positioning to R: "When a tool length offset (G43, G44, or G49) is specified in the canned cycle, the offset is
    applied at the time of positioning to point R" (FANUC Series 15i/150i-MA programming manual B-63784EN, canned
    cycles, "Tool length compensation").

    The initial level is a level in program coordinates, as LinuxCNC keeps it (interp_cycles.cc ``cycle_il``): rs274
    returns a G98 hole after a G43 H2 within the series to the program Z it began at, and after a ``G55`` within
    the series to that program Z in G55 (``G0 Z10. / G98 G81 .. R2. / G55 X5.`` with G55's Z offset -100: the return
    at machine -90, not 10); under G90 the cycle's R and bottom levels hold the new offsets already, a G91 R is
    measured from the moved initial level and a G98 returns to it: "G49 / G91 G81 .. R-3." with a 50 mm tool and the
    tool at Z 60 puts R at 7, not 57. Fanuc and Haas: our reading, no manual text on an offset change within a
    series being at hand (the Haas mill manual's "the Z-axis will be returned to the same position as at the start of
    the canned cycle" leaves the system open). Our reading too: a block of zero repeats (K0) takes the change up, its
    stored cycle holding the new offset; in G18/G19 (drilling along Y or X) a length change waits for the next Z
    word. Under G10 R alone (LinuxCNC) the level is kept in program coordinates already
    (:func:`interpolators.iso_frames.framed_initial`)."""
    axis = CYCLE_AXES[st.plane][2]
    travels = axis == 2  # a pending length change is travelled at R in G17 only
    program = bool(st.rotation) and st.frame is None  # under G10 R alone the level is kept in program coordinates
    zero = float(st.offset()[axis]) - (st.length_pending if travels else 0.0)
    if st.cycle.initial is None:
        if travels and st.length_pending:
            st.cycle.initial = float((st.to_program(st.pos) if program else st.pos)[2])
    elif st.cycle.zero is not None and not program:  # a shift between the series' blocks, travelled or not
        st.cycle.initial += zero - st.cycle.zero
    if travels and st.length_pending:
        st.cycle.initial += st.length_pending
        zero += st.length_pending
        st.length_pending = 0.0
    st.cycle.zero = zero


def length_moves_now(gcodes, motion: int | None, st: State) -> bool:
    """Whether the block's G43/G44/G49 (Fadal: its H word) moves Z by the tool length change at once: under
    compensation by an axis movement (:attr:`interpolators.context.Dialect.length_offset_motion`, Fanuc TOS = 0) in a
    G00 or G01 block, the block's own motion or the modal one, without a Z word.

    FANUC B-63943EN-1/02 12.5.2 names as the mark of the other type, TOS = 1, that "if no move command is specified
    together with the G43, G44, or G49 command, the tool will not move along the axis": under TOS = 0 that block
    moves it, by the change of the offset vector, at the block's own rate (rapid under G00, the feed under G01). A
    Fanuc-compatible control words the same rule from the other side: "Whenever a new tool length offset is
    initiated or cancelled, the block that changes the offset must be a linear block (G00 or G01)" (Allen-Bradley
    8520 9/Series mill operation and programming manual, chapter 20 "Tool Control Functions", p. 20-7, Example
    20.2, whose "N2 G43 H01;" and "N8 G49;" have no axis word). Our reading
    for other blocks: an arc or a canned cycle keeps the change for the next Z word (a cycle's R-point positioning
    takes it, Fanuc 15i-MA B-63784EN "Tool length compensation" in a canned cycle), and so does a block before any
    motion code; under tool centre point control (G43.4, G234) the tip is programmed, and a G53 block cancels the
    vector instead (:func:`length_cancelled`)."""
    return bool(st.length_pending) and "length compensation" in gcodes and motion in (0, 10) and not st.tcp


def _set_length(entry, seen, st: State, where: Where, notes: Notes) -> None:
    key, w = entry
    if st.comp_side is not None and st.context.dialect.name == "linuxcnc":
        # LinuxCNC interp_convert.cc convert_tool_length_offset, for G43, G43.1, G43.2 and G49 alike: "Cannot
        # change tool offset with cutter radius compensation on" (G40 on the same line comes first); Fanuc and
        # Haas change the length under G41/G42
        where.fail(f"{w.text.upper()}: cannot change tool offset with cutter radius compensation on (LinuxCNC)",
                   column=w.column, text=w.text, expected=f"G40 before {w.text.upper()}")
    st.length_code = key / 10
    if key == 490:
        st.tool_length = 0.0
        st.tool_xy = np.zeros(2)
        return
    if key == 432:
        _additional_length(seen, st, where, w, notes)
        return
    if key == 431 and st.context.dialect.name == "fanuc":
        # Fanuc "Tool length compensation in tool axis direction (G43.1)": along the tool axis, Z while the rotary
        # axes stand at 0 (a 3-axis machine): G43
        if np.any(st.extra[:3] != 0):
            where.fail("G43.1 tool length compensation in tool axis direction with a rotary axis turned: not "
                       "supported", column=w.column, text=w.text, expected="G43.1 H.. with the rotary axes at 0")
        notes.add("G43.1 tool length compensation in tool axis direction run as G43 (the tool axis is Z)")
        key = 430
    elif key == 431:
        # LinuxCNC g-code.adoc "G43.1"; interp_convert.cc convert_tool_length_offset: the axis words
        # are the offsets (no motion), an axis not named keeps its offset
        if not any(a in seen for a in "XYZ"):
            where.fail("G43.1 needs the tool offsets as axis words", column=w.column, text=w.text,
                       expected="G43.1 Z<length> (and X, Y)")
        old = [st.tool_xy[0], st.tool_xy[1], st.tool_length]
        xyz = [seen.pop(a).value * st.scale if a in seen else old[i] for i, a in enumerate("XYZ")]
        st.tool_xy, st.tool_length = np.array(xyz[:2]), xyz[2]
        return
    h = seen.pop("H", None)
    code = f"{'G44' if key == 440 else 'G43'} mode" if w is h else w.text.upper()  # an H alone (h_alone): its mode
    number, tool = _h_tool(offset_number(h, where, code) if h is not None else None, st, notes)
    st.length_number = number or 0
    length = 0.0 if tool is None else tool.length
    sign = -1.0 if key == 440 else 1.0
    if key == 440 and st.context.dialect.name == "linuxcnc":
        # LinuxCNC's G-code set has G43, G43.1, G43.2 and G49 only (interp_array.cc gees[]: G44 is -1): rs274 stops
        # at it with "Unknown g code used"; vcnc runs it as Fanuc's G44 (subtracting), as it runs the other codes
        # LinuxCNC lacks, noted
        notes.add('G44 tool length offset subtracted as Fanuc does (LinuxCNC refuses it: "Unknown g code used")')
    st.tool_length = sign * length
    st.tool_xy = sign * (np.zeros(2) if tool is None else np.array([tool.offset_x, tool.offset_y]))
    notes.add("G43/G44 tool length from the table")


def _h_tool(h: int | None, st: State, notes: Notes) -> tuple[int | None, Tool | None]:
    """The number and the tool whose offsets ``H<h>`` of G43 / G43.2 takes (``h`` None: G43 without H, the loaded
    tool's offset number), noted when the table lacks it. LinuxCNC interp_find.cc find_tool_index: tool 0 is index 0,
    the spindle's (the loaded) tool, whose offsets convert_tool_length_offset then takes: "T212 M6" then "G43 H0" (a
    Mastercam post) is T212's length, and "G43.2 H0" adds it, as rs274 2.9.0~pre1 runs them; Fanuc's and Haas's
    H0/H00 stay the zero offset."""
    loaded = h == 0 and st.context.dialect.name == "linuxcnc"
    number = (st.tool_offsets.get(st.tool_current, st.tool_current) if h is None else
              st.tool_current if loaded else h)
    tool = st.tool(number) if number is not None else None
    if tool is None and number not in (None, 0):
        notes.add(f"H0 (the loaded tool T{number}) not in the tool table (length 0)" if loaded else
                  f"H{number} not in the tool table (length 0)")
    return number, tool


def _additional_length(seen, st: State, where: Where, w: Word, notes: Notes) -> None:
    """LinuxCNC G43.2 (g-code.adoc "G43.2 Apply additional Tool Length Offset"; interp_convert.cc
    convert_tool_length_offset): ``G43.2 H<n>`` adds tool n's offsets (length, X, Y) to the ones in effect,
    ``G43.2 X.. Y.. Z..`` adds the words; no motion, the next move of an axis goes to the compensated point.
    Errors as LinuxCNC's: both H and axis words, neither, and cutter compensation on ("Cannot change tool
    offset with cutter radius compensation on"); an H not in the table adds 0 (noted, as for G43 here)."""
    axes = [a for a in ("X", "Y", "Z", *EXTRA_LETTERS) if a in seen]
    why = ("can not have both H and axis words" if "H" in seen and axes else
           "no axes specified and H word missing" if "H" not in seen and not axes else
           "cannot change tool offset with cutter radius compensation on" if st.comp_side is not None else
           f"axis word {axes[-1]} (an offset of an axis beyond X, Y, Z): not supported"
           if axes and axes[-1] in EXTRA_LETTERS else None)  # X Y Z come first in axes
    if why is not None:
        where.fail(f"G43.2: {why} (LinuxCNC)", column=w.column, text=w.text,
                   expected="G43.2 H<tool> or G43.2 X.. Y.. Z.. (no motion), without G41/G42")
    add = np.zeros(3)
    if "H" in seen:
        _, tool = _h_tool(offset_number(seen.pop("H"), where, "G43.2"), st, notes)
        if tool is not None:
            add = np.array([tool.offset_x, tool.offset_y, tool.length])
    for i, a in enumerate("XYZ"):
        if a in seen:
            add[i] = seen.pop(a).value * st.scale
    st.tool_xy = st.tool_xy + add[:2]
    st.tool_length += float(add[2])
    notes.add("G43.2 additional tool length offset (added to the offsets in effect)")


def reference_p(key: int, seen, st: State, where: Where, notes: Notes) -> None:
    """A P word on G28, G30, G52, G53 or G92: Fanuc/Haas ``G30 P2``-``P4`` (Fanuc 0i-MD B-64304EN "2nd, 3rd, and
    4th reference position return": P2 the second, the default; the third and fourth are machine parameters
    No. 1242/1243 the machine context does not hold: the second is used, noted); elsewhere the P is ignored,
    noted (LinuxCNC refuses it: "P word with no G2 G3 G4 G10 G64 ... to use it")."""
    p = seen["P"]
    code = f"G{key / 10:g}"
    if key == 300 and st.context.dialect.name in ("fanuc", "haas"):
        if p.value not in (2, 3, 4):
            where.fail(f"G30 P{p.value:g}: no such reference position", column=p.column, text=p.text,
                       expected="G30 P2, P3 or P4 (2nd, 3rd, 4th reference position)")
        if p.value != 2:
            notes.add(f"G30 P{p.value:g}: the {('third', 'fourth')[int(p.value) - 3]} reference position is not in the "
                      "machine context: the second one used")
        return
    refused = ' (LinuxCNC refuses it: "P word with no ... to use it")' if st.context.dialect.name == "linuxcnc" else ""
    notes.add(f"P word on {code} ignored{refused}")


def local_offset(seen, axis_words, st: State, where: Where, w: Word) -> None:
    """G52 X.. Y.. Z..: the named axes' offset becomes the value (LinuxCNC interp_convert.cc
    convert_axis_offsets, G_52: axis_offset = value); it is the offset G92 sets too (#5211..), cleared by
    G92.1 and suspended by G92.2. Fanuc and Haas keep the local system apart from the G92 shift (Fanuc
    0i-MD "Local coordinate system": G52 sets it in every workpiece system, G52 X0 cancels it, a G92
    cancels it on the axes it names): there the value replaces the local part of the offset only."""
    if st.comp_side is not None:  # LinuxCNC NCE_CANNOT_CHANGE_AXIS_OFFSETS_WITH_CUTTER_RADIUS_COMP
        where.fail("G52 with cutter radius compensation on", column=w.column, text=w.text, expected="G40 before G52")
    fanuc = st.context.dialect.name in ("fanuc", "haas")
    for a in axis_words:
        i, value = "XYZ".index(a), seen[a].value * st.scale
        st.g92[i] = st.g92[i] - st.local[i] + value if fanuc else value
        st.local[i] = value if fanuc else 0.0
    v = word_values({a: seen[a].value for a in EXTRA_LETTERS if a in seen}, scale=st.scale)
    given = ~np.isnan(v)
    st.g92_extra[given] = v[given]  # A-W as X-Z: the offset is the value
    st.g92_saved, st.g92_extra_saved = st.g92.copy(), st.g92_extra.copy()
    st.g92_applied = True


def g10(seen, st: State, where: Where, w: Word) -> str:
    """G10: set a work or tool offset; returns the note of the run. A Fanuc/Haas tool offset P0 is left
    alone with a note: "the offset amount corresponding to H00 always means 0, and it is not possible to set
    the offset amount corresponding to H00" (Fanuc 0i-MD B-64304EN "Tool length compensation (G43, G44,
    G49)", offset number; the same wording in its copies), as a ``P#4120`` (the tool in the spindle) writes
    it before any T of the run."""
    l_word, p_word = seen.get("L"), seen.get("P")
    fanuc = st.context.dialect.name in ("fanuc", "haas")
    if l_word is not None and l_word.value == 50 and st.context.dialect.name == "fanuc":
        st.parameter_input = True  # the lines up to G11 are parameter data (interpolators.iso ``_execute``)
        return "G10 L50 parameter input by program (its data lines up to G11 not run: parameters not modelled)"
    if l_word is not None and int(l_word.value) in TOOL_LEVELS and fanuc and p_word is not None \
            and p_word.value == 0 and "R" in seen:
        return f"G10 L{int(l_word.value)} P0: offset 0 (H00/D00) always means 0 and cannot be set: ignored"
    if l_word is not None and int(l_word.value) in TOOL_LEVELS and fanuc:
        try:  # Fanuc/Haas tool offsets: L10 L11 (L1) length geometry / wear, L12 L13 radius (interpolators.iso_offsets)
            set_tool_offset(int(l_word.value), None if p_word is None else p_word.value,
                            {k: v.value for k, v in seen.items()}, st, st.context.dialect.name)
        except WordError as exc:
            fail_words(where, f"G10 L{int(l_word.value)} tool offset", exc, seen, w)
        return "G10 offsets set"
    if l_word is not None and int(l_word.value) in (1, 10, 11):
        _g10_tool(int(l_word.value), seen, st, where, w)
        return "G10 offsets set"
    if l_word is not None and int(l_word.value) in (2, 20) and fanuc:
        try:  # Fanuc/Haas: L2 G54-G59, L20 G54.1 P / G154 P, G91 adds (interpolators.iso_offsets)
            set_work_offset(int(l_word.value), None if p_word is None else p_word.value,
                            {k: v.value for k, v in seen.items()}, st, st.context.dialect.name)
        except WordError as exc:
            fail_words(where, f"G10 L{int(l_word.value)} work offset", exc, seen, w)
        return "G10 offsets set"
    if l_word is None or int(l_word.value) not in (2, 20):
        where.fail("G10: only L1, L10, L11 (tool table) and L2, L20 (work offsets) are supported", column=w.column,
                   text=w.text, expected="G10 L2 P<n> X.. Y.. Z.., G10 L20 P<n> ... or G10 L1 P<tool> Z.. R..")
    r_word = seen.get("R")
    p = int(p_word.value) if p_word is not None else 0
    code = st.wcs if p == 0 else (WORK_OFFSETS[p - 1] if 1 <= p <= 9 else None)
    if int(l_word.value) == 20 and r_word is not None:  # LinuxCNC convert_setup: "R not allowed in G10 L20"
        where.fail("R not allowed in G10 L20", column=r_word.column, text=r_word.text,
                   expected="G10 L2 P<n> R<angle> to rotate a coordinate system")
    if code is None:
        where.fail(f"G10 P{p}: coordinate system number must be 0-9", column=p_word.column, text=p_word.text,
                   expected="P0 (current) .. P9")
    current = st.offsets.get(code, st.context.offset(code)).copy()
    if int(l_word.value) == 20:
        refuse_wrapped_offset(seen, st, where, "G10 L20")
        current = _l20_offset(seen, st, current, st.rotations.get(code, 0.0))
    for a in ("X", "Y", "Z"):
        if a in seen and int(l_word.value) == 2:
            current["XYZ".index(a)] = seen[a].value * st.scale
    st.offsets[code] = current
    v = word_values({a: seen[a].value for a in EXTRA_LETTERS if a in seen}, scale=st.scale)
    given = ~np.isnan(v)
    if np.any(given):  # L2: the offset is the value; L20: the offset that makes the current position the value
        extra = st.extra_offsets.get(code, np.zeros(6)).copy()
        extra[given] = (v if int(l_word.value) == 2 else st.extra - st.g92_extra - v)[given]
        st.extra_offsets[code] = extra
    if r_word is not None:  # LinuxCNC G10 L2 R: the system's rotation about Z [deg] (#5210 + 20 n)
        st.rotations[code] = r_word.value
    return "G10 offsets set"


def _g10_tool(level: int, seen, st: State, where: Where, w: Word) -> None:
    """G10 L1 / L10 / L11 P<tool>: write the tool table (LinuxCNC G-code reference "G10 L1", "G10 L10",
    "G10 L11"; interp_convert.cc convert_setup_tool). L1 sets the offsets X Y Z and the radius R
    directly; L10 sets them so that the current position, in the current coordinate system without
    tool offsets, reads the programmed values; L11 the same in G59.3 without the G92 offset. X and Y
    are rotated with the system's rotation (G10 L2 R); an L10/L11 with only one of them keeps the
    old offset's part along the other rotated axis. The change applies at the next G43 (the offset in
    effect is not changed)."""
    p_word = seen.get("P")
    if p_word is None or p_word.value != int(p_word.value) or p_word.value < 0:
        where.fail(f"G10 L{level}: the tool number P is missing or not a whole number >= 0", column=w.column,
                   text=w.text, expected=f"G10 L{level} P<tool> X.. Y.. Z.. R..")
    if p_word.value < 1:  # interp_check.cc check_g_codes: "P value out of range with G10 L%d" (p_int < 1)
        where.fail(f"G10 L{level} P0: no tool 0 in the tool table (LinuxCNC: 'P value out of range with G10 "
                   f"L{level}')", column=p_word.column, text=p_word.text, expected=f"G10 L{level} P<tool> with P >= 1")
    if not any(k in seen for k in ("X", "Y", "Z", "R")):
        where.fail(f"G10 L{level} without offsets has no effect (LinuxCNC refuses it)", column=w.column, text=w.text,
                   expected=f"G10 L{level} P<tool> with X, Y, Z and/or R")
    number = int(p_word.value)
    tool = st.tool(number) or Tool(number=number)
    value = {a: seen[a].value * st.scale for a in "XYZ" if a in seen}
    xy, length = np.array([tool.offset_x, tool.offset_y]), tool.length
    if level == 1:
        xy = np.array([value.get("X", xy[0]), value.get("Y", xy[1])])
        length = value.get("Z", length)
    else:
        here, rotation = _here_without_tool(st, fixture=level == 11)
        a = math.radians(rotation)
        c, s = math.cos(a), math.sin(a)
        if "X" in value or "Y" in value:
            # the old offset's part along the rotated axis not named is kept
            old_u, old_v = c * xy[0] + s * xy[1], -s * xy[0] + c * xy[1]
            u = here[0] - value["X"] if "X" in value else old_u
            v = here[1] - value["Y"] if "Y" in value else old_v
            xy = np.array([c * u - s * v, s * u + c * v])
        if "Z" in value:
            length = here[2] - value["Z"]
    radius = seen["R"].value * st.scale if "R" in seen else tool.radius
    st.tools[number] = dataclasses.replace(tool, length=float(length), radius=float(radius),
                                           offset_x=float(xy[0]), offset_y=float(xy[1]))


def _here_without_tool(st: State, *, fixture: bool) -> tuple[np.ndarray, float]:
    """The current position [mm] in the current system (``fixture``: in G59.3, without the G92 offset)
    as if no tool offset were applied (the machine position less the work and G92 offsets only), and
    that system's rotation [deg] (LinuxCNC interp_find.cc find_current_in_system_without_tlo)."""
    wcs = "G59.3" if fixture else st.wcs
    work = st.offsets.get(wcs)
    work = st.context.offset(wcs) if work is None else work
    rotation = st.rotations.get(wcs, 0.0)
    g92 = np.zeros(3) if fixture else st.g92
    m = st.pos - work
    a = math.radians(rotation)
    c, s = math.cos(a), math.sin(a)
    return np.array([c * m[0] + s * m[1], -s * m[0] + c * m[1], m[2]]) - g92, rotation


def _l20_offset(seen, st: State, offset: np.ndarray, rotation: float) -> np.ndarray:
    """G10 L20: the offset of a system (rotated by ``rotation`` [deg]) that makes the current position
    read the programmed values there (LinuxCNC interp_convert.cc convert_setup: the old and the desired
    position are rotated into the unrotated frame; an axis not named keeps its current coordinate).
    Machine = R (program + G92) + offset, so offset = machine - R (desired + G92)."""
    a = math.radians(rotation)
    c, s = math.cos(a), math.sin(a)
    px, py = st.pos[0] - st.tool_xy[0], st.pos[1] - st.tool_xy[1]  # without the tool's X Y offsets
    dx, dy = px - offset[0], py - offset[1]
    here = np.array([c * dx + s * dy - st.g92[0], -s * dx + c * dy - st.g92[1]])  # current X Y in that system
    new = offset.copy()
    if "X" in seen or "Y" in seen:
        want = np.array([seen[k].value * st.scale if k in seen else here[i] for i, k in enumerate("XY")]) + st.g92[:2]
        new[0] = px - (c * want[0] - s * want[1])
        new[1] = py - (s * want[0] + c * want[1])
    if "Z" in seen:
        new[2] = st.pos[2] - st.g92[2] - st.tool_length - seen["Z"].value * st.scale
    return new
