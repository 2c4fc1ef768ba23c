"""Export a reduced axis model as an FMI 2.0 / 3.0 Co-Simulation FMU, built and validated."""

from __future__ import annotations

import contextlib
import hashlib
import logging
import os
import subprocess
import sys
import tempfile
import uuid
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

from vcnc.core.errors import ExportError, SimulationError
from vcnc.core.io import atomic_path
from vcnc.fmu._description import TOKEN_PLACEHOLDER, build_description, model_description
from vcnc.fmu._sources import compiled_sources, source_files
from vcnc.fmu._spec import ExportSpec, export_spec

__all__ = ["export_fmu", "fmu_files", "CHECK_TOLERANCE_MM"]

log = logging.getLogger(__name__)

#: largest difference [mm] between the built FMU and the Python model accepted by the export check
CHECK_TOLERANCE_MM = 1e-9


def _token(files: dict[str, str], fmi_version: int) -> str:
    """Deterministic GUID / instantiation token: a hash of everything else in the FMU."""
    h = hashlib.sha256(f"vcnc-fmu fmi{fmi_version}\n".encode())
    for name, text in sorted(files.items()):
        h.update(name.encode() + b"\0" + text.encode() + b"\0")
    return "{" + str(uuid.UUID(bytes=h.digest()[:16], version=5)) + "}"


def fmu_files(spec: ExportSpec, *, fmi_version: int) -> dict[str, str]:
    """Every text file of the FMU (path inside the archive -> text), token filled in."""
    if fmi_version not in (2, 3):
        raise ExportError(f"FMI version must be 2 or 3, got {fmi_version!r}")
    compiled = compiled_sources(fmi_version)

    def assemble(token: str) -> dict[str, str]:
        files = {"modelDescription.xml": model_description(spec, fmi_version=fmi_version, sources=compiled,
                                                           token=token)}
        files.update({f"sources/{k}": v for k, v in source_files(spec, fmi_version=fmi_version, token=token).items()})
        if fmi_version == 3:
            files["sources/buildDescription.xml"] = build_description(spec, sources=compiled)
        return files

    return assemble(_token(assemble(TOKEN_PLACEHOLDER), fmi_version))


@contextlib.contextmanager
def _captured_output() -> Iterator[Any]:
    """Send this process' stdout/stderr (file descriptors, so also child processes) to a file."""
    with tempfile.TemporaryFile() as sink:
        sys.stdout.flush()
        sys.stderr.flush()
        saved = (os.dup(1), os.dup(2))
        os.dup2(sink.fileno(), 1)
        os.dup2(sink.fileno(), 2)
        try:
            yield sink
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])


def _cmake_options() -> dict[str, str]:
    if sys.platform == "win32":
        return {}
    options = {
        "CMAKE_C_VISIBILITY_PRESET:STRING": "hidden",  # only the FMI functions are exported
        "CMAKE_C_FLAGS:STRING": "-ffp-contract=off",  # no fused multiply-add: same rounding as numpy
        "CMAKE_C_STANDARD_LIBRARIES:STRING": "-lm",
    }
    if sys.platform.startswith("linux"):
        options["CMAKE_SHARED_LINKER_FLAGS:STRING"] = "-Wl,--no-undefined"
    return options


def _compile(unzipdir: Path, build_dir: Path) -> None:
    from fmpy.build import build_platform_binary

    with _captured_output() as out:
        try:
            build_platform_binary(unzipdir, build_dir=build_dir, cmake_options=_cmake_options())
            error = None
        except FileNotFoundError as exc:
            error = f"building the FMU binary needs CMake and a C compiler on the PATH ({exc.filename} not found)"
        except (subprocess.CalledProcessError, OSError) as exc:
            error = f"building the FMU binary failed ({exc})"
        out.seek(0)
        text = out.read().decode("utf-8", errors="replace")
    if error:
        raise ExportError(error + ":\n" + text[-4000:])
    log.debug("build log:\n%s", text)


def _zip(unzipdir: Path, target: Path) -> None:
    """Deterministic archive: sorted names, fixed time stamps."""
    paths = sorted(p for p in unzipdir.rglob("*") if p.is_file())
    with zipfile.ZipFile(target, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for p in paths:
            info = zipfile.ZipInfo(p.relative_to(unzipdir).as_posix(), date_time=(1980, 1, 1, 0, 0, 0))
            info.external_attr = 0o644 << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            zf.writestr(info, p.read_bytes())


#: samples of the identification test the export check runs (exported / recomputed discretisation)
CHECK_SAMPLES = (20_000, 5_000)


def _check(fmu: Path, spec: ExportSpec) -> None:
    """Validate the archive with fmpy and run it against ``model.simulate()`` (both discretisations)."""
    import dataclasses

    from fmpy.validation import validate_fmu

    from vcnc.engine.fmu_axis import FmuAxis
    from vcnc.fmu._oracle import check_reference, expected_position

    problems = validate_fmu(str(fmu))
    if problems:
        raise ExportError("the FMU does not validate: " + "; ".join(problems))
    ts = spec.sample_time
    a1 = float(np.nextafter(spec.parameters["a1"], np.inf))  # forces the FMU's own discretisation
    tuned = dataclasses.replace(spec, parameters={**spec.parameters, "a1": a1})
    for (label, s, start), n in zip((("exported", spec, None), ("recomputed", tuned, {"a1": a1})), CHECK_SAMPLES):
        ref = check_reference(n, ts, seed=1)  # starts at 0 mm, moves both ways, dwells
        expected = expected_position(s, ref)
        if not np.all(np.isfinite(expected)):
            raise ExportError(
                f"model.simulate() itself diverges over the export check's {n}-sample identification test "
                "(moves of up to 20 mm): the FMU cannot be checked; export with check=False at your own risk"
            )
        try:
            with FmuAxis(fmu, start_values=start) as axis:
                got = axis.simulate_reference(ref, ts)
        except SimulationError as exc:
            raise ExportError(f"the built FMU failed the export check ({label} discretisation): {exc}") from exc
        err = float(np.max(np.abs(got - expected)))
        if not err <= CHECK_TOLERANCE_MM:
            names = ", ".join(e.NAME for e in spec.elements) or "none"
            raise ExportError(
                f"the built FMU departs from model.simulate() by {err:.3g} mm over a {n}-sample identification "
                f"test ({label} discretisation; effects: {names}; at most {CHECK_TOLERANCE_MM:g} mm expected)"
            )


def export_fmu(
    model: Any,
    path: str | os.PathLike[str],
    *,
    fmi_version: int = 2,
    check: bool = True,
) -> Path:
    """Export a reduced axis model as a Co-Simulation FMU.

    Parameters
    ----------
    model : path, dict or ReducedAxisModel
        A ``vcnc.axis-model/1`` file, its dictionary, or the model.
    path : path
        The ``.fmu`` to write; written only when the FMU was built and checked (atomic).
    fmi_version : {2, 3}
        FMI 2.0 or FMI 3.0 Co-Simulation.
    check : bool
        Validate with ``fmpy.validation.validate_fmu`` and compare a simulation of the binary
        against ``model.simulate()`` (:func:`vcnc.fmu.expected_position`; a 20,000-sample
        identification test with the embedded discretisation and 5,000 samples with the FMU's
        own, to 1e-9 mm) before writing. Default True.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    ModelFileError
        A bad model file (an ``InputError``: exit 2 on the command line).
    ExportError
        Effects the FMU cannot represent exactly (:data:`vcnc.fmu.REPRESENTABLE_EFFECTS`), a
        failed build or a failed check.

    Notes
    -----
    The FMU has inputs ``x_ref`` [mm] (commanded position) and ``w_ext`` [mm/s^2] (disturbance),
    outputs ``position`` [mm] and ``tracking_error`` [mm], and the parameters a1..d1 of Eq. (3.3)
    of the thesis, ``sample_time`` [s] and those of the model's effects (:mod:`vcnc.fmu`), all
    settable until the end of initialisation. Communication steps must be whole multiples of the
    sample time. See ``vcnc/fmu/c/vcnc_model.h`` for the model.

    Timing: ``position`` has direct feedthrough from ``x_ref`` (first-order hold and b0; declared
    in the ``ModelStructure``), so a master sets x_r,k at t_k, then reads the position at t_k,
    then calls ``doStep`` (as :class:`FmuAxis` does): that reproduces ``model.simulate()`` sample
    for sample. ``fmpy.simulate_fmu`` records its row at t_k right after ``doStep`` and before it
    applies the input of t_k, so there the feedthrough part ``d x_r`` still holds x_r,k-1.

    The discretisation of the exported parameters is embedded (computed by scipy at export, so
    the FMU is bit-identical to the Python model); parameters changed before initialisation are
    discretised by the FMU's own C code (scaling and squaring, Pade 13).
    """
    spec = export_spec(model)
    if fmi_version not in (2, 3):
        raise ExportError(f"FMI version must be 2 or 3, got {fmi_version!r}")
    files = fmu_files(spec, fmi_version=fmi_version)
    final = Path(path)
    with tempfile.TemporaryDirectory(prefix="vcnc-fmu-") as work:
        unzipdir = Path(work) / "fmu"
        for name, text in files.items():
            target = unzipdir / name
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(text, encoding="utf-8")
        build_dir = Path(work) / "build"
        build_dir.mkdir()
        _compile(unzipdir, build_dir)
        with atomic_path(final) as tmp:
            _zip(unzipdir, tmp)
            if check:
                _check(tmp, spec)
    log.info("wrote %s (FMI %d.0 Co-Simulation, %s)", final, fmi_version, spec.model_identifier)
    return final
