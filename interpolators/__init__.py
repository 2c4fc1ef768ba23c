"""G-code (ISO and Heidenhain conversational) -> program -> feed profiles -> sampled setpoints.

::

    from interpolators import load_program, interpolate
    program = load_program("part.nc")                 # dialect detected from the content
    setpoints = interpolate(program, profile="scurve") # DEFAULT_LIMITS, Ts = 1 ms

Units: positions mm, feeds mm/s inside (``F`` is mm/min in the program), time s.
"""

from interpolators.arcs import ARC_TOLERANCE
from interpolators.interpolate import MAX_SAMPLES, interpolate
from interpolators.limits import DEFAULT_LIMITS, DEFAULT_ROTARY_LIMITS, DEFAULT_SECONDARY_LIMITS, AxisLimits
from interpolators.lookahead import DEFAULT_TOLERANCE
from interpolators.parse import detect_dialect, load_program, parse_program
from interpolators.profiles import PROFILES
from interpolators.program import Block, Program

__all__ = [
    "ARC_TOLERANCE",
    "AxisLimits",
    "Block",
    "DEFAULT_LIMITS",
    "DEFAULT_ROTARY_LIMITS",
    "DEFAULT_SECONDARY_LIMITS",
    "DEFAULT_TOLERANCE",
    "MAX_SAMPLES",
    "PROFILES",
    "Program",
    "detect_dialect",
    "interpolate",
    "load_program",
    "parse_program",
]
