"""The variables of an exported axis FMU: one table serving the XML and the C configuration.

Value references are fixed across models and FMI versions, so a master written for one exported
drive works with any other.
"""

from __future__ import annotations

import dataclasses

__all__ = ["Variable", "VARIABLES", "UNITS", "MAX_DELAY", "variable"]


@dataclasses.dataclass(frozen=True, kw_only=True)
class Variable:
    """One FMU variable.

    Attributes
    ----------
    name : str
        Variable name (also the key of start values in :class:`ExportSpec.start`).
    vr : int
        Value reference.
    causality : str
        ``input``, ``output``, ``parameter`` or ``independent``.
    type : str
        ``float`` (FMI 2 Real / FMI 3 Float64) or ``int`` (Integer / Int32).
    unit : str or None
        Unit name (declared in :data:`UNITS`).
    description : str
        What it is.
    minimum, maximum : float, optional
        Range, for the model description.
    """

    name: str
    vr: int
    causality: str
    type: str = "float"
    unit: str | None = None
    description: str = ""
    minimum: float | None = None
    maximum: float | None = None

    @property
    def macro(self) -> str:
        """Suffix of the C macros ``VCNC_VR_<macro>`` and ``VCNC_START_<macro>``."""
        return self.name.upper()

    @property
    def variability(self) -> str:
        if self.causality == "parameter":
            return "fixed"  # settable until the end of initialisation
        return "continuous" if self.type == "float" else "discrete"


#: (unit name, exponents of the SI base units, factor to SI) of every unit used.
UNITS: dict[str, tuple[dict[str, int], float]] = {
    "mm": ({"m": 1}, 0.001),
    "mm/s2": ({"m": 1, "s": -2}, 0.001),
    "s": ({"s": 1}, 1.0),
    "1/s": ({"s": -1}, 1.0),
    "1/s2": ({"s": -2}, 1.0),
    "1/s3": ({"s": -3}, 1.0),
}

#: longest command delay [samples]; VCNC_MAX_DELAY in c/vcnc_model.h (a test checks they agree)
MAX_DELAY = 4096

VARIABLES: tuple[Variable, ...] = (
    Variable(name="time", vr=0, causality="independent", unit="s", description="simulation time"),
    Variable(name="x_ref", vr=1, causality="input", unit="mm", description="commanded position x_r"),
    Variable(
        name="w_ext",
        vr=2,
        causality="input",
        unit="mm/s2",
        description="external disturbance, added to the friction term w of Eq. 3.3 (held over each sample)",
    ),
    Variable(name="position", vr=3, causality="output", unit="mm", description="measured position x"),
    Variable(name="tracking_error", vr=4, causality="output", unit="mm", description="x_ref - position"),
    *(
        Variable(name=name, vr=vr, causality="parameter", unit=unit, description=f"Eq. 3.3: {what}")
        for name, vr, unit, what in (
            ("a1", 5, "1/s", "coefficient of s^2 in the denominator"),
            ("a2", 6, "1/s2", "coefficient of s in the denominator"),
            ("a3", 7, "1/s3", "constant of the denominator (> 0)"),
            ("b0", 8, None, "coefficient of s^3 in the numerator"),
            ("b1", 9, "1/s", "coefficient of s^2 in the numerator"),
            ("b2", 10, "1/s2", "coefficient of s in the numerator"),
            ("d0", 11, "mm/s2", "friction for positive velocity"),
            ("d1", 12, "mm/s2", "friction for negative velocity"),
        )
    ),
    Variable(
        name="sample_time",
        vr=13,
        causality="parameter",
        unit="s",
        description="sample time of the discrete-time model; communication steps must be whole multiples",
    ),
    Variable(
        name="backlash",
        vr=14,
        causality="parameter",
        unit="mm",
        description="effect backlash: total lost motion between the drive and the measured position",
        minimum=0.0,
    ),
    Variable(
        name="delay_samples",
        vr=15,
        causality="parameter",
        type="int",
        description="effect delay: transport delay of the command [samples]",
        minimum=0,
        maximum=MAX_DELAY,
    ),
)


def variable(name: str) -> Variable:
    """The variable called ``name``."""
    for v in VARIABLES:
        if v.name == name:
            return v
    raise KeyError(name)
