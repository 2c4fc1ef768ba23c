"""A program's reading as text, bit for bit: what the readers' shortcuts (``iso_fast``, ``heidenhain_fast``) must
give exactly as their general paths do; and the corpus' programs of one language to compare them on."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator

import numpy as np

from benchmarks.gcode_corpus import corpus_dir, manifest, origin_context
from interpolators import detect_dialect
from interpolators._words import program_text
from interpolators.context import MachineContext
from interpolators.program import Block, Program


def program_digest(prog: Program) -> list[str]:
    """The program's axes, notes, messages and name, then one line per block: every field of
    :class:`interpolators.program.Block` (also one added later, which a shortcut must set) and its segment's
    type and slots, floats and arrays by their bits."""
    out = [repr((prog.axes, prog.notes, prog.messages, prog.name))]
    for b in prog.blocks:
        fields = [exact(getattr(b, f.name)) for f in dataclasses.fields(Block) if f.name != "segment"]
        seg = b.segment
        if seg is not None:
            fields.append(type(seg).__name__)
            fields.extend(exact(getattr(seg, s)) for s in type(seg).__slots__)
        out.append(" ".join(fields))
    return out


def exact(v) -> str:  # noqa: ANN001
    """``v`` as text that differs whenever a bit of it does."""
    if isinstance(v, np.ndarray):
        return v.tobytes().hex()
    if isinstance(v, float):
        return v.hex()
    if isinstance(v, tuple):
        return "(" + ",".join(exact(x) for x in v) + ")"
    return repr(v)


def corpus_programs(dialect: str) -> Iterator[tuple[str, str, MachineContext]]:
    """``(file, text, context of its origin)`` of each corpus program in ``dialect`` (``"iso"`` or
    ``"heidenhain"``, by content); none when the corpus is absent."""
    folder = corpus_dir()
    for row in manifest(folder) if folder is not None else ():
        text = program_text(str(folder / row["file"]))
        if detect_dialect(text) == dialect:
            yield row["file"], text, origin_context(row["origin"])
