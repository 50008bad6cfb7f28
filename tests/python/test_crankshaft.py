"""The crankshaft FMU (scenes/crankshaft.toml): a second model exported by the same FMI shell
and packager as the rod, driven through FMPy with the rod's lifecycle and state tests: the
description validates, simulation matches the closed form, instances are independent, saved
and serialized states continue bit for bit (in another instance and another process), foreign
and corrupted states are refused, bad inputs leave the instance usable, reset restores the
start values; it turns the rod's FMU in the engine's loop, and runs in libcosim too."""

import json
import math
import subprocess
import sys

import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu
from helpers import ROOT, LogCapture, build_fmu

SCENE = ROOT / "scenes" / "crankshaft.toml"
J, C, W0 = 0.25, 0.01, 628.3


@pytest.fixture(scope="module")
def crankshaft_fmu(tmp_path_factory):
    return build_fmu(tmp_path_factory.mktemp("crankshaft"), SCENE)


@pytest.fixture(scope="module")
def crankshaft_fmu3(crankshaft_fmu):
    path = crankshaft_fmu.with_name(crankshaft_fmu.stem + "-fmi3.fmu")
    assert path.is_file()
    return path


@pytest.fixture(scope="module")
def cs_dir(crankshaft_fmu, tmp_path_factory):
    return extract(str(crankshaft_fmu), str(tmp_path_factory.mktemp("crankshaft_unzipped")))


def closed_form(t, torque):
    """w(t) = T/c + (w0 - T/c) e^(-c t / J) and its integral, for a constant net torque T."""
    tau, w_inf = J / C, torque / C
    decay = np.exp(-t / tau)
    return w_inf * t + (W0 - w_inf) * tau * (1 - decay), w_inf + (W0 - w_inf) * decay


class Crank:
    """One crankshaft instance through FMPy's FMU2Slave."""

    def __init__(self, unzipdir, name="crankshaft"):
        self.md = read_model_description(str(unzipdir))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.log = LogCapture()
        self.fmu = FMU2Slave(
            guid=self.md.guid,
            unzipDirectory=str(unzipdir),
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName=name,
        )
        self.fmu.instantiate(callbacks=self.log.callbacks)

    def init(self, drive=0.0, load=0.0, params=None):
        self.fmu.setupExperiment(startTime=0.0)
        for name, value in (params or {}).items():
            self.fmu.setReal([self.vr[name]], [value])
        self.fmu.enterInitializationMode()
        self.set(drive=drive, load=load)
        self.fmu.exitInitializationMode()

    def set(self, drive, load):
        self.fmu.setReal([self.vr["drive.torque"], self.vr["load.torque"]], [drive, load])

    def outputs(self):
        names = ["crank.angle", "crank.speed", "crank.acceleration"]
        return self.fmu.getReal([self.vr[n] for n in names])

    def run(self, t0, n, h=1e-4, torque=lambda t: (50.0, 20.0 + 10.0 * math.sin(300 * t))):
        rows = []
        for k in range(n):
            t = t0 + k * h
            self.set(*torque(t))
            self.fmu.doStep(t, h)
            rows.append(self.outputs())
        return np.array(rows)


def test_fmpy_validates_both_descriptions(crankshaft_fmu, crankshaft_fmu3):
    assert validate_fmu(str(crankshaft_fmu)) == []
    assert validate_fmu(str(crankshaft_fmu3)) == []
    md = read_model_description(str(crankshaft_fmu))
    names = {v.name for v in md.modelVariables}
    assert {"drive.torque", "load.torque", "crank.angle", "crank.speed"} <= names
    assert not any(n.startswith("rod.") for n in names)


@pytest.mark.parametrize("fmi3", [False, True])
def test_simulate_fmu_matches_the_closed_form(crankshaft_fmu, crankshaft_fmu3, fmi3):
    path = crankshaft_fmu3 if fmi3 else crankshaft_fmu
    torque = 30.0
    result = simulate_fmu(
        str(path),
        stop_time=0.1,
        output_interval=1e-3,
        start_values={"drive.torque": torque},
        output=["crank.angle", "crank.speed"],
    )
    angle, speed = closed_form(result["time"], torque)
    assert np.allclose(result["crank.speed"], speed, rtol=1e-12, atol=1e-9)
    assert np.allclose(result["crank.angle"], angle, rtol=1e-12, atol=1e-9)


def test_a_torque_ramp_set_as_input_derivative_is_exact(cs_dir):
    """drive.torque = 40 + 2000 t, given by its value and first derivative at each point; c = 0
    makes the motion the polynomial w = w0 + (40 t + 1000 t^2) / J."""
    s = Crank(cs_dir)
    s.init(params={"crankshaft.damping": 0.0})
    h = 1e-3
    for k in range(50):
        t = k * h
        s.set(drive=40.0 + 2000.0 * t, load=0.0)
        s.fmu.setRealInputDerivatives([s.vr["drive.torque"]], [1], [2000.0])
        s.fmu.doStep(t, h)
    t = 50 * h
    speed = W0 + (40.0 * t + 1000.0 * t * t) / J
    assert abs(s.outputs()[1] - speed) < 1e-10 * speed
    s.fmu.terminate()
    s.fmu.freeInstance()


def test_two_instances_are_independent(cs_dir):
    alone = Crank(cs_dir, "alone")
    alone.init()
    expected = alone.run(0.0, 200)
    a, b = Crank(cs_dir, "a"), Crank(cs_dir, "b")
    a.init()
    b.init(params={"crankshaft.inertia": 2.0})
    rows = []
    for k in range(200):
        rows.append(a.run(k * 1e-4, 1)[0])
        b.run(k * 1e-4, 1, torque=lambda t: (1e3, 0.0))
    assert np.array_equal(np.array(rows), expected)


def test_get_step_set_step_is_bit_identical(cs_dir):
    s = Crank(cs_dir)
    s.init()
    s.run(0.0, 100)
    state = s.fmu.getFMUstate()
    first = s.run(100e-4, 100)
    s.fmu.setFMUstate(state)
    second = s.run(100e-4, 100)
    assert np.array_equal(first, second)
    s.fmu.freeFMUstate(state)


RESUME = r"""
import json, sys
sys.path.insert(0, sys.argv[1])
from test_crankshaft import Crank
s = Crank(sys.argv[2], "resumed")
state = s.fmu.deSerializeFMUstate(bytes.fromhex(sys.argv[3]))
s.fmu.setFMUstate(state)
print(json.dumps([[x.hex() for x in row] for row in s.run(100e-4, 100).tolist()]))
"""


def test_serialized_state_continues_identically_in_another_process(cs_dir):
    s = Crank(cs_dir)
    s.init()
    s.run(0.0, 100)
    blob = s.fmu.serializeFMUstate(s.fmu.getFMUstate())
    here = s.run(100e-4, 100)
    proc = subprocess.run(
        [sys.executable, "-c", RESUME, str(ROOT / "tests" / "python"), str(cs_dir), blob.hex()],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 0, proc.stderr
    there = np.array([[float.fromhex(x) for x in row] for row in json.loads(proc.stdout)])
    assert np.array_equal(here, there)


def test_foreign_truncated_and_corrupted_states_are_refused(cs_dir, default_unzipdir):
    s = Crank(cs_dir)
    s.init()
    s.run(0.0, 10)
    blob = s.fmu.serializeFMUstate(s.fmu.getFMUstate())
    before = s.outputs()
    corrupted = bytearray(blob)
    corrupted[len(blob) // 2] ^= 0x10
    for bad in [blob[:-1], bytes(corrupted), b"not a state"]:
        with pytest.raises(Exception):
            s.fmu.deSerializeFMUstate(bad)
    assert "serialized state rejected" in s.log.last()
    # A state of the rod's FMU is refused by its token.
    rod = read_model_description(str(default_unzipdir))
    rod_slave = FMU2Slave(
        guid=rod.guid,
        unzipDirectory=str(default_unzipdir),
        modelIdentifier=rod.coSimulation.modelIdentifier,
        instanceName="rod",
    )
    rod_slave.instantiate()
    rod_blob = rod_slave.serializeFMUstate(rod_slave.getFMUstate())
    with pytest.raises(Exception):
        s.fmu.deSerializeFMUstate(rod_blob)
    assert "GUID" in s.log.last()
    assert s.outputs() == before
    s.run(10e-4, 10)


def test_bad_values_are_refused_and_the_instance_stays_usable(cs_dir):
    s = Crank(cs_dir)
    s.init()
    before = s.outputs()
    for value in [float("nan"), 1e9]:
        with pytest.raises(Exception):
            s.fmu.setReal([s.vr["drive.torque"]], [value])
    assert "drive.torque" in s.log.last()
    with pytest.raises(Exception):
        s.fmu.setReal([s.vr["crankshaft.inertia"]], [2.0])  # fixed after initialization
    with pytest.raises(Exception):
        s.fmu.setRealInputDerivatives([s.vr["drive.torque"]], [2], [1.0])
    assert "order = 2" in s.log.last()
    assert s.outputs() == before
    s.run(0.0, 5)


def test_a_step_past_the_speed_window_is_refused_with_the_state_kept(cs_dir):
    s = Crank(cs_dir)
    s.init(params={"crankshaft.inertia": 1e-6, "crankshaft.damping": 0.0})
    before = s.outputs()
    s.set(drive=1e7, load=0.0)
    with pytest.raises(Exception):  # fmi2Error, refused before anything changed
        s.fmu.doStep(0.0, 1.0)
    assert "crank.speed" in s.log.last()
    # Angle and speed kept; the acceleration follows the torque just set (direct feedthrough).
    assert s.outputs()[:2] == before[:2]
    s.set(drive=0.0, load=0.0)
    s.fmu.doStep(0.0, 1e-3)


def test_reset_restores_the_start_values(cs_dir):
    s = Crank(cs_dir)
    s.init(params={"crankshaft.start_speed": 10.0})
    s.run(0.0, 10)
    s.fmu.reset()
    s.init()
    assert s.outputs()[1] == W0


def test_fmi3_instance_steps_and_serializes(crankshaft_fmu3, tmp_path):
    unzipdir = extract(str(crankshaft_fmu3), str(tmp_path / "u3"))
    md = read_model_description(unzipdir)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu = FMU3Slave(
        guid=md.guid,
        unzipDirectory=unzipdir,
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="cs3",
    )
    fmu.instantiate()
    fmu.enterInitializationMode(startTime=0.0)
    fmu.setFloat64([vr["drive.torque"]], [30.0])
    fmu.exitInitializationMode()
    state = fmu.getFMUState()
    for k in range(100):
        fmu.doStep(k * 1e-3, 1e-3)
    angle, speed = closed_form(np.array([0.1]), 30.0)
    out = fmu.getFloat64([vr["crank.angle"], vr["crank.speed"], vr["time"]])
    assert abs(out[1] - speed[0]) < 1e-9 and abs(out[0] - angle[0]) < 1e-9
    assert abs(out[2] - 0.1) < 1e-12
    blob = fmu.serializeFMUState(state)
    fmu.setFMUState(fmu.deserializeFMUState(blob))
    assert fmu.getFloat64([vr["crank.speed"]])[0] == W0
    fmu.terminate()
    fmu.freeInstance()


def rod_slave(unzipdir, name):
    md = read_model_description(str(unzipdir))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu = FMU2Slave(
        guid=md.guid,
        unzipDirectory=str(unzipdir),
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName=name,
    )
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.setReal([vr["crank.angle"], vr["crank.speed"]], [0.0, 150.0])
    fmu.exitInitializationMode()
    return fmu, vr


def test_the_crankshaft_fmu_turns_the_rod_fmu_as_a_scripted_shaft_does(cs_dir, default_unzipdir):
    """The engine's loop (Jacobi): the shaft takes the rod's crank.torque as load.torque, the rod
    follows the shaft's angle, speed and acceleration. Without loss the shaft's exact motion
    over a step with a held torque is the script's theta += omega h + alpha h^2 / 2, omega +=
    alpha h, so the coupled runs agree to round-off."""
    j, h, n = 0.05, 1e-4, 300
    shaft = Crank(cs_dir, "shaft")
    shaft.init(
        params={
            "crankshaft.inertia": j,
            "crankshaft.damping": 0.0,
            "crankshaft.start_speed": 150.0,
        }
    )
    rod_a, vr = rod_slave(default_unzipdir, "rod_a")
    rod_b, _ = rod_slave(default_unzipdir, "rod_b")
    torque = vr["crank.torque"]
    theta, omega = 0.0, 150.0
    speeds_fmu, speeds_script = [], []
    for k in range(n):
        t = k * h
        # With the crankshaft FMU.
        tau = rod_a.getReal([torque])[0]
        shaft.set(drive=0.0, load=tau)
        angle, speed, alpha = shaft.outputs()
        rod_a.setReal([vr["crank.angle"], vr["crank.speed"]], [angle, speed])
        rod_a.setRealInputDerivatives([vr["crank.speed"]], [1], [alpha])
        shaft.fmu.doStep(t, h)
        rod_a.doStep(t, h)
        speeds_fmu.append(shaft.outputs()[1])
        # With the shaft in the script.
        tau = rod_b.getReal([torque])[0]
        alpha = -tau / j
        rod_b.setReal([vr["crank.angle"], vr["crank.speed"]], [theta, omega])
        rod_b.setRealInputDerivatives([vr["crank.speed"]], [1], [alpha])
        theta, omega = theta + omega * h + alpha * h * h / 2, omega + alpha * h
        rod_b.doStep(t, h)
        speeds_script.append(omega)
    speeds_fmu, speeds_script = np.array(speeds_fmu), np.array(speeds_script)
    assert np.max(np.abs(speeds_fmu - speeds_script)) < 1e-9 * 150.0
    # The rod's torque moves the shaft: the speed is not constant.
    assert np.ptp(speeds_fmu) > 1e-3


def test_libcosim_runs_the_crankshaft_fmu_to_the_closed_form(crankshaft_fmu):
    """A second importer: libcosim (Open Simulation Platform) with a fixed step, the drive
    torque as an initial value."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    md = read_model_description(str(crankshaft_fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    step_ns, n, torque = 1_000_000, 100, 30.0
    execution = CosimExecution.from_step_size(step_size=step_ns)
    index = execution.add_local_slave(
        CosimLocalSlave(fmu_path=str(crankshaft_fmu), instance_name="crankshaft")
    )
    assert execution.real_initial_value(index, vr["drive.torque"], torque)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    refs = [vr["crank.angle"], vr["crank.speed"]]
    for _ in range(n):
        assert execution.step()
    angle, speed = observer.last_real_values(index, refs)
    exact_angle, exact_speed = closed_form(np.array([n * step_ns * 1e-9]), torque)
    assert abs(speed - exact_speed[0]) < 1e-9 and abs(angle - exact_angle[0]) < 1e-9
