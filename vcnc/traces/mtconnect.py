"""MTConnect data that is no trace: an agent's streams document and an adapter's SHDR stream, named as such.

An MTConnect agent answers ``/sample`` and ``/current`` with an ``MTConnectStreams`` XML document whose samples
are observations on change, each with its own time stamp (MTConnect Standard, Part 3 "Observation Information
Model"): an axis' ``Position`` sample carries a ``subType`` ``ACTUAL``, ``COMMANDED``, ``PROGRAMMED`` or
``TARGET``, a path's ``PathPosition`` the tool's position as one "x y z" value. An adapter sends the agent the same
observations as SHDR lines, ``timestamp|key|value|key|value`` (cppagent wiki "SHDR 2.0", e.g.
``2009-06-15T00:00:00.000000|power|ON|line|412|Xact|-1.1761875153``).

Neither is a drive trace: the observations are taken when a value changes and at the agent's or the adapter's
rate (tens to hundreds of ms; an Okuma agent's streams seen in tracewild5 hold ``ACTUAL`` positions only, 100 to
200 ms apart), not at the control's servo rate, and a commanded position is rarely among them. vcnc names the
document and the positions it holds instead of reading it (our reading: a wrong reading of such data as a trace
would be worse than a question); a trace of the control's own (TNCscope, SINUMERIK trace, a drive's scope) is
what identification needs. The agent's other response documents, ``MTConnectDevices`` (``/probe``),
``MTConnectAssets`` and ``MTConnectError``, hold no observation and are named as what they are too.
"""

from __future__ import annotations

import re
from collections import Counter

__all__ = ["looks_like_shdr", "streams_reason", "shdr_reason", "document_reason"]

#: A position sample, also with a namespace prefix (``<m:Position ..>``, as the root ``<m:MTConnectStreams>``).
_SAMPLE = re.compile(r"<(?:[A-Za-z_][\w.-]*:)?(Position|PathPosition)\b([^>]*)>")
_ATTR = re.compile(r'\b(name|dataItemId|subType)="([^"]*)"')
#: An SHDR line: an optional time stamp, then ``|key|value`` pairs.
_SHDR = re.compile(r"^(?:\d{4}-\d\d-\d\dT[\d:.]+Z?|TIME)?\|[A-Za-z_][\w.:-]*\|[^|]*(?:\|[^|]*)*$")


#: What identification needs instead, ending each reason.
_NEEDED = (". vcnc identifies a drive from its control's or drive's own trace (TNCscope, SINUMERIK trace, a drive's "
           "scope) of a commanded and a measured position")


def looks_like_shdr(text: str) -> bool:
    """True when most of the first non-blank lines (up to 20, at least 2) are SHDR lines (module docstring)."""
    lines = [s for s in (line.strip() for line in text.splitlines()[:200]) if s and not s.startswith(("*", "#"))][:20]
    return len(lines) >= 2 and sum(bool(_SHDR.match(s)) for s in lines) >= 0.8 * len(lines)


def _sample_names(text: str) -> Counter[str]:
    """``name (subType)`` of each position sample of a streams document, counted."""
    found: Counter[str] = Counter()
    for kind, attrs in _SAMPLE.findall(text):
        a = dict(_ATTR.findall(attrs))
        name = a.get("name") or a.get("dataItemId") or kind
        found[f"{name} ({a['subType']})" if "subType" in a else f"{name} ({kind})"] += 1
    return found


def streams_reason(text: str) -> str:
    """Why an ``MTConnectStreams`` document is not read: the position samples it holds (module docstring)."""
    found = _sample_names(text)
    held = ", ".join(f"{k} x{n}" for k, n in found.most_common(12)) if found else "none"
    commanded = any("(COMMANDED)" in k for k in found)
    return ("an MTConnect streams document (an agent's /sample or /current answer): observations taken on change at "
            f"the agent's rate, each with its own time stamp, not a trace sampled at the control's servo rate; its "
            f"position samples: {held}" + ("" if commanded else "; no COMMANDED position among them") + _NEEDED)


def shdr_reason(text: str) -> str:
    """Why an SHDR stream is not read: the keys it sends (module docstring)."""
    keys: dict[str, None] = {}
    for line in text.splitlines()[:2000]:
        if _SHDR.match(line.strip()):
            keys.update(dict.fromkeys(k.strip() for k in line.strip().split("|")[1::2]))
    return ("an MTConnect SHDR adapter stream (timestamp|key|value lines, cppagent wiki 'SHDR 2.0'): observations sent "
            "on change at the adapter's rate, not a trace sampled at the control's servo rate; keys: "
            f"{list(keys)[:20]}" + _NEEDED)


#: The agent's other answers (MTConnect Standard, Part 1 "Overview and Fundamentals", the response documents):
#: none holds an observation.
_DOCUMENTS = {
    "MTConnectDevices": "an agent's /probe answer: the machine's components and data items, no observations",
    "MTConnectAssets": "an agent's /assets answer: tools, programs or fixtures, no observations",
    "MTConnectError": "an agent's answer to a request it refused, no observations",
}


def document_reason(root: str) -> str | None:
    """Why an MTConnect response document other than streams is not read (``root``: its root element, without a
    namespace prefix), or None for another root."""
    what = _DOCUMENTS.get(root)
    if what is None:
        return None
    return (f"an MTConnect {root[len('MTConnect'):].lower()} document ({what}); an agent's /sample answer (a streams "
            "document) holds the observations, taken on change at the agent's rate, which is no servo trace either"
            + _NEEDED)
