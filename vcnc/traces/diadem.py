"""DIAdem DAT files: a text header naming each channel, its values in binary companion files beside it.

KUKA's robot controllers (KR C4, KSS 8) record their trace (KUKA.Trace, ``$TRACE``) in this format: per recording a
``<name>_KRCIpo.dat`` and one ``<name>_NextGenDrive#<n>.dat`` per drive, each with a ``.r64`` of REAL64 values beside
it (the readers of such traces: ``xikuibin/KukaTraceHelper`` "KUKA robots use DIAdem data file to storage the trace
data", and a KR C4 client whose ``KUKA_Trace.read_dat`` reads channels ``Sollposition``, ``Istposition``,
``Positionsschleppfehler``, ``Istmoment``, ``Iststrom`` and the time channel ``Zeit``). Other recorders write it too.

Layout, as National Instruments documents the DIAdem header (the DIAdem help, "DIAdem data file format": the keys
as KukaTraceHelper's ``Channel_Header_KEY`` lists them):

- ``#BEGINGLOBALHEADER`` ... ``#ENDGLOBALHEADER``, then per channel ``#BEGINCHANNELHEADER`` ...
  ``#ENDCHANNELHEADER``, each line ``code,value``: ``200`` the channel's name, ``202`` its unit, ``210`` the channel
  type (``EXPLICIT``/``EXPLIZIT``: values in a file; ``IMPLICIT``/``IMPLIZIT``: values ``240 + i * 241``, an
  equidistant time axis), ``211`` the file holding the values, ``213`` the storage method (``BLOCK``: one record per
  sample holding a value of each channel of that file, ``221`` the channel's place in the record; ``CHANNEL``: the
  channel's values one after another, ``221`` the place of its first value), ``214`` the data type (``REAL64``,
  ``REAL32``, ``INT16``, ``INT32``, ``WORD8``, ``WORD16``, ``WORD32``), ``220`` the number of values, ``240`` and
  ``241`` offset and factor (an explicit channel's value is ``240 + 241 * stored``; the places of ``221`` count
  from 1);
- the values little-endian (Windows, global header ``1,WINDOWS``).

:func:`read_diadem_channels` returns the channels' names (with their units, ``Sollposition [Grad]``) and values; the
delimited reader (:mod:`vcnc.traces.delimited`) maps them by their names as any table. German unit names DIAdem
writes in a German installation (``Grad``) are read as their symbols (our reading: KUKA's German channel names come
with German units). ASCII channel files and binary files with a header (``222``) are refused naming the channel.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import NamedTuple

import numpy as np

from vcnc.core.errors import CaptureError

__all__ = ["DiademChannels", "header_naming", "looks_like_diadem", "read_diadem_channels"]

_BEGIN = "#BEGINCHANNELHEADER"
_END = "#ENDCHANNELHEADER"
_LINE = re.compile(r"^\s*(\d+)\s*,(.*)$")
#: DIAdem's binary data types (NI's list for key 214), little-endian.
_TYPES = {"REAL64": "<f8", "REAL32": "<f4", "INT16": "<i2", "INT32": "<i4", "WORD8": "u1", "WORD16": "<u2",
          "WORD32": "<u4"}
_EXPLICIT = {"EXPLICIT", "EXPLIZIT"}
_IMPLICIT = {"IMPLICIT", "IMPLIZIT"}
#: German unit names of a German DIAdem installation, as the unit symbols vcnc reads.
_UNITS = {"grad": "deg", "sekunden": "s", "sek": "s"}


class DiademChannels(NamedTuple):
    """A DIAdem file's channels."""

    names: list[str]  #: ``name [unit]`` per channel, in the header's order
    plain: list[str]  #: the channels' names alone (key 200)
    values: np.ndarray  #: one column per channel
    header_line: int  #: the 1-based line of the first channel header
    files: list[str]  #: the companion files read


def looks_like_diadem(text: str) -> bool:
    """True for a DIAdem DAT header: a ``#BEGINCHANNELHEADER`` line with a ``200,`` name line after it."""
    i = text.find(_BEGIN)
    return i >= 0 and re.search(r"^\s*200\s*,", text[i:i + 2000], flags=re.M) is not None


def header_naming(data_file: Path) -> Path | None:
    """The DIAdem header beside ``data_file`` that names it as a channel's data file (key 211), else None: the header
    of the same name first (KUKA.Trace's ``T1_NextGenDrive#1.dat`` beside its ``.r64``), then any ``.dat``."""
    try:
        siblings = sorted((p for p in data_file.parent.iterdir() if p.suffix.lower() == ".dat" and p.is_file()),
                          key=lambda p: p.stem != data_file.stem)
    except OSError:
        return None
    named = re.compile(r"^\s*211\s*,\s*" + re.escape(data_file.name) + r"\s*$", flags=re.M | re.I)
    for header in siblings:
        try:
            with header.open("rb") as f:
                text = f.read(200000).decode("latin-1")
        except OSError:
            continue
        if looks_like_diadem(text) and named.search(text):
            return header
    return None


def _channel_headers(text: str) -> list[tuple[int, dict[str, str]]]:
    """Each channel header's first line (1-based) and its ``code -> value``."""
    out: list[tuple[int, dict[str, str]]] = []
    current: dict[str, str] | None = None
    for n, line in enumerate(text.splitlines(), start=1):
        s = line.strip()
        if s == _BEGIN:
            current = {}
            out.append((n, current))
        elif s == _END:
            current = None
        elif current is not None:
            m = _LINE.match(s)
            if m:
                current.setdefault(m.group(1), m.group(2).strip())
    return out


def _number(keys: dict[str, str], code: str, default: float, src: str, line: int) -> float:
    text = keys.get(code, "").strip()
    if not text:
        return default
    try:
        return float(text)
    except ValueError:
        raise CaptureError(f"DIAdem channel {keys.get('200', '?')!r}: key {code} is {text!r}, not a number",
                           file=src, line=line) from None


def _explicit(keys: dict[str, str], count: int, folder: Path, src: str, line: int,
              cache: dict[tuple[str, str], np.ndarray]) -> np.ndarray:
    """An explicit channel's stored values (module docstring), before 240/241."""
    name = keys.get("200", "?")
    dtype = _TYPES.get(keys.get("214", "").upper())
    if dtype is None:
        raise CaptureError(f"DIAdem channel {name!r} has data type {keys.get('214', '(none)')!r}; read are "
                           f"{', '.join(_TYPES)} (binary)", file=src, line=line)
    if _number(keys, "222", 0.0, src, line) != 0:
        raise CaptureError(f"DIAdem channel {name!r} is stored with a per-value offset (key 222), which is not read",
                           file=src, line=line)
    file = keys.get("211", "")
    path = folder / file
    if not file or not path.is_file():
        raise CaptureError(f"DIAdem channel {name!r}: its values are in {file or '(no file named, key 211)'!r}, which "
                           f"is not beside the header; copy the .dat with its data files (KUKA.Trace: the .r64 of "
                           f"the same name)", file=src, line=line)
    raw = cache.get((file, dtype))
    if raw is None:  # not setdefault: its argument, the file's whole read, would run for every channel
        raw = cache[(file, dtype)] = np.fromfile(path, dtype=dtype)
    place = int(_number(keys, "221", 1, src, line)) - 1
    if keys.get("213", "BLOCK").upper() == "CHANNEL":
        values = raw[max(place, 0):max(place, 0) + count]
    elif count and raw.size % count == 0 and 0 <= place < raw.size // count:
        values = raw.reshape(count, -1)[:, place]
    else:
        values = raw[:0]
    if values.size != count:
        raise CaptureError(f"DIAdem channel {name!r}: {file!r} holds {raw.size} values of {keys.get('214')}, fewer "
                           f"than the header's {count} at place {place + 1}", file=src, line=line)
    return values.astype(float)


def read_diadem_channels(text: str, path: Path, src: str) -> DiademChannels:
    """The channels of the DIAdem header ``text`` of ``path`` (module docstring), their values read from the
    companion files beside it."""
    headers = _channel_headers(text)
    if not headers:
        raise CaptureError("a DIAdem header without channel headers", file=src)
    names: list[str] = []
    plain: list[str] = []
    columns: list[np.ndarray] = []
    cache: dict[tuple[str, str], np.ndarray] = {}
    for line, keys in headers:
        count = int(_number(keys, "220", 0, src, line))
        kind = keys.get("210", "").upper()
        offset, factor = _number(keys, "240", 0.0, src, line), _number(keys, "241", 1.0, src, line)
        if kind in _IMPLICIT:
            values = offset + factor * np.arange(count, dtype=float)
        elif kind in _EXPLICIT:
            values = offset + factor * _explicit(keys, count, path.parent, src, line, cache)
        else:
            raise CaptureError(f"DIAdem channel {keys.get('200', '?')!r} has channel type {kind or '(none)'!r}; read "
                               "are EXPLICIT and IMPLICIT", file=src, line=line)
        unit = keys.get("202", "").strip()
        unit = _UNITS.get(unit.lower(), unit)
        plain.append(keys.get("200", "").strip())
        names.append(f"{plain[-1]} [{unit}]" if unit else plain[-1])
        columns.append(values)
    lengths = {c.size for c in columns}
    if len(lengths) != 1:
        sizes = ", ".join(f"{n}: {c.size}" for n, c in zip(names, columns))
        raise CaptureError(f"the DIAdem channels hold different numbers of values ({sizes}); vcnc reads channels "
                           "sampled together", file=src, line=headers[0][0])
    return DiademChannels(names, plain, np.column_stack(columns), headers[0][0], sorted({f for f, _ in cache}))
