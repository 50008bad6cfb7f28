"""Session fixtures: the packaged FMUs (built once through the packager) and the core's
reference results."""

import shutil

import pytest
from fmpy import extract

from helpers import ROOT, build_fmu, reference


@pytest.fixture(scope="session")
def fmu_path(tmp_path_factory):
    """The default FMU (scenes/benchmark.toml), built by `cargo run --release -p fmu`."""
    return build_fmu(tmp_path_factory.mktemp("fmu"))


@pytest.fixture(scope="session")
def unzipdir(fmu_path, tmp_path_factory):
    return extract(str(fmu_path), str(tmp_path_factory.mktemp("unzipped")))


@pytest.fixture(scope="session")
def segments_fmu(tmp_path_factory):
    """The benchmark rod with rod.model = "segments"; skipped if the core cannot build it."""
    text = (ROOT / "scenes" / "benchmark.toml").read_text()
    text = text.replace('model = "ffr"', 'model = "segments"')
    text = text.replace('name = "FlexibleSliderCrank"', 'name = "FlexibleSliderCrankSegments"')
    directory = tmp_path_factory.mktemp("segments")
    scene = directory / "segments.toml"
    scene.write_text(text)
    try:
        return build_fmu(directory, scene)
    except RuntimeError as e:
        pytest.skip(f"the segments rod model is not available from the core: {e}")


@pytest.fixture(scope="session")
def ref(tmp_path_factory):
    """The core's own results of the default experiment: ref(accel=0, steps=None)."""
    cache = {}
    directory = tmp_path_factory.mktemp("reference")

    def get(accel=0.0, steps=None):
        key = (accel, tuple(steps) if steps else None)
        if key not in cache:
            cache[key] = reference(directory / f"ref{len(cache)}.csv", accel, steps)
        return cache[key]

    return get


@pytest.fixture
def spaced_dir(tmp_path):
    """A directory whose path contains a space (and a percent sign)."""
    d = tmp_path / "dir with space %41"
    d.mkdir()
    yield d
    shutil.rmtree(d, ignore_errors=True)
