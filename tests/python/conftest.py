"""Fixtures built once per test run: the packaged FMUs (through the packager) and the core's
reference results."""

import shutil
import subprocess

import pytest
from fmpy import extract
from helpers import ROOT, build_fmu, reference

# Every FMU test runs on both rod models (the segments FMU passes the same tests).
MODELS = ["ffr", "segments"]


@pytest.fixture(scope="session", params=MODELS)
def model(request):
    return request.param


@pytest.fixture(scope="session")
def scene_path(model, tmp_path_factory):
    """The scene of the FMU under test: scenes/benchmark.toml, or the same rod as a segment
    chain (rod.model = "segments", as many segments as the scene has elements)."""
    if model == "ffr":
        return ROOT / "scenes" / "benchmark.toml"
    text = (ROOT / "scenes" / "benchmark.toml").read_text()
    assert 'model = "auto"' in text
    text = text.replace('model = "auto"', 'model = "segments"')
    text = text.replace('name = "FlexibleSliderCrank"', 'name = "FlexibleSliderCrankSegments"')
    scene = tmp_path_factory.mktemp("segments") / "segments.toml"
    scene.write_text(text)
    return scene


@pytest.fixture(scope="session")
def fmu_path(scene_path, tmp_path_factory):
    """The FMU of the scene under test, built by `cargo run --release -p fmu -- SCENE`."""
    return build_fmu(tmp_path_factory.mktemp("fmu"), scene_path)


@pytest.fixture(scope="session")
def unzipdir(fmu_path, tmp_path_factory):
    return extract(str(fmu_path), str(tmp_path_factory.mktemp("unzipped")))


@pytest.fixture(scope="session")
def default_fmu(tmp_path_factory):
    """The default FMU (scenes/benchmark.toml) alone, for the engine coupling tests."""
    return build_fmu(tmp_path_factory.mktemp("default_fmu"))


@pytest.fixture(scope="session")
def default_unzipdir(default_fmu, tmp_path_factory):
    return extract(str(default_fmu), str(tmp_path_factory.mktemp("default_unzipped")))


@pytest.fixture(scope="session")
def segments_fmu(tmp_path_factory):
    """The benchmark rod as a segment chain, for tests that compare the two models."""
    text = (ROOT / "scenes" / "benchmark.toml").read_text()
    assert 'model = "auto"' in text
    text = text.replace('model = "auto"', 'model = "segments"')
    text = text.replace('name = "FlexibleSliderCrank"', 'name = "FlexibleSliderCrankSegments"')
    directory = tmp_path_factory.mktemp("segments_fmu")
    scene = directory / "segments.toml"
    scene.write_text(text)
    return build_fmu(directory, scene)


@pytest.fixture(scope="session")
def ref(scene_path, tmp_path_factory):
    """The core's own results of the scene's default experiment: ref(accel=0, steps=None)."""
    cache = {}
    directory = tmp_path_factory.mktemp("reference")

    def get(accel=0.0, steps=None):
        key = (accel, tuple(steps) if steps else None)
        if key not in cache:
            cache[key] = reference(directory / f"ref{len(cache)}.csv", accel, steps, scene_path)
        return cache[key]

    return get


@pytest.fixture
def spaced_dir(tmp_path):
    """A directory whose path contains a space (and a percent sign)."""
    d = tmp_path / "dir with space %41"
    d.mkdir()
    yield d
    shutil.rmtree(d, ignore_errors=True)


@pytest.fixture(scope="session")
def c_master(tmp_path_factory):
    """tests/c_master/master.c compiled with gcc: a fixed-step master that declares the stop
    time in fmi2SetupExperiment (see the file's header for its arguments)."""
    source = ROOT / "tests" / "c_master" / "master.c"
    binary = tmp_path_factory.mktemp("c_master") / "master"
    command = [
        "gcc",
        "-std=c99",
        "-O1",
        "-Wall",
        "-Wextra",
        "-Werror",
        "-o",
        str(binary),
        str(source),
        "-ldl",
        "-lm",
    ]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{result.stdout}\n{result.stderr}")
    return binary
