"""The FMI 3.0 Co-Simulation FMU: written by the packager beside the FMI 2.0 one from
the same scene and the same library. fmpy validates it; fmpy simulates it to the FMI 2.0 FMU's
results within 1e-12 of peak (both rod models); FMU states and their serialization are bit
exact; the crank acceleration is the input `crank.acceleration`; the arrays `rod.shape` and
`rod.frequency`; and the bad inputs of test_errors.py / test_messages.py through the FMI 3.0
API: fmi3Error with a message naming the problem, the instance unchanged."""

import ctypes
import math

import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu
from helpers import DT, OUTPUTS, STOP, Slave, crank_input, run_loop, schedule

OK, WARNING, DISCARD, ERROR = 0, 1, 2, 3
LEAKS = ("Some(", "None")


@pytest.fixture(scope="session")
def fmu3_path(fmu_path):
    """The FMI 3.0 FMU the packager wrote beside the FMI 2.0 one (`<name>-fmi3.fmu`)."""
    path = fmu_path.with_name(fmu_path.stem + "-fmi3.fmu")
    assert path.is_file(), f"{path} was not written by the packager"
    return path


@pytest.fixture(scope="session")
def unzipdir3(fmu3_path, tmp_path_factory):
    return extract(str(fmu3_path), str(tmp_path_factory.mktemp("unzipped3")))


class Slave3:
    """One FMU instance driven through fmpy's FMU3Slave, with a capturing logger."""

    def __init__(self, unzipdir, name="instance", logging_on=False, token=None):
        self.md = read_model_description(str(unzipdir))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.size = {
            v.name: (int(v.dimensions[0].start) if v.dimensions else 1)
            for v in self.md.modelVariables
        }
        self.messages = []
        self.hook = None

        def log(env, status, category, message):
            text = message.decode("utf-8", "replace")
            self.messages.append((status, category.decode(), text))
            if self.hook is not None:
                self.hook(status, text)

        self.fmu = FMU3Slave(
            guid=token or self.md.guid,
            unzipDirectory=str(unzipdir),
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName=name,
        )
        self.fmu.instantiate(loggingOn=logging_on, logMessage=log)
        self.c = self.fmu.component

    def text(self):
        return "\n".join(m for _, _, m in self.messages)

    def get(self, *names):
        return self.fmu.getFloat64([self.vr[n] for n in names])

    def array(self, name):
        return self.fmu.getFloat64([self.vr[name]], nValues=self.size[name])

    def set(self, **values):
        names = [n.replace("__", ".") for n in values]
        self.fmu.setFloat64([self.vr[n] for n in names], list(values.values()))

    def init(self, start=0.0, stop=None, angle=0.0, speed=150.0, accel=None, params=None):
        self.fmu.enterInitializationMode(startTime=start, stopTime=stop)
        if params:
            for name, value in params.items():
                self.fmu.setFloat64([self.vr[name]], [value])
        self.set(crank__angle=angle, crank__speed=speed)
        if accel is not None:
            self.set(crank__acceleration=accel)
        self.fmu.exitInitializationMode()

    def outputs(self):
        return self.get(*OUTPUTS)

    def step(self, t, h):
        return self.fmu.doStep(t, h)

    def raw(self, name, restype, *argtypes):
        f = self.fmu.dll[name]
        f.argtypes = list(argtypes)
        f.restype = restype
        return f

    def free(self):
        self.fmu.freeInstance()


def expect_error(slave, call, *needles, status=ERROR):
    slave.messages.clear()
    with pytest.raises(FMICallException) as e:
        call()
    assert e.value.status == status
    text = slave.text()
    for needle in needles:
        assert needle in text, f"{needle!r} not in {text!r}"
    return text


def loop3(slave, times, accel=0.0, between=None):
    """As helpers.run_loop for FMI 3.0: the crank law's inputs at every point (the acceleration
    as the input crank.acceleration), step; outputs per point."""
    out = [slave.outputs()]
    for k in range(len(times) - 1):
        t, h = times[k], times[k + 1] - times[k]
        angle, speed = crank_input(t, 0.0, 150.0, accel)
        slave.set(crank__angle=angle, crank__speed=speed, crank__acceleration=accel)
        slave.step(t, h)
        if between is not None:
            between(k)
        out.append(slave.outputs())
    return np.array(out)


@pytest.fixture
def slave3(unzipdir3):
    s = Slave3(unzipdir3)
    yield s
    s.free()


@pytest.fixture
def running3(slave3):
    slave3.init()
    loop3(slave3, schedule(0.0, 0.001, 1e-4))
    return slave3


def peak_error(a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return np.max(np.abs(a - b)) / max(np.max(np.abs(a)), 1e-300)


# --- the description and validation ----------------------------------------------------------


def test_fmpy_validate_passes(fmu3_path):
    assert validate_fmu(str(fmu3_path)) == []


def test_description(fmu3_path, fmu_path):
    md3 = read_model_description(str(fmu3_path))
    md2 = read_model_description(str(fmu_path))
    assert md3.fmiVersion == "3.0" and md2.fmiVersion == "2.0"
    assert md3.guid.startswith("{") and md3.guid != md2.guid  # instantiationToken
    assert md3.coSimulation.modelIdentifier == md2.coSimulation.modelIdentifier
    v3 = {v.name: v for v in md3.modelVariables}
    v2 = {v.name: v for v in md2.modelVariables}
    # Every FMI 2.0 variable is there under its name and value reference, except the
    # frequencies, which are one array; the FMI 3.0 additions use value references 150..199.
    for name, v in v2.items():
        if name.startswith("rod.frequency["):
            continue
        assert v3[name].valueReference == v.valueReference, name
        assert v3[name].causality == v.causality, name
    assert v3["time"].causality == "independent" and v3["time"].valueReference == 150
    acc = v3["crank.acceleration"]
    assert (acc.causality, acc.type, acc.unit, acc.valueReference) == (
        "input",
        "Float64",
        "rad/s2",
        151,
    )
    shape = v3["rod.shape"]
    assert (shape.causality, shape.type, shape.unit) == ("output", "Float64", "m")
    assert [int(d.start) for d in shape.dimensions] == [11]
    freq = v3["rod.frequency"]
    k = sum(1 for n in v2 if n.startswith("rod.frequency["))
    assert freq.causality == "calculatedParameter" and [int(d.start) for d in freq.dimensions] == [
        k
    ]
    assert v3["rod.model"].type == "Enumeration" and v3["rod.model_index"].type == "Int32"
    assert v3["rod.elements"].type == "Int32"
    jerk = v3["crank.jerk"]
    assert (jerk.causality, jerk.type, jerk.unit, jerk.valueReference) == (
        "input",
        "Float64",
        "rad/s3",
        154,
    )
    for name in ["crank.acceleration", "crank.jerk", "rod.shape", "rod.frequency", "time"]:
        assert 150 <= v3[name].valueReference <= 199, name
    assert md3.coSimulation.canGetAndSetFMUstate and md3.coSimulation.canSerializeFMUstate


# --- FMI 3.0 gives the FMI 2.0 results -------------------------------------------------------


@pytest.mark.parametrize("values", [{}, {"rod.model": 2}])
def test_simulate_fmi3_equals_fmi2(fmu_path, fmu3_path, values):
    """fmpy.simulate_fmu of both FMUs: the outputs agree to 1e-12 of their peak (in fact bit
    for bit: the same instance code runs both), for the scene's rod and with rod.model set."""
    kwargs = dict(
        start_values=values, step_size=DT, output_interval=DT, stop_time=STOP, output=OUTPUTS
    )
    r2 = simulate_fmu(str(fmu_path), **kwargs)
    r3 = simulate_fmu(str(fmu3_path), **kwargs)
    assert len(r2) == len(r3) == round(STOP / DT) + 1
    np.testing.assert_array_equal(r2["time"], r3["time"])
    for name in OUTPUTS:
        assert peak_error(r2[name], r3[name]) <= 1e-12, name
        np.testing.assert_array_equal(r2[name], r3[name], err_msg=name)
    assert np.max(np.abs(r3["rod.deflection"])) > 0


def test_crank_acceleration_input_gives_the_input_derivative_results(unzipdir, unzipdir3):
    """FMI 2.0 gets the crank acceleration as the order-1 derivative of crank.speed at every
    point; FMI 3.0 as the input crank.acceleration: the same law, the same results."""
    accel = 2000.0
    times = schedule(0.0, 0.004, 2.5e-4)
    s2 = Slave(unzipdir)
    s2.init(accel=accel)
    out2 = run_loop(s2, times, accel=accel)
    s2.free()
    s3 = Slave3(unzipdir3)
    s3.init(accel=accel)
    out3 = loop3(s3, times, accel=accel)
    # The input keeps its value: after the steps the law's speed grew by accel * t.
    assert s3.get("crank.acceleration") == [accel]
    assert math.isclose(s3.get("crank.speed")[0], 150.0 + accel * times[-1], rel_tol=1e-12)
    s3.free()
    for j, name in enumerate(OUTPUTS):
        assert peak_error(out2[:, j], out3[:, j]) <= 1e-12, name


def test_crank_jerk_input_gives_the_input_derivative_results(unzipdir, unzipdir3):
    """FMI 2.0 gets the crank jerk as the order-2 derivative of crank.speed at every point;
    FMI 3.0 as the input crank.jerk, set once (it holds): the same cubic laws, the same results
    bit for bit, and the laws' speed read back after the steps."""
    accel, jerk, h, n = 1500.0, -2.0e6, 1e-4, 8
    s2 = Slave(unzipdir)
    s2.init(accel=accel)
    rows2 = []
    for k in range(n):
        if k > 0:
            s2.fmu.setRealInputDerivatives([s2.vr["crank.speed"]], [1], [accel])
        s2.fmu.setRealInputDerivatives([s2.vr["crank.speed"]], [2], [jerk])
        s2.fmu.doStep(k * h, h)
        rows2.append(s2.outputs())
    speed2 = s2.get("crank.speed")[0]
    s2.free()
    s3 = Slave3(unzipdir3)
    s3.init(accel=accel)
    s3.set(crank__jerk=jerk)
    rows3 = []
    for k in range(n):
        s3.step(k * h, h)
        rows3.append(s3.outputs())
    assert s3.get("crank.jerk") == [jerk]
    speed3 = s3.get("crank.speed")[0]
    s3.free()
    assert np.array_equal(np.array(rows2), np.array(rows3))
    t = n * h
    assert speed2 == speed3
    # Every step starts at the acceleration set, its jerk adding j h^2 / 2 to the speed.
    assert math.isclose(speed3, 150.0 + accel * t + n * 0.5 * jerk * h * h, rel_tol=1e-12)


def test_crank_jerk_input_beyond_its_window_is_refused(unzipdir3):
    """crank.jerk past |j| <= 1e12 rad/s^3: fmi3Error at the set call naming it, nothing set."""
    s = Slave3(unzipdir3)
    s.init()
    expect_error(s, lambda: s.set(crank__jerk=2e12), "crank.jerk", "1e12")
    assert s.get("crank.jerk") == [0.0]
    s.step(0.0, 1e-4)
    s.free()


def test_acceleration_input_holds_between_points(unzipdir3):
    """Set once, crank.acceleration holds over later steps (an FMI 2.0 input derivative would
    be reset to 0 at the next point): the angle and speed follow theta0 + w0 t + a t^2/2."""
    s = Slave3(unzipdir3)
    s.init(accel=1000.0)
    t = 0.0
    for _ in range(4):
        s.step(t, 1e-4)
        t += 1e-4
    angle, speed = s.get("crank.angle", "crank.speed")
    assert math.isclose(speed, 150.0 + 1000.0 * t, rel_tol=1e-12)
    assert math.isclose(angle, 150.0 * t + 0.5 * 1000.0 * t * t, rel_tol=1e-9)
    s.free()


# --- arrays --------------------------------------------------------------------------------


def test_shape_and_frequency_arrays(running3, unzipdir):
    s = running3
    shape = s.array("rod.shape")
    assert len(shape) == 11
    assert shape[0] == 0.0 and shape[-1] == 0.0
    # The middle point is the material midpoint: rod.deflection.
    assert shape[5] == s.get("rod.deflection")[0]
    assert np.max(np.abs(shape)) > 0
    # Neighbours of the midpoint deflect the same way, less than twice as far (a smooth,
    # first-mode-like shape after 1 ms).
    assert np.sign(shape[4]) == np.sign(shape[5]) == np.sign(shape[6])
    # Mixed with scalars in one call: the values follow one another.
    mixed = s.fmu.getFloat64(
        [s.vr["crank.speed"], s.vr["rod.shape"], s.vr["rod.deflection"]], nValues=13
    )
    assert mixed[0] == 150.0 and mixed[1:12] == shape and mixed[12] == shape[5]
    # The frequencies are those of the FMI 2.0 FMU, in one array.
    freq = s.array("rod.frequency")
    s2 = Slave(unzipdir)
    s2.init()
    k = len(freq)
    assert freq == s2.get(*[f"rod.frequency[{i}]" for i in range(1, k + 1)])
    assert all(a < b for a, b in zip(freq, freq[1:]))
    s2.free()


def test_wrong_number_of_values(running3):
    s = running3
    expect_error(
        s,
        lambda: s.fmu.getFloat64([s.vr["rod.shape"]], nValues=1),
        "nValues = 1",
        "allowed nValues = 11",
    )
    expect_error(s, lambda: s.fmu.setFloat64([s.vr["crank.speed"]], [1.0, 2.0]), "nValues = 2")
    assert s.get("crank.speed") == [150.0]


# --- FMU states -----------------------------------------------------------------------------


def test_state_save_restore_and_serialization_bit_exact(unzipdir3):
    s = Slave3(unzipdir3)
    s.init(accel=500.0)
    times = schedule(0.0, 0.002, 1e-4)
    loop3(s, times[:11], accel=500.0)
    state = s.fmu.getFMUState()
    blob = s.fmu.serializeFMUState(state)
    rest = [t for t in times[10:]]
    first = loop3(s, rest, accel=500.0)
    shape_first = s.array("rod.shape")
    s.fmu.setFMUState(state)
    again = loop3(s, rest, accel=500.0)
    np.testing.assert_array_equal(first, again)
    assert s.array("rod.shape") == shape_first
    # Deserialized into another instance: the same bits again.
    other = Slave3(unzipdir3, name="other")
    copy = other.fmu.deserializeFMUState(blob)
    other.fmu.setFMUState(copy)
    third = loop3(other, rest, accel=500.0)
    np.testing.assert_array_equal(first, third)
    assert other.fmu.serializeFMUState(other.fmu.getFMUState())[:8] == b"FLXRFMI2"
    other.fmu.freeFMUState(copy)
    other.free()
    s.fmu.freeFMUState(state)
    s.free()


def test_fmi2_state_bytes_are_refused(unzipdir, running3):
    s2 = Slave(unzipdir)
    s2.init()
    blob = s2.fmu.serializeFMUstate(s2.fmu.getFMUstate())
    s2.free()
    text = expect_error(
        running3,
        lambda: running3.fmu.deserializeFMUState(blob),
        "fmi3DeserializeFMUState",
        "instantiationToken",
    )
    # FMI 3.0 messages name FMI 3.0 functions and terms only.
    assert "fmi2" not in text and "GUID" not in text, text


def test_truncated_and_foreign_serialized_state(running3):
    s = running3
    blob = s.fmu.serializeFMUState(s.fmu.getFMUState())
    expect_error(s, lambda: s.fmu.deserializeFMUState(blob[: len(blob) // 2]), "truncated")
    expect_error(s, lambda: s.fmu.deserializeFMUState(b"not an FMU state at all"), "foreign")
    corrupted = bytearray(blob)
    corrupted[len(blob) // 2] ^= 1
    expect_error(s, lambda: s.fmu.deserializeFMUState(bytes(corrupted)), "rejected")
    expect_error(s, lambda: s.fmu.setFMUState(ctypes.c_void_p(12345678)), "not a state")
    s.step(s.get("time")[0], 1e-4)


# --- bad inputs through the FMI 3.0 API (as test_errors.py) ---------------------------------


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_input_rejected_instance_unchanged(running3, bad):
    s = running3
    before = s.get("crank.speed", "rod.deflection")
    expect_error(s, lambda: s.set(crank__speed=bad), "fmi3SetFloat64", "crank.speed", "finite")
    expect_error(s, lambda: s.set(crank__angle=1.0, crank__acceleration=bad), "crank.acceleration")
    assert s.get("crank.speed", "rod.deflection") == before
    s.step(s.get("time")[0], 1e-4)


def test_unknown_value_reference_and_wrong_type(running3):
    s = running3
    expect_error(s, lambda: s.fmu.getFloat64([9999]), "unknown value reference 9999")
    expect_error(s, lambda: s.fmu.setFloat64([9999], [1.0]), "9999")
    expect_error(s, lambda: s.fmu.getInt32([9999]), "9999")
    expect_error(s, lambda: s.fmu.getBoolean([1]), "fmi3GetBoolean", "1")
    expect_error(s, lambda: s.fmu.getFloat32([1]), "fmi3GetFloat32", "Float32")
    expect_error(s, lambda: s.fmu.getInt32([s.vr["rod.length"]]), "fmi3GetFloat64")
    # FMI 3.0 reads Enumerations with fmi3GetInt64; their Int32 twins with fmi3GetInt32.
    expect_error(s, lambda: s.fmu.getInt32([s.vr["rod.model"]]), "fmi3GetInt64")
    assert s.fmu.getInt64([s.vr["rod.model"], s.vr["rod.reference"]]) == s.fmu.getInt32(
        [s.vr["rod.model_index"], s.vr["rod.reference_index"]]
    )
    assert s.get("crank.speed") == [150.0]


def test_parameters_and_enumerations(slave3):
    s = slave3
    expect_error(
        s,
        lambda: s.fmu.setInt64([s.vr["rod.model"]], [7]),
        "rod.model = 7",
        "1 (ffr), 2 (segments)",
    )
    expect_error(s, lambda: s.fmu.setInt64([s.vr["rod.model"]], [2**40]), "32-bit")
    for bad in [-2, 0, 4097]:
        expect_error(
            s,
            lambda: s.fmu.setInt32([s.vr["rod.elements"]], [bad]),
            f"rod.elements = {bad}",
            "..=128",
            "declared range",
        )
    expect_error(s, lambda: s.set(rod__length=math.nan), "rod.length", "finite")
    s.fmu.enterInitializationMode(startTime=0.0)
    s.fmu.setInt64([s.vr["rod.model"]], [2])
    assert s.fmu.getInt32([s.vr["rod.model_index"]]) == [2]
    s.fmu.setInt32([s.vr["rod.model_index"]], [1])
    assert s.fmu.getInt64([s.vr["rod.model"]]) == [1]
    s.fmu.exitInitializationMode()
    expect_error(s, lambda: s.set(rod__length=0.4), "rod.length", "fixed parameter")
    expect_error(s, lambda: s.set(rod__deflection=0.0), "rod.deflection", "output")
    expect_error(
        s,
        lambda: s.fmu.setFloat64([s.vr["rod.frequency"]], [1.0] * s.size["rod.frequency"]),
        "rod.frequency",
        "calculatedParameter",
    )
    expect_error(s, lambda: s.set(time=1.0), "time", "independent")
    assert s.get("rod.length") == [0.3048]


def test_wrong_call_order(slave3):
    s = slave3
    expect_error(s, lambda: s.step(0.0, 1e-4), "fmi3DoStep", "Instantiated", "StepComplete")
    expect_error(s, s.fmu.exitInitializationMode, "fmi3ExitInitializationMode")
    # FMI 3.0 allows reading in Instantiated: parameters and inputs, not yet outputs.
    assert s.get("rod.length", "crank.speed") == [0.3048, 150.0]
    expect_error(s, lambda: s.get("rod.deflection"), "fmi3GetFloat64", "not initialized")
    expect_error(s, s.fmu.terminate, "fmi3Terminate")
    s.init()
    expect_error(s, lambda: s.fmu.enterInitializationMode(), "fmi3EnterInitializationMode")
    s.step(0.0, 1e-4)


@pytest.mark.parametrize("h", [0.0, -1e-4, math.nan, math.inf])
def test_bad_step_size(running3, h):
    s = running3
    t = s.get("time")[0]
    before = s.outputs()
    expect_error(s, lambda: s.step(t, h), "communicationStepSize", "allowed")
    assert s.outputs() == before
    s.step(t, 1e-4)


def test_time_mismatch_and_stop_time(slave3):
    s = slave3
    s.init(stop=0.001)
    expect_error(s, lambda: s.step(1e-3, 1e-4), "does not match the FMU time")
    expect_error(s, lambda: s.step(0.0, 0.002), "stopTime")
    _, _, _, last = s.step(0.0, 0.0005)
    assert last == 0.0005 == s.get("time")[0]


def test_crank_longer_than_rod_fails_initialization_then_reset(slave3):
    s = slave3
    s.fmu.enterInitializationMode(startTime=0.0)
    s.set(crank__length=0.4)
    expect_error(s, s.fmu.exitInitializationMode, "crank.length = 0.4", "rod.length = 0.3048")
    expect_error(s, lambda: s.get("rod.deflection"), "not available", "crank.length")
    expect_error(s, lambda: s.array("rod.shape"), "not available")
    expect_error(s, lambda: s.step(0.0, 1e-4), "fmi3DoStep", "Error")
    s.fmu.reset()
    s.init()
    s.step(0.0, 1e-4)


def test_unsupported_functions(running3):
    s = running3
    p, n = ctypes.c_void_p, ctypes.c_size_t
    for name in [
        "fmi3EnterEventMode",
        "fmi3EnterStepMode",
        "fmi3EnterConfigurationMode",
        "fmi3EvaluateDiscreteStates",
        "fmi3EnterContinuousTimeMode",
    ]:
        s.messages.clear()
        assert s.raw(name, ctypes.c_int, p)(s.c) == ERROR, name
        assert f"{name}: not provided" in s.text(), s.text()
    s.messages.clear()
    assert (
        s.raw("fmi3GetOutputDerivatives", ctypes.c_int, p, p, n, p, p, n)(
            s.c, None, 0, None, None, 0
        )
        == ERROR
    )
    assert "maxOutputDerivativeOrder" in s.text()
    s.messages.clear()
    assert (
        s.raw("fmi3GetDirectionalDerivative", ctypes.c_int, p, p, n, p, n, p, n, p, n)(
            s.c, None, 0, None, 0, None, 0, None, 0
        )
        == ERROR
    )
    expect_error(s, lambda: s.fmu.setDebugLogging(True, ["logNonsense"]), "logNonsense")
    s.fmu.setDebugLogging(True, ["logEvents"])
    s.step(s.get("time")[0], 1e-4)


def test_null_pointers_and_null_instance(running3):
    s = running3
    p, n, d = ctypes.c_void_p, ctypes.c_size_t, ctypes.c_double
    get = s.raw("fmi3GetFloat64", ctypes.c_int, p, p, n, p, n)
    s.messages.clear()
    assert get(s.c, None, 2, None, 2) == ERROR
    assert "valueReferences[] is NULL" in s.text()
    assert get(s.c, None, 0, None, 0) == OK
    step = s.raw("fmi3DoStep", ctypes.c_int, p, d, d, ctypes.c_bool, p, p, p, p)
    assert step(None, 0.0, 1e-4, True, None, None, None, None) == ERROR
    t = s.get("time")[0]
    s.messages.clear()
    assert step(s.c, t, 1e-4, True, None, None, None, None) == ERROR
    assert "eventHandlingNeeded is NULL" in s.text()
    assert s.get("time") == [t]
    assert s.raw("fmi3GetFMUState", ctypes.c_int, p, p)(s.c, None) == ERROR
    s.raw("fmi3FreeInstance", None, p)(None)
    s.step(t, 1e-4)


def test_instantiation_token_and_other_interfaces(unzipdir3):
    with pytest.raises(Exception):
        Slave3(unzipdir3, token="{00000000-0000-0000-0000-000000000000}")
    s = Slave3(unzipdir3)
    p, b = ctypes.c_void_p, ctypes.c_bool
    me = s.raw(
        "fmi3InstantiateModelExchange",
        ctypes.c_void_p,
        ctypes.c_char_p,
        ctypes.c_char_p,
        ctypes.c_char_p,
        b,
        b,
        p,
        p,
    )
    assert me(b"me", s.md.guid.encode(), b"/nowhere/", False, False, None, None) is None
    cs = s.raw(
        "fmi3InstantiateCoSimulation",
        ctypes.c_void_p,
        ctypes.c_char_p,
        ctypes.c_char_p,
        ctypes.c_char_p,
        b,
        b,
        b,
        b,
        p,
        ctypes.c_size_t,
        p,
        p,
        p,
    )
    # Event mode is not offered: refused.
    assert (
        cs(
            b"x",
            s.md.guid.encode(),
            b"/nowhere/",
            False,
            False,
            True,
            False,
            None,
            0,
            None,
            None,
            None,
        )
        is None
    )
    # A wrong token with the default scene's fallback: refused too.
    assert (
        cs(b"x", b"{bad}", b"/nowhere/", False, False, False, False, None, 0, None, None, None)
        is None
    )
    s.free()


def test_reentrant_call_from_the_logger_is_refused(running3):
    s = running3
    get = s.raw(
        "fmi3GetFloat64",
        ctypes.c_int,
        ctypes.c_void_p,
        ctypes.c_void_p,
        ctypes.c_size_t,
        ctypes.c_void_p,
        ctypes.c_size_t,
    )
    nested, entered = [], []

    def hook(status, text):
        if entered:
            return  # the report of the nested call comes back here too
        entered.append(True)
        value = (ctypes.c_double * 1)()
        nested.append(get(s.c, (ctypes.c_uint * 1)(s.vr["crank.speed"]), 1, value, 1))

    s.hook = hook
    expect_error(
        s,
        lambda: s.fmu.getFloat64([9999]),
        "unknown value reference 9999",
        "fmi3GetFloat64: illegal call while another call",
    )
    s.hook = None
    assert nested == [ERROR]
    assert s.get("crank.speed") == [150.0]


def test_messages_read_as_text(fmu3_path, unzipdir3):
    """As test_messages.py: no Rust debug formatting leaks into the FMI 3.0 messages."""
    messages = []

    def logger(env, status, category, message):
        messages.append(message.decode("utf-8", "replace"))

    simulate_fmu(
        str(fmu3_path),
        step_size=DT,
        output_interval=DT,
        stop_time=STOP,
        debug_logging=True,
        logger=logger,
        output=["rod.deflection"],
    )
    assert any("initialized at t = 0" in m for m in messages), messages
    s = Slave3(unzipdir3, logging_on=True)
    for call in [
        lambda: s.get("rod.deflection"),
        lambda: s.fmu.setFloat64([9999], [1.0]),
        lambda: s.fmu.setInt32([s.vr["rod.model_index"]], [7]),
    ]:
        with pytest.raises(FMICallException):
            call()
    s.init(stop=0.001)
    for call in [lambda: s.step(0.0, 0.002), lambda: s.step(0.1, 1e-4)]:
        with pytest.raises(FMICallException):
            call()
    s.free()
    for text in messages + [m for _, _, m in s.messages]:
        for leak in LEAKS:
            assert leak not in text, f"{leak!r} in {text!r}"


def test_discard_keeps_the_state(tmp_path):
    """As test_errors.py: a step the solver cannot complete returns fmi3Discard with the reason;
    lastSuccessfulTime is the time before the step, whose state is kept and can be restored."""
    from helpers import ROOT, build_fmu

    text = (ROOT / "scenes" / "benchmark.toml").read_text()
    text = text.replace(
        "rho_inf = 0.8",
        "rho_inf = 0.8\nnewton_tolerance = 1e-300\nmax_newton_iterations = 1\nmax_halvings = 0",
    )
    text = text.replace('method = "auto"', 'method = "generalized_alpha"')
    text = text.replace('name = "FlexibleSliderCrank"', 'name = "StiffSliderCrank"')
    scene = tmp_path / "stiff.toml"
    scene.write_text(text)
    fmu2 = build_fmu(tmp_path, scene)
    d = extract(str(fmu2.with_name(fmu2.stem + "-fmi3.fmu")), str(tmp_path / "x"))
    s = Slave3(d)
    try:
        s.init()
        state = s.fmu.getFMUState()
        before = s.outputs()
        p, dbl, b = ctypes.c_void_p, ctypes.c_double, ctypes.c_bool
        step = s.raw("fmi3DoStep", ctypes.c_int, p, dbl, dbl, b, p, p, p, p)
        flags = [ctypes.c_bool(True) for _ in range(3)]
        last = ctypes.c_double(-1.0)
        s.messages.clear()
        status = step(s.c, 0.0, 1e-3, True, *[ctypes.byref(f) for f in flags], ctypes.byref(last))
        assert status == DISCARD
        assert "smaller communication step" in s.text()
        assert "fmi3DoStep" in s.text() and "fmi3SetFMUState" in s.text(), s.text()
        assert "fmi2" not in s.text(), s.text()
        assert s.messages[-1][1] == "logStatusDiscard"
        assert last.value == 0.0 and [f.value for f in flags] == [False] * 3
        assert s.outputs() == before
        expect_error(s, lambda: s.step(0.0, 1e-3), "StepFailed")
        s.fmu.setFMUState(state)
        s.fmu.terminate()
    finally:
        s.free()


def test_logger_gets_the_instance_environment(unzipdir3):
    """The FMI 3.0 logger callback receives the instanceEnvironment given at instantiation, and
    messages are plain text (FMI 3.0's callback is not a printf format: no '%%' escaping)."""
    s = Slave3(unzipdir3)
    seen = []

    def log(env, status, category, message):
        seen.append((env, message.decode()))

    callback = ctypes.CFUNCTYPE(
        None, ctypes.c_void_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p
    )(log)
    p, b = ctypes.c_void_p, ctypes.c_bool
    cs = s.raw(
        "fmi3InstantiateCoSimulation",
        ctypes.c_void_p,
        ctypes.c_char_p,
        ctypes.c_char_p,
        ctypes.c_char_p,
        b,
        b,
        b,
        b,
        p,
        ctypes.c_size_t,
        p,
        p,
        p,
    )
    resources = (str(unzipdir3) + "/resources/").encode()
    c = cs(
        b"env-test",
        s.md.guid.encode(),
        resources,
        False,
        True,
        False,
        False,
        None,
        0,
        0xC0FFEE,
        callback,
        None,
    )
    assert c
    set_debug = s.raw("fmi3SetDebugLogging", ctypes.c_int, p, b, ctypes.c_size_t, p)
    categories = (ctypes.c_char_p * 1)(b"log%Nonsense")
    assert set_debug(c, True, 1, categories) == ERROR
    s.raw("fmi3FreeInstance", None, p)(c)
    s.free()
    assert seen and all(env == 0xC0FFEE for env, _ in seen), seen
    assert any("log%Nonsense" in m and "%%" not in m for _, m in seen), seen
