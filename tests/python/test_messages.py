"""Every message the FMU sends to the importer's logger reads as text meant for a user: no
Rust debug formatting of optional values ("Some(...)", "None") leaks into it.
Messages are collected through fmpy's logger callback, with every log category on."""

import math

import pytest
from fmpy import simulate_fmu
from fmpy.fmi1 import FMICallException
from helpers import DT, STOP, Slave, restore_fmpy_default_logger, run_loop, schedule

LEAKS = ("Some(", "None")


def assert_clean(messages):
    assert messages, "no message was logged"
    for text in messages:
        for leak in LEAKS:
            assert leak not in text, f"{leak!r} in the message {text!r}"


@pytest.mark.parametrize("values", [{}, {"rod.model_index": 2}, {"rod.modes": 0}])
def test_messages_of_a_run_read_as_text(fmu_path, values):
    messages = []

    def logger(component, instance_name, status, category, message):
        messages.append(message.decode("utf-8", "replace").replace("%%", "%"))

    simulate_fmu(
        str(fmu_path),
        start_values=values,
        step_size=DT,
        output_interval=DT,
        stop_time=STOP,
        relative_tolerance=1e-6,
        debug_logging=True,
        logger=logger,
    )
    restore_fmpy_default_logger()
    assert any("initialized at t = 0" in m for m in messages), messages
    assert any("lowest natural frequency" in m and " Hz" in m for m in messages), messages
    assert_clean(messages)


def test_messages_of_rejected_calls_read_as_text(unzipdir):
    s = Slave(unzipdir, logging_on=True)
    calls = [
        lambda: s.fmu.getReal([s.vr["rod.deflection"]]),  # not readable in Instantiated
        lambda: s.fmu.setReal([9999], [1.0]),
        lambda: s.fmu.setInteger([s.vr["rod.model_index"]], [7]),
        lambda: s.fmu.setReal([s.vr["rod.length"]], [math.nan]),
    ]
    for call in calls:
        with pytest.raises(FMICallException):
            call()
    s.init(stop=0.001)
    run_loop(s, schedule(0.0, 0.0005, 1e-4))
    for call in [
        lambda: s.fmu.doStep(0.0005, 0.002),  # past stopTime
        lambda: s.fmu.doStep(0.1, 1e-4),  # not the FMU time
        lambda: s.fmu.setReal([s.vr["rod.length"]], [0.3]),  # fixed after initialization
        lambda: s.fmu.getIntegerStatus(0),
        lambda: s.fmu.setRealInputDerivatives([s.vr["crank.speed"]], [0], [1.0]),
    ]:
        with pytest.raises(FMICallException):
            call()
    s.fmu.setRealInputDerivatives([s.vr["slider.force"]], [1], [2.0])  # warning
    s.fmu.terminate()
    s.fmu.reset()
    s.free()
    assert len(s.log.messages) >= 9
    assert_clean([text for _, _, text in s.log.messages])
