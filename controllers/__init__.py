"""Servo laws: P-PI cascade, PID, adaptive sliding mode, pole placement + Kalman filter (+ ZPETC),
and PDF with integer parameters.

Every law is a frozen keyword-only dataclass following :class:`controllers._base.Controller`:
``pack`` (parameters of the compiled kernel), ``discrete_law`` (the sampled linear law as
python-control transfer functions), ``closed_loop`` (G_track, G_dist of Eq. (3.1)) and, for the
continuous laws, ``reduced_parameters`` (Eqs. (3.4), (3.5)).
"""

from controllers._base import Controller, DiscreteLaw, discrete_closed_loop, frequency_response
from controllers.pdf import PDF
from controllers.pid import PID
from controllers.pole_placement import PolePlacement, design_pole_placement
from controllers.ppi import PPI
from controllers.sliding_mode import SlidingMode
from controllers.zpetc import ZPETC, design_zpetc

__all__ = [
    "Controller",
    "DiscreteLaw",
    "PID",
    "PPI",
    "SlidingMode",
    "PolePlacement",
    "PDF",
    "ZPETC",
    "design_zpetc",
    "design_pole_placement",
    "discrete_closed_loop",
    "frequency_response",
    "CONTROLLERS",
]

#: TOML ``type`` of ``[axes.<a>.controller]`` -> class
CONTROLLERS = {cls.TABLE: cls for cls in (PID, PPI, SlidingMode, PolePlacement, PDF)}
