"""Exact path geometry (lines, arcs, helices) and ready-made part programs.

Programs are returned as text (mm, absolute); write them with :func:`write_program` (atomic).
"""

from toolpaths.geometry import AXIS_LETTERS, PLANE_AXES, Arc, Line, Path, Segment
from toolpaths.identification import IDENTIFICATION_KINDS, heidenhain_identification, random_moves
from toolpaths.packed import PackedSegments
from toolpaths.shapes import back_and_forth, circle, diamond
from toolpaths.writer import DIALECTS, ProgramWriter, write_program

__all__ = [
    "AXIS_LETTERS",
    "DIALECTS",
    "IDENTIFICATION_KINDS",
    "PLANE_AXES",
    "Arc",
    "Line",
    "PackedSegments",
    "Path",
    "ProgramWriter",
    "Segment",
    "back_and_forth",
    "circle",
    "diamond",
    "heidenhain_identification",
    "random_moves",
    "write_program",
]
