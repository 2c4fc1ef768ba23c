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
  the G52 entry of its offset table, ``#5201``-``#5205``); X Y Z only here.
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
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from types import MappingProxyType
from typing import Protocol

import numpy as np

from interpolators.context import WORK_OFFSETS, MachineContext, Tool, extended_offset
from interpolators.iso_axes import EXTRA_LETTERS, word_values
from interpolators.iso_words import WordError

__all__ = ["EXTENDED_CODES", "P_SELECT_CODES", "MAX_EXTENDED", "selected_offset", "set_work_offset",
           "extended_number", "offset_parameter", "g54_takes_p", "set_tool_offset", "TOOL_LEVELS",
           "ToolRegister", "tool_offset_variable", "fanuc_tool_variable", "tool_offset", "with_tool_offset"]

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


def _set_external(words: dict[str, float], st: OffsetState) -> None:
    """G10 L2 P0: the external offset of the named axes becomes the value (G90) or moves by it (G91); the
    shift every system shares moves with it."""
    extra = [a for a in EXTRA_LETTERS if a in words]
    if extra:
        raise WordError("G10 L2 P0 (the external offset) with a rotary or secondary axis word: not supported",
                        letter=extra[0], expected="G10 L2 P0 X.. Y.. Z..")
    for i, a in enumerate("XYZ"):
        if a in words:
            value = (st.external[i] if st.incremental else 0.0) + words[a] * st.scale
            st.g92[i] += value - st.external[i]
            st.external[i] = value


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
    ``#10001``-``#13999``)."""
    return 2001 <= n <= 2400 or (10001 <= n <= 13999 and n % 1000 != 0)


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
