"""The gas force as a function of crank angle (`[slider.gas_force]`, docs/fmu.md), through fmpy
on an FMU of scenes/automotive_rod.toml with the engine run's pulse as a table: the parameter
`slider.gas_force_scale` (VR 108) declared and range checked, the force followed inside every
communication step (a 1 ms grid gives what a 20 us grid gives), and the scale acting."""

import math

import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from helpers import ROOT, Slave, build_fmu

SCENE = ROOT / "scenes" / "automotive_rod.toml"
SPEED = 628.3
CYCLE = 1440.0
FIRING = 375.0  # degrees: 15 degrees after the second top dead centre
STOP = 4.0 * math.pi / SPEED  # two revolutions


def pulse(angle_deg):
    return -38.0e3 * math.exp(-(((angle_deg - FIRING) / 20.0) ** 2))


@pytest.fixture(scope="module")
def gas_fmu(tmp_path_factory):
    angles = [0.5 * i for i in range(int(CYCLE / 0.5))]
    table = (
        "\n[slider.gas_force]\n"
        f"cycle = {CYCLE}\n"
        f"angle = [{', '.join(repr(a) for a in angles)}]\n"
        f"force = [{', '.join(repr(pulse(a)) for a in angles)}]\n"
    )
    text = SCENE.read_text()
    assert "[slider]" in text
    scene = tmp_path_factory.mktemp("gas_scene") / "automotive_gas.toml"
    scene.write_text(text + table)
    return build_fmu(tmp_path_factory.mktemp("gas_fmu"), scene)


@pytest.fixture(scope="module")
def unzipdir(gas_fmu, tmp_path_factory):
    return extract(str(gas_fmu), str(tmp_path_factory.mktemp("gas_unzipped")))


def started(unzipdir, scale=None):
    """An instance initialized at crank angle 0 and full speed (the scale set if given)."""
    s = Slave(unzipdir)
    s.fmu.setupExperiment(startTime=0.0)
    s.fmu.enterInitializationMode()
    if scale is not None:
        s.set(**{"slider.gas_force_scale": scale})
    s.set(**{"crank.angle": 0.0, "crank.speed": SPEED})
    s.fmu.exitInitializationMode()
    return s


def run(unzipdir, dt, scale=None):
    """Two revolutions at constant speed from the undeformed start on the grid dt: the outputs
    at every communication point."""
    s = started(unzipdir, scale)
    names = ["rod.deflection_rel", "pinB.force_x", "pinC.force_x", "crank.torque"]
    rows = [s.get(*names)]
    n = int(round(STOP / dt))
    for k in range(n):
        t = k * dt
        s.set(**{"crank.angle": SPEED * t, "crank.speed": SPEED})
        s.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=dt)
        rows.append(s.get(*names))
    s.free()
    return np.array(rows)


def test_scale_is_declared_with_its_window(unzipdir):
    s = Slave(unzipdir)
    v = {v.name: v for v in s.md.modelVariables}["slider.gas_force_scale"]
    assert v.valueReference == 108 and v.causality == "parameter"
    assert float(v.start) == 1.0 and float(v.min) == 0.0 and float(v.max) == 100.0
    s.free()


def test_fmi3_declares_the_scale_too(gas_fmu, tmp_path):
    # The FMI 3.0 FMU written beside it, driven through fmpy's FMU3Slave: the same parameter,
    # and the pulse acting (the pin force at C reaches the gas force's order).
    from fmpy.fmi3 import FMU3Slave

    unzipped = extract(str(gas_fmu.with_name(gas_fmu.stem + "-fmi3.fmu")), str(tmp_path))
    md = read_model_description(unzipped)
    v = {v.name: v for v in md.modelVariables}
    scale = v["slider.gas_force_scale"]
    assert scale.valueReference == 108 and scale.causality == "parameter"
    assert float(scale.start) == 1.0 and float(scale.min) == 0.0 and float(scale.max) == 100.0
    s = FMU3Slave(
        guid=md.guid,
        unzipDirectory=unzipped,
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="gas3",
    )
    s.instantiate()
    s.enterInitializationMode(startTime=0.0)
    s.setFloat64([v["crank.speed"].valueReference], [SPEED])
    s.exitInitializationMode()
    dt, pin_c = 2e-5, v["pinC.force_x"].valueReference
    largest = 0.0
    for k in range(int(round(STOP / dt))):
        s.setFloat64(
            [v["crank.angle"].valueReference, v["crank.speed"].valueReference],
            [SPEED * k * dt, SPEED],
        )
        s.doStep(currentCommunicationPoint=k * dt, communicationStepSize=dt)
        largest = max(largest, abs(s.getFloat64([pin_c])[0]))
    s.terminate()
    s.freeInstance()
    assert largest > 20e3


@pytest.mark.parametrize("bad", [-0.5, 101.0, float("nan")])
def test_scale_out_of_range_is_refused_by_name(unzipdir, bad):
    s = Slave(unzipdir, logging_on=True)
    s.fmu.setupExperiment(startTime=0.0)
    s.fmu.enterInitializationMode()
    try:
        s.set(**{"slider.gas_force_scale": bad})
    except FMICallException:
        assert "slider.gas_force_scale" in s.log.text()
        s.free()
        return
    with pytest.raises(FMICallException):
        s.fmu.exitInitializationMode()
    assert "slider.gas_force_scale" in s.log.text()
    s.free()


def test_coarse_grid_gives_the_fine_grids_outputs(unzipdir):
    fine_grid = run(unzipdir, 2e-5)
    # The pulse is there: the slider's pin force reaches the gas force's order.
    assert np.abs(fine_grid[:, 2]).max() > 20e3
    fine = fine_grid[::50]
    coarse = run(unzipdir, 1e-3)
    assert fine.shape == coarse.shape
    peak = np.abs(fine).max(axis=0)
    worst = (np.abs(coarse - fine) / peak).max(axis=0)
    assert (worst < 5e-3).all(), worst


def test_scale_acts_on_the_force(unzipdir):
    # Scale 0 is the rod without gas force; at scale 2 the pulse's share of the pin force at C
    # doubles (the pin force is linear in the slider force up to the rod's small deflection).
    base, one, two = (run(unzipdir, 1e-3, scale) for scale in (0.0, 1.0, 2.0))
    d1, d2 = one[:, 2] - base[:, 2], two[:, 2] - base[:, 2]
    assert np.abs(d1).max() > 10e3
    assert np.abs(d2 - 2.0 * d1).max() < 0.02 * np.abs(d1).max()


def test_serialized_state_replays_the_pulse_bit_for_bit(unzipdir):
    # Save before the pulse (crank at 300 degrees), run through it, restore the serialized state
    # into a second instance and replay: identical outputs (the table is part of the model).
    dt = 1e-4
    names = ["rod.deflection_rel", "pinC.force_x", "crank.torque"]

    def advance(s, k0, k1):
        out = []
        for k in range(k0, k1):
            s.set(**{"crank.angle": SPEED * k * dt, "crank.speed": SPEED})
            s.fmu.doStep(currentCommunicationPoint=k * dt, communicationStepSize=dt)
            out.append(s.get(*names))
        return out

    save_at = int(round(math.radians(300.0) / SPEED / dt))
    end = int(round(math.radians(450.0) / SPEED / dt))
    first = started(unzipdir)
    advance(first, 0, save_at)
    blob = first.fmu.serializeFMUstate(first.fmu.getFMUstate())
    through = advance(first, save_at, end)
    assert max(abs(r[1]) for r in through) > 20e3  # the pulse is in the replayed part
    # Restored into an instance with the table scaled otherwise: a state carries its
    # parameters (docs/fmu.md, "FMU states and serialization"), so it replays the same pulse.
    second = started(unzipdir, scale=2.0)
    second.fmu.setFMUstate(second.fmu.deSerializeFMUstate(blob))
    assert advance(second, save_at, end) == through
    assert second.get("slider.gas_force_scale")[0] == 1.0
    first.free()
    second.free()
