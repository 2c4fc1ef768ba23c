"""Directive lines of the CNCSimulator Pro school simulator in an ISO program (not G-code).

CNCSimulator Pro user guide, 6. "Codes and commands" and 6.3 "$-commands and regions"
(http://cncsimulator.info/OnlineHelp2/codes_and_commands.htm, .../__commands_and_regions.htm):
"$-commands" are "special simulation commands for controlling the various aspects of the simulation.
They have nothing to do with CNC codes and should not be transferred to a real CNC controller"; a
$-command "always starts with a $ sign followed by the command word" (``$AddRegPart 1 X2.9 Y2.0``
places workpiece 1 of the simulator's registry on the table, ``$Inches``, ``$Mill`` check the
simulated machine), and a block of them may be wrapped in ``#region`` ... ``#endregion`` lines so that
the simulator's editor can fold it. Programs written in that simulator for a Fanuc or Haas mill keep
those lines. They place the workpiece in the simulator only: the tool does not move, so they are not
run here, with a note naming them, as a real control's operator would delete them before loading.

Only lines that *start* with ``$`` and a command word of four letters or more (the shortest in the
guide's examples is ``$Mill``), or that are ``#region`` / ``#endregion`` (a region name may follow after
a space), are such lines: none of them is G-code in LinuxCNC (``$`` is its spindle-number word and takes a
number), Fanuc or Haas (``#`` followed by a letter is no parameter; ``#1``, ``#<name>`` and ``#[..]`` stay
parameters). grbl's system commands are shorter (``$H``, ``$G``, ``$I``, ``$X``, ``$SLP``, ``$RST=..``):
outside the ``grbl`` dialect they stay errors (a grbl file read as another control's), and under it every
``$`` line keeps grbl's meaning (:mod:`interpolators.iso_grbl`).
"""

from __future__ import annotations

import re

__all__ = ["simulator_lines"]

#: A CNCSimulator Pro directive line: ``$`` and a command word, or a region mark (our reading of the
#: user guide: the command word follows the ``$`` directly, the region line may name the region). A ``$`` and
#: a file name (``$OKUMA.SSB%``, an Okuma OSP file header) is no directive: the reader names that control.
_DIRECTIVE = re.compile(r"[ \t]*(?:\$[A-Za-z]{4,}(?![A-Za-z=.])|#(?:end)?region(?:[ \t]|$))", re.IGNORECASE)
#: The region marks alone (the lines kept from grbl's ``$`` reading).
_REGION = re.compile(r"[ \t]*#(?:end)?region(?:[ \t]|$)", re.IGNORECASE)


def simulator_lines(text: str, *, dollar: bool = True) -> tuple[str, int]:
    """``text`` with the CNCSimulator Pro directive lines blanked (line numbers kept), and how many.

    Parameters
    ----------
    text : str
        The program, lines split at ``\\n``.
    dollar : bool
        Whether ``$`` lines are the simulator's (False under grbl, where they are system commands):
        then only the ``#region`` / ``#endregion`` lines are blanked.
    """
    if "$" not in text and "#" not in text:
        return text, 0
    pattern = _DIRECTIVE if dollar else _REGION
    lines = text.split("\n")
    blanked = 0
    for i, raw in enumerate(lines):
        if pattern.match(raw):
            lines[i] = ""
            blanked += 1
    return ("\n".join(lines), blanked) if blanked else (text, 0)
