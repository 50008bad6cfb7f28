"""The real-rod parameters of the contract (docs/fmu.md, "Real connecting rods"):
rod.shear_modulus (138), rod.big_end.mass / .inertia (139, 140), rod.small_end.mass / .inertia
(141, 142), on the FMU of scenes/automotive_rod.toml: present with their scene values, range
checked with a message naming the variable, and acting on the model."""

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
                s.fmu.setReal([s.vr["crank.angle"], s.vr["crank.speed"]],
                              [0.5 * accel * t * t, accel * t])
                s.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=dt)
                assert math.isfinite(s.get("rod.stress_max")[0])
            final[model] = s.get("rod.stress_max")[0]
        finally:
            s.free()
    assert final[1] > 1e6
    assert math.isclose(final[1], final[2], rel_tol=0.02), final
