"""The real-rod parameters of the contract (docs/fmu.md, "Real connecting rods"):
rod.shear_modulus (138), rod.big_end.mass / .inertia (139, 140), rod.small_end.mass / .inertia
(141, 142), and the modes chosen for the mechanism, rod.loaded_modes (143) and rod.mode_band_hz
(144), on the FMU of scenes/automotive_rod.toml: present with their scene values, range checked
with a message naming the variable, and acting on the model."""

import math

import pytest
from fmpy import extract
from fmpy.fmi1 import FMICallException
from helpers import ROOT, Slave, build_fmu

SCENE = ROOT / "scenes" / "automotive_rod.toml"
EXPECTED = {
    "rod.shear_modulus": (138, "Pa", 7.7e10),
    "rod.big_end.mass": (139, "kg", 0.22),
    "rod.big_end.inertia": (140, "kg.m2", 3.1e-4),
    "rod.small_end.mass": (141, "kg", 0.05),
    "rod.small_end.inertia": (142, "kg.m2", 1.1e-5),
}


@pytest.fixture(scope="module")
def automotive_unzipdir(tmp_path_factory):
    fmu = build_fmu(tmp_path_factory.mktemp("automotive_fmu"), SCENE)
    return extract(str(fmu), str(tmp_path_factory.mktemp("automotive_unzipped")))


@pytest.fixture
def slave(automotive_unzipdir):
    s = Slave(automotive_unzipdir)
    yield s
    s.free()


def initializing(slave):
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.enterInitializationMode()


def test_parameters_declared_with_scene_values(slave):
    initializing(slave)
    variables = {v.name: v for v in slave.md.modelVariables}
    for name, (vr, unit, start) in EXPECTED.items():
        v = variables[name]
        assert v.valueReference == vr, name
        assert v.causality == "parameter", name
        assert v.unit == unit, name
        assert math.isclose(float(v.start), start, rel_tol=1e-12), name
        assert math.isclose(slave.get(name)[0], start, rel_tol=1e-12), name


@pytest.mark.parametrize(
    "name, bad",
    [
        ("rod.shear_modulus", 0.0),
        ("rod.shear_modulus", -1.0e9),
        ("rod.big_end.mass", -0.1),
        ("rod.big_end.inertia", -1e-6),
        ("rod.small_end.mass", -0.1),
        ("rod.small_end.inertia", -1e-6),
    ],
)
def test_out_of_range_rejected_naming_the_variable(slave, name, bad):
    """As every Real parameter of the FMU: the model rejects it at
    fmi2ExitInitializationMode (fmi2Error, the message names the parameter)."""
    slave.fmu.setupExperiment(startTime=0.0)
    slave.set(**{name.replace(".", "__"): bad})
    slave.fmu.enterInitializationMode()
    slave.log.clear()
    with pytest.raises(FMICallException):
        slave.fmu.exitInitializationMode()
    assert name in slave.log.text(), slave.log.text()


def test_non_finite_rejected_when_set(slave):
    slave.log.clear()
    with pytest.raises(FMICallException):
        slave.set(rod__small_end__mass=math.nan)
    assert "rod.small_end.mass" in slave.log.text()
    initializing(slave)
    assert slave.get("rod.small_end.mass") == [0.05]


def test_end_masses_and_shear_modulus_act_on_the_model(automotive_unzipdir):
    def after_init(params):
        s = Slave(automotive_unzipdir)
        try:
            s.init(params=params, speed=628.3)
            return s.get("rod.mass", "rod.frequency[1]")
        finally:
            s.free()

    mass0, f0 = after_init({})
    mass1, _ = after_init({"rod.big_end.mass": 0.32, "rod.small_end.mass": 0.10})
    assert math.isclose(mass1 - mass0, 0.15, rel_tol=1e-9)
    # A softer shear modulus lowers the first bending frequency of this stubby rod.
    _, f_soft = after_init({"rod.shear_modulus": 2.0e10})
    assert f_soft < 0.99 * f0
    # A heavier small end lowers it too.
    _, f_heavy = after_init({"rod.small_end.inertia": 1.0e-4})
    assert f_heavy < f0


def test_both_rod_models_run_the_shear_deformable_rod_and_say_what_they_keep(automotive_unzipdir):
    """The automotive rod (shear deformation, end bodies, stress outputs) through the
    FMU as the FFR rod and as the segment chain (shear deformation as slides between the segments).
    With logging on, fmi2ExitInitializationMode says which modes the FFR rod keeps (bending and
    axial) and what the chain has. Both spin up from rest at a constant 31416 rad/s^2 to
    628 rad/s in 20 ms (the scene's 2 % damping lets the start transient die out) and end with
    the same largest stress within 2 % (16 segments)."""
    final = {}
    accel, dt, steps = 31415.9, 1e-5, 2000
    for model, elements in [(1, 8), (2, 16)]:
        s = Slave(automotive_unzipdir, logging_on=True)
        try:
            s.fmu.setupExperiment(startTime=0.0)
            s.fmu.setInteger([s.vr["rod.model"], s.vr["rod.elements"]], [model, elements])
            s.fmu.enterInitializationMode()
            s.fmu.setReal([s.vr["crank.angle"], s.vr["crank.speed"]], [0.0, 0.0])
            s.fmu.exitInitializationMode()
            text = s.log.text()
            if model == 1:
                assert "modes kept:" in text and "axial" in text and "bending" in text, text
            else:
                assert "segment chain, 16 segments" in text and "shear slides" in text, text
            for k in range(steps):
                t = k * dt
                s.fmu.setReal(
                    [s.vr["crank.angle"], s.vr["crank.speed"]], [0.5 * accel * t * t, accel * t]
                )
                s.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=dt)
                assert math.isfinite(s.get("rod.stress_max")[0])
            final[model] = s.get("rod.stress_max")[0]
        finally:
            s.free()
    assert final[1] > 1e6
    assert math.isclose(final[1], final[2], rel_tol=0.02), final


# The modes chosen for the mechanism (docs/fmu.md, "Mode band and mass-loaded modes"):
# rod.loaded_modes (143, Integer 0/1) and rod.mode_band_hz (144, Real, Hz), declared in scenes that
# use them. A scene with a band declares rod.mode_band_hz and not rod.modes, so that neither is
# ignored.
PISTON_AXIAL_HZ = 3268.5


def initialized(unzipdir, integers=None, reals=None):
    """An instance after fmi2ExitInitializationMode at 628.3 rad/s with these parameters, and
    its log."""
    s = Slave(unzipdir, logging_on=True)
    s.fmu.setupExperiment(startTime=0.0)
    for name, value in (integers or {}).items():
        s.fmu.setInteger([s.vr[name]], [value])
    for name, value in (reals or {}).items():
        s.fmu.setReal([s.vr[name]], [value])
    s.fmu.enterInitializationMode()
    s.fmu.setReal([s.vr["crank.angle"], s.vr["crank.speed"]], [0.0, 628.3])
    s.fmu.exitInitializationMode()
    return s


def frequencies(slave):
    return slave.get(*[f"rod.frequency[{k}]" for k in range(1, 7)])


def test_mode_parameters_declared_with_scene_values(slave):
    variables = {v.name: v for v in slave.md.modelVariables}
    loaded = variables["rod.loaded_modes"]
    assert (loaded.valueReference, loaded.type, loaded.causality) == (143, "Integer", "parameter")
    assert (loaded.min, loaded.max, loaded.start) == ("0", "1", "1")
    band = variables["rod.mode_band_hz"]
    assert (band.valueReference, band.type, band.unit) == (144, "Real", "Hz")
    assert float(band.start) == 6000.0 and float(band.min) == 0.0
    # The band chooses the modes: the count is not declared.
    assert "rod.modes" not in variables
    # The frequencies depend on both switches of the eigenproblem and on the slider's mass.
    unknown = next(u for u in slave.md.initialUnknowns if u.variable.name == "rod.frequency[1]")
    names = {d.name for d in unknown.dependencies}
    assert {"rod.loaded_modes", "slider.mass", "rod.small_end.mass"} <= names, names
    # And on what decides the model class: the band (against the slider-rod axial mode), the
    # switches, the tolerance.
    assert {
        "rod.mode_band_hz",
        "rod.axial_dynamics",
        "rod.shear_deformation",
        "solver.tolerance",
    } <= names, names


def test_loaded_modes_give_the_piston_rod_axial_mode(automotive_unzipdir):
    s = initialized(automotive_unzipdir)
    try:
        loaded = frequencies(s)
        text = s.log.text()
    finally:
        s.free()
    assert math.isclose(loaded[1], PISTON_AXIAL_HZ, abs_tol=0.5), loaded
    assert "3269 Hz axial" in text, text
    # Free modes: loaded modes and the automatic axial mode off.
    s = initialized(
        automotive_unzipdir, integers={"rod.loaded_modes": 0, "rod.axial_dynamics_index": 3}
    )
    try:
        free = frequencies(s)
        text = s.log.text()
    finally:
        s.free()
    # Bending is not loaded by the slider's axial mass: the same first bending frequency. The
    # free rod's first axial mode is far above the piston-rod mode.
    assert math.isclose(free[0], loaded[0], rel_tol=1e-9), (free, loaded)
    assert all(abs(f - PISTON_AXIAL_HZ) > 1000.0 for f in free), free
    assert "axial" not in text.split("modes kept:")[1].split(";")[0], text
    # With loaded modes the slider's mass moves the axial mode: a lighter piston raises it.
    s = initialized(automotive_unzipdir, reals={"slider.mass": 0.3})
    try:
        lighter = frequencies(s)
    finally:
        s.free()
    assert lighter[1] > 1.1 * PISTON_AXIAL_HZ, lighter


def test_mode_band_chooses_the_retained_modes(automotive_unzipdir):
    def kept(reals):
        s = initialized(automotive_unzipdir, reals=reals)
        try:
            text = s.log.text()
        finally:
            s.free()
        return text.split("modes kept:")[1].split(";")[0]

    assert kept({}).count("Hz") == 3, kept({})
    wide = kept({"rod.mode_band_hz": 20000.0})
    assert wide.count("Hz") == 6 and "17510 Hz axial" in wide, wide
    assert "no elastic modes" in kept({"rod.mode_band_hz": 1000.0})


@pytest.mark.parametrize("bad", [0.0, -5.0])
def test_mode_band_out_of_range_rejected_naming_the_variable(slave, bad):
    slave.fmu.setupExperiment(startTime=0.0)
    slave.set(rod__mode_band_hz=bad)
    slave.fmu.enterInitializationMode()
    slave.log.clear()
    with pytest.raises(FMICallException):
        slave.fmu.exitInitializationMode()
    assert "rod.mode_band_hz" in slave.log.text(), slave.log.text()


def test_loaded_modes_outside_0_1_rejected_when_set(slave):
    slave.log.clear()
    with pytest.raises(FMICallException):
        slave.fmu.setInteger([slave.vr["rod.loaded_modes"]], [2])
    text = slave.log.text()
    assert "rod.loaded_modes" in text and "0 (free modes) or 1" in text, text
    initializing(slave)
    assert slave.fmu.getInteger([slave.vr["rod.loaded_modes"]]) == [1]
