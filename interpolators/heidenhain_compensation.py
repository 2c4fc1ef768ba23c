"""Tool radius compensation of Heidenhain conversational programs: ``RL`` / ``RR`` / ``R0`` switched at motion
blocks, and the finished run's blocks replaced by the tool-centre path of
:func:`interpolators.compensation.compensate` (on the machine state :class:`interpolators.heidenhain.Machine`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from interpolators._words import Where
from interpolators.compensation import CompensationError, compensate
from interpolators.heidenhain_words import Word

if TYPE_CHECKING:
    from interpolators.heidenhain import Machine

__all__ = ["set_compensation", "finish_compensation", "TANGENT_TOLERANCE"]

#: Turns [rad] up to which two compensated elements meet as tangent ones (rounding of the program's coordinates
#: and of arcs' ends, far below a display step of 0.0001 mm on any tool radius): a larger outside turn gets its
#: transition arc, a larger inside one the intersection. The TNC has no LinuxCNC-like 0.05 rad tolerance: "If you
#: program radius compensation, the TNC moves the tool around outside corners on a transitional arc" and "The TNC
#: calculates the intersection of the tool center paths at inside corners" (TNC 640 ISO user's manual 34059x-05,
#: 5.3 "Radius compensation: Machining corners"; TNC 426/425/415 B/407 manual: the tool "rolls around" the corner
#: point), for every corner; how small a corner the control still rounds is not documented (our reading: all).
TANGENT_TOLERANCE = 1e-9


def set_compensation(word: Word, m: Machine, where: Where) -> bool:
    """Switch RL/RR/R0 at a motion block; True when this block is the exit move of a run.

    The block with RL/RR is the entry move of a compensated run and the first block with R0 its
    exit move (TNC 640 user's manual, "Tool radius compensation": RL/RR take effect in the
    block that programs them; R0 cancels it), as in :func:`interpolators.compensation.compensate`.
    """
    comp = word.key
    if comp == m.comp:
        return False
    if comp != "R0" and m.comp != "R0":
        where.fail(f"{comp} while {m.comp} is active", column=word.column, text=word.text,
                   expected="R0 between RL and RR")
    if comp != "R0" and m.tool_radius < 0:
        # R + DR below zero (a TNC simulator's demo: DR-2 on a tool the context's table does not hold, radius
        # 0); no manual page found says which side, if any, the control then compensates on
        where.fail(f"{comp} with a negative tool radius {m.tool_radius:g} mm (the tool's radius R plus DR of its "
                   "TOOL CALL) is not modelled", column=word.column, text=word.text,
                   expected="R + DR >= 0: the tool in the machine context's tool table or a TOOL DEF n L.. R..")
    m.comp = comp
    if comp == "R0":
        return True
    m.comp_start = len(m.blocks)
    # a mirrored contour has its left side on the right (TNC: "the machining direction is reversed")
    m.comp_side = {"RL": "RR", "RR": "RL"}[comp] if m.transform.flips(m.plane) else comp
    m.comp_radius = m.tool_radius
    return False


def finish_compensation(m: Machine, *, open_end: bool = False, closed: bool = False) -> None:
    """Replace the blocks of the finished run by the tool-centre path. ``open_end``: the run's last
    block is a contour element (the arc of DEP CT/LCT), offset as the others, not a straight exit move.
    ``closed``: the run's last block is the R0 block, which positions the tool at its programmed point
    even when it names only the tool axis (iTNC 530 / TNC 620 ISO user's manuals, "Tool radius
    compensation": "In the first block in which radius compensation is ... canceled with G40 the TNC
    always positions the tool perpendicular to the programmed starting or end position"; R0: "The tool
    center moves ... to the programmed coordinates"), as :func:`compensate`'s ``closed``."""
    start, m.comp_start = m.comp_start, None
    side = "left" if m.comp_side == "RL" else "right"
    m.comp = "R0"
    look_ahead, m.look_ahead = m.look_ahead, False  # R0 ends M120
    run = m.blocks[start:]
    if m.comp_radius == 0.0 or not run:
        return
    try:
        new = compensate(run, side=side, radius=m.comp_radius, plane=m.plane, entry="perpendicular",
                         open_end=open_end, closed=closed, convex_tolerance=TANGENT_TOLERANCE, every_line=True)
    except CompensationError as exc:
        b = run[min(exc.index, len(run) - 1)]
        ahead = " (M120 LA would leave the undercut out: not modelled)" if look_ahead else ""
        Where(m.source, b.line, b.text).fail(f"radius compensation {m.comp_side}: {exc.message}{ahead}", column=1,
                                              text=b.text,
                                              expected="a contour the tool of radius "
                                                       f"{m.comp_radius:g} mm can follow")
    m.blocks[start:] = new
    m.pos = np.array(new[-1].target, dtype=float)
