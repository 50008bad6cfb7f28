"""The FMU against the core's own simulation (flexrod::Simulation driven without FMI)."""

import math

import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from helpers import (
    DT,
    OUTPUTS,
    STOP,
    Slave,
    assert_close,
    crank_input,
    run_loop,
    schedule,
    unexpected_warnings,
)


def constant_speed_input(stop=STOP):
    t = np.array([0.0, stop])
    return np.array(
        list(zip(t, 150.0 * t, [150.0, 150.0])),
        dtype=[("time", float), ("crank.angle", float), ("crank.speed", float)],
    )


def compare(result, expected, what):
    assert_close(result["time"], expected["time"], 1e-12, what + ": time")
    for name in OUTPUTS:
        assert_close(result[name], expected[name], 1e-9, f"{what}: {name}")


def test_simulate_fmu_matches_the_core(fmu_path, ref):
    result = simulate_fmu(
        str(fmu_path), input=constant_speed_input(), output=OUTPUTS, output_interval=DT
    )
    expected = ref()
    assert len(result) == len(expected["time"]) == 839
    compare(result, expected, "simulate_fmu")
    # The rod does deform: the comparison is not between zeros.
    assert np.max(np.abs(expected["rod.deflection_rel"])) > 1e-5


def test_without_inputs_the_default_law_continues(fmu_path, ref):
    result = simulate_fmu(str(fmu_path), output=OUTPUTS, output_interval=DT)
    compare(result, ref(), "no inputs")


def test_input_derivatives_of_a_constant_speed(unzipdir, ref):
    """Derivatives as simulate_fmu(set_input_derivatives=True) would send them (its table of
    derivatives has a fixed size of 9 in FMPy 0.3, so the loop is written out): order 1 of
    crank.angle (= the speed; accepted, not used) and of crank.speed (= 0)."""
    slave = Slave(unzipdir)
    slave.init()
    vr = [slave.vr["crank.angle"], slave.vr["crank.speed"]]
    out = run_loop(slave, schedule(0.0, STOP, DT), between=None)
    slave.fmu.reset()
    slave.init()
    times = schedule(0.0, STOP, DT)
    rows = [slave.outputs()]
    for k in range(len(times) - 1):
        slave.set(crank__angle=150.0 * times[k], crank__speed=150.0)
        slave.fmu.setRealInputDerivatives(vr, [1, 1], [150.0, 0.0])
        slave.fmu.doStep(times[k], times[k + 1] - times[k])
        rows.append(slave.outputs())
    slave.free()
    assert not unexpected_warnings(slave), slave.log.text()
    expected = ref()
    for i, name in enumerate(OUTPUTS):
        assert_close(np.array(rows)[:, i], expected[name], 1e-9, name)
        assert_close(out[:, i], expected[name], 1e-9, name)


def test_crank_acceleration_from_input_derivatives(unzipdir, ref):
    accel = 1000.0  # 150 -> 234 rad/s: inside the default deflection limit (0.05 L)
    slave = Slave(unzipdir)
    slave.init(accel=accel)
    out = run_loop(slave, schedule(0.0, STOP, DT), accel=accel)
    slave.free()
    expected = ref(accel=accel)
    for i, name in enumerate(OUTPUTS):
        assert_close(out[:, i], expected[name], 1e-9, name)
    # Without the derivative the input is piecewise linear: different results.
    assert not np.allclose(out[:, 2], ref()["pinB.force_x"], rtol=1e-6)


def test_crank_acceleration_as_order_2_of_the_angle(unzipdir, ref):
    """Order 2 of crank.angle is the crank acceleration too: the same run as with order 1 of
    crank.speed, bit for bit."""
    accel = 1000.0  # 150 -> 234 rad/s: inside the default deflection limit (0.05 L)
    times = schedule(0.0, STOP, DT)[:300]
    runs = []
    for name, order in [("crank.speed", 1), ("crank.angle", 2)]:
        slave = Slave(unzipdir)
        slave.fmu.setupExperiment(startTime=0.0)
        slave.fmu.enterInitializationMode()
        slave.set(crank__angle=0.0, crank__speed=150.0)
        slave.fmu.setRealInputDerivatives([slave.vr[name]], [order], [accel])
        slave.fmu.exitInitializationMode()
        rows = [slave.outputs()]
        for k in range(len(times) - 1):
            angle, speed = crank_input(times[k], accel=accel)
            slave.set(crank__angle=angle, crank__speed=speed)
            slave.fmu.setRealInputDerivatives([slave.vr[name]], [order], [accel])
            slave.fmu.doStep(times[k], times[k + 1] - times[k])
            rows.append(slave.outputs())
        slave.free()
        assert not unexpected_warnings(slave), slave.log.text()
        runs.append(np.array(rows))
    assert np.array_equal(runs[0], runs[1])
    expected = ref(accel=accel)
    for i, name in enumerate(OUTPUTS):
        assert_close(runs[0][:, i], expected[name][:300], 1e-9, name)


def test_crank_jerk_from_input_derivatives(unzipdir):
    """Order 2 of crank.speed is the crank jerk j_k of the law that starts at t_k, order 3 of
    crank.angle the same (bit for bit), and it holds for that step only:
    theta = theta_k + omega_k s + alpha_k s^2 / 2 + j_k s^3 / 6, read back after the step."""
    accel, jerk, h, n = 2000.0, -4.0e6, 1e-4, 6
    laws, runs = [], []
    for name, order in [("crank.speed", 2), ("crank.angle", 3)]:
        slave = Slave(unzipdir)
        slave.init(accel=accel)
        law = [slave.get("crank.angle", "crank.speed")]
        rows = [slave.outputs()]
        for k in range(n):
            if k < 2:
                if k == 1:
                    slave.fmu.setRealInputDerivatives([slave.vr["crank.speed"]], [1], [accel])
                slave.fmu.setRealInputDerivatives([slave.vr[name]], [order], [jerk])
            slave.fmu.doStep(k * h, h)
            law.append(slave.get("crank.angle", "crank.speed"))
            rows.append(slave.outputs())
        slave.free()
        assert not unexpected_warnings(slave), slave.log.text()
        laws.append(np.array(law))
        runs.append(np.array(rows))
    assert np.array_equal(runs[0], runs[1])
    assert np.array_equal(laws[0], laws[1])
    # Steps 0 and 1 carry the acceleration and the jerk; then the law runs on at constant speed.
    theta, omega = 0.0, 150.0
    expected = [(theta, omega)]
    for k in range(n):
        alpha, j = (accel, jerk) if k < 2 else (0.0, 0.0)
        theta, omega = (
            theta + omega * h + 0.5 * alpha * h * h + j * h**3 / 6.0,
            omega + alpha * h + 0.5 * j * h * h,
        )
        expected.append((theta, omega))
    np.testing.assert_allclose(laws[0], np.array(expected), rtol=1e-13, atol=1e-13)
    assert laws[0][1, 1] == pytest.approx(150.0 + accel * h + 0.5 * jerk * h * h, abs=1e-12)


def test_input_law_without_inputs_continues_without_acceleration(unzipdir):
    """Nothing set at t_k: theta_k, omega_k continue the previous law, alpha_k = 0 (an
    acceleration set at t_0 holds only for the step from t_0). fmi2GetReal of the inputs after
    a step gives the law's values at the new time, exactly those the integrator used: setting
    them explicitly gives the same run bit for bit."""
    accel, h, n = 2000.0, 1e-4, 40
    a = Slave(unzipdir)
    a.init(accel=accel)
    law = [a.get("crank.angle", "crank.speed")]
    out_a = [a.outputs()]
    for k in range(n):
        if k == 1:
            a.fmu.setRealInputDerivatives([a.vr["crank.speed"]], [1], [accel])
        a.fmu.doStep(k * h, h)
        law.append(a.get("crank.angle", "crank.speed"))
        out_a.append(a.outputs())
    a.free()
    law = np.array(law)
    # Step 0 (alpha set in initialization mode) and step 1 (set at t_1) accelerate; all
    # others run at constant speed from where the previous law ended.
    theta, omega = 0.0, 150.0
    expected = [(theta, omega)]
    for k in range(n):
        alpha = accel if k in (0, 1) else 0.0
        theta, omega = theta + omega * h + 0.5 * alpha * h * h, omega + alpha * h
        expected.append((theta, omega))
    np.testing.assert_allclose(law, np.array(expected), rtol=1e-13, atol=1e-13)
    assert law[1, 1] == pytest.approx(150.0 + accel * h, abs=1e-12)
    assert law[2, 1] == pytest.approx(150.0 + 2 * accel * h, abs=1e-12)
    assert np.all(law[3:, 1] == law[2, 1])

    b = Slave(unzipdir)
    b.init(accel=accel)
    out_b = [b.outputs()]
    for k in range(n):
        b.set(crank__angle=law[k, 0], crank__speed=law[k, 1])
        if k in (0, 1):
            b.fmu.setRealInputDerivatives([b.vr["crank.speed"]], [1], [accel])
        b.fmu.doStep(k * h, h)
        out_b.append(b.outputs())
    b.free()
    assert np.array_equal(np.array(out_a), np.array(out_b))


def test_variable_communication_steps(unzipdir, ref):
    steps = [1e-4, 2.5e-4, 5e-5, 3e-4, 1.7e-4]
    slave = Slave(unzipdir)
    slave.init()
    times = schedule(0.0, STOP, steps=steps)
    out = run_loop(slave, times)
    slave.free()
    expected = ref(steps=steps)
    assert_close(times, expected["time"], 1e-12, "time")
    for i, name in enumerate(OUTPUTS):
        assert_close(out[:, i], expected[name], 1e-9, name)


def test_reset_then_the_same_run_is_identical(unzipdir):
    slave = Slave(unzipdir)
    times = schedule(0.0, 0.01, DT)
    slave.init(params={"rod.damping_ratio": 0.02})
    first = run_loop(slave, times)
    slave.fmu.terminate()
    slave.fmu.reset()
    slave.init(params={"rod.damping_ratio": 0.02})
    second = run_loop(slave, times)
    slave.free()
    assert np.array_equal(first, second)


def test_reset_restores_start_values(unzipdir):
    slave = Slave(unzipdir)
    slave.init(params={"rod.length": 0.35})
    assert slave.get("rod.length") == [0.35]
    slave.fmu.reset()
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.enterInitializationMode()
    assert slave.get("rod.length", "crank.speed") == [0.3048, 150.0]
    slave.free()


def test_resource_location_with_a_space(fmu_path, spaced_dir, ref):
    unzipped = spaced_dir / "fmu"
    extract(str(fmu_path), str(unzipped))
    result = simulate_fmu(
        str(unzipped), input=constant_speed_input(), output=OUTPUTS, output_interval=DT
    )
    compare(result, ref(), "spaced path")


def test_parameters_and_frequencies(unzipdir):
    slave = Slave(unzipdir)
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.enterInitializationMode()
    names = [f"rod.frequency[{k}]" for k in range(1, 7)]
    f = slave.get(*names)
    assert all(x > 0 for x in f) and f == sorted(f)
    # In initialization mode a parameter change is seen by the calculated parameters.
    slave.set(rod__youngs_modulus=2 * 2.068e11)
    f2 = slave.get(*names)
    assert f2[0] == pytest.approx(f[0] * math.sqrt(2), rel=1e-6)
    slave.set(rod__youngs_modulus=2.068e11)
    slave.fmu.exitInitializationMode()
    assert slave.get(*names) == f
    # Undeformed at the start, slider at r + L for theta = 0.
    assert slave.get("rod.deflection", "slider.position") == pytest.approx(
        [0.0, 0.1524 + 0.3048], abs=1e-12
    )
    slave.free()


def test_segments_model(segments_fmu, default_fmu):
    """The segment chain FMU is valid and agrees with the FFR FMU (two discretizations of the
    same stiffened rod; tests/segments.rs measures both against the exact beam). At the
    scene's 8 segments the chain's own discretization error shows (order 2 in N; measured
    +1.1 % in the peak, 1.6 % pointwise of the peak); at
    32 segments, set through the FMU parameter rod.elements, within 0.05 % in the peak and 0.9 %
    pointwise (the chain's generalized-alpha phase at h = 1e-4 s)."""
    from fmpy.validation import validate_fmu

    assert validate_fmu(str(segments_fmu)) == []
    md = read_model_description(str(segments_fmu))
    model = next(v for v in md.modelVariables if v.name == "rod.model")
    assert model.start == "2"
    ffr = simulate_fmu(
        str(default_fmu), input=constant_speed_input(), output=OUTPUTS, output_interval=DT
    )
    ffr_v = ffr["rod.deflection_rel"]
    ffr_peak = np.max(np.abs(ffr_v))
    assert 0.01 < ffr_peak < 0.02
    errors = {}
    for elements, peak_bound, pointwise_bound in [(8, 0.015, 0.025), (32, 0.002, 0.015)]:
        result = simulate_fmu(
            str(segments_fmu),
            input=constant_speed_input(),
            output=OUTPUTS,
            output_interval=DT,
            start_values={"rod.elements": elements},
        )
        assert np.array_equal(result["time"], ffr["time"])
        v = result["rod.deflection_rel"]
        assert np.all(np.isfinite(v))
        peak_error = np.max(np.abs(v)) / ffr_peak - 1.0
        pointwise = np.max(np.abs(v - ffr_v)) / ffr_peak
        # Pin B force, the largest output: within 2 % of its peak (measured 1.0 % at both N).
        force = np.hypot(result["pinB.force_x"], result["pinB.force_y"])
        ffr_force = np.hypot(ffr["pinB.force_x"], ffr["pinB.force_y"])
        force_error = np.max(np.abs(force - ffr_force)) / np.max(ffr_force)
        print(
            f"segments N = {elements} against FFR: peak {100 * peak_error:+.3f} %, pointwise "
            f"{100 * pointwise:.3f} %, |F_B| {100 * force_error:.3f} % of the peak"
        )
        assert abs(peak_error) < peak_bound, (elements, peak_error)
        assert pointwise < pointwise_bound, (elements, pointwise)
        assert force_error < 0.02, (elements, force_error)
        errors[elements] = pointwise
    # More segments: closer to the FFR rod.
    assert errors[32] < errors[8]
