"""``modelDescription.xml`` (FMI 2.0 and 3.0 Co-Simulation) and ``buildDescription.xml``."""

from __future__ import annotations

import xml.etree.ElementTree as ET

from vcnc.fmu._spec import ExportSpec
from vcnc.fmu._variables import UNITS, Variable

__all__ = ["model_description", "build_description", "TOKEN_PLACEHOLDER"]

#: stands for the GUID / instantiation token until it is known (it is a hash of everything else)
TOKEN_PLACEHOLDER = "{00000000-0000-0000-0000-000000000000}"

_LOG_CATEGORIES = (("logEvents", "life-cycle events"), ("logStatusError", "errors"))


def _num(value: float | int) -> str:
    return repr(int(value)) if isinstance(value, int) else repr(float(value))


def _to_text(root: ET.Element) -> str:
    ET.indent(root, space="  ")
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def _units(parent: ET.Element) -> None:
    defs = ET.SubElement(parent, "UnitDefinitions")
    for name, (exponents, factor) in UNITS.items():
        unit = ET.SubElement(defs, "Unit", name=name)
        base = ET.SubElement(unit, "BaseUnit", {k: str(v) for k, v in exponents.items()})
        if factor != 1.0:
            base.set("factor", repr(factor))


def _log_categories(parent: ET.Element) -> None:
    cats = ET.SubElement(parent, "LogCategories")
    for name, text in _LOG_CATEGORIES:
        ET.SubElement(cats, "Category", name=name, description=text)


def _common_attributes(v: Variable) -> dict[str, str]:
    attrs = {"name": v.name, "valueReference": str(v.vr), "description": v.description, "causality": v.causality,
             "variability": v.variability}
    if v.causality == "parameter":
        attrs["initial"] = "exact"
    elif v.causality == "output":
        attrs["initial"] = "calculated"
    return attrs


def _type_attributes(v: Variable, start: dict) -> dict[str, str]:
    attrs: dict[str, str] = {}
    if v.unit:
        attrs["unit"] = v.unit
    if v.minimum is not None:
        attrs["min"] = _num(v.minimum if v.type == "float" else int(v.minimum))
    if v.maximum is not None:
        attrs["max"] = _num(v.maximum if v.type == "float" else int(v.maximum))
    if v.name in start:
        attrs["start"] = _num(start[v.name])
    return attrs


def _outputs_and_inputs(variables: tuple[Variable, ...]):
    outputs = [v for v in variables if v.causality == "output"]
    x_ref = next(v for v in variables if v.name == "x_ref")
    return outputs, x_ref


def model_description(spec: ExportSpec, *, fmi_version: int, sources: list[str], token: str) -> str:
    """The ``modelDescription.xml`` text of ``spec`` for FMI ``fmi_version`` (2 or 3)."""
    from vcnc import __version__

    ident = spec.model_identifier
    start = spec.start()
    description = (
        f"vcnc reduced closed-loop model of axis {spec.axis} (Eq. 3.3 of Wong's thesis), "
        f"discrete-time at {spec.sample_time!r} s"
        + (f", with effects {', '.join(e.NAME for e in spec.elements)}" if spec.elements else "")
        + (" (sampled controller + plant form)" if spec.structured else "")
    )
    variables = spec.variables
    outputs, x_ref = _outputs_and_inputs(variables)
    if fmi_version == 2:
        root = ET.Element("fmiModelDescription", fmiVersion="2.0", modelName=ident, guid=token,
                          description=description, generationTool=f"vcnc {__version__}",
                          variableNamingConvention="flat", numberOfEventIndicators="0")
        cs = ET.SubElement(root, "CoSimulation", modelIdentifier=ident, canHandleVariableCommunicationStepSize="true",
                           canGetAndSetFMUstate="true", canSerializeFMUstate="true",
                           canNotUseMemoryManagementFunctions="true")
        files = ET.SubElement(cs, "SourceFiles")
        for name in sources:
            ET.SubElement(files, "File", name=name)
        _units(root)
        _log_categories(root)
        ET.SubElement(root, "DefaultExperiment", startTime="0.0", stepSize=repr(float(spec.sample_time)))
        mv = ET.SubElement(root, "ModelVariables")
        index = {}
        for v in variables:
            if v.causality == "independent":
                continue  # FMI 2 has no time variable
            sv = ET.SubElement(mv, "ScalarVariable", _common_attributes(v))
            ET.SubElement(sv, "Real" if v.type == "float" else "Integer", _type_attributes(v, start))
            index[v.name] = len(index) + 1
        ms = ET.SubElement(root, "ModelStructure")
        outs = ET.SubElement(ms, "Outputs")
        for v in outputs:
            ET.SubElement(outs, "Unknown", index=str(index[v.name]), dependencies=str(index[x_ref.name]))
        init = ET.SubElement(ms, "InitialUnknowns")
        for v in outputs:
            ET.SubElement(init, "Unknown", index=str(index[v.name]))
    elif fmi_version == 3:
        root = ET.Element("fmiModelDescription", fmiVersion="3.0", modelName=ident, instantiationToken=token,
                          description=description, generationTool=f"vcnc {__version__}",
                          variableNamingConvention="flat")
        ET.SubElement(root, "CoSimulation", modelIdentifier=ident, canHandleVariableCommunicationStepSize="true",
                      canGetAndSetFMUState="true", canSerializeFMUState="true",
                      fixedInternalStepSize=repr(float(spec.sample_time)))
        _units(root)
        _log_categories(root)
        ET.SubElement(root, "DefaultExperiment", startTime="0.0", stepSize=repr(float(spec.sample_time)))
        mv = ET.SubElement(root, "ModelVariables")
        for v in variables:
            attrs = _common_attributes(v)
            attrs.update(_type_attributes(v, start))
            ET.SubElement(mv, "Float64" if v.type == "float" else "Int32", attrs)
        ms = ET.SubElement(root, "ModelStructure")
        for v in outputs:
            ET.SubElement(ms, "Output", valueReference=str(v.vr), dependencies=str(x_ref.vr))
        for v in outputs:
            ET.SubElement(ms, "InitialUnknown", valueReference=str(v.vr))
    else:
        raise ValueError(f"fmi_version must be 2 or 3, got {fmi_version!r}")
    return _to_text(root)


def build_description(spec: ExportSpec, *, sources: list[str]) -> str:
    """``sources/buildDescription.xml`` (FMI 3.0) listing the C sources."""
    root = ET.Element("fmiBuildDescription", fmiVersion="3.0")
    bc = ET.SubElement(root, "BuildConfiguration", modelIdentifier=spec.model_identifier)
    sfs = ET.SubElement(bc, "SourceFileSet", language="C99")
    for name in sources:
        ET.SubElement(sfs, "SourceFile", name=name)
    return _to_text(root)
