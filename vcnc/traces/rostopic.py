"""ROS 1 ``rostopic echo -p`` tables (a topic, or a bag with ``-b``, printed for plotting), read by
:mod:`vcnc.traces.delimited`.

``rostopic echo -p`` writes one comma-separated row per message: ``%time``, the time the message was received in
nanoseconds since 1970 (ROS' ``Time.to_nsec()``), then every field of the message under its path, ``field.`` and the
field names joined by dots, an array's elements numbered after its name (``field.position0``, ``field.position1``,
``field.desired.positions0``; ``rostopic`` ``_str_plot_fields``). A joint controller's state
(``control_msgs/JointTrajectoryControllerState``: ``desired``, ``actual`` and ``error`` points) thus names joint N's
commanded and measured position ``field.desired.positionsN`` and ``field.actual.positionsN``;
``sensor_msgs/JointState`` holds measured positions only (``field.positionN``). ROS states positions in SI units (REP
103, "Standard Units of Measure and Coordinate Conventions": metres, radians): a prismatic joint's in m, a revolute
joint's in rad, which the table does not say; vcnc never assumes one (:func:`unit_question`).
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence

__all__ = ["TIME_UNIT", "is_rostopic_table", "unit_question", "unit_options", "joint_states_question"]

#: The unit of ``%time`` and of header stamps: nanoseconds.
TIME_UNIT = "ns"
_FIELD = "field."


def is_rostopic_table(header: Sequence[str] | None) -> bool:
    """True for the names of a ``rostopic echo -p`` table: ``%time`` (read as ``time``, its comment mark set
    aside) and then only message fields, ``field.<path>``."""
    return (header is not None and len(header) > 1 and header[0].lstrip("%").strip().lower() == "time"
            and all(h.startswith(_FIELD) for h in header[1:]))


def unit_question(columns: Mapping[str, str]) -> str:
    """The error's text for positions of a ``rostopic echo -p`` table read without a unit (module docstring)."""
    named = ", ".join(f"{k}={v}" for k, v in columns.items() if k != "t")
    return (f"rostopic echo -p positions {named} are in SI units (ROS REP 103): m for a prismatic joint, rad for a "
            "revolute one, and the table does not say which")


def unit_options(columns: Mapping[str, str]) -> str:
    """The options that read the positions of ``columns`` (a mapping of one axis): ``--unit m`` for a prismatic
    joint, or the joint mapped as a rotary axis with ``--unit rad``."""
    ref = next(k for k in columns if k.endswith("_ref"))
    act = next(k for k in columns if k not in ("t", ref))
    time = f"t={columns['t']}," if "t" in columns else ""
    return (f"--unit m (a prismatic joint), or --columns {time}a_ref={columns[ref]},a{act[1:]}={columns[act]} "
            "--unit rad (a revolute joint, as a rotary axis)")


#: A JointState's measured positions, ``field.position0`` ...
_JOINT_STATE = re.compile(r"field\.position(\d+)")


def joint_states_question(header: Sequence[str]) -> str | None:
    """The question for a ``rostopic echo -p`` table of ``sensor_msgs/JointState`` (``field.positionN`` only: the
    joints' measured positions, no command beside them), else None (module docstring)."""
    if not is_rostopic_table(header):
        return None
    joints = [int(m.group(1)) for h in header if (m := _JOINT_STATE.fullmatch(h))]
    if not joints or any(".positions" in h for h in header):
        return None
    return (f"a rostopic echo -p table of sensor_msgs/JointState: the joints' measured positions field.positionN "
            f"(N = {joints}) with no commanded position beside them; identification needs both: record the joint "
            "controller's state topic (control_msgs/JointTrajectoryControllerState, field.desired.positionsN and "
            "field.actual.positionsN)")
