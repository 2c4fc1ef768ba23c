"""LinuxCNC halscope logs ("Save log"), in the two layouts ``write_log_file`` has written
(LinuxCNC ``src/hal/utils/scope_files.c``):

- **LinuxCNC 2.9 and later** (commit ff911089a7, 2022, "Change logfile to csv format"):
  ``# Sampling period is <n> ns``, a line of channel names separated by ``;``, optional ``#``
  lines (``# Position: ...``, ``# Scale: ...`` since 2026), then one line per sample of values
  separated by ``;`` (``%.14f``, C locale).
- **LinuxCNC 2.8 and earlier**: ``Sampling period is <n> ns`` (``nSec`` in 2006), then one line
  per sample of ``<label> <value>`` pairs (``%+.14f``); the last line may be a partial sample.
  Read as real logs of this layout were found written (tracewild, session 16), following the
  source of those versions: the numbers are printed in the user's locale (LinuxCNC pull request
  #1500 set ``LC_NUMERIC`` to ``C`` only for 2.9), so a decimal comma (``+5,00000000000000``) is
  read; the loop ran ``while (n <= samples)`` (fixed in commit 8eae446b80, "Fixes some minor bugs
  regarding logging"), so the last line is one sample past the record, read from beyond the
  captured data (zeros in the logs found), and is dropped (``meta["dropped"]``); channels not
  enabled are labelled ``(null)``.

Only the channels that become positions must hold numbers: a ``nan`` or ``-nan`` that halscope
printed in another channel (an unused acceleration, found in a real log) is not an error.

Without a mapping, the position pins of each joint pair up: ``joint.N.motor-pos-cmd`` /
``joint.N.motor-pos-fb`` (before ``joint.N.pos-cmd`` / ``pos-fb``; ``axis.N`` in LinuxCNC 2.7),
or signals named ``<axis>-pos-cmd`` / ``<axis>-pos-fb`` or ``<axis>pos-cmd`` / ``<axis>pos-fb``
(the names stepconf and pncconf give them). Joints are named x, y, z... in order (``axes``
overrides), signals by their axis letter. A commanded pin without its ``-fb`` pin (a real log
traced the encoder's position instead) is an error naming the pin and the other position channels.

**Following error.** A joint traced with its commanded pin and ``joint.N.f-error`` (``axis.N.f-error``
up to 2.7) but no ``-fb`` pin, or mapped as ``x_lag=LABEL``, is read with the measured position =
commanded - following error. LinuxCNC computes ``joint->ferror = joint->pos_cmd - joint->pos_fb`` in
``process_inputs`` (``src/emc/motion/control.c``), before ``get_pos_cmds`` moves ``pos_cmd`` on, and
``output_to_hal`` then publishes both: the ``f-error`` of a sample is against the ``pos-cmd`` of the
sample before. So the measured position of sample k is the commanded position of sample k - 1 less
the ``f-error`` of sample k, and the first sample is dropped (``meta["dropped_first"]``); the same
holds for ``motor-pos-cmd``, which adds the motor offset that ``motor-pos-fb`` carries too. A real
log (tracewild's ``halscope_skyfire_svm2.log``, LinuxCNC 2.8, Mesa 7i76e: ``motor-pos-cmd``,
``f-error`` and the encoder's position, 2000 samples with a 65 mm/s move) holds this to 4e-14 mm,
against 0.065 mm (one sample at speed) from the same sample's command. It is exact when the scope
samples the servo thread every period (halscope's multiplier 1). Another channel mapped as a
following error (``pid.N.error``, command - feedback of the same period, pid(9)) is subtracted
from the same sample's command. The sign is checked on the data (:mod:`vcnc.traces.lag`). With both
a ``-fb`` pin and ``f-error``, the ``-fb`` pin is used: it is the measurement, and needs neither the
convention nor the one-sample shift.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from vcnc.core.axes import AXIS_NAMES
from vcnc.core.capture import Capture
from vcnc.core.errors import CaptureError
from vcnc.traces.columns import (
    LAG_SUFFIX,
    mapped_axes,
    mapping_meta,
    parse_number,
    position_scale,
    read_text,
    with_following_errors,
)
from vcnc.traces.names import channels_from_names, mapping_note

__all__ = ["read_halscope", "looks_like_halscope"]

_PERIOD = re.compile(r"^\s*(#)?\s*Sampling period is\s+(\d+)\s*n(?:s|sec)\b", re.I)
_PIN = re.compile(r"^(?P<joint>(?:joint|axis)\.(?P<n>\d+)\.)(?P<motor>motor-)?pos-(?P<role>cmd|fb)$")
_FERROR = re.compile(r"^(?:joint|axis)\.(?P<n>\d+)\.f-error$")
#: How LinuxCNC signs a joint's following error, and where it says so.
LAG_CONVENTION = ("pos-cmd - pos-fb (LinuxCNC src/emc/motion/control.c: joint->ferror = joint->pos_cmd - "
                  "joint->pos_fb)")
#: The label halscope (LinuxCNC <= 2.8) prints for a channel not enabled (``label[chan_num]`` of an unset
#: channel, printed with ``%s``).
_UNUSED = "(null)"
_SIGNAL = re.compile(r"^(?P<axis>[xyzabcuvw])-?pos-(?P<role>cmd|fb)$", re.I)


def looks_like_halscope(text: str) -> bool:
    """True when the first line that is not blank is halscope's ``Sampling period is ... ns``."""
    first = next((ln for ln in text.lstrip("\ufeff").splitlines() if ln.strip()), "")
    return bool(_PERIOD.match(first))


def read_halscope(path: str | os.PathLike[str], *, columns: Mapping[str, str] | None = None,
                  unit: str | None = None, axes: Sequence[str] | None = None) -> Capture:
    """Read a halscope log (module docstring) into a capture.

    Parameters
    ----------
    path : path-like
        The log.
    columns : mapping, optional
        ``{"x_ref": LABEL, "x": LABEL, ...}`` (``"x_lag": LABEL`` for a following error); default
        the joint position pins, paired (module docstring).
    unit : {"mm", "um", "nm", "m", "in", "deg"} or a count size ("0.1um"), optional
        Unit of the positions, or the size of one count of positions logged in increments
        (:func:`vcnc.traces.columns.length_unit`) (default mm: the machine units of a metric configuration).
    axes : sequence of str, optional
        Names of the joints, in joint order.

    Raises
    ------
    CaptureError
        Naming the file and line: no samples, a value that is not a number, a row of the wrong
        length, labels that change, a channel not found (listing the channels).
    """
    src = str(Path(path))
    lines = read_text(path, src).lstrip("\ufeff").splitlines()
    first = next((i for i, ln in enumerate(lines) if ln.strip()), None)
    m = _PERIOD.match(lines[first]) if first is not None else None
    if m is None:
        raise CaptureError("expected 'Sampling period is <n> ns' on the first line (halscope log)", file=src, line=1)
    period = int(m.group(2)) * 1e-9
    if period <= 0:
        raise CaptureError("the sampling period must be > 0 ns", file=src, line=first + 1)
    body = list(enumerate(lines[first + 1:], start=first + 2))
    table = m.group(1) is not None
    labels, rows, row_lines = (_table if table else _pairs)(body, src)
    meta = {"format": "halscope log", "sample_time_s": f"{period:.9g}", "unit": unit or "mm"}
    if not table and rows:
        meta["dropped"] = f"line {row_lines[-1]}: one sample past the record (LinuxCNC <= 2.8)"
        rows, row_lines = rows[:-1], row_lines[:-1]
    if len(rows) < 2:
        raise CaptureError(f"fewer than two samples after 'Sampling period is ... ns'; channels: {labels}", file=src)
    mapping, note = ({k: v for k, v in columns.items() if k != "t"}, "") if columns else _joint_pairs(labels, axes, src)
    if note:
        meta["columns"] = note
    ax = mapped_axes(mapping, src)
    missing = [v for v in mapping.values() if v not in labels]
    if missing:
        raise CaptureError(f"channel(s) {missing} not found; channels found: {labels}", file=src, line=row_lines[0])
    s = position_scale(ax, unit, src)
    second = [mapping.get(a) or mapping[a + LAG_SUFFIX] for a in ax]
    used = [labels.index(mapping[f"{a}_ref"]) for a in ax] + [labels.index(name) for name in second]
    data = _numbers(rows, row_lines, used, labels, src, decimal_comma=not table) * s
    ref, meas = data[:, : len(ax)], data[:, len(ax):]
    prev = ref
    if any(_FERROR.match(name) for name in second):
        # motion's f-error of a sample is against the pos-cmd of the one before (module docstring)
        if len(rows) < 3:
            raise CaptureError(f"fewer than three samples; a following error pin needs one more; channels: {labels}",
                               file=src)
        prev, ref, meas = ref[:-1], ref[1:], meas[1:]
        meta["dropped_first"] = (f"line {row_lines[0]}: motion's f-error is against the previous sample's pos-cmd "
                                 "(control.c), so the first sample has no measured position")
    # motion's f-error pins against the previous sample's command, another channel (pid.N.error) the same sample's
    against = np.column_stack([(prev if _FERROR.match(name) else ref)[:, j] for j, name in enumerate(second)])
    meas, lag_meta = with_following_errors(ax, mapping, against, meas, period, src, expected=LAG_CONVENTION,
                                           line=row_lines[0])
    return Capture(t=np.round(np.arange(ref.shape[0]) * period, 12), axes=tuple(ax), reference=ref, measured=meas,
                   meta={**meta, **mapping_meta(ax, mapping), **lag_meta}, source=src)


def _numbers(rows: list[list[str]], row_lines: list[int], used: list[int], labels: list[str], src: str, *,
             decimal_comma: bool) -> np.ndarray:
    """The values of the channels ``used`` (indices into ``labels``) as numbers, rows by samples;
    a cell that is empty or not a number is an error naming the line and the channel."""
    out = np.empty((len(rows), len(used)))
    for k, (cells, i) in enumerate(zip(rows, row_lines)):
        for j, c in enumerate(used):
            try:
                out[k, j] = parse_number(cells[c], decimal_comma=decimal_comma)
            except ValueError:
                raise CaptureError(f"channel {labels[c]!r}: {cells[c].strip()!r} is not a number", file=src,
                                   line=i) from None
            if out[k, j] != out[k, j]:
                raise CaptureError(f"channel {labels[c]!r}: an empty value", file=src, line=i)
    return out


def _table(body: list[tuple[int, str]], src: str) -> tuple[list[str], list[list[str]], list[int]]:
    """LinuxCNC 2.9+: a ``;`` line of names, then ``;`` rows of values (``#`` lines skipped)."""
    content = [(i, ln) for i, ln in body if ln.strip() and not ln.lstrip().startswith("#")]
    if not content:
        raise CaptureError("no channel names after 'Sampling period is ... ns'", file=src)
    labels = [c.strip() for c in content[0][1].split(";")]
    rows, row_lines = [], []
    for k, (i, line) in enumerate(content[1:], start=1):
        cells = line.split(";")
        if len(cells) != len(labels):
            if k == len(content) - 1 and len(cells) < len(labels):  # a log cut short in its last line
                break
            raise CaptureError(f"{len(cells)} values, expected {len(labels)} (channels {labels})", file=src, line=i)
        rows.append(cells)
        row_lines.append(i)
    return labels, rows, row_lines


def _pairs(body: list[tuple[int, str]], src: str) -> tuple[list[str], list[list[str]], list[int]]:
    """LinuxCNC 2.8 and earlier: ``<label> <value>`` pairs, one sample per line; the last line,
    complete or partial, is the one written past the record (module docstring)."""
    content = [(i, ln.split()) for i, ln in body if ln.strip()]
    labels: list[str] = []
    rows, row_lines = [], []
    for k, (i, parts) in enumerate(content):
        last = k == len(content) - 1
        names, values = parts[::2], parts[1::2]
        if len(parts) % 2 or (labels and names != labels):
            if last and labels and names == labels[: len(names)]:  # halscope may end on a partial sample
                rows.append(values)
                row_lines.append(i)
                break
            if len(parts) % 2:
                raise CaptureError("expected '<label> <value>' pairs", file=src, line=i, text=" ".join(parts))
            raise CaptureError(f"labels {names} differ from the first sample's {labels}", file=src, line=i)
        labels = labels or names
        rows.append(values)
        row_lines.append(i)
    return labels, rows, row_lines


def _joint_pairs(labels: list[str], axes: Sequence[str] | None, src: str) -> tuple[dict[str, str], str]:
    """Commanded/feedback pins of each joint (module docstring), named ``axes`` in joint order; without
    joint or axis pins, channels whose names leave no doubt (``pid.x.command`` / ``pid.x.feedback``, the
    PID component's pins a tuning session scopes; :func:`vcnc.traces.names.columns_from_names`, no
    following error: its sign convention is the pins'), with the note for ``meta["columns"]``."""
    pins: dict[tuple[int, str], dict[str, str]] = {}
    letters: dict[str, dict[str, str]] = {}
    ferrors: dict[int, str] = {}
    for name in labels:
        m = _PIN.match(name)
        if m:
            rank = 0 if m.group("motor") else 1
            pins.setdefault((int(m.group("n")), m.group("role")), {}).setdefault(str(rank), name)
        f = _FERROR.match(name)
        if f:
            ferrors.setdefault(int(f.group("n")), name)
        s = _SIGNAL.match(name)
        if s:
            letters.setdefault(s.group("axis").lower(), {}).setdefault(s.group("role").lower(), name)
    joints = sorted({n for n, _ in pins if (n, "cmd") in pins and ((n, "fb") in pins or n in ferrors)})
    out: dict[str, str] = {}
    if joints:
        names = list(axes) if axes else list(AXIS_NAMES[: len(joints)])
        if len(names) != len(joints):
            raise CaptureError(f"{len(names)} axis name(s) for joints {joints}", file=src)
        for a, j in zip(names, joints):
            cmd, fb = pins[(j, "cmd")], pins.get((j, "fb"))
            if fb is None:  # the following error in the feedback's place (module docstring)
                out[f"{a}_ref"], out[a + LAG_SUFFIX] = cmd.get("0") or cmd["1"], ferrors[j]
                continue
            rank = "0" if "0" in cmd and "0" in fb else "1"
            out[f"{a}_ref"] = cmd.get(rank) or next(iter(cmd.values()))
            out[a] = fb.get(rank) or next(iter(fb.values()))
        return out, ""
    for a in AXIS_NAMES:
        if {"cmd", "fb"} <= letters.get(a, {}).keys():
            out[f"{a}_ref"], out[a] = letters[a]["cmd"], letters[a]["fb"]
    if not out:
        alone = sorted(name for (_, role), names in pins.items() if role == "cmd" for name in names.values())
        if alone:  # a real log (tracewild): the feedback traced was an encoder's position, not the joint's pin
            others = [n for n in labels if "pos" in n.lower() and n not in alone]
            raise CaptureError(f"{alone[0]} has no -fb pin: give --columns x_ref={alone[0]},x=FEEDBACK; channels "
                               f"found: {labels}; other position channels: {others}", file=src)
        # halscope labels the channels not enabled '(null)' (module docstring): no names, and no repeated one
        named, why = channels_from_names([n for n in labels if n != _UNUSED], "channel")
        if named is not None and not any(k.endswith(LAG_SUFFIX) for k in named):
            return named, mapping_note("channel", named)
        raise CaptureError("no joint.N.motor-pos-cmd / joint.N.motor-pos-fb pair (nor <axis>-pos-cmd / -fb "
                           f"signals); give --columns x_ref=LABEL,x=LABEL; channels found: {labels} (not read from "
                           f"the names: {why or 'a following error channel'})", file=src)
    return out, ""
