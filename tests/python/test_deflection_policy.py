"""rod.deflection_limit and rod.deflection_policy (1 warn, 2 discard, 3 error) through
fmpy, on both rod models. A refused step keeps the state from before it."""

import pytest
from fmpy.fmi1 import FMICallException
from helpers import Slave

OK, WARNING, DISCARD, ERROR = 0, 1, 2, 3
DT, N = 1e-4, 150


def slave_with(unzipdir, policy, limit):
    s = Slave(unzipdir, logging_on=True)
    s.fmu.setReal([s.vr["rod.deflection_limit"]], [limit])
    s.fmu.setInteger([s.vr["rod.deflection_policy"]], [policy])
    s.init()
    return s


def reference(unzipdir):
    """Outputs after each step with the limit out of reach (policy warn, limit 1)."""
    s = slave_with(unzipdir, 1, 1.0)
    rows = [s.get("rod.deflection_rel", "pinB.force_x")]
    for k in range(N):
        s.fmu.doStep(k * DT, DT)
        rows.append(s.get("rod.deflection_rel", "pinB.force_x"))
    s.free()
    return rows


@pytest.fixture(scope="module")
def ref(unzipdir):
    rows = reference(unzipdir)
    peak = max(abs(r[0]) for r in rows)
    limit = 0.5 * peak
    first = next(k for k, r in enumerate(rows) if abs(r[0]) > limit)
    assert first > 3
    return rows, limit, first


def test_warn_continues_with_one_warning(unzipdir, ref):
    rows, limit, first = ref
    s = slave_with(unzipdir, 1, limit)
    for k in range(N):
        s.fmu.doStep(k * DT, DT)
        assert s.get("rod.deflection_rel", "pinB.force_x") == rows[k + 1]
    assert s.log.text().count("exceeds rod.deflection_limit") == 1
    s.free()


@pytest.mark.parametrize("policy,status", [(2, DISCARD), (3, ERROR)])
def test_discard_and_error_refuse_the_step_state_kept(unzipdir, ref, policy, status):
    rows, limit, first = ref
    s = slave_with(unzipdir, policy, limit)
    for k in range(first - 1):
        s.fmu.doStep(k * DT, DT)
    saved = s.fmu.getFMUstate()  # at step first - 1 (the last one below the limit)
    s.log.clear()
    with pytest.raises(FMICallException) as e:
        s.fmu.doStep((first - 1) * DT, DT)
    assert e.value.status == status
    text = s.log.text()
    assert "rod.deflection_limit" in text and "refused" in text, text
    # The state from before the refused step: the outputs of the run that never tried.
    assert s.get("rod.deflection_rel", "pinB.force_x") == rows[first - 1]
    # Restore and continue: the same outputs as the run that never tried.
    s.fmu.setFMUstate(saved)
    assert s.get("rod.deflection_rel", "pinB.force_x") == rows[first - 1]
    s.fmu.freeFMUstate(saved)
    s.fmu.reset()
    s.free()


def test_limit_and_policy_ranges(unzipdir):
    s = Slave(unzipdir)
    for bad in [0.0, -0.1, 1.5]:
        with pytest.raises(FMICallException):
            s.fmu.setReal([s.vr["rod.deflection_limit"]], [bad])
            s.init()
        s.fmu.reset()
    for bad in [0, 4]:
        with pytest.raises(FMICallException):
            s.fmu.setInteger([s.vr["rod.deflection_policy"]], [bad])
    s.free()


def test_default_policy_is_discard(unzipdir, ref):
    """Without setting rod.deflection_policy, a step past the limit is refused with fmi2Discard
    (the default), the state from before it kept, and the instance continues after a restore."""
    rows, limit, first = ref
    s = Slave(unzipdir, logging_on=True)
    policy = next(v for v in s.md.modelVariables if v.name == "rod.deflection_policy")
    assert int(policy.start) == 2
    s.fmu.setReal([s.vr["rod.deflection_limit"]], [limit])
    s.init()
    for k in range(first - 1):
        s.fmu.doStep(k * DT, DT)
    with pytest.raises(FMICallException) as e:
        s.fmu.doStep((first - 1) * DT, DT)
    assert e.value.status == DISCARD
    assert s.get("rod.deflection_rel", "pinB.force_x") == rows[first - 1]
    s.free()
