"""Exception types of vcnc (defined in :mod:`vcnc.core.errors`, re-exported here)."""

from vcnc.core.errors import (
    CaptureError,
    ExportError,
    GCodeError,
    IdentificationError,
    InputError,
    MachineError,
    ModelFileError,
    SimulationError,
    VcncError,
)

__all__ = [
    "VcncError",
    "InputError",
    "GCodeError",
    "CaptureError",
    "MachineError",
    "ModelFileError",
    "IdentificationError",
    "SimulationError",
    "ExportError",
]
