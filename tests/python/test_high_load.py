"""Large deflection through fmpy: the benchmark rod at 300 rad/s (peak |v_mid/L| 0.07, abrupt
start) against Exudyn's geometrically exact shear beam (tests/data/exudyn_shear_beam_300rad_s.csv,
512 elements, converged). With the FMU's defaults (`rod.model = auto`) the crank speed at
initialization calls for the segment chain on its modes, which follows the exact beam, in fmi2OK
steps and in one fmi2DoStep alike; the FFR rod, set, refuses the step past its limit 0.05 with
fmi2Discard and names the model that goes further."""

import math

import numpy as np
import pytest
from fmpy import extract
from fmpy.fmi1 import FMICallException
from helpers import ROOT, Slave

W = 300.0
DT = 1e-4
DISCARD = 2


@pytest.fixture(scope="module")
def default_dir(default_fmu, tmp_path_factory):
    """The default FMU (scenes/benchmark.toml: `rod.model = auto`), unzipped."""
    return extract(str(default_fmu), str(tmp_path_factory.mktemp("high_load")))


def exact_beam():
    rows = [
        [float(x) for x in line.split(",")]
        for line in open(ROOT / "tests" / "data" / "exudyn_shear_beam_300rad_s.csv")
        if line.strip() and not line.startswith("#") and not line.startswith("t")
    ]
    return np.array(rows)


def started(unzipdir, params=None, integers=None):
    s = Slave(unzipdir, logging_on=True)
    for name, value in (integers or {}).items():
        s.fmu.setInteger([s.vr[name]], [value])
    s.init(speed=W, params=params)
    return s


def test_ffr_refuses_the_step_past_its_limit_and_names_the_model_that_goes_on(default_dir):
    s = started(default_dir, integers={"rod.model_index": 1})
    exact = exact_beam()
    peak = np.abs(exact[:, 1]).max()
    with pytest.raises(FMICallException) as refused:
        for k in range(len(exact) - 1):
            t = k * DT
            s.set(crank__angle=W * t, crank__speed=W)
            s.fmu.doStep(t, DT)
            # Every accepted step is within 1 % of the exact beam's peak.
            (v,) = s.get("rod.deflection_rel")
            assert abs(v - exact[k + 1, 1]) < 1e-2 * peak, (t, v)
    assert refused.value.status == DISCARD
    text = s.log.text()
    assert "rod.deflection_limit = 0.05" in text and "rod.model = modal_segments" in text, text
    s.free()


def test_the_defaults_take_the_chain_and_follow_the_exact_beam(default_dir):
    exact = exact_beam()
    peak = np.abs(exact[:, 1]).max()
    s = started(default_dir)
    # `auto` stays the setting; the speed it chose for is written into crank.design_speed.
    assert s.fmu.getInteger([s.vr["rod.model_index"]]) == [4]
    assert s.get("crank.design_speed") == [W]
    assert "rod model modal_segments (auto: predicted peak" in s.log.text(), s.log.text()
    worst = 0.0
    for k in range(len(exact) - 1):
        t = k * DT
        s.set(crank__angle=W * t, crank__speed=W)
        assert s.fmu.doStep(t, DT) is None
        (v,) = s.get("rod.deflection_rel")
        worst = max(worst, abs(v - exact[k + 1, 1]) / peak)
    assert worst < 5e-3, worst
    # Its error estimate says what it is (the chain's discretization and the integration),
    # within the tolerance: no warning.
    (estimate,) = s.get("rod.error_estimate")
    assert worst / 3 < estimate < 3 * worst, (estimate, worst)
    assert estimate <= 1e-3 and "exceeds solver.tolerance" not in s.log.text()
    s.free()
    # Two revolutions in one fmi2DoStep: the same motion at its end.
    one = started(default_dir)
    stop = 4 * math.pi / W
    one.fmu.doStep(0.0, stop)
    (v,) = one.get("rod.deflection_rel")
    k = round(stop / DT)
    assert abs(v - np.interp(stop, exact[:, 0], exact[:, 1])) < 5e-3 * peak, (v, exact[k, 1])
    one.free()


def test_the_design_speed_chooses_for_a_start_from_rest(default_dir):
    """From rest the crank speed says nothing of the load to come: `auto` takes the FFR rod,
    and with crank.design_speed = 300 the chain on its modes."""
    for params, model in [(None, "ffr"), ({"crank.design_speed": W}, "modal_segments")]:
        s = Slave(default_dir, logging_on=True)
        s.init(speed=0.0, params=params)
        assert f"rod model {model} (auto: predicted peak" in s.log.text(), (model, s.log.text())
        s.free()
