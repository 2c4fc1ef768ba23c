"""``vcnc export-fmu MODEL.json -o drive.fmu [--fmi 2|3]``: the model as a validated FMU.

Generates the C sources and ``modelDescription.xml``, compiles the binary (fmpy's CMake build),
validates the archive with fmpy and checks a simulation of the binary against the Python model
before the file appears; on any failure nothing is written (exit 2 for a bad model file, 1 for an
unsupported effect or a failed build or check).
"""

from __future__ import annotations

import argparse

HELP = "export an axis model as an FMI 2.0/3.0 Co-Simulation FMU (built and validated)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("model", metavar="MODEL.json", help="model file (vcnc.axis-model/1)")
    parser.add_argument("-o", "--output", required=True, metavar="FILE.fmu", help="FMU to write")
    parser.add_argument("--fmi", type=int, choices=(2, 3), default=2, help="FMI version (default 2)")


def check_model_file(path: str) -> None:
    """:class:`vcnc.InputError` naming what ``path`` is when it is plainly another of vcnc's files (a capture or
    setpoints CSV, a machine TOML, an FMU, an empty file; :func:`vcnc.commands.interpolate.other_file_kind`), not a
    model file: before, a capture given as the model read "FILE:1:1: invalid JSON: Expecting value" (newuser34)."""
    from vcnc.commands.interpolate import other_file_kind
    from vcnc.core.errors import ModelFileError

    kind = other_file_kind(path)
    if kind is not None and not kind.startswith("a JSON file"):
        raise ModelFileError(f"this is {kind}, not a model file", file=path,
                             expected="a model file written by vcnc identify --json (vcnc.axis-model)")


def run(args: argparse.Namespace) -> int:
    from vcnc.core.io import check_output
    from vcnc.fmu import export_fmu, export_spec

    check_output(args.output, option="-o", what="the FMU", inputs=(args.model,))
    check_model_file(args.model)
    spec = export_spec(args.model)  # a bad model file fails here, before any build
    path = export_fmu(args.model, args.output, fmi_version=args.fmi)
    effects = spec.effect_names
    print(
        f"wrote {path}: FMI {args.fmi}.0 Co-Simulation, model {spec.model_identifier}, "
        f"step {spec.sample_time:g} s" + (f", effects {', '.join(effects)}" if effects else "")
        + "; validated with fmpy and checked against the model"
    )
    return 0
