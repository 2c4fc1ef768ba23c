"""The simple contour formula of the SL cycles, ``CONTOUR DEF``, in Heidenhain conversational programs.

TNC 640 / TNC 620 / iTNC 530 user's manuals for cycle programming, "SL cycles with simple contour formula"
("Simple contour formula", "Entering a simple contour formula"): instead of cycle 14 CONTOUR GEOMETRY, the block
``CONTOUR DEF P1 = LBL 1 I2 = LBL 2 ..`` names up to nine subcontours, each a pocket (``Pn``) or an island
(``In``) by its letter, not by its direction and RL/RR as cycle 14 tells them; the SL cycles 20-24 then machine
the whole contour as they machine cycle 14's, and cycle 25 the first subcontour. Each subcontour may carry a
depth of its own (``DPn`` / ``DIn``; 0, the default: cycle 20's Q1 applies). No copy of those manual pages is in
the search index we could use: the words here are those of the dialog as the TNC writes it (``CONTOUR DEF`` /
``P1 = LBL 1`` / ``I2 = LBL 2`` / ``DI2 = +5``, continued over lines with ``~``), and the rules our reading.

What this module reads: :func:`contour_def`, the labels in the order of their numbers and their roles. The
regions are :func:`interpolators.heidenhain_contours.superimposed_region`'s: the union of the pockets less the
union of the islands, as cycle 14 superimposes its contours (TNC 426/430 user's manual, "Overlapping contours");
our reading, whatever the order: a pocket drawn inside an island stays uncut (a formula read from left to right,
P1 less I2, then with P3, would cut it; the manual's own pages on this are not in the index).

Not run, each with an error naming it: a subcontour in another program (``P1 = "FILE"``,
``SEL CONTOUR`` and the contour formula file with ``DECLARE CONTOUR`` and ``QC1 = ..``), and a depth DP/DI other
than 0 (the SL cycles here machine the whole region to one depth, cycle 20's Q1).
"""

from __future__ import annotations

import dataclasses
import re

from interpolators._words import Where
from interpolators.heidenhain_params import QParameters
from interpolators.heidenhain_words import read_value

__all__ = ["ContourDef", "contour_def", "MAX_SUBCONTOURS"]

#: Most subcontours of one simple contour formula (the manual: "up to nine subcontours").
MAX_SUBCONTOURS: int = 9

#: ``P1 = LBL 1``, ``I2 = LBL "NAME"``, ``P3 = LBL NAME``; group 3 the rest when the contour is not a label.
_ITEM_RE = re.compile(r"\s*([PI])(\d+)\s*=\s*(?:LBL\s*(?:\"([^\"]+)\"|'([^']+)'|(\d+)|([A-Z_]\w*))|(\S+))", re.I)
#: ``DP1 = ..``, ``DI2 = ..``: the depth of subcontour n.
_DEPTH_RE = re.compile(r"\s*D([PI])(\d+)\s*=\s*", re.I)


@dataclasses.dataclass(frozen=True, kw_only=True)
class ContourDef:
    """The subcontours of a ``CONTOUR DEF``, in the order of their numbers.

    Attributes
    ----------
    labels : tuple of str
        The label of each subcontour (``"1"`` or a name in upper case), as cycle 14's labels are kept.
    roles : tuple of str
        ``"P"`` (pocket) or ``"I"`` (island) for each.
    """

    labels: tuple[str, ...]
    roles: tuple[str, ...]


def _label(m: re.Match) -> str:
    for g in m.groups()[2:6]:
        if g is not None:
            return str(int(g)) if g.isdigit() else g.upper()
    raise AssertionError("a label pattern matched without a label")  # pragma: no cover


def contour_def(rest: str, where: Where, params: QParameters, *, column0: int) -> ContourDef:
    """The subcontours of ``CONTOUR DEF`` + ``rest`` (``column0``: the source column of ``rest[0]``).

    Each ``Pn = LBL m`` / ``In = LBL m`` once, n from 1 to :data:`MAX_SUBCONTOURS`; ``DPn = value`` / ``DIn = value``
    (a number, Q parameter or formula) after its subcontour. Errors name the word: a contour in another program, a
    depth other than 0 (not supported here, see the module's docstring), a number given twice, a depth for a
    subcontour not defined, anything else."""
    items: dict[int, tuple[str, str]] = {}
    pos = 0
    while rest[pos:].strip():
        start = pos + len(rest[pos:]) - len(rest[pos:].lstrip())
        tok = rest[start:].split()[0]
        d = _DEPTH_RE.match(rest, pos)
        if d is not None:
            role, n = d.group(1).upper(), int(d.group(2))
            value, pos = read_value(rest, d.end(), where, params, what=f"D{role}{n}", column0=column0)
            if items.get(n, ("", ""))[1] != role:
                where.fail(f"CONTOUR DEF: depth D{role}{n} of a subcontour {role}{n} not defined before it",
                           column=column0 + start, text=tok, expected=f"{role}{n} = LBL .. before D{role}{n}")
            if value != 0.0:
                where.fail(f"CONTOUR DEF: the depth D{role}{n} = {value:g} of a subcontour of its own is not "
                           "supported (the SL cycles here machine every subcontour to cycle 20's depth Q1)",
                           column=column0 + start, text=tok, expected=f"D{role}{n} = 0 or no D{role}{n} (Q1 applies)")
            continue
        m = _ITEM_RE.match(rest, pos)
        if m is None:
            where.fail(f"CONTOUR DEF: {tok!r} is not a subcontour", column=column0 + start, text=tok,
                       expected="Pn = LBL m (a pocket), In = LBL m (an island), DPn / DIn = depth")
        role, n = m.group(1).upper(), int(m.group(2))
        if m.group(7) is not None:
            where.fail(f"CONTOUR DEF: the subcontour {role}{n} = {m.group(7)} in another program is not supported",
                       column=column0 + m.start(7), text=m.group(7),
                       expected=f"{role}{n} = LBL m (a label of this program)")
        if not 1 <= n <= MAX_SUBCONTOURS or n in items:
            where.fail(f"CONTOUR DEF: subcontour number {role}{n}", column=column0 + start, text=tok,
                       expected=f"each number from 1 to {MAX_SUBCONTOURS} once")
        items[n] = (_label(m), role)
        pos = m.end()
    if not items:
        where.fail("CONTOUR DEF without a subcontour", column=column0, text=rest.strip() or "CONTOUR DEF",
                   expected="CONTOUR DEF P1 = LBL 1 [I2 = LBL 2 ..]")
    if "0" in (label for label, _ in items.values()):
        where.fail("CONTOUR DEF: LBL 0 cannot be a subcontour", column=column0, text=rest.strip(),
                   expected="a label 1..999 or a name")
    order = sorted(items)
    return ContourDef(labels=tuple(items[n][0] for n in order), roles=tuple(items[n][1] for n in order))
