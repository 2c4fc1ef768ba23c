"""FMU export and import of axis models (FMI 2.0 and 3.0 Co-Simulation).

* :func:`export_fmu` turns a ``vcnc.axis-model/1`` model into a validated FMU whose binary is
  plain C (libm only) generated from ``vcnc/fmu/c``: the model code (``vcnc_model.c``, matrix
  exponential in ``vcnc_linalg.c``, life cycle in ``vcnc_instance.c``) is shared by both FMI
  versions; ``fmi2_layer.c`` / ``fmi3_layer.c`` only translate calls.
* :class:`FmuAxis` is a machine axis backed by any Co-Simulation FMU (``simulate_reference``),
  so an exported model or a third-party drive can be the "true machine".

Effects found by the residual diagnosis (:mod:`identification.effects`, the model file's
``effects``) are exported exactly: the binary reproduces ``model.simulate()`` of the
:class:`identification.augmented.AugmentedAxisModel` (checked at every export to
:data:`CHECK_TOLERANCE_MM` over a 20,000-sample identification test). :data:`REPRESENTABLE_EFFECTS`
lists them with their FMU parameters:

* disturbance and output effects run in the exact sampled loop of the reduced model (FOH/ZOH):
  ``friction_stribeck``, ``friction_viscous_asymmetric``, ``position_periodic``,
  ``time_periodic`` (t counted from initialisation) and ``drift``;
* the in-loop elements ``delay``, ``saturation``, ``backlash`` and ``resonance`` switch the FMU to
  the sampled controller + plant ("split") loop of :mod:`identification.augmented`, with the
  plant viscous rate as parameter ``plant_viscous_rate``.

All effect parameters are FMU parameters, tunable until the end of initialisation, and exist
only in FMUs of models with that effect. Structural, fixed at export: the number of Fourier
harmonics (each coefficient is a scalar parameter ``<effect>_sin_<h>`` / ``_cos_<h>``, FMI 2
having no arrays; at most 64), resonance ``measured_at``, and the form (exact or split). Any
other effect - an unknown one, or the same effect twice - makes the export fail with an
:class:`~vcnc.errors.ExportError` naming it and the representable ones; it is never exported
approximately. (The former FMU-only ``delay``/``backlash`` of the command and the output are
gone: those records are the diagnosis' in-loop effects now.)
"""

from vcnc.engine.fmu_axis import FmuAxis
from vcnc.fmu._export import CHECK_TOLERANCE_MM, export_fmu, fmu_files
from vcnc.fmu._oracle import expected_position
from vcnc.fmu._spec import REPRESENTABLE_EFFECTS, ExportSpec, export_spec

__all__ = [
    "export_fmu",
    "FmuAxis",
    "ExportSpec",
    "export_spec",
    "fmu_files",
    "expected_position",
    "REPRESENTABLE_EFFECTS",
    "CHECK_TOLERANCE_MM",
]
