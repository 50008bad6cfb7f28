"""The archive, its modelDescription.xml and the exported C symbols."""

import ctypes
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

FMI2_FUNCTIONS = """
fmi2GetTypesPlatform fmi2GetVersion fmi2SetDebugLogging fmi2Instantiate fmi2FreeInstance
fmi2SetupExperiment fmi2EnterInitializationMode fmi2ExitInitializationMode fmi2Terminate
fmi2Reset fmi2GetReal fmi2GetInteger fmi2GetBoolean fmi2GetString fmi2SetReal
fmi2SetInteger fmi2SetBoolean fmi2SetString fmi2GetFMUstate fmi2SetFMUstate
fmi2FreeFMUstate fmi2SerializedFMUstateSize fmi2SerializeFMUstate fmi2DeSerializeFMUstate
fmi2GetDirectionalDerivative fmi2SetRealInputDerivatives fmi2GetRealOutputDerivatives
fmi2DoStep fmi2CancelStep fmi2GetStatus fmi2GetRealStatus fmi2GetIntegerStatus
fmi2GetBooleanStatus fmi2GetStringStatus
""".split()


def test_fmpy_validate_reports_no_problems(fmu_path):
    assert validate_fmu(str(fmu_path)) == []
    cli = subprocess.run(
        [sys.executable, "-m", "fmpy.cli", "validate", str(fmu_path)],
        capture_output=True,
        text=True,
    )
    assert cli.returncode == 0, cli.stdout + cli.stderr
    assert "No problems found" in cli.stdout, cli.stdout


IDENTIFIERS = {"ffr": "FlexibleSliderCrank", "segments": "FlexibleSliderCrankSegments"}


def test_archive_layout(fmu_path, model):
    with zipfile.ZipFile(fmu_path) as z:
        names = sorted(i.filename for i in z.infolist())
        assert names == sorted(
            [
                "modelDescription.xml",
                f"binaries/linux64/{IDENTIFIERS[model]}.so",
                "resources/scene.toml",
                "documentation/index.html",
            ]
        )
        for info in z.infolist():
            assert info.compress_type == zipfile.ZIP_DEFLATED, info.filename
            assert not info.filename.startswith("./") and "\\" not in info.filename
        doc = z.read("documentation/index.html").decode()
        assert "rod.frequency[1]" in doc and "crank.angle" in doc


def test_all_34_functions_exported(unzipdir, model):
    assert len(FMI2_FUNCTIONS) == 34
    so = Path(unzipdir) / "binaries" / "linux64" / f"{IDENTIFIERS[model]}.so"
    lib = ctypes.CDLL(str(so))
    missing = [f for f in FMI2_FUNCTIONS if not hasattr(lib, f)]
    assert missing == []
    nm = subprocess.run(["nm", "-D", "--defined-only", str(so)], capture_output=True, text=True)
    exported = set(re.findall(r"\bT (fmi2\w+)", nm.stdout))
    assert exported == set(FMI2_FUNCTIONS)
    lib.fmi2GetVersion.restype = ctypes.c_char_p
    lib.fmi2GetTypesPlatform.restype = ctypes.c_char_p
    assert lib.fmi2GetVersion() == b"2.0"
    assert lib.fmi2GetTypesPlatform() == b"default"


def test_model_description_follows_the_contract(fmu_path, model):
    md = read_model_description(str(fmu_path))
    assert md.fmiVersion == "2.0"
    assert md.variableNamingConvention == "structured"
    assert re.fullmatch(
        r"\{[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}\}", md.guid
    )
    cs = md.coSimulation
    assert cs.modelIdentifier == IDENTIFIERS[model]
    assert cs.canHandleVariableCommunicationStepSize
    assert cs.canInterpolateInputs
    assert cs.canGetAndSetFMUstate and cs.canSerializeFMUstate
    assert not cs.canBeInstantiatedOnlyOncePerProcess
    assert not cs.needsExecutionTool
    assert cs.maxOutputDerivativeOrder == 0

    v = {x.name: x for x in md.modelVariables}
    expected = {
        "crank.angle": ("input", "rad"),
        "crank.speed": ("input", "rad/s"),
        "slider.force": ("input", "N"),
        "rod.deflection": ("output", "m"),
        "rod.deflection_rel": ("output", None),
        "pinB.force_x": ("output", "N"),
        "pinB.force_y": ("output", "N"),
        "pinC.force_x": ("output", "N"),
        "pinC.force_y": ("output", "N"),
        "crank.torque": ("output", "N.m"),
        "slider.position": ("output", "m"),
        "slider.velocity": ("output", "m/s"),
        "crank.length": ("parameter", "m"),
        "rod.length": ("parameter", "m"),
        "rod.youngs_modulus": ("parameter", "Pa"),
        "rod.density": ("parameter", "kg/m3"),
        "rod.area": ("parameter", "m2"),
        "rod.area_moment": ("parameter", "m4"),
        "rod.damping_ratio": ("parameter", None),
        "slider.mass": ("parameter", "kg"),
    }
    for name, (causality, unit) in expected.items():
        assert v[name].causality == causality, name
        assert v[name].unit == unit, name
    assert v["crank.angle"].displayUnit == "deg"
    assert v["crank.speed"].displayUnit == "rpm"
    for name in [
        "crank.length",
        "rod.length",
        "rod.model",
        "rod.elements",
        "rod.reference",
        "rod.modes",
    ]:
        assert v[name].variability == "fixed", name
    assert v["rod.model"].type == "Enumeration"
    assert [i.name for i in v["rod.model"].declaredType.items] == [
        "ffr",
        "segments",
        "modal_segments",
        "auto",
    ]
    assert [i.name for i in v["rod.reference"].declaredType.items] == [
        "simply_supported",
        "mean_axis",
        "body_fixed_mid",
        "cantilever",
    ]
    assert v["rod.elements"].type == "Integer" and v["rod.elements"].start == "8"
    assert float(v["rod.length"].start) == 0.3048
    frequencies = [n for n in v if n.startswith("rod.frequency[")]
    assert frequencies == [f"rod.frequency[{k}]" for k in range(1, 7)]
    assert all(v[n].causality == "calculatedParameter" and v[n].unit == "Hz" for n in frequencies)
    assert float(md.defaultExperiment.stepSize) == 1e-4
    assert {c.name for c in md.logCategories} >= {
        "logStatusError",
        "logStatusWarning",
        "logEvents",
        "logAll",
    }


def test_golden_model_description_matches_the_archive(fmu_path, model):
    if model != "ffr":
        pytest.skip("the golden copy is the default scene's description")
    golden = Path(__file__).resolve().parents[2] / "modelDescription" / "modelDescription.xml"
    with zipfile.ZipFile(fmu_path) as z:
        assert z.read("modelDescription.xml").decode() == golden.read_text()
