"""Fanuc and Haas positioning codes around the reference position, and their one-shot stops.

Besides ``G28``/``G30`` (:mod:`interpolators.iso`), Fanuc and Haas mills read these group 00 (one-shot)
codes, and Fanuc the group 04 stroke check; LinuxCNC has none of them (its G-code reference
``docs/src/gcode/g-code.adoc`` lists no G9, G22, G23, G27, G29 or G60; ``interp_array.cc`` ``gees[]``
marks them -1, "Unknown g code used"), so there they stay errors naming the feature.

Sources: Fanuc Series 0i-MD operator's manual (B-64304EN) II-"Reference position" ("Reference position
return (G28)", "Movement from the reference position (G29)", "Reference position return check (G27)"),
II-"Feedrate control" ("Exact stop (G09)"), II-"Stored stroke check" ("G22/G23") and II-"Single direction
positioning (G60)"; Haas mill operator's manual, G-code pages "G09 Exact Stop (Group 00)", "G29 Return From
Reference Point (Group 00)" ("the axes selected in this block are moved to the G29 reference point saved in
G28, and then moved to the location specified in the G29 command") and "G60 Uni-Directional Positioning
(Group 00)". The Fanuc manual's own text was not found in our search index: the rules below are our reading
of it, and of the secondary descriptions the index holds (Mitsubishi M700V programming manual 14.7
"Reference (Zero) Position Return; G28, G29": "by commanding G29, the axes are first positioned
independently at high speed to the G28 or G30 intermediate point and then positioned by G0 at the
commanded position",
https://manualshive.com/en/manual/mitsubishi-electric/m700v-series/238523?page=523; Centroid M-Series
operator's manual "G29 - Return from Reference Point").

* ``G09`` (Fanuc, Haas): the block's motion ends in an exact stop (no blending into the next block); the
  modal path mode (G61/G64) is unchanged.
* ``G27 X.. Y.. Z..`` (Fanuc): a rapid to the point (G90/G91, as G00), then the control checks that the named
  axes are at the reference position (the G28 position) and alarms (PS0092) where they are not. vcnc's
  reference position is the machine context's home, which need not be the real machine's: a miss is
  noted, not refused.
* ``G29 X.. Y.. Z..`` (Fanuc, Haas): the named axes go at rapid to the intermediate point the last G28 or
  G30 passed through (its program coordinates, so that it follows a change of work offset: Fanuc), then to
  the programmed point (under G91 an increment from the intermediate point). Only the named axes move; an
  axis no G28/G30 named has no intermediate point, which is an error here.
* ``G60 X.. Y.. Z..`` (Fanuc, Haas): positioning whose last stretch approaches the end point from one
  direction, after an overrun (Fanuc parameter No. 5440 per axis, its sign the direction; a Haas setting).
  vcnc has no machine setting for it: the positioning is run as a rapid to the end point (the end point
  is the same), with a note saying the overrun is not modelled.
* ``G22 X Y Z I J K`` / ``G23`` (Fanuc): stored stroke check 2 on (the words are the forbidden area's corners,
  no motion) / off: no motion, noted.
* ``G43.1 H..`` (Fanuc, "Tool length compensation in tool axis direction"): along the tool axis, which is Z
  while the rotary axes stand at 0: run as ``G43`` (noted); with a rotary axis turned, an error. (LinuxCNC's
  G43.1 is the dynamic offset of its axis words.)
* ``G30.1`` (Fanuc "Floating reference position return"): to a position the operator sets on the machine,
  unknown here: an error (LinuxCNC's G30.1 stores the current position, and runs so under ``linuxcnc``).
* ``G62`` / ``G63`` (Fanuc, modal group 15 with G61 and G64: "Automatic corner override", "Tapping mode"):
  blocks are not stopped at their ends (G63 also ignores the feed override; G62 lowers the feed at inner
  corners under cutter compensation): run as continuous path (G64), noted.

The Fanuc Series 15 format rigid tapping codes ``G84.2``/``G84.3`` are named in the error of every dialect:
no manual of the controls vcnc reads (Fanuc 0i-MF in its own format, Haas, LinuxCNC) that documents them
for the milling control was found (Fanuc writes ``M29 S..`` before ``G84``/``G74`` for rigid tapping).
"""

from __future__ import annotations

import numpy as np

__all__ = ["MILL_CODES", "FANUC_CODES", "NAMED_CODES", "REFERENCE_TOLERANCE", "off_reference",
           "stored_intermediate"]

#: Codes the ``fanuc`` and ``haas`` dialects run (round(10 * G) -> (group, name)).
MILL_CODES: dict[int, tuple[str, str]] = {
    90: ("exact stop check", "G09 exact stop"),
    290: ("nonmodal", "G29 return from the reference position"),
    600: ("nonmodal", "G60 single direction positioning"),
    # LinuxCNC's G30.1 stores the position; Fanuc's returns to the floating reference position, a position the
    # operator sets on the machine (Fanuc 0i-MD "Floating reference position return (G30.1)"): refused
    301: ("refused", "G30.1 floating reference position return (Fanuc: the floating reference is a machine "
                     "position vcnc does not know)"),
}

#: Codes only the ``fanuc`` dialect runs.
FANUC_CODES: dict[int, tuple[str, str]] = {
    270: ("nonmodal", "G27 reference position return check"),
    220: ("stroke check", "G22 stored stroke check on"), 230: ("stroke check", "G23 stored stroke check off"),
    620: ("path", "G62 automatic corner override"), 630: ("path", "G63 tapping mode"),
    431: ("length compensation", "G43.1 tool length compensation in tool axis direction"),
}

#: The same codes (and G84.2/G84.3) named in the error of a dialect that does not run them.
NAMED_CODES: dict[int, str] = {
    90: "G09 exact stop for one block (Fanuc/Haas; --dialect fanuc or haas; LinuxCNC has G61 exact path mode)",
    270: "G27 reference position return check (Fanuc; --dialect fanuc)",
    290: "G29 return from the reference position (Fanuc/Haas; --dialect fanuc or haas)",
    600: "G60 single direction positioning (Fanuc/Haas; --dialect fanuc or haas)",
    220: "G22 stored stroke check on (Fanuc; --dialect fanuc)",
    230: "G23 stored stroke check off (Fanuc; --dialect fanuc)",
    620: "G62 automatic corner override (Fanuc; --dialect fanuc)", 630: "G63 tapping mode (Fanuc; --dialect fanuc)",
    53: "G5.3 end of a G5.2 NURBS block", 1360: "G136 automatic work offset centre measurement (Haas probing)",
    1530: "G153 5-axis high speed peck drilling cycle (Haas)", 110: "G11 parameter input by program cancel (Fanuc)",
    # named after the Fanuc 0i-MF G code list (B-64604EN "G code list", our reading) and Haas "G37":
    # run under --dialect fanuc (interpolators.iso_modal_call); the Haas mill G-code list has G65 but no G66/G67
    660: "G66 modal macro call (Fanuc; --dialect fanuc; Haas mills have G65 only)",
    661: "G66.1 modal macro call, each block (Fanuc; --dialect fanuc; Haas mills have G65 only)",
    670: "G67 modal macro call cancel (Fanuc; --dialect fanuc; Haas mills have G65 only)",
    370: "G37 automatic tool length measurement (Fanuc/Haas probing)",
    121: "G12.1 polar coordinate interpolation (Fanuc)", 131: "G13.1 polar coordinate interpolation cancel (Fanuc)",
    71: "G07.1 cylindrical interpolation (Fanuc)", 22: "G02.2 involute interpolation (Fanuc)",
    32: "G03.2 involute interpolation (Fanuc)",
    390: "G39 corner circular interpolation (Fanuc/Haas; --dialect fanuc or haas)",
    721: "G72.1 figure copy, rotary (Fanuc mill) / lathe facing cycle (LinuxCNC)",
    722: "G72.2 figure copy, linear (Fanuc mill)",
    542: "G54.2 rotary table dynamic fixture offset (Fanuc)",
    842: "G84.2 rigid tapping cycle (Fanuc Series 15 program format; Fanuc 0i: M29 S.. then G84)",
    843: "G84.3 left-handed rigid tapping cycle (Fanuc Series 15 program format; Fanuc 0i: M29 S.. then G74)",
}

#: How far [mm] an axis may be from the reference position for ``G27`` to find it there (our choice: 1 um,
#: the least input increment of a metric Fanuc mill; the control checks its in-position width).
REFERENCE_TOLERANCE = 1e-3


def off_reference(pos: np.ndarray, reference: np.ndarray, axes: list[str]) -> list[str]:
    """The axes among ``axes`` (``"X"``, ``"Y"``, ``"Z"``) whose machine position ``pos`` [mm] is not at
    ``reference`` [mm] within :data:`REFERENCE_TOLERANCE`: where ``G27`` alarms."""
    return [a for a in axes if abs(pos["XYZ".index(a)] - reference["XYZ".index(a)]) > REFERENCE_TOLERANCE]


def stored_intermediate(stored: np.ndarray, current: np.ndarray, axes: list[str]) -> np.ndarray:
    """Program coordinates [mm] of the ``G29`` intermediate point: ``stored`` (the last G28/G30 intermediate
    point, NaN where no G28/G30 named the axis) for the named ``axes``, ``current`` elsewhere.

    Raises
    ------
    KeyError
        With the first named axis that has no stored intermediate point.
    """
    point = np.array(current, dtype=float)
    for a in axes:
        i = "XYZ".index(a)
        if np.isnan(stored[i]):
            raise KeyError(a)
        point[i] = stored[i]
    return point
