"""Rapid identification of reduced closed-loop axis models (thesis chapters 3 and 4).

Public surface:

* :class:`ReducedAxisModel`, :func:`discretize`, :func:`simulate` - the model of Eq. (3.3) and its
  exact sampled simulation (``identification.reduced_model``);
* :func:`regressor`, :func:`iter_regressor`, :class:`SufficientStatistics`, :func:`statistics` -
  the regression of Eqs. (3.9)-(3.11) and its streamed statistics (Eq. 3.19);
* :func:`solve` (P, R, gamma) and :func:`solve_statistics` - the constrained problem with methods
  ``exact``, ``ga`` (Sec. 4.2) and ``kkt`` (Sec. 3.3);
* :func:`identify` / :class:`Identifier` - capture in, model out (the fit, then the residual diagnosis);
  :func:`load_model` - model file;
* :func:`identify_gain_scales` - controller scale gains of an integer PDF loop (Liu et al. 2008).
"""

from identification.bounds import PoleBounds, default_bounds
from identification.capture_checks import check_capture
from identification.effect_record import EffectRecord
from identification.exact import ExactOptions
from identification.ga import GAOptions
from identification.gain_scales import GainScaleResult, identify_gain_scales, pdf_gain_scales
from identification.model_file import load_model
from identification.pipeline import Identifier, identify
from identification.reduced_model import (
    PARAMETER_NAMES,
    PARAMETER_UNITS,
    DiscreteModel,
    ReducedAxisModel,
    discretize,
    simulate,
)
from identification.regressor import (
    COLUMNS,
    RegressorOptions,
    SufficientStatistics,
    iter_regressor,
    regressor,
    statistics,
)
from identification.solve import METHODS, SolveResult, solve, solve_statistics

__all__ = [
    "ReducedAxisModel",
    "EffectRecord",
    "DiscreteModel",
    "discretize",
    "simulate",
    "PARAMETER_NAMES",
    "PARAMETER_UNITS",
    "COLUMNS",
    "RegressorOptions",
    "regressor",
    "iter_regressor",
    "SufficientStatistics",
    "statistics",
    "PoleBounds",
    "default_bounds",
    "solve",
    "solve_statistics",
    "SolveResult",
    "METHODS",
    "ExactOptions",
    "GAOptions",
    "identify",
    "Identifier",
    "check_capture",
    "load_model",
    "identify_gain_scales",
    "pdf_gain_scales",
    "GainScaleResult",
]
