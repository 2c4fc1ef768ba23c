"""``M128`` (TCPM, tool centre point management) of Heidenhain conversational programs, on positioned rotary axes.

HEIDENHAIN TNC7 user's manual (German, 81762x-17, content.heidenhain.de/doku/tnc_guide/pdf_files/TNC7/81762x-17),
M128: "Wenn sich im NC-Programm die Position einer gesteuerten Drehachse ändert, kompensiert die Steuerung mit
M128 während des Schwenkvorgangs automatisch die Werkzeuganstellung mithilfe einer Ausgleichsbewegung der
Linearachsen. Somit bleibt die Position der Werkzeugspitze gegenüber dem Werkstück unverändert (TCPM)." (the
TNC 640 manual's "Retaining the position of the tool tip when positioning tilting axes (TCPM): M128"); the
programmed X, Y, Z are the tool tip on the workpiece; M129 cancels it. On a machine whose rotary axes turn
the part (a trunnion table, :class:`interpolators.tilted.Kinematics` ``kind = "table"``) the spindle stays
along Z, so the tip of a workpiece point ``p`` (where it is with every rotary axis at 0, tool length included
along Z) is where the table carries it: ``machine = place(p - L, angles) + L``.

What vcnc reads (the "3+2" use of M128 that CAM posts write, NX: ``L B76.323 C-150.677 FMAX``, ``L M128
F3000.``, then straight lines): the rotary axes stay where they are while M128 is on, and the blocks are
straight lines ``L`` (and ``M140`` retracts along the spindle). Then every line maps to a straight line of the
machine (a rigid motion of the table) and its end points are exact. A rotary axis moving under M128
(simultaneous 5-axis: the tip path is no straight line of the machine), an arc, a polar, approach or
compensated block, a cycle, a tilted plane, a head-tilting machine or a tool axis other than Z are errors
naming them.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from interpolators._words import Where
from interpolators.tilted import Kinematics

__all__ = ["TCPM_EXPECTED", "check_tcpm_on", "part_point", "machine_point"]

#: What M128 needs here.
TCPM_EXPECTED = ("M128 on a machine whose rotary axes turn the part ([program.kinematics] kind = \"table\"), tool "
                 "axis Z, no tilted plane, the rotary axes positioned before M128 and straight lines L until M129")


def check_tcpm_on(kinematics: Kinematics | None, *, tool_axis: int, tilted: bool, where: Where, column: int,
                  text: str) -> None:
    """An error at ``where`` unless M128 can be read on this machine in this state (see the module text)."""
    if kinematics is None:
        where.fail("M128 (TCPM, tool centre point management) needs the machine's kinematics", column=column,
                   text=text, expected=TCPM_EXPECTED)
    if kinematics.kind != "table":
        where.fail("M128 (TCPM) on a head-tilting machine is not supported", column=column, text=text,
                   expected=TCPM_EXPECTED)
    if tool_axis != 2 or tilted:
        where.fail("M128 (TCPM) with a tilted working plane or a tool axis other than Z is not supported",
                   column=column, text=text, expected=TCPM_EXPECTED)


def _tool(length: float) -> np.ndarray:
    return np.array([0.0, 0.0, length])


def part_point(kinematics: Kinematics, extra: Sequence[float], position: Sequence[float], length: float) -> np.ndarray:
    """Where the tool tip at machine ``position`` [mm] is on the part with every rotary axis at 0 [mm, machine,
    tool length ``length`` along Z included], the rotary axes at ``extra`` (a, b, c first) [deg]."""
    angles = kinematics.solution_at(extra)
    return kinematics.unplace(np.asarray(position, dtype=float) - _tool(length), angles) + _tool(length)


def machine_point(kinematics: Kinematics, extra: Sequence[float], point: Sequence[float], length: float) -> np.ndarray:
    """The inverse of :func:`part_point`: the machine position [mm] of the part point ``point``."""
    angles = kinematics.solution_at(extra)
    return kinematics.place(np.asarray(point, dtype=float) - _tool(length), angles) + _tool(length)
