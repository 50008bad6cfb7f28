"""Integer twins of the Enumeration parameters: rod.model_index and
rod.reference_index are a second name, of type Integer, for rod.model and rod.reference, so
that masters which ignore Enumeration variables can switch them. One value with two names:
setting either sets both, the last value set wins (also within one fmi2SetInteger call)."""

import pytest
from fmpy.fmi1 import FMICallException
from helpers import Slave

TWINS = {
    "rod.model": "rod.model_index",
    "rod.reference": "rod.reference_index",
    "rod.shear_deformation": "rod.shear_deformation_index",
    "rod.axial_dynamics": "rod.axial_dynamics_index",
}


@pytest.fixture
def slave(unzipdir):
    s = Slave(unzipdir)
    yield s
    s.free()


@pytest.fixture
def initializing(slave):
    """In initialization mode, where parameters can be both set and read."""
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.enterInitializationMode()
    return slave


def get_int(slave, *names):
    return slave.fmu.getInteger([slave.vr[n] for n in names])


def set_int(slave, **values):
    names = [n.replace("__", ".") for n in values]
    slave.fmu.setInteger([slave.vr[n] for n in names], list(values.values()))


def test_every_enumeration_parameter_has_an_integer_twin(slave):
    variables = {v.name: v for v in slave.md.modelVariables}
    enumerations = [
        v for v in slave.md.modelVariables if v.causality == "parameter" and v.type == "Enumeration"
    ]
    assert {v.name for v in enumerations} == set(TWINS)
    for v in enumerations:
        twin = variables[TWINS[v.name]]
        assert twin.type == "Integer"
        assert (twin.causality, twin.variability) == ("parameter", "fixed")
        assert twin.start == v.start
        items = v.declaredType.items
        assert (int(twin.min), int(twin.max)) == (1, len(items))
        # The description lists the codes with the item names.
        for item in items:
            assert f"{item.value} = {item.name}" in twin.description, twin.description
    # Every parameter is a Real, an Integer or an Enumeration with a twin (no Boolean or
    # String parameters exist).
    assert {v.type for v in slave.md.modelVariables if v.causality == "parameter"} <= {
        "Real",
        "Integer",
        "Enumeration",
    }


def test_the_last_value_set_wins(initializing):
    slave = initializing
    set_int(slave, rod__model=2)
    assert get_int(slave, "rod.model", "rod.model_index") == [2, 2]
    set_int(slave, rod__model_index=1)
    assert get_int(slave, "rod.model", "rod.model_index") == [1, 1]
    set_int(slave, rod__reference_index=3)
    assert get_int(slave, "rod.reference", "rod.reference_index") == [3, 3]
    set_int(slave, rod__reference=2)
    assert get_int(slave, "rod.reference", "rod.reference_index") == [2, 2]
    # Both in one call, in conflict: the later array entry wins.
    slave.fmu.setInteger([slave.vr["rod.model"], slave.vr["rod.model_index"]], [2, 1])
    assert get_int(slave, "rod.model", "rod.model_index") == [1, 1]
    slave.fmu.setInteger([slave.vr["rod.reference_index"], slave.vr["rod.reference"]], [4, 1])
    assert get_int(slave, "rod.reference", "rod.reference_index") == [1, 1]


def test_the_twin_switches_the_model(slave, unzipdir):
    """The frequencies of the model chosen through the twin are those of the model chosen
    through the Enumeration."""
    slave.fmu.setupExperiment(startTime=0.0)
    set_int(slave, rod__model_index=2, rod__reference_index=1)
    slave.fmu.enterInitializationMode()
    by_twin = slave.get("rod.frequency[1]")
    other = Slave(unzipdir, "other")
    other.fmu.setupExperiment(startTime=0.0)
    set_int(other, rod__model=2)
    other.fmu.enterInitializationMode()
    assert other.get("rod.frequency[1]") == by_twin
    set_int(other, rod__model=1)
    assert other.get("rod.frequency[1]") != by_twin
    other.free()


@pytest.mark.parametrize(
    "name, bad, allowed",
    [
        ("rod.model_index", 0, "1 (ffr), 2 (segments), 3 (modal_segments), 4 (auto)"),
        ("rod.model_index", 5, "1 (ffr), 2 (segments), 3 (modal_segments), 4 (auto)"),
        ("rod.reference_index", 5, "4 (cantilever)"),
    ],
)
def test_out_of_range_twin_rejected_nothing_set(initializing, name, bad, allowed):
    slave = initializing
    before = get_int(slave, "rod.model", "rod.reference")
    slave.log.clear()
    with pytest.raises(FMICallException):
        slave.fmu.setInteger([slave.vr["rod.elements"], slave.vr[name]], [10, bad])
    assert f"{name} = {bad}" in slave.log.text() and allowed in slave.log.text()
    assert get_int(slave, "rod.model", "rod.reference") == before
    assert get_int(slave, "rod.elements") == [8]


def test_twins_are_fixed_after_initialization(slave):
    slave.init()
    for name in TWINS.values():
        with pytest.raises(FMICallException):
            set_int(slave, **{name.replace(".", "__"): 1})
        assert "fixed parameter" in slave.log.last()
