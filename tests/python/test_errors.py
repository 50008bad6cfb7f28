"""Every bad input of the contract: fmi2Error (FMICallException) with a logged message that
names the problem, the instance unchanged or cleanly failed, Python never crashes."""

import ctypes
import math

import pytest
from fmpy import extract
from fmpy.fmi1 import FMICallException

from helpers import ROOT, Slave, build_fmu, run_loop, schedule

ERROR, DISCARD = 3, 2


def expect_error(slave, call, *needles, status=ERROR):
    slave.log.clear()
    with pytest.raises(FMICallException) as e:
        call()
    assert e.value.status == status
    text = slave.log.text()
    for needle in needles:
        assert needle in text, f"{needle!r} not in {text!r}"
    return text


@pytest.fixture
def slave(unzipdir):
    s = Slave(unzipdir)
    yield s
    s.free()


@pytest.fixture
def running(slave):
    slave.init()
    run_loop(slave, schedule(0.0, 0.001, 1e-4))
    return slave


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_input_rejected_instance_unchanged(running, bad):
    before = running.get("crank.speed", "rod.deflection")
    expect_error(running, lambda: running.set(crank__speed=bad), "crank.speed", "finite")
    assert running.get("crank.speed", "rod.deflection") == before
    # Also when mixed with a good value: nothing is set.
    expect_error(running, lambda: running.set(crank__angle=1.0, crank__speed=bad), "crank.speed")
    assert running.get("crank.speed") == before[:1]
    t = running.fmu.getRealStatus(2)
    running.fmu.doStep(t, 1e-4)  # still steps


def test_non_finite_parameter_rejected(slave):
    expect_error(slave, lambda: slave.set(rod__length=math.nan), "rod.length", "finite")


def test_unknown_value_reference(running):
    expect_error(running, lambda: running.fmu.getReal([9999]), "unknown value reference 9999")
    expect_error(running, lambda: running.fmu.setReal([9999], [1.0]), "9999")
    expect_error(running, lambda: running.fmu.getInteger([9999]), "9999")
    expect_error(running, lambda: running.fmu.getBoolean([1]), "1")
    expect_error(running, lambda: running.fmu.getString([5]), "5")
    # A Real through the Integer getter names the right function.
    expect_error(running, lambda: running.fmu.getInteger([running.vr["rod.length"]]), "fmi2GetReal")
    assert running.get("crank.speed") == [150.0]


def test_fixed_parameter_after_initialization(running):
    expect_error(running, lambda: running.set(rod__length=0.4), "rod.length", "fixed parameter")
    expect_error(running, lambda: running.fmu.setInteger([running.vr["rod.elements"]], [4]),
                 "rod.elements", "fixed parameter")
    assert running.get("rod.length") == [0.3048]


def test_outputs_cannot_be_set(running):
    expect_error(running, lambda: running.set(rod__deflection=0.0), "rod.deflection", "output")
    expect_error(running, lambda: running.fmu.setReal([running.vr["rod.frequency[1]"]], [1.0]),
                 "rod.frequency[1]")


def test_wrong_call_order(slave):
    expect_error(slave, lambda: slave.fmu.doStep(0.0, 1e-4), "fmi2DoStep", "Instantiated", "StepComplete")
    expect_error(slave, lambda: slave.fmu.exitInitializationMode(), "fmi2ExitInitializationMode")
    expect_error(slave, lambda: slave.fmu.getReal([slave.vr["rod.deflection"]]), "fmi2GetReal")
    expect_error(slave, lambda: slave.fmu.terminate(), "fmi2Terminate")
    slave.init()
    expect_error(slave, lambda: slave.fmu.setupExperiment(startTime=0.0), "fmi2SetupExperiment")
    expect_error(slave, lambda: slave.fmu.cancelStep(), "fmi2CancelStep")
    slave.fmu.doStep(0.0, 1e-4)


@pytest.mark.parametrize("h", [0.0, -1e-4, math.nan, math.inf])
def test_bad_step_size(running, h):
    t = running.fmu.getRealStatus(2)
    before = running.outputs()
    expect_error(running, lambda: running.fmu.doStep(t, h), "communicationStepSize", "allowed")
    assert running.outputs() == before
    running.fmu.doStep(t, 1e-4)


def test_time_mismatch(running):
    t = running.fmu.getRealStatus(2)
    expect_error(running, lambda: running.fmu.doStep(t + 1e-3, 1e-4), "does not match the FMU time")
    expect_error(running, lambda: running.fmu.doStep(math.nan, 1e-4), "does not match")
    running.fmu.doStep(t, 1e-4)


def test_stop_time_enforced(slave):
    slave.init(stop=0.001)
    expect_error(slave, lambda: slave.fmu.doStep(0.0, 0.002), "stopTime")
    slave.fmu.doStep(0.0, 0.001)


def test_crank_longer_than_rod_fails_initialization_then_reset(slave):
    slave.fmu.setupExperiment(startTime=0.0)
    slave.set(crank__length=0.4)
    slave.fmu.enterInitializationMode()
    expect_error(slave, slave.fmu.exitInitializationMode, "crank.length = 0.4", "rod.length = 0.3048",
                 "allowed")
    # The instance still answers (parameters) and fails cleanly (outputs), and can be reset.
    assert slave.get("crank.length") == [0.4]
    expect_error(slave, lambda: slave.get("rod.deflection"), "not available", "crank.length")
    expect_error(slave, lambda: slave.fmu.doStep(0.0, 1e-4), "fmi2DoStep", "Error")
    slave.fmu.reset()
    slave.init()
    slave.fmu.doStep(0.0, 1e-4)


@pytest.mark.parametrize("name,value", [
    ("rod.youngs_modulus", -1.0),
    ("rod.density", 0.0),
    ("rod.area", -3e-5),
    ("rod.area_moment", 0.0),
    ("rod.length", 0.0),
])
def test_impossible_parameters_name_the_parameter(slave, name, value):
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.setReal([slave.vr[name]], [value])
    slave.fmu.enterInitializationMode()
    expect_error(slave, slave.fmu.exitInitializationMode, name)


def test_too_many_modes(slave):
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.setInteger([slave.vr["rod.modes"]], [1000])
    slave.fmu.enterInitializationMode()
    expect_error(slave, slave.fmu.exitInitializationMode, "rod.modes")


def test_enumeration_out_of_range(slave):
    expect_error(slave, lambda: slave.fmu.setInteger([slave.vr["rod.model"]], [7]),
                 "rod.model = 7", "1 (ffr), 2 (segments)")
    expect_error(slave, lambda: slave.fmu.setInteger([slave.vr["rod.elements"]], [-2]),
                 "rod.elements = -2", ">= 0")


def test_input_derivatives_checked(running):
    vr = running.vr
    expect_error(running, lambda: running.fmu.setRealInputDerivatives([vr["crank.speed"]], [2], [1.0]),
                 "order 2")
    expect_error(running, lambda: running.fmu.setRealInputDerivatives([vr["rod.length"]], [1], [1.0]),
                 "rod.length", "not an input")
    expect_error(running, lambda: running.fmu.setRealInputDerivatives([vr["crank.speed"]], [1], [math.nan]),
                 "finite")
    expect_error(running, lambda: running.fmu.setRealInputDerivatives([vr["slider.force"]], [1], [5.0]),
                 "slider.force")
    running.fmu.setRealInputDerivatives([vr["crank.angle"]], [1], [150.0])  # consistent: accepted


def test_unsupported_functions(running):
    expect_error(running, lambda: running.fmu.getRealOutputDerivatives([running.vr["rod.deflection"]], [1]),
                 "maxOutputDerivativeOrder")
    expect_error(running, lambda: running.fmu.getIntegerStatus(0), "fmi2GetIntegerStatus")
    expect_error(running, lambda: running.fmu.getStringStatus(1), "fmi2GetStringStatus")
    expect_error(running, lambda: running.fmu.getStatus(7), "status kind 7")
    expect_error(running, lambda: running.fmu.setDebugLogging(True, ["logNonsense"]), "logNonsense")
    running.fmu.setDebugLogging(True, ["logEvents", "logStatusError"])
    assert running.fmu.getBooleanStatus(3) is False
    assert running.fmu.getStatus(0) == 0


def test_truncated_and_foreign_serialized_state(running):
    state = running.fmu.getFMUstate()
    blob = running.fmu.serializeFMUstate(state)
    expect_error(running, lambda: running.fmu.deSerializeFMUstate(blob[: len(blob) // 2]), "truncated")
    expect_error(running, lambda: running.fmu.deSerializeFMUstate(b"not an FMU state at all"), "foreign")
    expect_error(running, lambda: running.fmu.deSerializeFMUstate(blob + b"\0"), "unexpected")
    corrupted = bytearray(blob)
    corrupted[-5] ^= 0xFF
    running.log.clear()
    try:
        running.fmu.deSerializeFMUstate(bytes(corrupted))
    except FMICallException:
        assert "rejected" in running.log.text()
    # A handle that was freed or never existed.
    running.fmu.freeFMUstate(state)
    expect_error(running, lambda: running.fmu.setFMUstate(ctypes.c_void_p(12345678)), "not a state")
    t = running.fmu.getRealStatus(2)
    running.fmu.doStep(t, 1e-4)


def test_null_pointers_and_null_instance(running):
    lib = running.fmu.dll
    c = running.fmu.component
    lib.fmi2GetReal.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p]
    running.log.clear()
    assert lib.fmi2GetReal(c, None, 2, None) == ERROR
    assert "vr[] is NULL" in running.log.text()
    assert lib.fmi2GetReal(c, None, 0, None) == 0
    lib.fmi2DoStep.argtypes = [ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_int]
    assert lib.fmi2DoStep(None, 0.0, 1e-4, 1) == ERROR
    lib.fmi2GetFMUstate.argtypes = [ctypes.c_void_p, ctypes.c_void_p]
    assert lib.fmi2GetFMUstate(c, None) == ERROR
    assert "FMUstate is NULL" in running.log.text()
    lib.fmi2FreeInstance.argtypes = [ctypes.c_void_p]
    lib.fmi2FreeInstance(None)


def test_guid_mismatch_and_model_exchange(unzipdir):
    with pytest.raises(Exception, match="Failed to instantiate"):
        Slave(unzipdir, guid="{00000000-0000-0000-0000-000000000000}")
    s = Slave(unzipdir)
    lib = s.fmu.dll
    lib.fmi2Instantiate.restype = ctypes.c_void_p
    lib.fmi2Instantiate.argtypes = [ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p,
                                    ctypes.c_void_p, ctypes.c_int, ctypes.c_int]
    s.log.clear()
    c = lib.fmi2Instantiate(b"me", 0, s.md.guid.encode(), b"file:///nowhere", ctypes.byref(s.log.callbacks), 0, 0)
    assert c is None
    assert "fmuType = 0" in s.log.text()
    s.log.clear()
    c = lib.fmi2Instantiate(b"x", 1, b"{bad}", b"file:///nowhere", ctypes.byref(s.log.callbacks), 0, 0)
    assert c is None and "{bad}" in s.log.text()
    s.free()


def test_missing_or_foreign_resources(fmu_path, tmp_path):
    d = tmp_path / "fmu"
    extract(str(fmu_path), str(d))
    # Without resources/scene.toml the compiled-in default scene serves (same GUID).
    (d / "resources" / "scene.toml").unlink()
    s = Slave(d, logging_on=True)
    s.init()
    s.fmu.doStep(0.0, 1e-4)
    s.free()
    # A different scene under the same description: GUID mismatch, instantiation fails.
    scene = (ROOT / "scenes" / "benchmark.toml").read_text()
    (d / "resources" / "scene.toml").write_text(scene.replace("length = 0.3048", "length = 0.31"))
    with pytest.raises(Exception, match="Failed to instantiate"):
        Slave(d)


def test_discard_keeps_the_state(fmu_path, tmp_path):
    """A step the solver cannot complete returns fmi2Discard with the reason; the state from
    before the step is kept and can be restored and retried with a smaller step."""
    text = (ROOT / "scenes" / "benchmark.toml").read_text()
    text = text.replace("rho_inf = 0.8", "rho_inf = 0.8\nmax_newton_iterations = 1\nmax_halvings = 0")
    text = text.replace('name = "FlexibleSliderCrank"', 'name = "StiffSliderCrank"')
    scene = tmp_path / "stiff.toml"
    scene.write_text(text)
    fmu = build_fmu(tmp_path, scene)
    d = extract(str(fmu), str(tmp_path / "x"))
    s = Slave(d)
    s.init()
    state = s.fmu.getFMUstate()
    before = s.outputs()
    try:
        s.fmu.doStep(0.0, 1e-2)
    except FMICallException as e:
        assert e.status == DISCARD
        assert "failed" in s.log.text()
        assert s.fmu.getStatus(0) == DISCARD
        assert s.fmu.getRealStatus(2) == 0.0
        assert s.outputs() == before
        expect_error(s, lambda: s.fmu.doStep(0.0, 1e-3), "StepFailed")
        s.fmu.setFMUstate(state)
        s.fmu.terminate()
    else:
        pytest.skip("the solver completed the step even with one Newton iteration")
    finally:
        s.free()
