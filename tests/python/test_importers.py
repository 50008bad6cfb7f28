"""The FMU in importers other than fmpy: libcosim (Open Simulation Platform, through
libcosimpy), and a fixed-step C master (tests/c_master/master.c) that declares the stop time
in fmi2SetupExperiment. Each runs the default experiment, also with the rod model and the
reference conditions switched by parameter, and agrees with fmpy to 1e-9 of each output's
peak.

libcosim ignores Enumeration variables: it switches the model and the reference conditions
through their Integer twins (rod.model_index, rod.reference_index). The C master sets the
Enumerations themselves (rod.model, rod.reference, by value reference with fmi2SetInteger),
and fmpy the twins, so the comparison also checks that both names set the same parameter."""

import subprocess

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from helpers import DT, OUTPUTS, STOP
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimSlave import CosimLocalSlave

# Parameter sets, by the names fmpy and libcosim use. `other` is the rod model the FMU was
# not exported with; the reference conditions apply to the FFR rod, so those cases set it.
CASES = {
    "default": {},
    "model_switched": {"rod.model_index": "other"},
    "mean_axis": {"rod.model_index": 1, "rod.reference_index": 2},
    "cantilever": {"rod.model_index": 1, "rod.reference_index": 4},
    "slider_mass": {"slider.mass": 0.1},
}

# The Enumeration each twin stands for (what the C master sets instead).
ENUMERATION_OF = {"rod.model_index": "rod.model", "rod.reference_index": "rod.reference"}

TOLERANCE = 1e-9  # of the peak of each output

log_output_level(CosimLogLevel.WARNING)  # libcosim's own debug output off


def parameters(case, model):
    other = 2 if model == "ffr" else 1
    return {name: (other if value == "other" else value) for name, value in CASES[case].items()}


@pytest.fixture(scope="module")
def md(fmu_path):
    return read_model_description(str(fmu_path))


@pytest.fixture(scope="module")
def fmpy_runs(fmu_path, model):
    """fmpy's results per case: array (time, outputs...) at t = 0, DT, ..., STOP."""
    cache = {}

    def get(case):
        if case not in cache:
            result = simulate_fmu(
                str(fmu_path),
                start_values=parameters(case, model),
                output=OUTPUTS,
                step_size=DT,
                output_interval=DT,
                stop_time=STOP,
            )
            cache[case] = np.column_stack([result["time"]] + [result[n] for n in OUTPUTS])
        return cache[case]

    return get


def compare(name, actual, expected):
    """Largest difference over each output, relative to the output's peak (fmpy's); an output
    that is zero throughout (pinC.force_x of a massless slider) must stay exactly zero."""
    assert actual.shape == expected.shape, f"{name}: shape {actual.shape} != {expected.shape}"
    np.testing.assert_allclose(actual[:, 0], expected[:, 0], rtol=0, atol=1e-12, err_msg="time")
    worst = 0.0
    for i, output in enumerate(OUTPUTS, start=1):
        peak = np.max(np.abs(expected[:, i]))
        difference = np.max(np.abs(actual[:, i] - expected[:, i]))
        assert difference <= TOLERANCE * peak, (
            f"{name}, {output}: largest difference {difference:e} > {TOLERANCE} x peak {peak:e}"
        )
        if peak > 0:
            worst = max(worst, difference / peak)
    print(f"{name}: largest difference / peak = {worst:.3e}")
    return worst


def run_c_master(binary, unzipdir, md, values):
    vr = {v.name: v.valueReference for v in md.modelVariables}
    args = [str(binary), str(unzipdir)]
    for name, value in values.items():
        if name in ENUMERATION_OF:
            args += ["-i", f"{vr[ENUMERATION_OF[name]]}={value}"]
        else:
            args += ["-r", f"{vr[name]}={value!r}"]
    for name in OUTPUTS:
        args += ["-o", f"{vr[name]}:{name}"]
    result = subprocess.run(args, capture_output=True, text=True)
    assert result.returncode == 0, f"{' '.join(args)}:\n{result.stderr}"
    header = result.stdout.splitlines()[0].split(",")
    assert header == ["time"] + OUTPUTS
    return np.loadtxt(result.stdout.splitlines()[1:], delimiter=",", ndmin=2)


def run_libcosim(fmu_path, md, values):
    """libcosim with a fixed step of DT (in nanoseconds), parameters as initial values, the
    outputs read after every step (t = DT .. STOP)."""
    vr = {v.name: v.valueReference for v in md.modelVariables}
    step_ns = round(DT * 1e9)
    n_steps = round(STOP / DT)
    execution = CosimExecution.from_step_size(step_size=step_ns)
    index = execution.add_local_slave(CosimLocalSlave(fmu_path=str(fmu_path), instance_name="rod"))
    visible = {v.name.decode() for v in execution.slave_variables(index)}
    for name, value in values.items():
        assert name in visible, f"libcosim does not see {name}"
        if isinstance(value, int):
            assert execution.integer_initial_value(index, vr[name], value)
        else:
            assert execution.real_initial_value(index, vr[name], value)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    refs = [vr[n] for n in OUTPUTS]
    rows = []
    for k in range(1, n_steps + 1):
        assert execution.step(), f"libcosim step {k} failed"
        rows.append([k * step_ns * 1e-9] + list(observer.last_real_values(index, refs)))
    assert execution.status().current_time == n_steps * step_ns
    return np.array(rows)


def test_libcosim_hides_enumerations_but_sees_their_twins(fmu_path, md):
    execution = CosimExecution.from_step_size(step_size=round(DT * 1e9))
    index = execution.add_local_slave(CosimLocalSlave(fmu_path=str(fmu_path), instance_name="rod"))
    visible = {v.name.decode() for v in execution.slave_variables(index)}
    declared = {v.name: v for v in md.modelVariables}
    assert "rod.model" not in visible and "rod.reference" not in visible
    # Every parameter is reachable without Enumeration support.
    for name, v in declared.items():
        if v.causality == "parameter":
            assert (name if v.type != "Enumeration" else f"{name}_index") in visible, name


@pytest.mark.parametrize("case", list(CASES))
def test_c_master_matches_fmpy(case, model, c_master, unzipdir, md, fmpy_runs):
    actual = run_c_master(c_master, unzipdir, md, parameters(case, model))
    compare(f"C master, {model}, {case}", actual, fmpy_runs(case))


@pytest.mark.parametrize("case", list(CASES))
def test_libcosim_matches_fmpy(case, model, fmu_path, md, fmpy_runs):
    actual = run_libcosim(fmu_path, md, parameters(case, model))
    compare(f"libcosim, {model}, {case}", actual, fmpy_runs(case)[1:])


def test_parameter_cases_differ(model, fmpy_runs):
    """The switches take effect: each case gives other results than the default."""
    default = fmpy_runs("default")
    for case in CASES:
        if case != "default":
            assert not np.allclose(fmpy_runs(case)[:, 1], default[:, 1], rtol=1e-6), case
