"""Every bad input of the contract: fmi2Error (FMICallException) with a logged message that
names the problem, the instance unchanged or cleanly failed, Python never crashes."""

import ctypes
import math
from pathlib import Path

import pytest
from fmpy import extract
from fmpy.fmi1 import FMICallException
from helpers import ROOT, Slave, build_fmu, run_loop, schedule

OK, WARNING, DISCARD, ERROR = 0, 1, 2, 3


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
    expect_error(
        running,
        lambda: running.fmu.setInteger([running.vr["rod.elements"]], [4]),
        "rod.elements",
        "fixed parameter",
    )
    assert running.get("rod.length") == [0.3048]


def test_outputs_cannot_be_set(running):
    expect_error(running, lambda: running.set(rod__deflection=0.0), "rod.deflection", "output")
    expect_error(
        running,
        lambda: running.fmu.setReal([running.vr["rod.frequency[1]"]], [1.0]),
        "rod.frequency[1]",
    )


def test_wrong_call_order(slave):
    expect_error(
        slave, lambda: slave.fmu.doStep(0.0, 1e-4), "fmi2DoStep", "Instantiated", "StepComplete"
    )
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
    slave.fmu.doStep(0.0, 0.0005)
    # The message names the communication point the master passed (here within the time
    # tolerance of the FMU's own time, but not equal to it) and the end of its step.
    t = 0.0005 + 3e-13
    text = expect_error(slave, lambda: slave.fmu.doStep(t, 0.001), "stopTime = 0.001 s")
    assert f"currentCommunicationPoint = {t!r} s" in text, text
    assert f"would end at {t + 0.001!r} s" in text, text
    slave.fmu.doStep(0.0005, 0.0005)


def test_crank_longer_than_rod_fails_initialization_then_reset(slave):
    slave.fmu.setupExperiment(startTime=0.0)
    slave.set(crank__length=0.4)
    slave.fmu.enterInitializationMode()
    expect_error(
        slave,
        slave.fmu.exitInitializationMode,
        "crank.length = 0.4",
        "rod.length = 0.3048",
        "allowed",
    )
    # The instance still answers (parameters) and fails cleanly (outputs), and can be reset.
    assert slave.get("crank.length") == [0.4]
    expect_error(slave, lambda: slave.get("rod.deflection"), "not available", "crank.length")
    expect_error(slave, lambda: slave.fmu.doStep(0.0, 1e-4), "fmi2DoStep", "Error")
    slave.fmu.reset()
    slave.init()
    slave.fmu.doStep(0.0, 1e-4)


def test_failed_initialization_leaves_no_stale_outputs(slave):
    """Outputs read (and the model built and started) in initialization mode, then a failed
    fmi2ExitInitializationMode: outputs give fmi2Error with the reason, never old values."""
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.enterInitializationMode()
    # Built and started here: undeformed but for the left-out modes' static correction.
    assert abs(slave.get("rod.deflection")[0]) < 1e-12
    slave.fmu.setReal([slave.vr["crank.length"]], [0.5])
    expect_error(slave, slave.fmu.exitInitializationMode, "crank.length")
    for name in ["rod.deflection", "pinB.force_x", "rod.frequency[1]"]:
        expect_error(slave, lambda: slave.get(name), "not available", "crank.length")
    assert slave.get("crank.speed", "rod.length") == [150.0, 0.3048]
    expect_error(slave, lambda: slave.fmu.getRealStatus(2), "fmi2GetRealStatus", "Error")


@pytest.mark.parametrize(
    "name,value",
    [
        ("rod.youngs_modulus", -1.0),
        ("rod.density", 0.0),
        ("rod.area", -3e-5),
        ("rod.area_moment", 0.0),
        ("rod.length", 0.0),
    ],
)
def test_impossible_parameters_name_the_parameter(slave, name, value):
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.setReal([slave.vr[name]], [value])
    slave.fmu.enterInitializationMode()
    expect_error(slave, slave.fmu.exitInitializationMode, name)


def test_too_many_modes(slave, model):
    if model != "ffr":
        pytest.skip("rod.modes applies to the FFR rod only")
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.setInteger([slave.vr["rod.modes"]], [1000])
    slave.fmu.enterInitializationMode()
    expect_error(slave, slave.fmu.exitInitializationMode, "rod.modes")


def test_enumeration_out_of_range(slave):
    expect_error(
        slave,
        lambda: slave.fmu.setInteger([slave.vr["rod.model"]], [7]),
        "rod.model = 7",
        "1 (ffr), 2 (segments)",
    )
    for bad in [-2, 0, 4097]:
        expect_error(
            slave,
            lambda: slave.fmu.setInteger([slave.vr["rod.elements"]], [bad]),
            f"rod.elements = {bad}",
            "..=128",
            "declared range",
        )
    expect_error(
        slave, lambda: slave.fmu.setInteger([slave.vr["rod.modes"]], [-1]), "rod.modes = -1", ">= 0"
    )


def set_derivatives(slave, vrs, orders, values):
    """fmi2SetRealInputDerivatives through ctypes: the status, also for fmi2Warning."""
    n = len(vrs)
    f = slave.raw(
        "fmi2SetRealInputDerivatives",
        ctypes.c_void_p,
        ctypes.c_void_p,
        ctypes.c_size_t,
        ctypes.c_void_p,
        ctypes.c_void_p,
    )
    slave.log.clear()
    return f(
        slave.fmu.component,
        (ctypes.c_uint * n)(*vrs),
        n,
        (ctypes.c_int * n)(*orders),
        (ctypes.c_double * n)(*values),
    )


def test_input_derivatives_errors(running):
    vr = running.vr
    for order in [0, -1]:
        assert set_derivatives(running, [vr["crank.speed"]], [order], [1.0]) == ERROR
        assert (
            f"order {order}" in running.log.text() and "allowed an order >= 1" in running.log.text()
        )
    assert set_derivatives(running, [vr["rod.length"]], [1], [1.0]) == ERROR
    assert "rod.length" in running.log.text() and "parameter" in running.log.text()
    assert set_derivatives(running, [vr["rod.deflection"]], [1], [1.0]) == ERROR
    assert set_derivatives(running, [9999], [1], [1.0]) == ERROR
    assert "unknown value reference 9999" in running.log.text()
    for bad in [math.nan, math.inf]:
        assert set_derivatives(running, [vr["crank.speed"]], [1], [bad]) == ERROR
        assert "finite" in running.log.text()
    # An error anywhere in the array: nothing is set (the good first entry neither).
    assert (
        set_derivatives(running, [vr["crank.speed"], vr["crank.speed"]], [1, 0], [5.0, 1.0])
        == ERROR
    )


@pytest.mark.parametrize(
    "name,order",
    [
        ("slider.force", 1),
        ("slider.force", 2),
        ("crank.speed", 3),
        ("crank.speed", 4),
        ("crank.angle", 4),
        ("crank.angle", 5),
    ],
)
def test_unusable_input_derivatives_are_ignored_with_a_warning(running, name, order):
    vr = running.vr[name]
    assert set_derivatives(running, [vr], [order], [5.0]) == WARNING
    assert f"order-{order} derivative of {name} = 5" in running.log.text()
    assert "ignored" in running.log.text()
    assert running.log.messages[-1][:2] == (WARNING, "logStatusWarning")
    # The value the law has anyway (0) is accepted silently.
    assert set_derivatives(running, [vr], [order], [0.0]) == OK
    assert running.log.messages == []
    t = running.fmu.getRealStatus(2)
    running.fmu.doStep(t, 1e-4)


def test_crank_jerk_beyond_its_window_is_refused_by_the_step(running):
    """A jerk (order 2 of crank.speed) is checked finite when set and against its window,
    |j| <= 1e12 rad/s^3, by fmi2DoStep: fmi2Error naming it, the instance unchanged; the
    next point's derivatives step on."""
    vr = running.vr
    t = running.fmu.getRealStatus(2)
    before = running.get("crank.angle", "crank.speed", "rod.deflection")
    assert set_derivatives(running, [vr["crank.speed"]], [2], [2e12]) == OK
    expect_error(running, lambda: running.fmu.doStep(t, 1e-4), "crank jerk", "1e12")
    assert running.get("crank.angle", "crank.speed", "rod.deflection") == before
    assert running.fmu.getRealStatus(2) == t
    assert set_derivatives(running, [vr["crank.speed"]], [2], [1e6]) == OK
    running.fmu.doStep(t, 1e-4)
    assert running.fmu.getRealStatus(2) == pytest.approx(t + 1e-4)


def test_crank_acceleration_from_angle_and_speed(running):
    vr = running.vr
    angle, speed = vr["crank.angle"], vr["crank.speed"]
    assert set_derivatives(running, [angle], [2], [900.0]) == OK
    assert set_derivatives(running, [speed, angle], [1, 2], [900.0, 900.0]) == OK
    assert set_derivatives(running, [angle], [1], [150.0]) == OK  # = crank.speed: not used
    assert set_derivatives(running, [angle], [1], [151.0]) == WARNING
    assert "differs from crank.speed" in running.log.text()
    # Both accelerations at one point, different: crank.speed's is used, with a warning, in
    # either order (also over two calls).
    assert set_derivatives(running, [speed, angle], [1, 2], [900.0, 800.0]) == WARNING
    assert "crank.speed's is used" in running.log.text()
    assert set_derivatives(running, [angle], [2], [700.0]) == WARNING
    assert "crank.speed = 900" in running.log.text()


def test_unsupported_functions(running):
    expect_error(
        running,
        lambda: running.fmu.getRealOutputDerivatives([running.vr["rod.deflection"]], [1]),
        "maxOutputDerivativeOrder",
    )
    # Status kinds the FMU cannot provide: fmi2Discard (FMI 2.0, 4.2.3), logged.
    for call, needle in [
        (lambda: running.fmu.getIntegerStatus(0), "fmi2GetIntegerStatus"),
        (lambda: running.fmu.getStringStatus(1), "fmi2GetStringStatus"),
        (lambda: running.fmu.getStatus(1), "fmi2PendingStatus"),
        (lambda: running.fmu.getRealStatus(0), "fmi2DoStepStatus"),
        (lambda: running.fmu.getBooleanStatus(2), "fmi2LastSuccessfulTime"),
    ]:
        text = expect_error(running, call, needle, "cannot provide", status=DISCARD)
        assert running.log.messages[-1][1] == "logStatusDiscard", text
    # Kind codes that are not an fmi2StatusKind: fmi2Error.
    expect_error(running, lambda: running.fmu.getStatus(7), "status kind 7")
    expect_error(running, lambda: running.fmu.getRealStatus(-1), "status kind -1")
    expect_error(running, lambda: running.fmu.setDebugLogging(True, ["logNonsense"]), "logNonsense")
    running.fmu.setDebugLogging(True, ["logEvents", "logStatusError"])
    assert running.fmu.getBooleanStatus(3) is False
    assert running.fmu.getStatus(0) == 0


def test_truncated_and_foreign_serialized_state(running):
    state = running.fmu.getFMUstate()
    blob = running.fmu.serializeFMUstate(state)
    expect_error(
        running, lambda: running.fmu.deSerializeFMUstate(blob[: len(blob) // 2]), "truncated"
    )
    expect_error(
        running, lambda: running.fmu.deSerializeFMUstate(b"not an FMU state at all"), "foreign"
    )
    expect_error(running, lambda: running.fmu.deSerializeFMUstate(blob + b"\0"), "checksum")
    # Any corrupted byte is rejected (a checksum covers the bytes): header, format version,
    # GUID, flags, the scene, the core's doubles, the checksum itself.
    for at in [
        0,
        8,
        14,
        len(blob) // 3,
        len(blob) // 2,
        len(blob) - 40,
        len(blob) - 5,
        len(blob) - 1,
    ]:
        corrupted = bytearray(blob)
        corrupted[at] ^= 0x01
        expect_error(running, lambda: running.fmu.deSerializeFMUstate(bytes(corrupted)), "rejected")
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


def test_null_arrays_with_zero_length(running):
    """NULL arrays are fine when their length is 0 (nothing to read or write)."""
    c = running.fmu.component
    p, n = ctypes.c_void_p, ctypes.c_size_t
    running.log.clear()
    for name in [
        "fmi2SetReal",
        "fmi2SetInteger",
        "fmi2SetBoolean",
        "fmi2SetString",
        "fmi2GetReal",
        "fmi2GetInteger",
        "fmi2GetBoolean",
        "fmi2GetString",
    ]:
        assert running.raw(name, p, p, n, p)(c, None, 0, None) == OK, name
    assert running.raw("fmi2SetRealInputDerivatives", p, p, n, p, p)(c, None, 0, None, None) == OK
    assert running.raw("fmi2SetDebugLogging", p, ctypes.c_int, n, p)(c, 1, 0, None) == OK
    assert running.raw("fmi2SetDebugLogging", p, ctypes.c_int, n, p)(c, 0, 0, None) == OK
    # With a length, NULL is an error naming the array.
    assert running.raw("fmi2SetReal", p, p, n, p)(c, None, 1, None) == ERROR
    assert running.raw("fmi2SetDebugLogging", p, ctypes.c_int, n, p)(c, 1, 2, None) == ERROR
    assert "categories[] is NULL" in running.log.text()
    assert (
        running.raw("fmi2SetRealInputDerivatives", p, p, n, p, p)(c, None, 3, None, None) == ERROR
    )
    assert "vr[] is NULL" in running.log.text()
    t = running.fmu.getRealStatus(2)
    running.fmu.doStep(t, 1e-4)


def test_logger_gets_environment_and_instance_name(unzipdir):
    s = Slave(unzipdir, name="rod-under-test", logging_on=True, environment=0xC0FFEE)
    s.init()
    expect_error(s, lambda: s.fmu.getReal([9999]), "9999")
    s.free()
    assert s.log.callers, "no messages"
    assert all(env == 0xC0FFEE for env, _ in s.log.callers), s.log.callers
    assert all(name == b"rod-under-test" for _, name in s.log.callers), s.log.callers


def test_instance_names(unzipdir):
    s = Slave(unzipdir)
    lib = s.fmu.dll
    instantiate = s.raw(
        "fmi2Instantiate",
        ctypes.c_char_p,
        ctypes.c_int,
        ctypes.c_char_p,
        ctypes.c_char_p,
        ctypes.c_void_p,
        ctypes.c_int,
        ctypes.c_int,
    )
    instantiate.restype = ctypes.c_void_p
    free_instance = lib["fmi2FreeInstance"]
    free_instance.argtypes = [ctypes.c_void_p]
    free_instance.restype = None
    location = Path(unzipdir, "resources").as_uri().encode()
    s.log.clear()
    c = instantiate(b"", 1, s.md.guid.encode(), location, ctypes.byref(s.log.callbacks), 0, 0)
    assert c is None
    assert "instanceName is empty" in s.log.text()
    # A name that is not UTF-8 is accepted (shown with replacement characters).
    s.log.clear()
    c = instantiate(
        b"caf\xe9", 1, s.md.guid.encode(), location, ctypes.byref(s.log.callbacks), 0, 1
    )
    assert c is not None, s.log.text()
    get_real = s.raw(
        "fmi2GetReal", ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p
    )
    assert get_real(c, (ctypes.c_uint * 1)(9999), 1, (ctypes.c_double * 1)()) == ERROR
    assert s.log.callers[-1][1] == "caf\ufffd".encode()
    free_instance(c)
    s.free()


def test_reset_restores_the_logging_of_instantiate(unzipdir):
    def events(s):
        s.log.clear()
        s.fmu.setupExperiment(tolerance=1e-6, startTime=0.0)
        return [m for m in s.log.messages if m[1] == "logEvents"]

    quiet = Slave(unzipdir, logging_on=False)
    assert events(quiet) == []
    quiet.fmu.reset()
    quiet.fmu.setDebugLogging(True, [])
    assert events(quiet) != []
    quiet.fmu.reset()
    assert events(quiet) == []
    quiet.free()

    loud = Slave(unzipdir, logging_on=True)
    loud.fmu.setDebugLogging(False, [])
    loud.fmu.reset()
    assert events(loud) != []
    loud.free()


def test_reentrant_call_from_the_logger_is_refused(running):
    """A logger that calls back into the instance it is logging for gets fmi2Error for that
    nested call (no aliasing of the running call's state), reported through the logger."""
    c = running.fmu.component
    get_real = running.raw(
        "fmi2GetReal", ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p
    )
    free_instance = running.fmu.dll["fmi2FreeInstance"]
    free_instance.argtypes = [ctypes.c_void_p]
    free_instance.restype = None
    nested, entered = [], []

    def hook(status, text):
        if entered:
            return  # the reports of the nested calls come back here too
        entered.append(True)
        value = (ctypes.c_double * 1)()
        nested.append(get_real(c, (ctypes.c_uint * 1)(running.vr["crank.speed"]), 1, value))
        free_instance(c)  # refused as well: the outer call still runs
        nested.append(value[0])

    running.log.hook = hook
    expect_error(
        running,
        lambda: running.fmu.getReal([9999]),
        "unknown value reference 9999",
        "illegal call while another call on this instance is in progress",
    )
    running.log.hook = None
    assert nested == [ERROR, 0.0]
    assert "fmi2GetReal: illegal call" in running.log.text()
    assert "fmi2FreeInstance: illegal call" in running.log.text()
    # The instance is intact and usable.
    assert running.get("crank.speed") == [150.0]
    t = running.fmu.getRealStatus(2)
    running.fmu.doStep(t, 1e-4)


def test_fmu_state_functions_work_in_the_error_state(unzipdir):
    """As in Reference-FMUs: after an error the importer can save, serialize and restore
    states; fmi2SetFMUstate with a state saved before brings the instance back."""
    s = Slave(unzipdir)
    s.init()
    run_loop(s, schedule(0.0, 0.001, 1e-4))
    good = s.fmu.getFMUstate()
    outputs = s.outputs()
    t = s.fmu.getRealStatus(2)
    s.fmu.reset()
    s.fmu.setupExperiment(startTime=0.0)
    s.set(crank__length=0.4)
    s.fmu.enterInitializationMode()
    expect_error(s, s.fmu.exitInitializationMode, "crank.length")
    expect_error(s, lambda: s.fmu.doStep(0.0, 1e-4), "Error")
    failed = s.fmu.getFMUstate()
    blob = s.fmu.serializeFMUstate(good)
    copy = s.fmu.deSerializeFMUstate(blob)
    s.fmu.freeFMUstate(failed)
    s.fmu.setFMUstate(copy)
    assert s.outputs() == outputs
    assert s.get("crank.length") == [0.1524]
    s.fmu.doStep(t, 1e-4)
    s.fmu.setFMUstate(good)
    s.fmu.doStep(t, 1e-4)
    s.fmu.freeFMUstate(copy)
    s.fmu.freeFMUstate(good)
    s.free()


def test_guid_mismatch_and_model_exchange(unzipdir):
    with pytest.raises(Exception, match="Failed to instantiate"):
        Slave(unzipdir, guid="{00000000-0000-0000-0000-000000000000}")
    s = Slave(unzipdir)
    lib = s.fmu.dll
    lib.fmi2Instantiate.restype = ctypes.c_void_p
    lib.fmi2Instantiate.argtypes = [
        ctypes.c_char_p,
        ctypes.c_int,
        ctypes.c_char_p,
        ctypes.c_char_p,
        ctypes.c_void_p,
        ctypes.c_int,
        ctypes.c_int,
    ]
    s.log.clear()
    c = lib.fmi2Instantiate(
        b"me", 0, s.md.guid.encode(), b"file:///nowhere", ctypes.byref(s.log.callbacks), 0, 0
    )
    assert c is None
    assert "fmuType = 0" in s.log.text()
    s.log.clear()
    c = lib.fmi2Instantiate(
        b"x", 1, b"{bad}", b"file:///nowhere", ctypes.byref(s.log.callbacks), 0, 0
    )
    assert c is None and "{bad}" in s.log.text()
    s.free()


def test_missing_or_foreign_resources(fmu_path, tmp_path, model):
    d = tmp_path / "fmu"
    extract(str(fmu_path), str(d))
    (d / "resources" / "scene.toml").unlink()
    if model == "ffr":
        # Without resources/scene.toml the compiled-in default scene serves (same GUID).
        s = Slave(d, logging_on=True)
        s.init()
        s.fmu.doStep(0.0, 1e-4)
        s.free()
    else:
        # Another scene's FMU cannot fall back on the default scene: its GUID differs.
        with pytest.raises(Exception, match="Failed to instantiate"):
            Slave(d)
    # A different scene under the same description: GUID mismatch, instantiation fails.
    scene = (ROOT / "scenes" / "benchmark.toml").read_text()
    (d / "resources" / "scene.toml").write_text(scene.replace("length = 0.3048", "length = 0.31"))
    with pytest.raises(Exception, match="Failed to instantiate"):
        Slave(d)


def test_discard_keeps_the_state(fmu_path, tmp_path):
    """A step the solver cannot complete returns fmi2Discard with the reason; the state from
    before the step is kept and can be restored and retried with a smaller step."""
    text = (ROOT / "scenes" / "benchmark.toml").read_text()
    # Newton can never meet a tolerance of 1e-300 in one iteration, and no halving is allowed:
    # every step fails.
    text = text.replace(
        "rho_inf = 0.8",
        "rho_inf = 0.8\nnewton_tolerance = 1e-300\nmax_newton_iterations = 1\nmax_halvings = 0",
    )
    # The implicit integrator (its Newton iteration is what fails here).
    text = text.replace('method = "auto"', 'method = "generalized_alpha"')
    text = text.replace('name = "FlexibleSliderCrank"', 'name = "StiffSliderCrank"')
    scene = tmp_path / "stiff.toml"
    scene.write_text(text)
    fmu = build_fmu(tmp_path, scene)
    d = extract(str(fmu), str(tmp_path / "x"))
    s = Slave(d)
    try:
        s.init()
        state = s.fmu.getFMUstate()
        before = s.outputs()
        text = expect_error(
            s,
            lambda: s.fmu.doStep(0.0, 1e-3),
            "failed",
            "smaller communication step",
            status=DISCARD,
        )
        assert s.log.messages[-1][1] == "logStatusDiscard", text
        assert s.fmu.getStatus(0) == DISCARD
        assert s.fmu.getRealStatus(2) == 0.0
        assert s.outputs() == before
        expect_error(s, lambda: s.fmu.doStep(0.0, 1e-3), "StepFailed")
        s.fmu.setFMUstate(state)
        assert s.fmu.getStatus(0) == 0
        s.fmu.terminate()
    finally:
        s.free()
