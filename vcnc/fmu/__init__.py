"""FMU export and import of axis models (FMI 2.0 and 3.0 Co-Simulation).

* :func:`export_fmu` turns a ``vcnc.axis-model/1`` model into a validated FMU whose binary is
  plain C (libm only) generated from ``vcnc/fmu/c``: the model code (``vcnc_model.c``, matrix
  exponential in ``vcnc_linalg.c``, life cycle in ``vcnc_instance.c``) is shared by both FMI
  versions; ``fmi2_layer.c`` / ``fmi3_layer.c`` only translate calls.
* :class:`FmuAxis` is a machine axis backed by any Co-Simulation FMU (``simulate_reference``),
  so an exported model or a third-party drive can be the "true machine".

Effects of the model file the FMU represents (:data:`REPRESENTABLE_EFFECTS`): ``delay``
(``samples``) and ``backlash`` (``width`` [mm]); any other effect makes the export fail with an
:class:`~vcnc.errors.ExportError` naming it.
"""

from vcnc.fmu._axis import FmuAxis
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
