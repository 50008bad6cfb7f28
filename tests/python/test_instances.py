"""Independent instances, saved and serialized states."""

import json
import subprocess
import sys
import threading

import numpy as np
from helpers import DT, OUTPUTS, STOP, Slave, assert_close, crank_input, run_loop, schedule


def test_two_instances_interleaved_in_one_process(unzipdir):
    times = schedule(0.0, 0.02, DT)
    alone_a = Slave(unzipdir, "alone_a")
    alone_a.init()
    expected_a = run_loop(alone_a, times)
    alone_a.free()
    alone_b = Slave(unzipdir, "alone_b")
    alone_b.init(params={"rod.damping_ratio": 0.05}, speed=100.0)
    expected_b = run_loop(alone_b, times, omega0=100.0)
    alone_b.free()

    a, b = Slave(unzipdir, "a"), Slave(unzipdir, "b")
    a.init()
    b.init(params={"rod.damping_ratio": 0.05}, speed=100.0)
    out_b = []

    def step_b(k):
        t, h = times[k], times[k + 1] - times[k]
        angle, speed = crank_input(t, omega0=100.0)
        b.set(crank__angle=angle, crank__speed=speed)
        b.fmu.doStep(t, h)
        out_b.append(b.outputs())

    out_a = run_loop(a, times, between=step_b)
    a.free()
    b.free()
    assert np.array_equal(out_a, expected_a)
    assert np.array_equal(np.array(out_b), expected_b[1:])


def test_two_instances_on_two_threads(unzipdir, ref):
    times = schedule(0.0, STOP, DT)
    results, errors = {}, []

    def work(name):
        try:
            s = Slave(unzipdir, name)
            s.init()
            results[name] = run_loop(s, times)
            s.free()
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(n,)) for n in ("t1", "t2")]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    assert np.array_equal(results["t1"], results["t2"])
    expected = ref()
    for i, name in enumerate(OUTPUTS):
        assert_close(results["t1"][:, i], expected[name], 1e-9, name)


def test_get_step_set_step_is_bit_identical(unzipdir):
    s = Slave(unzipdir)
    s.init()
    times = schedule(0.0, STOP, DT)
    run_loop(s, times[:200])
    state = s.fmu.getFMUstate()
    first = run_loop(s, times[199:400])
    s.fmu.setFMUstate(state)
    assert abs(s.fmu.getRealStatus(2) - times[199]) < 1e-12  # fmi2LastSuccessfulTime
    second = run_loop(s, times[199:400])
    assert np.array_equal(first, second)
    s.fmu.freeFMUstate(state)
    s.free()


RESUME = r"""
import json, sys
import numpy as np
sys.path.insert(0, sys.argv[1])
from helpers import Slave, run_loop
unzipdir, blob, times = sys.argv[2], bytes.fromhex(sys.argv[3]), json.loads(sys.argv[4])
s = Slave(unzipdir, "resumed")
state = s.fmu.deSerializeFMUstate(blob)
s.fmu.setFMUstate(state)
s.fmu.freeFMUstate(state)
out = run_loop(s, times)
print(json.dumps([[x.hex() for x in row] for row in out.tolist()]))
"""


def test_serialized_state_continues_identically_in_another_process(unzipdir):
    s = Slave(unzipdir)
    s.init()
    times = schedule(0.0, STOP, DT)
    run_loop(s, times[:300])
    state = s.fmu.getFMUstate()
    blob = s.fmu.serializeFMUstate(state)
    here = run_loop(s, times[299:500])
    s.fmu.freeFMUstate(state)
    s.free()
    helpers_dir = str(__import__("pathlib").Path(__file__).parent)
    proc = subprocess.run(
        [
            sys.executable,
            "-c",
            RESUME,
            helpers_dir,
            str(unzipdir),
            blob.hex(),
            json.dumps(times[299:500]),
        ],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 0, proc.stderr
    there = np.array([[float.fromhex(x) for x in row] for row in json.loads(proc.stdout)])
    assert np.array_equal(here, there)


def test_serialize_deserialize_in_the_same_instance(unzipdir):
    s = Slave(unzipdir)
    s.init()
    times = schedule(0.0, 0.02, DT)
    run_loop(s, times[:50])
    state = s.fmu.getFMUstate()
    blob = s.fmu.serializeFMUstate(state)
    assert s.fmu.serializeFMUstate(state) == blob
    first = run_loop(s, times[49:120])
    restored = s.fmu.deSerializeFMUstate(blob)
    s.fmu.setFMUstate(restored)
    second = run_loop(s, times[49:120])
    assert np.array_equal(first, second)
    s.fmu.freeFMUstate(restored)
    s.fmu.freeFMUstate(state)
    s.free()


def test_deserialize_into_another_instance_with_a_foreign_handle(unzipdir):
    """The slot of fmi2DeSerializeFMUstate may hold a handle of another instance (here the
    one the bytes come from): the receiving instance allocates its own handle and leaves the
    other instance's state alone."""
    from fmpy.fmi2 import fmi2FMUstate

    times = schedule(0.0, 0.02, DT)
    a, b = Slave(unzipdir, "a"), Slave(unzipdir, "b")
    a.init()
    run_loop(a, times[:40])
    state_a = a.fmu.getFMUstate()
    blob = a.fmu.serializeFMUstate(state_a)
    slot = fmi2FMUstate(state_a.value)
    state_b = b.fmu.deSerializeFMUstate(blob, slot)
    assert state_b.value not in (None, state_a.value)
    b.fmu.setFMUstate(state_b)
    out_b = run_loop(b, times[39:80])
    # A's state is untouched and still A's.
    a.fmu.setFMUstate(state_a)
    out_a = run_loop(a, times[39:80])
    assert np.array_equal(out_a, out_b)
    # B reuses its own handle when it is passed back.
    again = b.fmu.deSerializeFMUstate(blob, state_b)
    assert again.value == state_b.value
    # fmi2GetFMUstate with a foreign handle in the slot: a new handle as well.
    slot = fmi2FMUstate(state_a.value)
    b.fmu.fmi2GetFMUstate(b.fmu.component, __import__("ctypes").byref(slot))
    assert slot.value not in (None, state_a.value, state_b.value)
    b.fmu.freeFMUstate(slot)
    b.fmu.freeFMUstate(state_b)
    a.fmu.freeFMUstate(state_a)
    a.free()
    b.free()
