"""Which column of a delimited trace is what, from its header names, when no mapping is given.

Loggers name their channels in their maker's words and language: ``Time [ms]``, ``X Sollposition``,
``Axis X Actual Position``, ``x_cmd`` / ``x_fb``, ``PosCmd`` / ``PosAct``, ``Lageistwert``,
``X following error``. :func:`columns_from_names` reads such a header into the mapping that
``--columns`` would give (``t=..., x_ref=..., x=...`` or ``x_lag=...``), and only when the reading
is unambiguous:

- each name is split into words (separators, camelCase, a unit in brackets set aside); a name made
  of time words only (``t``, ``time``, ``Zeit``, ``timestamp``...) is the time column, and there must
  be exactly one;
- a name with a word of commanding (``cmd``, ``command``, ``set``, ``ref``, ``soll``, ``nominal``,
  ``target``, ``demand``...), of measuring (``act``, ``actual``, ``fb``, ``feedback``, ``ist``,
  ``measured``, ``encoder``...) or of a following error (``lag``, ``ferror``, ``following error``,
  ``Schleppfehler``, ``deviation``, ``diff``...) is a position of that role; one that names a
  velocity, current, torque, acceleration, force... or carries a unit that is not a length
  (``[mm/min]``, ``[A]``, ``[%]``) is not a position at all;
- its axis is the one axis letter among its words (``X Soll``, ``x_cmd``, ``xact``); a file whose
  positions name no axis has one axis, x, when it has one pair; beside positions of one named axis, a
  position naming none fills a role that axis has no column of, when it is the only one of its role
  (``pos_cmd``, ``pos_fb`` beside ``X Following Error``; tracewild10);
- each axis needs exactly one commanded and one measured column (or, without a measured one,
  exactly one following error). Two candidates for one role make the header ambiguous.

vcnc addition (tracewild2, drive tools' exports): positions logged in increments (a unit ``[inc]``,
``(counts)``, ``[pulse]``, Delta's ``(PUU)``, SINAMICS' ``[LU]``, or a word ``pulses``/``counts`` in the
name, as Mitsubishi's "Cumulative feedback pulses") are positions whose size the file may not state
(:func:`counted`; the reader then asks for ``--unit``); Kollmorgen AKD's ``VL.``/``IL.`` parameters (velocity
and current loop, AKD User Guide) are not positions; without a time column, a column of sample numbers
(``Sample #``, ``No.``, ``Index``: MEI Motion Scope's export starts with ``Sample #``) or none is the time
when the sampling period is known (``period_known``: stated in the file's preamble or given); a
commanded position without a measured one takes as measured the column named as it without the word of
commanding (``position`` beside ``positionCmd``, ``x`` beside ``x_cmd``; our reading of loggers that name
the feedback plainly and mark the command).

vcnc addition (tracewild3, recorders' signal paths): a channel named by its path (``BoosterMotorEncosTest/t``,
``MAIN.Axis.Time``) whose last element is ``t``, ``time``, ``timestamp`` or ``Zeit`` is a time column; a
controller's gains (``kp``, ``ki``, ``kd``, ``kv``, ``gain``) and ``tor`` (torque, as in ``MotorCmdTor``) are not
positions (a recorder of a joint's command words logs ``MotorCmdKp``, ``MotorCmdPos``, ``MotorCmdTor`` side by side);
positions that name no axis letter but number their axis, joint or motor (``CH0 Axis1 ...``, ``joint 2 cmd``) pair
only within one number, and the one number with a pair is axis x (several such numbers are a question); PMAC's motor
registers as gather tools name them (``Motor present desired position``, ``... actual position``, ``Motor following
error``) are in counts (:func:`counted`).

vcnc addition (tracewild7, robot controllers): KUKA.RobotSensorInterface names the Cartesian actual position ``RIst``
and the setpoint ``RSol`` (the controller's XML elements, as ROS' ``kuka_rsi_hw_interface`` ``rsi_state.h`` reads them
beside ``AIPos``/``ASPos`` and ``IPOC``): a logger's ``X_RIst`` / ``X_RSol`` are axis x's measured and commanded
position, and its ``IPOC``, the controller's interpolation-cycle time stamp, counts milliseconds (a KR C4 logs it in
steps of 12 in IPO mode, 4 in IPO_FAST) and is the time before a logging PC's own time stamp. (tracewild8)
``RIst``/``RSol`` hold the pose of the tool, X, Y, Z in mm and A, B, C in degrees, KUKA's E6POS angles of its
orientation (A about Z, B about Y, C about X, as ``$POS_ACT``); they are no axes, and a machine's A, B, C turn about X,
Y, Z: the names do not map ``A_RIst``... (:func:`rsi_orientation`), and the capture's note names them as left out; a
joint's positions ``ASPos``/``AIPos`` (A1..A6, deg) are a question naming them (:func:`rsi_joints`). Universal Robots'
RTDE recorder (``record.py``, ``rtde/csv_writer.py``: a VECTOR6D field as ``name_0`` ... ``name_5``) names joint N's
target and actual position ``target_q_N`` / ``actual_q_N``, in radians (RTDE guide: "Target joint positions", "Actual
joint positions"), and the tool's pose ``target_TCP_pose_N`` / ``actual_TCP_pose_N`` (x, y, z in m, then a rotation
vector): a robot's joint is no axis of the capture by itself, so such a header is a question naming them and the
unit (:func:`rtde_joints`), never millimetres.

vcnc addition (tracewild8): CoDeSys V2.3's "Trace in ASCII-File" (ABB Automation Builder 2.2 help, "'Trace in
ASCII-File'": a title line, the project's path, the names line, then the values separated by a blank) writes the task
cycle in the first column, named ``Cycle``, when the trace has no frequency scan: a column of sample numbers; with a
frequency scan that column holds the time in ms instead (the reader refuses sample numbers that do not step by 1).

vcnc addition (tracewild6): ECP Executive's encoder channels (``Encoder 1 Pos``, ``Encoder 2 Pos``) are in counts
(:func:`counted`), and two of them beside one ``Commanded Pos`` are a question (which encoder closes the loop, the
collocated or the far one, the file does not say).

vcnc addition (traces38): a counter is another quantity unless it counts pulses: Yaskawa's "Reference pulse counter" /
"Feedback pulse counter" and Panasonic MINAS' "command pulse counter" / "feedback pulse counter" are the commanded and
measured position in counts (:func:`_other_quantity`); the plurals of other quantities (``velocities``, ``efforts``,
as ``rostopic echo -p`` names a JointTrajectoryPoint's arrays) are no positions; and an array's element numbers the
joint in a ``rostopic echo -p`` table (``field.desired.positions2``, :mod:`vcnc.traces.rostopic`).

vcnc addition (traces40): a PLC symbol path whose last element names a role on its own is read by that element
(``MAIN.afbAxes[3].stAxisStruct.stStatus.fActPosition``, as TwinCAT's Scope View names a channel by its symbol); the
elements before it add only whole axis letters, a status structure's name (``stStatus``) is no status word, and a
quantity they name (``Spindle.ActPos``, ``Axis.Velocity.Cmd``) still makes the variable no position
(:func:`_path_words`).

Anything else returns None with the reason, and the reader asks for ``--columns`` as before. The
words are our reading of the exports seen (TwinCAT's ``SetPos``/``ActPos``, LinuxCNC's
``pos-cmd``/``pos-fb``, TNCscope's ``noml``/``actl``/``diff``, Siemens' and German loggers'
``Soll``/``Ist``), not a standard.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence

from vcnc.core.axes import AXIS_NAMES
from vcnc.traces.columns import COUNT_UNITS, IPOC, LAG_SUFFIX, unit_in_name
from vcnc.traces.rostopic import joint_states_question

__all__ = ["columns_from_names", "channels_from_names", "mapping_note", "counted", "is_sample_number", "no_positions",
           "rtde_joints", "rsi_orientation", "rsi_orientation_note", "rsi_joints"]

_TIME = frozenset({"t", "time", "times", "zeit", "timestamp", "stamp", "zeitstempel", "temps", "tiempo", "tempo",
                   "sec", "secs", "seconds", "ms", "msec", "elapsed", "rel", "relative", "us", "\u00b5s",
                   "\u6642\u9593", "\u65f6\u95f4"})  # 時間 (Japanese), 时间 (Chinese)
_REF = frozenset({"cmd", "command", "commanded", "ref", "reference", "set", "setpoint", "setpos", "soll",
                  "sollwert", "sollposition", "sollpos", "nominal", "noml", "nom", "target", "demand", "demanded",
                  "dem", "desired", "consigne", "commande", "sp", "sol"})
_ACT = frozenset({"act", "actual", "actl", "actpos", "ist", "istwert", "istposition", "istpos", "fb", "feedback",
                  "meas", "measured", "measurement", "enc", "encoder", "real", "reel", "mesure", "pv"})
_LAG = frozenset({"lag", "ferror", "ferr", "following", "schleppfehler", "schleppabstand", "posdiff", "deviation",
                  "droop", "diff", "regeldifferenz", "ecart"})
#: Words that make "error" a following error: "following error", "position error", "f-error".
_LAG_ERROR = frozenset({"following", "tracking", "position", "pos", "servo", "f", "lag", "contouring"})
_ERROR = frozenset({"error", "err", "fehler"})
#: German compounds naming a following error: KUKA.Trace's "Positionsschleppfehler" (:mod:`vcnc.traces.diadem`).
_LAG_PARTS = ("schleppfehler", "schleppabstand")
#: Words of quantities that are not positions (an amplitude, in dB: a signal logger's, tracewild9).
_OTHER = frozenset({"vel", "velocity", "speed", "feed", "feedrate", "rpm", "current", "curr", "iq", "id", "torque",
                    "trq", "moment", "force", "acc", "accel", "acceleration", "jerk", "voltage", "volt", "temp",
                    "temperature", "power", "load", "strom", "drehzahl", "geschwindigkeit", "beschleunigung",
                    "kraft", "spannung", "leistung", "vitesse", "courant", "couple", "velocidad", "corriente",
                    "spindle", "spindel", "index", "sample", "samples", "count", "counter", "nr", "no", "status",
                    "state", "enable", "mode", "output", "out", "effort", "duty", "pwm", "dac", "off", "offset", "time",
                    "zeit", "timestamp", "vl", "il", "tor", "kp", "ki", "kd", "kv", "gain", "amp", "amps",
                    "amplitude", "db", "dbm", "velocities", "speeds", "currents", "torques", "forces", "accelerations",
                    "efforts", "voltages"})
#: Words of a symbol path's structures (``stStatus``, ``AxisState``) that name no quantity of their members
#: (:func:`_path_words`).
_STRUCTURES = frozenset({"status", "state"})
#: Words of a counter, another quantity unless a word of counts says it counts a position's increments (Yaskawa
#: SigmaWin+'s and Panasonic PANATERM's "Feedback pulse counter", "Command pulse counter"; :func:`_other_quantity`).
_COUNTERS = frozenset({"counter", "count"})
#: Words of a column of sample numbers (``Sample #``, ``Sample No.``, ``Nr.``, ``Index``, ``Point``; CoDeSys V2.3's
#: ``Cycle``, module docstring).
_SAMPLE = frozenset({"sample", "samples", "no", "nr", "n", "index", "idx", "point", "points", "number", "num", "cycle",
                     "cycles"})
#: Words of a name that say its values are counts (Mitsubishi's "Cumulative feedback pulses").
_COUNT_WORDS = frozenset({"pulse", "pulses", "counts", "increments", "inc", "incr", "cnt", "cnts"})
#: German compounds are one word: a commanded "Lagesollwert", a measured "Lageistwert", a velocity
#: "Drehzahlsollwert".
_OTHER_PARTS = ("geschw", "drehzahl", "strom", "moment", "beschl", "kraft", "spannung", "velocity", "speed",
                "current", "torque", "\u901f\u5ea6", "\u30c8\u30eb\u30af", "\u96fb\u6d41", "\u7535\u6d41",
                "\u8f6c\u77e9", "\u626d\u77e9", "\u96fb\u5727", "\u7535\u538b", "\u8f6c\u901f")
#: Japanese and Chinese compounds (one word without spaces) by their parts: 指令 command, 目标 target, 给定 setpoint;
#: フィードバック / 帰還 / 反馈 feedback, 実際 / 实际 actual, 現在 / 当前 present (Fanuc's 現在位置); 溜り (droop, of
#: Mitsubishi's 溜りパルス), 偏差 deviation, 误差 error, 跟随 following. Other parts: 速度 speed, トルク / 转矩 / 扭矩
#: torque, 電流 / 电流 current, 電圧 / 电压 voltage, 转速 rotational speed.
_CJK_PARTS = {"ref": ("\u6307\u4ee4", "\u76ee\u6807", "\u7ed9\u5b9a", "\u7d66\u5b9a"),
              "act": ("\u30d5\u30a3\u30fc\u30c9\u30d0\u30c3\u30af", "\u5e30\u9084", "\u53cd\u9988",
                      "\u5b9e\u9645", "\u5b9f\u969b", "\u73fe\u5728", "\u5f53\u524d"),
              "lag": ("\u6e9c\u308a", "\u504f\u5dee", "\u8bef\u5dee", "\u8ddf\u968f")}
#: PMAC's motor registers as gather tools name them, logged in counts (dls-pmac-control ``gatherchannel.py``:
#: "Motor present desired position", "Motor present actual position", "Motor following error", unit ``[cts]``,
#: scaled by 1/(Ix08*32), the Turbo PMAC's position scale factor), though the export writes no unit.
_PMAC_COUNTS = ("motor present desired position", "motor present actual position", "motor following error")
#: Heidenhain's scope channel types name their quantity by a letter before the role (TNCscope's ``s ist`` position,
#: ``v ist`` velocity, ``I ist`` current, as in its ``.sco`` files' ``%CHANNELTYPE``; pyLSV2's ``scope2csv.py`` writes
#: them as ``x_s_ist``, ``x_i_ist``): ``I`` before one of these role words is a current, not a position. (``v`` and
#: ``a`` are axis letters: beside the axis' own letter the name names two axes and is no position already.)
_TNC_ROLES = frozenset({"ist", "soll", "noml", "actl", "nom", "nominal"})
#: PA (Power Automation) CNC's axis variables, logged in the control's internal increments (PaDataAnalyze.py,
#: yangxiaosheng27/PA_Data_Analysize: "SSetPos, CommandedMachinePosCorr, SActMachinePos  Unit: internal increment
#: ... defaults to 1um"); the trace writes no unit and the increment is the machine's setting.
_PA_COUNTS = ("ssetpos", "commandedmachinepos", "sactmachinepos")
#: ECP Executive's encoder channels (``Encoder 1 Pos``, ``Encoder 2 Pos``, beside ``Commanded Pos``), in encoder counts
#: though its "Export Raw Data" writes no unit (our reading of its exports: integer positions, and the users' scripts
#: that scale them by the plant's counts per cm).
_ENCODER_COUNTS = re.compile(r"encoder\s*\d+\s*pos", re.IGNORECASE)
#: パルス / 脉冲: pulse.
_CJK_COUNTS = ("\u30d1\u30eb\u30b9", "\u8109\u51b2")
#: Universal Robots RTDE's joint positions and tool pose (module docstring): ``target_q_3``, ``actual_TCP_pose_0``.
_RTDE_Q = re.compile(r"(target|actual)_(q|TCP_pose)_(\d+)")
#: The last element of a signal path (``Test/t``, ``MAIN.Axis.Time``) that names a time column on its own.
_TIME_LEAVES = frozenset({"t", "time", "timestamp", "zeit"})
_PATH = re.compile(r"[/.]?(?:[\w#\[\]-]+[/.])+([\w#\[\]-]+)")
_WORD = re.compile(r"[A-Z]+(?![a-z])|[A-Z]?[a-z]+|\d+|[^\W\d_]+", re.UNICODE)
_BRACKETS = re.compile(r"[\[(][^\[\]()]*[\])]")
#: A unit in brackets at the end of a name; an integer in brackets is an index, not a unit (``SSetPos[2]``).
_TRAILING_UNIT = re.compile(r"[\[(](?!\s*\d+\s*[\])])\s*[^\[\]()]+?\s*[\])]\s*$")
#: An array index at the end of a name: the axis' number in a control's variable (``SActMachinePos[2]``).
_INDEX = re.compile(r"\[\s*(\d+)\s*\]\s*$")
#: An array's element as ``rostopic echo -p`` numbers it (:mod:`vcnc.traces.rostopic`): the joint of
#: ``field.desired.positions2`` and ``field.position2`` is 2.
_ROS_ELEMENT = re.compile(r"^field\.(?:.*\.)?positions?(\d+)$")
#: A first word shared by every name of a header (``EXP_`` of ``EXP_Time``, ``EXP_PosRef``), before its separator.
_PREFIX = re.compile(r"\s*([A-Za-z]+)[\s_.:/-]+(?=\S)")


def _words(name: str) -> list[str]:
    """The words of a column name, lower case, without units in brackets (``PosCmd`` -> pos, cmd)."""
    return [w.lower() for w in _WORD.findall(_BRACKETS.sub(" ", name))]


def _other_quantity(words: list[str]) -> bool:
    """True when the words of a name name a quantity that is no position (a velocity, a current, a sample counter...):
    a counter of pulses is a position in counts (``Feedback pulse counter``: Yaskawa's monitor Un00D "Feedback Pulse
    Counter" counts encoder pulses, Un00C "Input Reference Pulse Counter" reference units; Panasonic MINAS' "command
    pulse counter" and "feedback pulse counter", read out as positions by its RS232 command 2, modes 1 and 2)."""
    other = {w for w in words if w in _OTHER or any(p in w for p in _OTHER_PARTS)}
    return bool(other) and not (other <= _COUNTERS and _COUNT_WORDS.intersection(words))


def _role(words: list[str]) -> str | None:
    """``ref``, ``act``, ``lag`` or None for the words of a name (module docstring)."""
    if _other_quantity(words):
        return None
    roles = set()
    for w in words:
        if w in _REF or (len(w) > 4 and "soll" in w):
            roles.add("ref")
        elif w in _ACT or any(p in w for p in ("istwert", "istpos", "istlage")):
            roles.add("act")
        elif w in _LAG or (w in _ERROR and _LAG_ERROR.intersection(words)) or any(p in w for p in _LAG_PARTS):
            roles.add("lag")
        roles.update(r for r, parts in _CJK_PARTS.items() if any(p in w for p in parts))
    return roles.pop() if len(roles) == 1 else None


def _split_axis(words: list[str]) -> list[str]:
    """``xcmd`` -> ``x``, ``cmd``: a word that is an axis letter glued to a role word."""
    out = []
    for w in words:
        if len(w) > 1 and w[0] in AXIS_NAMES and _role([w[1:]]) is not None:
            out += [w[0], w[1:]]
        else:
            out.append(w)
    return out


def _is_time(name: str) -> bool:
    """A name made of time words only, its unit aside (``Zeit [ms]``, ``Zeit in ms``, ``rel_time_s``)."""
    words = _words(name)
    if unit_in_name(name, "time") is not None and not _TRAILING_UNIT.search(name):
        words = words[:-1]  # the unit after the name: 'in ms', '/ms', '_s'
    words = [w for w in words if w != "in"]
    return bool(words) and set(words) <= _TIME or _time_leaf(name) or _is_ipoc(name)


def _is_ipoc(name: str) -> bool:
    """KUKA RSI's ``IPOC`` (module docstring), with or without its unit, ms, in brackets or after a slash
    (``IPOC/ms``: tracewild37, trace_fuzz seed 42000516)."""
    return _words(name) in ([IPOC], [IPOC, "ms"])


def _time_leaf(name: str) -> bool:
    """A signal path whose last element is a time word alone (``BoosterMotorEncosTest/t``: recorders that name
    each channel by its block path, as Simulink's signal logging and ROS topics do; our reading)."""
    m = _PATH.fullmatch(name.strip())
    return m is not None and m.group(1).lower() in _TIME_LEAVES


def counted(name: str) -> str | None:
    """The count unit of a column logged in increments (``inc`` of ``Pos [inc]``, ``pulses`` of ``Droop
    pulses``, module docstring), else None."""
    m = _TRAILING_UNIT.search(name)
    unit = m.group(0).strip()[1:-1].strip().lower() if m else ""
    if unit in COUNT_UNITS:
        return unit
    if any(p in name.lower() for p in _PMAC_COUNTS):
        return "counts"
    if any(p in name.lower() for p in _PA_COUNTS):
        return "internal increments"
    if _ENCODER_COUNTS.fullmatch(name.strip()):
        return "counts"
    return next((w for w in _words(name) if w in _COUNT_WORDS or any(p in w for p in _CJK_COUNTS)), None)


def is_sample_number(name: str) -> bool:
    """True for a name of a column of sample numbers (``Sample #``, ``No.``, ``Index``)."""
    words = _words(name)
    return bool(words) and set(words) <= _SAMPLE or name.strip() == "#"


def rsi_orientation(name: str) -> bool:
    """True for KUKA RSI's orientation angles of the tool, ``A_RIst``, ``B_RSol``, ``RIst.C`` (module docstring)."""
    words = _words(name)
    rsi = any(a == "r" and b in ("ist", "sol") for a, b in zip(words, words[1:]))
    return rsi and any(w in ("a", "b", "c") for w in words)


def rsi_orientation_note(header: Sequence[str]) -> str:
    """The note for a header's KUKA RSI orientation angles that the names leave out, else ``""``."""
    angles = [h for h in header if rsi_orientation(h)]
    return (f"; left out {angles}: KUKA RSI's orientation angles of the tool (E6POS A about Z, B about Y, C about X), "
            "no axes" if angles else "")


def _position(name: str) -> tuple[str, str | None] | None:
    """(role, axis or None) of a position column, or None for any other column."""
    if rsi_orientation(name):
        return None
    if _TRAILING_UNIT.search(name) and unit_in_name(name, "length") is None and counted(name) is None:
        return None  # a unit that is neither a length nor counts: mm/min, A, Nm, %
    words = _path_words(name) or _split_axis(_words(name))
    role = _role(words)
    if role is None or any(a == "i" and b in _TNC_ROLES for a, b in zip(words, words[1:])):
        return None
    axes = {w for w in words if w in AXIS_NAMES}
    if len(axes) > 1:
        return None
    return role, (axes.pop() if axes else None)


def _path_words(name: str) -> list[str] | None:
    """The words of a PLC symbol or signal path whose last element names a position's role on its own
    (``MAIN.afbAxes[3].stAxisStruct.stStatus.fActPosition``, ``GVL.stAxis_X.fSetPosition``): that element's words
    after the whole axis letters of the elements before it (``Axis_X.SetPos``), else None.

    The elements before the last are the structures and arrays that hold the variable, named in a programmer's
    notation: their words give the variable no role (``afbAxes``, an array of function blocks, is no axis A's
    feedback ``a fb``), and a status structure (:data:`_STRUCTURES`: ``stStatus``, Tc2_MC2's ``ST_AxisStatus``) does
    not make its members status words; a quantity they name still makes the variable no position
    (``Spindle.ActPos``, ``Axis.Velocity.Cmd``). Our reading of IEC 61131-3 symbol paths as TwinCAT's Scope View
    exports them (its ``SymbolName`` row; anderssandstrom/amci_resolver_issue's exports, read by traces40); the whole
    name was read before: ``stStatus`` made a position a status word, ``afbAxes`` gave it two roles."""
    m = _PATH.fullmatch(name.strip())
    if m is None:
        return None
    leaf = _split_axis(_words(m.group(1)))
    before = _words(name.strip()[:m.start(1)])
    if _role(leaf) is None or _other_quantity([w for w in before if w not in _STRUCTURES]):
        return None
    return [w for w in before if w in AXIS_NAMES] + leaf


def columns_from_names(header: Sequence[str], *, period_known: bool = False) -> tuple[dict[str, str] | None, str]:
    """The mapping capture column -> header name read from the names (module docstring), and why
    not when it is None (``""`` with a mapping). With ``period_known`` (the sampling period is stated or
    given) a header without a time column maps a column of sample numbers, or none, as ``t``."""
    bare = _without_prefix(header)
    mapping = _columns(bare, period_known)[0] if bare is not None else None
    if bare is not None and mapping is not None:
        return {k: header[bare.index(v)] for k, v in mapping.items()}, ""
    return _columns(header, period_known)


def rtde_joints(header: Sequence[str]) -> str | None:
    """The question for a header of Universal Robots RTDE positions (module docstring), else None: joint positions
    ``target_q_N``/``actual_q_N`` in rad, or the tool's pose ``target_TCP_pose_N``/``actual_TCP_pose_N`` (N = 0, 1, 2:
    x, y, z in m; 3-5 a rotation vector in rad, no axis)."""
    found: dict[tuple[str, str], set[int]] = {}
    for h in header:
        if m := _RTDE_Q.fullmatch(h.strip()):
            found.setdefault((m.group(2), m.group(1)), set()).add(int(m.group(3)))
    for kind in ("q", "TCP_pose"):
        target, actual = found.get((kind, "target"), set()), found.get((kind, "actual"), set())
        both = sorted(target & actual)
        what = "joint positions" if kind == "q" else "tool (TCP) pose"
        if both and kind == "q":
            n = both[0]
            return (f"Universal Robots RTDE {what} target_q_N (commanded) and actual_q_N (measured), joints {both}, "
                    f"in rad: choose a joint and name it as a rotary axis, e.g. --columns "
                    f"t=timestamp,a_ref=target_q_{n},a=actual_q_{n} --unit rad")
        if both:
            return (f"Universal Robots RTDE {what} target_TCP_pose_N (commanded) and actual_TCP_pose_N (measured): "
                    "N = 0, 1, 2 are x, y, z in m (3-5 a rotation vector), e.g. --columns "
                    "t=timestamp,x_ref=target_TCP_pose_0,x=actual_TCP_pose_0 --unit m")
        for have, name, lack in ((actual, "actual", "target"), (target, "target", "actual")):
            if have:
                return (f"Universal Robots RTDE {what} {name}_{kind}_N only (N = {sorted(have)}), no {lack}_{kind}_N: "
                        "identification needs the commanded and the measured position (record both "
                        f"target_{kind} and actual_{kind})")
    return None


def rsi_joints(header: Sequence[str]) -> str | None:
    """The question for a header of KUKA RSI's axis-specific positions (``ASPos`` setpoint, ``AIPos`` actual, joints
    A1..A6 in deg, as ``kuka_rsi_hw_interface`` reads them; a logger's ``A1_AIPos`` or ``AIPos.A1``) without the
    Cartesian ``RIst``/``RSol`` pair, else None: a robot's joint is no axis of the capture by itself (as
    :func:`rtde_joints`); our reading of the names, no such log seen."""
    roles: dict[str, dict[int, str]] = {"ASPos": {}, "AIPos": {}}
    for h in header:
        words = _words(h)
        kind = next((f"A{a[1].upper()}Pos" for a, b in zip(words, words[1:]) if a in ("as", "ai") and b == "pos"),
                    None)
        joint = next((int(b) for a, b in zip(words, words[1:]) if a == "a" and b.isdigit()), None)
        if kind is not None and joint is not None:
            roles[kind].setdefault(joint, h)
    both = sorted(set(roles["ASPos"]) & set(roles["AIPos"]))
    if not both or any(_position(h) is not None for h in header):
        return None
    n = both[0]
    return (f"KUKA RSI axis-specific positions ASPos (setpoint) and AIPos (actual), joints "
            f"{[f'A{j}' for j in both]}, in deg: choose a joint and name it as a rotary axis, e.g. --columns "
            f"a_ref={roles['ASPos'][n]},a={roles['AIPos'][n]} with the time (IPOC, ms)")


def _columns(header: Sequence[str], period_known: bool) -> tuple[dict[str, str] | None, str]:
    """:func:`columns_from_names` of the names as they are."""
    rtde = rtde_joints(header) or rsi_joints(header) or joint_states_question(header)
    if rtde is not None:
        return None, rtde
    if len(set(header)) != len(header):
        return None, "the header repeats a name"
    mapping: dict[str, str] = {}
    times = [h for h in header if _is_time(h)]
    if len(times) > 1 and sum(map(_is_ipoc, times)) == 1:
        times = [h for h in times if _is_ipoc(h)]  # the controller's clock, not the logging PC's
    if not times and period_known:
        times = [h for h in header if is_sample_number(h)]
        if len(times) > 1:
            return None, f"several columns are named as sample numbers: {times}"
    elif len(times) != 1:
        samples = [h for h in header if is_sample_number(h)]
        timed = [h for h in header if _TIME.intersection(_words(h)) - {"us", "ms", "sec"}]  # 'motor_time [ms]'
        return None, (f"several columns are named as time: {times}" if times else "no column is named as time" + (
            f" ({samples[0]!r} counts samples: give --sample-time S, the sampling period)" if len(samples) == 1
            else f" (only names with more than time words: {timed}; give --columns t=NAME,...)" if timed
            else " (a file without one needs --sample-time S, the sampling period)"))
    if times:
        mapping["t"] = times[0]
    found = {h: _position(h) for h in header if h not in times}
    found = {h: p for h, p in found.items() if p is not None}
    found.update(_bare_counterparts(header, times, found))
    named_axes = {a for _, a in found.values() if a is not None}
    if len(named_axes) == 1:
        found.update(_roles_of_the_one_axis(found, named_axes.pop()))
        named_axes = {a for _, a in found.values() if a is not None}
    if not named_axes:
        found, why = _numbered_axis(found)
        if why:
            return None, why
    roles: dict[str, dict[str, list[str]]] = {}
    for h, (role, axis) in found.items():
        if axis is not None:
            roles.setdefault(axis, {"ref": [], "act": [], "lag": []})[role].append(h)
    for axis in [a for a in AXIS_NAMES if a in roles]:
        r = roles[axis]
        second = r["act"] or r["lag"]
        if len(r["ref"]) > 1 or len(second) > 1:
            return None, _several(axis, r)
        if r["ref"] and second:
            mapping[f"{axis}_ref"] = r["ref"][0]
            mapping[axis if r["act"] else axis + LAG_SUFFIX] = second[0]
    if len(mapping) == len(times):
        return None, _no_pair(header, times, found)
    return mapping, ""


def _several(axis: str, roles: dict[str, list[str]]) -> str:
    """Why an axis with several candidates for one role is a question: which role, and a role no column
    is named as (two encoders and no command are no pair to choose from)."""
    if len(roles["ref"]) > 1:
        many, role = roles["ref"], "the commanded position"
    else:
        many = roles["act"] or roles["lag"]
        role = "the measured position" if roles["act"] else "the following error"
    why = f"axis {axis}: several columns could be {role}: {many}"
    if not roles["ref"]:
        why += "; none is named as the commanded position, which identification needs beside the measured one"
    elif not (roles["act"] or roles["lag"]):
        why += "; none is named as the measured position"
    return why


def _without_prefix(header: Sequence[str]) -> list[str] | None:
    """The names without the first word they all share (``EXP_Time``, ``EXP_PosRef``, ``Exp_Current`` -> ``Time``,
    ``PosRef``, ``Current``: a logger's tag for its experiment or block), or None when they share none. A shared
    axis letter or a word of time, role, quantity or numbering (``X_cmd``, ``X_act``; ``Motor_1``) stays: it means
    something. Our reading of loggers that prefix every channel (ivliev123/Electro-Hydraulic-Actuator's exports)."""
    found = [_PREFIX.match(h) for h in header]
    if len(header) < 2 or not all(found):
        return None
    words = {m.group(1).lower() for m in found if m}
    word = words.pop() if len(words) == 1 else None
    if (word is None or word in AXIS_NAMES or _role([word]) is not None or word in _TIME | _OTHER | _NUMBERED | _SAMPLE
            or any(p in word for p in _OTHER_PARTS)):
        return None
    bare = [h[m.end():] for h, m in zip(header, found) if m]
    return bare if len(set(bare)) == len(bare) else None


def no_positions(header: Sequence[str]) -> bool:
    """True when no column of ``header`` can be a position: each is named as time or sample numbers, or as another
    quantity by a word (``setpoint_rpm``, ``Velocidad``, ``PWM``) or a unit that is neither a length nor counts
    (``Voltaje (V)``); a name without either (``Ch1``, ``Debug 0``) could be a position, and is not such a column."""
    def other(h: str) -> bool:
        unit = _TRAILING_UNIT.search(h) and unit_in_name(h, "length") is None and counted(h) is None
        return bool(unit) or _other_quantity(_words(h))

    named = [h for h in header if h.strip()]
    return bool(named) and all(_is_time(h) or is_sample_number(h) or other(h) for h in named)


def channels_from_names(names: Sequence[str], what: str) -> tuple[dict[str, str] | None, str]:
    """:func:`columns_from_names` for a reader that records its own time (TwinCAT Scope, halscope, camonitor): the
    channels' mapping without ``t``, or None and why not (also when a channel, a ``what``, is named as time)."""
    named, why = columns_from_names(names, period_known=True)
    if named is not None and "t" in named:
        return None, f"a {what} is named as time"
    return named, why


def mapping_note(what: str, mapping: Mapping[str, str]) -> str:
    """``meta["columns"]`` of a mapping read from the ``what`` names (``"from the channel names: x_ref=.., x=.."``)."""
    return f"from the {what} names: " + ", ".join(f"{k}={v}" for k, v in mapping.items())


#: Words before an axis' or motor's number in a channel name (``CH0 Axis1 ...``, ``joint 2 position``).
_NUMBERED = frozenset({"axis", "joint", "motor", "drive", "achse", "antrieb", "axe", "eje"})


def _axis_number(name: str) -> int | None:
    """The number of the axis, joint or motor a name belongs to (``1`` of ``CH0 Axis1 Motor present actual
    position``; ``2`` of ``SActMachinePos[2]``, an array index), else None."""
    words = _words(name)
    index = _INDEX.search(name) or _ROS_ELEMENT.match(name.strip())
    return next((int(b) for a, b in zip(words, words[1:]) if a in _NUMBERED and b.isdigit()),
                int(index.group(1)) if index else None)


def _numbered_axis(found: dict[str, tuple[str, str | None]]) -> tuple[dict[str, tuple[str, str | None]], str]:
    """Positions that name no axis letter, as axis x: when they number several axes or motors (a PMAC gather of
    motors 1 and 4), only those of the one number that has both a commanded and a measured position; a reason
    instead when none or several have (our reading: positions of different motors are never one pair)."""
    numbers = {h: _axis_number(h) for h in found}
    distinct = sorted({n for n in numbers.values() if n is not None})
    if len(distinct) < 2 or None in numbers.values():
        return {h: (role, "x") for h, (role, _) in found.items()}, ""
    roles = {n: {r for h, (r, _) in found.items() if numbers[h] == n} for n in distinct}
    paired = [n for n in distinct if "ref" in roles[n] and roles[n] & {"act", "lag"}]
    if len(paired) == 1:
        return {h: (role, "x") for h, (role, _) in found.items() if numbers[h] == paired[0]}, ""
    if paired:
        return {}, (f"axes {paired} each have a commanded and a measured position ({sorted(found)}): give --columns "
                    "for one")
    return {}, (f"the positions belong to axes {distinct}, none with both a commanded and a measured position: "
                f"{sorted(found)}")


def _bare_counterparts(header: Sequence[str], times: Sequence[str],
                       found: dict[str, tuple[str, str | None]]) -> dict[str, tuple[str, str | None]]:
    """The measured position named as its command without the command's word (``position`` beside
    ``positionCmd``, ``x`` beside ``x_cmd``: HEBI's and many loggers' logs), for a commanded position whose
    axis has no measured position or following error named (module docstring)."""
    out: dict[str, tuple[str, str | None]] = {}
    for h, (role, axis) in found.items():
        if role != "ref" or any(r != "ref" and a == axis for r, a in found.values()):
            continue
        key = [w for w in _split_axis(_words(h)) if _role([w]) is None]
        bare = [b for b in header if b not in found and b not in times and key and _split_axis(_words(b)) == key
                and not (_TRAILING_UNIT.search(b) and unit_in_name(b, "length") is None and counted(b) is None)
                and not _other_quantity(key)]
        if len(bare) == 1:
            out[bare[0]] = ("act", axis)
    return out


def _roles_of_the_one_axis(found: dict[str, tuple[str, str | None]], axis: str) -> dict[str, tuple[str, str]]:
    """Positions that name no axis (letter or number) beside positions of one named axis, as that axis' positions:
    each only for a role the axis has no column of, and only as the one of its role (``pos_cmd``, ``pos_fb`` beside
    ``X Following Error``: a logger naming the axis on some channels; tracewild10, from trace_fuzz seed 35100)."""
    taken = {r for r, a in found.values() if a == axis}
    bare: dict[str, list[str]] = {}
    for h, (role, a) in found.items():
        if a is None and _axis_number(h) is None:
            bare.setdefault(role, []).append(h)
    return {hs[0]: (role, axis) for role, hs in bare.items() if len(hs) == 1 and role not in taken}


def _no_pair(header: Sequence[str], times: Sequence[str], found: dict[str, tuple[str, str]]) -> str:
    """Why no pair was read: the positions named and the other quantities (a trace of speeds, currents or
    torques only cannot be read as positions)."""
    other = [h for h in header if h not in times and h not in found and _other_quantity(_words(h))
             and not is_sample_number(h)]
    plain = [h for h in header if h not in times and h not in found and h not in other
             and _POSITION_WORDS.intersection(_words(h))]
    seen = ([f"positions found: {sorted(found)}"] if found else []) + (
        [f"positions that name neither a command nor a measurement: {plain}"] if plain else []) + (
        [f"other quantities: {other}"] if other else [])
    return ("no pair of a commanded and a measured position is named" + (f" ({'; '.join(seen)})" if seen else "")
            + ("" if found else "; a position trace needs a commanded and a measured position" if other or plain
               else ""))


#: Words that name a position without its role (the ODrive GUI's "ODrive 0 Position"), for :func:`_no_pair`'s reason.
_POSITION_WORDS = frozenset({"position", "pos", "positions", "lage"})
