"""The variables of an exported axis FMU: one table serving the XML and the C configuration.

Value references are fixed across models and FMI versions, so a master written for one exported
drive works with any other.
"""

from __future__ import annotations

import dataclasses

__all__ = ["Variable", "VARIABLES", "UNITS", "MAX_DELAY", "MAX_REF_DELAY", "MAX_HARMONICS", "EFFECT_VARIABLES",
           "REFERENCE_DELAY", "variables", "variable"]


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
    "mm/s": ({"m": 1, "s": -1}, 0.001),
    "mm/s2": ({"m": 1, "s": -2}, 0.001),
    "Hz": ({"s": -1}, 1.0),
    "s": ({"s": 1}, 1.0),
    "1/s": ({"s": -1}, 1.0),
    "1/s2": ({"s": -2}, 1.0),
    "1/s3": ({"s": -3}, 1.0),
}

#: longest control delay [samples]; VCNC_MAX_DELAY in c/vcnc_model.h (a test checks they agree)
MAX_DELAY = 4096

#: longest Fourier series of the periodic effects; VCNC_MAX_HARMONICS in c/vcnc_model.h
MAX_HARMONICS = 64

#: first value reference of the (sin, cos) coefficients of position_periodic / time_periodic:
#: ``<effect>_sin_<h>`` at base + 2 (h - 1), ``<effect>_cos_<h>`` at base + 2 (h - 1) + 1
COEFFICIENT_BASE = {"position_periodic": 1000, "time_periodic": 2000}

#: the variables of every exported FMU (value references fixed across models and FMI versions)
BASE_VARIABLES: tuple[Variable, ...] = (
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
)

#: effect name -> its scalar parameters (present in an FMU only when the model has the effect).
#: Fourier coefficients of the periodic effects are added per harmonic (:func:`variables`).
EFFECT_VARIABLES: dict[str, tuple[Variable, ...]] = {
    "friction_stribeck": (
        Variable(name="stribeck_velocity", vr=20, causality="parameter", unit="mm/s",
                 description="effect friction_stribeck: Stribeck velocity v_s (<= 0 switches it off)"),
        Variable(name="stribeck_excess_positive", vr=21, causality="parameter", unit="mm/s2",
                 description="effect friction_stribeck: static minus Coulomb level s+ for v > 0"),
        Variable(name="stribeck_excess_negative", vr=22, causality="parameter", unit="mm/s2",
                 description="effect friction_stribeck: static minus Coulomb level s- for v < 0"),
    ),
    "friction_viscous_asymmetric": (
        Variable(name="viscous_asymmetry", vr=23, causality="parameter", unit="1/s",
                 description="effect friction_viscous_asymmetric: k_a, the term k_a |v| in w"),
    ),
    "position_periodic": (
        Variable(name="position_period", vr=24, causality="parameter", unit="mm",
                 description="effect position_periodic: spatial period P_x (<= 0 switches it off)"),
    ),
    "time_periodic": (
        Variable(name="time_period", vr=25, causality="parameter", unit="s",
                 description="effect time_periodic: period P_t (> 0), t from initialisation", minimum=0.0),
        Variable(name="time_mean", vr=26, causality="parameter", unit="mm/s2",
                 description="effect time_periodic: constant part of the load"),
    ),
    "drift": (
        Variable(name="drift_rate", vr=27, causality="parameter", unit="mm/s",
                 description="effect drift: rate of the offset added to the measured position (t from initialisation)"),
    ),
    "delay": (
        Variable(name="delay_samples", vr=31, causality="parameter", type="int",
                 description="effect delay: the control action reaches the plant this many samples late",
                 minimum=0, maximum=MAX_DELAY),
    ),
    "saturation": (
        Variable(name="saturation_limit", vr=32, causality="parameter", unit="mm/s2",
                 description="effect saturation: largest acceleration demand |u| of the split loop"),
    ),
    "backlash": (
        Variable(name="backlash_width", vr=33, causality="parameter", unit="mm",
                 description="effect backlash: play between the driven mass and the measured position (in the loop)"),
    ),
    "resonance": (
        Variable(name="resonance_frequency", vr=34, causality="parameter", unit="Hz",
                 description="effect resonance: free-free natural frequency of the two-mass plant"),
        Variable(name="resonance_damping", vr=35, causality="parameter",
                 description="effect resonance: modal damping ratio"),
        Variable(name="resonance_table_fraction", vr=36, causality="parameter",
                 description="effect resonance: share of the moving mass on the table side, in (0, 1)"),
    ),
}

#: the plant viscous rate of the split (element) form, present when the model has an element
PLANT_VISCOUS_RATE = Variable(name="plant_viscous_rate", vr=30, causality="parameter", unit="1/s",
                              description="split form: plant viscous rate c (controller derivative gain a1 - c)")

#: longest reference dead time and setpoint filter [samples]; VCNC_MAX_REF_DELAY in c/vcnc_model.h (a test
#: checks they agree)
MAX_REF_DELAY = 4096

#: the reference dead time of the model (``delay_s``), present when it is not zero
REFERENCE_DELAY = Variable(name="reference_delay_s", vr=40, causality="parameter", unit="s", minimum=0.0,
                           description="dead time of the reference: the loop runs on x_ref delayed by it, "
                                       "linearly interpolated between samples (identification.dead_time)")

#: the setpoint filter of the model (``setpoint_filter_s``), present when it is not zero
SETPOINT_FILTER = Variable(name="setpoint_filter_s", vr=41, causality="parameter", unit="s", minimum=0.0,
                           description="setpoint filter: the loop runs on the moving average of the delayed x_ref "
                                       "over this long, linear between samples (identification.setpoint_filter)")

#: every scalar variable any FMU may have (the C configuration defines all their macros)
ALL_SCALARS: tuple[Variable, ...] = (
    *BASE_VARIABLES, *(v for vs in EFFECT_VARIABLES.values() for v in vs), PLANT_VISCOUS_RATE, REFERENCE_DELAY,
    SETPOINT_FILTER,
)


def coefficient_variables(effect: str, harmonics: int) -> tuple[Variable, ...]:
    """The Fourier coefficient parameters of ``effect`` (position_periodic or time_periodic)."""
    base = COEFFICIENT_BASE[effect]
    what = "A_h sin / B_h cos of 2 pi h x / P_x" if effect == "position_periodic" else \
        "C_h sin / D_h cos of 2 pi h t / P_t"
    out = []
    for h in range(1, harmonics + 1):
        for j, kind in enumerate(("sin", "cos")):
            out.append(Variable(name=f"{effect}_{kind}_{h}", vr=base + 2 * (h - 1) + j, causality="parameter",
                                unit="mm/s2", description=f"effect {effect}: harmonic {h} ({what})"))
    return tuple(out)


def variables(effects: dict[str, int] | None = None, *, structured: bool = False,
              reference_delay: bool = False, setpoint_filter: bool = False) -> tuple[Variable, ...]:
    """The variables of an FMU with ``effects`` (effect name -> harmonics, 0 for non-periodic ones).

    ``reference_delay`` adds the ``reference_delay_s`` parameter (a model with ``delay_s`` != 0),
    ``setpoint_filter`` the ``setpoint_filter_s`` one (a model with ``setpoint_filter_s`` != 0).
    """
    out = list(BASE_VARIABLES)
    for name, harmonics in (effects or {}).items():
        out += EFFECT_VARIABLES[name]
        if name in COEFFICIENT_BASE:
            out += coefficient_variables(name, harmonics)
    if structured:
        out.append(PLANT_VISCOUS_RATE)
    if reference_delay:
        out.append(REFERENCE_DELAY)
    if setpoint_filter:
        out.append(SETPOINT_FILTER)
    return tuple(sorted(out, key=lambda v: v.vr))


#: the variables of an FMU without effects
VARIABLES = variables()


def variable(name: str) -> Variable:
    """The scalar variable called ``name`` (any FMU)."""
    for v in ALL_SCALARS:
        if v.name == name:
            return v
    raise KeyError(name)
