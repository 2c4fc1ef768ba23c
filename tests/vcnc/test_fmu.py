"""FMU export (FMI 2.0 / 3.0 Co-Simulation) and FMU-backed axes, with real binaries.

Each FMU is built once per session (fixtures); every check runs the compiled code.
"""

from __future__ import annotations

import ctypes
import json
import shutil
import subprocess
import sys
import zipfile
from importlib import resources
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg
from fmpy import read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from identification import ReducedAxisModel, discretize, simulate
from vcnc.cli import main
from vcnc.errors import MachineError, ModelFileError
from vcnc.fmu import FmuAxis, export_fmu, export_spec, fmu_files
from vcnc.fmu._sources import fmi_header_dir

pytestmark = pytest.mark.skipif(shutil.which("cmake") is None or shutil.which("cc") is None,
                                reason="building FMUs needs cmake and a C compiler")

TS = 0.001
# a 3rd-order closed loop (poles near 50 Hz, 0.7 damping, and 70 Hz) with feedforward zeros and
# asymmetric Coulomb friction, in the range the thesis identifies (Tables 3.3-3.5)
PARAMETERS = {"a1": 600.0, "a2": 1.5e5, "a3": 1.2e7, "b0": 0.02, "b1": 300.0, "b2": 1.4e5, "d0": 80.0, "d1": -70.0}


def identification_reference(n: int, ts: float, *, seed: int, start: float = 0.0) -> np.ndarray:
    """Random point-to-point moves with dwells (an identification test), smooth within each move."""
    rng = np.random.default_rng(seed)
    out = np.empty(n)
    k, pos = 0, start
    while k < n:
        target = rng.uniform(-20.0, 20.0)
        m = int(rng.integers(40, 300))
        s = 0.5 - 0.5 * np.cos(np.pi * np.arange(1, m + 1) / m)
        seg = pos + (target - pos) * s
        dwell = np.full(int(rng.integers(0, 80)), target)
        seg = np.concatenate([seg, dwell])[: n - k]
        out[k : k + seg.size] = seg
        k += seg.size
        pos = target
    return out


@pytest.fixture(scope="session")
def model() -> ReducedAxisModel:
    return ReducedAxisModel(parameters=PARAMETERS, sample_time=TS, axis="x")


@pytest.fixture(scope="session")
def model_file(model, tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("model") / "model.json"
    model.to_json(path)
    return path


@pytest.fixture(scope="session")
def fmus(model_file, tmp_path_factory) -> dict[int, Path]:
    """FMI 2 through the command line, FMI 3 through the Python API."""
    d = tmp_path_factory.mktemp("fmu")
    assert main(["export-fmu", str(model_file), "-o", str(d / "drive2.fmu"), "--fmi", "2"]) == 0
    export_fmu(model_file, d / "drive3.fmu", fmi_version=3)
    return {2: d / "drive2.fmu", 3: d / "drive3.fmu"}


def _slave(path: Path, tmp_path: Path):
    """An instantiated, initialised fmpy slave of ``path`` (FMI 2 or 3) and its version."""
    from fmpy import extract
    from fmpy.fmi2 import FMU2Slave
    from fmpy.fmi3 import FMU3Slave

    md = read_model_description(str(path))
    unzipdir = extract(str(path), unzipdir=str(tmp_path / path.stem))
    cls = FMU2Slave if md.fmiVersion == "2.0" else FMU3Slave
    fmu = cls(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier=md.coSimulation.modelIdentifier,
              instanceName="test")
    fmu.instantiate()
    if md.fmiVersion == "2.0":
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        fmu.set_x, fmu.get_x = fmu.setReal, fmu.getReal
    else:
        fmu.enterInitializationMode(startTime=0.0)
        fmu.exitInitializationMode()
        fmu.set_x, fmu.get_x = fmu.setFloat64, fmu.getFloat64
    return fmu


# ------------------------------------------------------------------------------------ validity


@pytest.mark.parametrize("version", [2, 3])
def test_validate_fmu_reports_no_problems(fmus, version):
    assert validate_fmu(str(fmus[version])) == []
    md = read_model_description(str(fmus[version]))
    assert md.fmiVersion == f"{version}.0"
    assert float(md.defaultExperiment.stepSize) == TS
    names = {v.name: v for v in md.modelVariables}
    assert names["x_ref"].causality == "input" and names["w_ext"].causality == "input"
    assert names["position"].causality == "output" and names["tracking_error"].causality == "output"
    for p in ("a1", "a2", "a3", "b0", "b1", "b2", "d0", "d1", "sample_time"):
        assert (names[p].causality, names[p].variability) == ("parameter", "fixed")
    assert float(names["a3"].start) == PARAMETERS["a3"]
    assert "backlash_width" not in names and "delay_samples" not in names  # effect parameters only with effects


@pytest.mark.parametrize("version", [2, 3])
def test_binary_exports_only_the_fmi_functions(fmus, version, tmp_path):
    nm = shutil.which("nm")
    if nm is None or not sys.platform.startswith("linux"):
        pytest.skip("needs nm on Linux")
    with zipfile.ZipFile(fmus[version]) as zf:
        (so,) = [n for n in zf.namelist() if n.endswith(".so")]
        lib = tmp_path / "lib.so"
        lib.write_bytes(zf.read(so))
    defined = subprocess.run([nm, "-D", "--defined-only", str(lib)], capture_output=True, text=True, check=True)
    symbols = {line.split()[-1] for line in defined.stdout.splitlines() if line.strip()}
    assert symbols and all(s.startswith(f"fmi{version}") for s in symbols), symbols
    assert "fmi2DoStep" in symbols if version == 2 else "fmi3DoStep" in symbols
    needed = subprocess.run(["ldd", str(lib)], capture_output=True, text=True).stdout
    assert "libm" in needed and "python" not in needed.lower()


def test_c_and_python_agree_on_the_longest_delay():
    from vcnc.fmu._variables import MAX_DELAY

    header = resources.files("vcnc.fmu.c").joinpath("vcnc_model.h").read_text()
    assert f"#define VCNC_MAX_DELAY {MAX_DELAY} " in header


def test_token_is_deterministic_and_follows_the_content(model):
    spec = export_spec(model)
    a = fmu_files(spec, fmi_version=2)
    assert a == fmu_files(spec, fmi_version=2)
    guid = read_model_description_text(a["modelDescription.xml"]).guid
    assert guid.startswith("{") and guid in a["sources/vcnc_config.h"]
    other = export_spec(ReducedAxisModel(parameters={**PARAMETERS, "d0": 81.0}, sample_time=TS))
    assert read_model_description_text(fmu_files(other, fmi_version=2)["modelDescription.xml"]).guid != guid
    token3 = read_model_description_text(fmu_files(spec, fmi_version=3)["modelDescription.xml"]).guid
    assert token3 != guid


def read_model_description_text(text: str):
    """The token of a modelDescription.xml text (FMI 2 guid or FMI 3 instantiationToken)."""
    import types
    import xml.etree.ElementTree as ET

    root = ET.fromstring(text)
    return types.SimpleNamespace(guid=root.get("guid") or root.get("instantiationToken"))


# ---------------------------------------------------------------------------- equal to model


@pytest.mark.parametrize("version", [2, 3])
def test_simulate_fmu_equals_model_over_20000_steps(fmus, model, version):
    n = 20_000
    ref = identification_reference(n, TS, seed=7)
    t = np.arange(n) * TS
    signals = np.zeros(n, dtype=[("time", float), ("x_ref", float), ("w_ext", float)])
    w = 40.0 * np.sin(2 * np.pi * 3.0 * t)  # external disturbance [mm/s^2], held over each sample
    signals["time"], signals["x_ref"], signals["w_ext"] = t, ref, w
    result = simulate_fmu(str(fmus[version]), input=signals, output=["position", "tracking_error"],
                          stop_time=t[-1], output_interval=TS)
    expected = model.simulate(ref, disturbance=w)
    assert result.shape == (n,)
    np.testing.assert_allclose(result["time"], t, rtol=0, atol=1e-12)
    # fmpy's convention: the row at t_k is recorded right after doStep reached t_k and before fmpy
    # applies the input of t_k, so the direct feedthrough d x_r (d = b0 + C N, FOH) still holds
    # x_r,k-1 there; at t_0 the input is already applied.
    d = discretize(PARAMETERS, TS).d
    held = np.concatenate([[ref[0]], ref[:-1]])
    fmpy_view = expected - d * (ref - held)
    assert np.max(np.abs(result["position"] - fmpy_view)) <= 1e-9
    assert np.max(np.abs(result["tracking_error"] - (held - fmpy_view))) <= 1e-9
    assert np.ptp(ref) > 20 and np.max(np.abs(expected - ref)) > 1e-3  # a real test, friction engaged
    assert np.max(np.abs(expected - model.simulate(ref))) > 1e-4  # and the disturbance matters


@pytest.mark.parametrize("version", [2, 3])
def test_fmu_axis_equals_model_from_any_start(fmus, model, version):
    ref = identification_reference(20_000, TS, seed=3, start=12.5)
    with FmuAxis(fmus[version]) as axis:
        got = axis.simulate_reference(ref, TS)
    assert np.max(np.abs(got - model.simulate(ref))) <= 1e-9


@pytest.mark.parametrize("version", [2, 3])
def test_tuned_parameters_are_discretised_by_the_fmu(fmus, version):
    tuned = {**PARAMETERS, "a1": 700.0, "b1": 250.0, "d0": 30.0, "d1": -90.0}
    ref = identification_reference(5_000, TS, seed=11)
    with FmuAxis(fmus[version], start_values={"a1": 700.0, "b1": 250.0, "d0": 30.0, "d1": -90.0}) as axis:
        got = axis.simulate_reference(ref, TS)
    assert np.max(np.abs(got - simulate(tuned, ref, TS))) <= 1e-9


def test_sample_time_is_a_parameter(fmus):
    ref = identification_reference(2_000, 0.0005, seed=5)
    with FmuAxis(fmus[2], start_values={"sample_time": 0.0005}) as axis:
        got = axis.simulate_reference(ref, 0.0005)
    assert np.max(np.abs(got - simulate(PARAMETERS, ref, 0.0005))) <= 1e-9


# -------------------------------------------------------------------------------- stepping


@pytest.mark.parametrize("version", [2, 3])
def test_one_step_of_ten_samples_equals_ten_steps(fmus, version, tmp_path):
    a, b = _slave(fmus[version], tmp_path / "a"), _slave(fmus[version], tmp_path / "b")
    try:
        for fmu in (a, b):
            fmu.set_x([1], [2.5])  # x_ref held over the step
        for k in range(10):
            a.doStep(k * TS, TS)
        b.doStep(0.0, 10 * TS)
        ya, yb = a.get_x([3, 4]), b.get_x([3, 4])
        assert ya == yb and ya[0] != 0.0
        a.doStep(10 * TS, TS)
        b.doStep(10 * TS, TS)  # both continue from the same time
        assert a.get_x([3]) == b.get_x([3])
    finally:
        a.freeInstance()
        b.freeInstance()


@pytest.mark.parametrize("version", [2, 3])
def test_step_not_a_multiple_of_the_sample_time_is_refused(fmus, version, tmp_path):
    fmu = _slave(fmus[version], tmp_path)
    try:
        fmu.set_x([1], [1.0])
        fmu.doStep(0.0, TS)
        before = fmu.get_x([3])
        with pytest.raises(FMICallException) as info:
            fmu.doStep(TS, 1.5 * TS)
        assert info.value.status == 3  # fmi2Error / fmi3Error
        assert fmu.get_x([3]) == before  # nothing happened
        fmu.doStep(TS, 2 * TS)  # a whole multiple still works
        with pytest.raises(FMICallException):
            fmu.set_x([5], [1.0])  # a1 is fixed after initialisation
    finally:
        fmu.freeInstance()


def test_a_binary_refuses_a_foreign_token(fmus, tmp_path):
    from fmpy import extract
    from fmpy.fmi2 import FMU2Slave

    md = read_model_description(str(fmus[2]))
    fmu = FMU2Slave(guid="{00000000-0000-0000-0000-000000000001}", unzipDirectory=extract(str(fmus[2]), str(tmp_path)),
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="foreign")
    with pytest.raises(Exception, match="Failed to instantiate"):
        fmu.instantiate()


def test_refusal_message_names_the_sample_time(fmus):
    axis = FmuAxis(fmus[2])
    from vcnc.errors import SimulationError

    with pytest.raises(SimulationError, match="not a whole multiple of the sample time"):
        axis.simulate_reference(np.zeros(5), 1.5 * TS)
    ref = identification_reference(400, TS, seed=2)
    coarse = axis.simulate_reference(ref[::2], 2 * TS)  # two samples per step, input held: runs
    assert coarse.shape == (200,)


# ------------------------------------------------------------------------- plain C, no Python

HARNESS = r"""
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include "fmi2Functions.h"

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status, fmi2String category,
                   fmi2String message, ...)
{
    (void)env; (void)name; (void)category;
    fprintf(stderr, "[%d] %s\n", (int)status, message);
}

#define LOAD(T, f) T *f = (T *)dlsym(lib, #f); if (!f) { fprintf(stderr, "missing %s\n", #f); return 3; }

int main(int argc, char **argv)
{
    void *lib;
    double ts, x, y;
    fmi2Component c;
    fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    const fmi2ValueReference vr_in = 1, vr_out = 3;
    long k = 0;
    if (argc != 4) return 2;
    ts = atof(argv[3]);
    lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib) { fprintf(stderr, "%s\n", dlerror()); return 3; }
    {
        LOAD(fmi2InstantiateTYPE, fmi2Instantiate)
        LOAD(fmi2SetupExperimentTYPE, fmi2SetupExperiment)
        LOAD(fmi2EnterInitializationModeTYPE, fmi2EnterInitializationMode)
        LOAD(fmi2ExitInitializationModeTYPE, fmi2ExitInitializationMode)
        LOAD(fmi2SetRealTYPE, fmi2SetReal)
        LOAD(fmi2GetRealTYPE, fmi2GetReal)
        LOAD(fmi2DoStepTYPE, fmi2DoStep)
        LOAD(fmi2FreeInstanceTYPE, fmi2FreeInstance)
        c = fmi2Instantiate("harness", fmi2CoSimulation, argv[2], "", &cb, fmi2False, fmi2False);
        if (!c) return 4;
        if (scanf("%lf", &x) != 1) return 5;
        if (fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) != fmi2OK) return 6;
        if (fmi2EnterInitializationMode(c) != fmi2OK) return 6;
        if (fmi2SetReal(c, &vr_in, 1, &x) != fmi2OK) return 6;
        if (fmi2ExitInitializationMode(c) != fmi2OK) return 6;
        do {
            if (k > 0 && fmi2DoStep(c, (k - 1) * ts, ts, fmi2True) != fmi2OK) return 7;
            if (fmi2SetReal(c, &vr_in, 1, &x) != fmi2OK) return 7;
            if (fmi2GetReal(c, &vr_out, 1, &y) != fmi2OK) return 7;
            printf("%.17g\n", y);
            k++;
        } while (scanf("%lf", &x) == 1);
        fmi2FreeInstance(c);
    }
    dlclose(lib);
    return 0;
}
"""


def test_binary_runs_from_plain_c_without_python(fmus, model, tmp_path):
    cc = shutil.which("cc") or shutil.which("gcc")
    (tmp_path / "harness.c").write_text(HARNESS)
    exe = tmp_path / "harness"
    subprocess.run([cc, "-std=c99", "-Wall", "-Werror", "-I", str(fmi_header_dir()), str(tmp_path / "harness.c"),
                    "-o", str(exe), "-ldl"], check=True, capture_output=True)
    with zipfile.ZipFile(fmus[2]) as zf:
        (so,) = [n for n in zf.namelist() if n.startswith("binaries/")]
        lib = tmp_path / Path(so).name
        lib.write_bytes(zf.read(so))
    guid = read_model_description(str(fmus[2])).guid
    ref = identification_reference(3_000, TS, seed=9, start=-4.0)
    run = subprocess.run([str(exe), str(lib), guid, repr(TS)], input="\n".join(repr(float(x)) for x in ref),
                         capture_output=True, text=True, env={"PATH": "/usr/bin:/bin"}, timeout=60)
    assert run.returncode == 0, run.stderr
    got = np.array([float(s) for s in run.stdout.split()])
    assert got.shape == ref.shape
    assert np.max(np.abs(got - model.simulate(ref))) <= 1e-9


def test_c_matrix_exponential_matches_scipy(tmp_path):
    cc = shutil.which("cc") or shutil.which("gcc")
    src = tmp_path / "vcnc_linalg.c"
    for name in ("vcnc_linalg.c", "vcnc_linalg.h"):
        (tmp_path / name).write_text(resources.files("vcnc.fmu.c").joinpath(name).read_text())
    lib = tmp_path / "linalg.so"
    subprocess.run([cc, "-O2", "-ffp-contract=off", "-shared", "-fPIC", str(src), "-o", str(lib), "-lm"],
                   check=True, capture_output=True)
    dll = ctypes.CDLL(str(lib))
    dll.vcnc_expm.argtypes = [ctypes.c_int, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)]

    def expm(a: np.ndarray) -> np.ndarray:
        a = np.ascontiguousarray(a, dtype=float)
        out = np.empty_like(a)
        dp = ctypes.POINTER(ctypes.c_double)
        assert dll.vcnc_expm(a.shape[0], a.ctypes.data_as(dp), out.ctypes.data_as(dp)) == 0
        return out

    rng = np.random.default_rng(0)
    cases = [rng.normal(size=(n, n)) * s for n in (1, 3, 6) for s in (1e-3, 0.3, 2.0, 40.0)]
    # the augmented matrices of the export at sample times from 0.1 ms to 10 ms
    for ts in (1e-4, 1e-3, 1e-2):
        from identification.reduced_model import continuous_state_space

        ss = continuous_state_space(PARAMETERS)
        m = np.zeros((6, 6))
        m[:3, :3], m[:3, 3], m[:3, 5], m[3, 4] = ss["A"] * ts, ss["B"][:, 0] * ts, ss["B"][:, 1] * ts, 1.0
        cases.append(m)
    for a in cases:
        ref = scipy.linalg.expm(a)
        err = np.max(np.abs(expm(a) - ref)) / max(1.0, np.max(np.abs(ref)))
        assert err < 1e-12 * max(1.0, np.linalg.norm(a, 1)), (a.shape, err)


# -------------------------------------------------------------------------------- effects
# (exported or refused: tests/vcnc/test_fmu_effects.py)


def test_malformed_effect_is_a_model_file_error(model, tmp_path):
    data = model.to_dict()
    data["effects"] = [{"name": "delay", "parameters": {"samples": "two"}}]
    path = tmp_path / "m.json"
    path.write_text(json.dumps(data))
    with pytest.raises(ModelFileError, match="samples"):
        export_spec(path)


# ------------------------------------------------------------------------------ command line


def test_cli_bad_model_file_exit_2_and_no_file(tmp_path, capsys):
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "vcnc.axis-model/1", "sample_time": 0.001,\n "parameters": {"a1": 1,}}')
    out = tmp_path / "drive.fmu"
    assert main(["export-fmu", str(bad), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error:") and str(bad) in err and ":2:" in err
    assert main(["export-fmu", str(tmp_path / "missing.json"), "-o", str(out)]) == 2
    assert not out.exists() and list(tmp_path.iterdir()) == [bad]


def test_cli_build_failure_exit_1_and_no_file(model_file, tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("PATH", str(tmp_path))  # no cmake, no compiler
    out = tmp_path / "drive.fmu"
    assert main(["export-fmu", str(model_file), "-o", str(out)]) == 1
    assert "cmake" in capsys.readouterr().err.lower()
    assert list(tmp_path.iterdir()) == []


# ------------------------------------------------------------------------------- the axis


def test_fmu_axis_input_and_output_selection(fmus):
    ref = identification_reference(500, TS, seed=8)
    with FmuAxis(fmus[3], input="x_ref", output="tracking_error") as axis:
        err = axis.simulate_reference(ref, TS)
    assert np.max(np.abs(err - (ref - simulate(PARAMETERS, ref, TS)))) <= 1e-9
    with pytest.raises(MachineError, match="no real output named 'speed'"):
        FmuAxis(fmus[3], output="speed")
    with pytest.raises(MachineError, match="no such parameter"):
        FmuAxis(fmus[3], start_values={"kp": 1.0})


# ------------------------------------------------------------------------------ round trip


def test_round_trip_fmu_axis_is_the_true_machine(fmus, model, tmp_path):
    """Export, then let the FMU be an axis of a vcnc machine: the same capture as the model."""
    from interpolators.limits import AxisLimits
    from vcnc.engine.machine import Machine, load_machine
    from vcnc.setpoints import Setpoints

    ref = np.column_stack([identification_reference(6_000, TS, seed=21, start=5.0),
                           identification_reference(6_000, TS, seed=22, start=-3.0)])
    setpoints = Setpoints.from_positions(ref, sample_time=TS, axes=("x", "y"))
    limits = {a: AxisLimits(velocity=500.0, acceleration=1e4) for a in "xy"}
    by_model = Machine.from_axes({"x": model, "y": model}, sample_time=TS, limits=limits).simulate(setpoints)

    toml = tmp_path / "fmu-machine.toml"
    shutil.copy(fmus[2], tmp_path / "drive2.fmu")
    shutil.copy(fmus[3], tmp_path / "drive3.fmu")
    toml.write_text(
        f'name = "fmu-machine"\nsample_time = {TS}\n'
        '[axes.x]\nfmu = "drive2.fmu"\n[axes.x.limits]\nvelocity = 500.0\nacceleration = 1e4\n'
        '[axes.y]\nfmu = "drive3.fmu"\n[axes.y.limits]\nvelocity = 500.0\nacceleration = 1e4\n'
    )
    by_fmu = load_machine(toml).simulate(setpoints)
    assert by_fmu.axes == by_model.axes
    np.testing.assert_array_equal(by_fmu.reference, by_model.reference)
    assert np.max(np.abs(by_fmu.measured - by_model.measured)) <= 1e-9


def test_machine_file_naming_a_broken_fmu_is_a_machine_error(tmp_path):
    from vcnc.engine.machine import load_machine

    (tmp_path / "broken.fmu").write_bytes(b"not a zip")
    toml = tmp_path / "m.toml"
    toml.write_text(f'sample_time = {TS}\n[axes.x]\nfmu = "broken.fmu"\n[axes.x.limits]\nvelocity = 1.0\n'
                    'acceleration = 1.0\n')
    with pytest.raises(MachineError, match="not a readable FMU"):
        load_machine(toml)
