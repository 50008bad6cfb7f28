"""docs/usage.md's shell and Python snippets run as written.

- The C master (```sh block that compiles tests/c_master/master.c): run with bash in a scratch
  working directory that sees the checkout's `tests/` and `target/fmu/` (the FMU built by
  `cargo run --release -p fmu`), with TMPDIR in a scratch folder; it writes nothing but the
  temporary folder it makes, and the CSV it writes there has the outputs at every
  communication point.
- examples/fmi3_fmpy.py, the FMI 3.0 FMU through FMPy with the crank acceleration and jerk as
  inputs: FMPy finds every input in its table (no "missing input" warning), it prints what
  docs/usage.md shows, and its outputs are the core's own run of the same crank law.
"""

import importlib.util
import os
import re
import subprocess
import sys

import numpy as np
import pytest
from helpers import ROOT, assert_close, cargo, reference

FMU_DIR = ROOT / "target" / "fmu"
USAGE = ROOT / "docs" / "usage.md"
EXAMPLE = ROOT / "examples" / "fmi3_fmpy.py"

FENCE = re.compile(r"^[ \t]*```(\w*)[^\n]*\n(.*?)^[ \t]*```[ \t]*$", re.M | re.S)


def blocks(text, lang):
    """The bodies of the fenced blocks of `text` in language `lang`, their indentation removed."""
    out = []
    for m in FENCE.finditer(text):
        if m.group(1) != lang:
            continue
        lines = m.group(2).splitlines()
        indent = min(len(line) - len(line.lstrip()) for line in lines if line.strip())
        out.append("\n".join(line[indent:] for line in lines) + "\n")
    return out


def test_blocks_are_read_without_their_indentation():
    text = "- item:\n\n  ```sh\n  a\n    b\n  ```\n\n```python\nx\n```\n"
    assert blocks(text, "sh") == ["a\n  b\n"]
    assert blocks(text, "python") == ["x\n"]


@pytest.fixture(scope="module")
def fmu_dir():
    """target/fmu with both FMUs of the default scene."""
    if not (FMU_DIR / "FlexibleSliderCrank-fmi3.fmu").exists():
        cargo("run", "--release", "-q", "-p", "fmu")
    assert (FMU_DIR / "FlexibleSliderCrank.fmu").exists()
    return FMU_DIR


@pytest.fixture
def checkout_view(tmp_path, fmu_dir):
    """A working directory with the checkout's `tests` and `target/fmu` (symbolic links)."""
    work = tmp_path / "work"
    (work / "target").mkdir(parents=True)
    os.symlink(fmu_dir, work / "target" / "fmu")
    os.symlink(ROOT / "tests", work / "tests")
    return work


def test_c_master_snippet_runs_in_a_temporary_folder(checkout_view, tmp_path):
    (script,) = [b for b in blocks(USAGE.read_text(), "sh") if "tests/c_master/master.c" in b]
    temporary = tmp_path / "tmp"
    temporary.mkdir()
    before = sorted(p.name for p in checkout_view.iterdir())
    result = subprocess.run(
        ["bash", "-euo", "pipefail", "-c", script],
        cwd=checkout_view,
        env={**os.environ, "TMPDIR": str(temporary)},
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0, f"{script}\n{result.stdout}\n{result.stderr}"
    # Nothing written into the working directory (the checkout), everything into mktemp's.
    assert sorted(p.name for p in checkout_view.iterdir()) == before
    (made,) = list(temporary.iterdir())
    assert {"master", "unpacked", "out.csv"} <= {p.name for p in made.iterdir()}
    assert (made / "unpacked" / "modelDescription.xml").is_file()
    lines = (made / "out.csv").read_text().splitlines()
    assert lines[0] == "time,rod.deflection,crank.torque", lines[0]
    values = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    # The default experiment: 838 steps of 1e-4 s, the outputs at every point, finite.
    assert values.shape == (839, 3), values.shape
    assert np.isclose(values[-1, 0], 0.0838)
    assert np.isfinite(values).all() and np.abs(values[:, 1]).max() > 1e-4


def load_example():
    """examples/fmi3_fmpy.py as a module."""
    spec = importlib.util.spec_from_file_location("fmi3_fmpy", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_fmi3_example_sets_every_input_and_prints_what_usage_md_shows(fmu_dir):
    """examples/fmi3_fmpy.py gives FMPy every input of the FMI 3.0 FMU (no "missing input"
    warning, no warning of the FMU), and prints what docs/usage.md shows under its command."""
    fmu3 = fmu_dir / "FlexibleSliderCrank-fmi3.fmu"
    result = subprocess.run(
        [sys.executable, str(EXAMPLE), str(fmu3)], cwd=ROOT, capture_output=True, text=True
    )
    assert result.returncode == 0, result.stdout + result.stderr
    output = result.stdout + result.stderr
    assert "missing input" not in output, output
    assert "WARNING" not in output, output
    text = USAGE.read_text()
    command = ".venv/bin/python examples/fmi3_fmpy.py"
    fence = text.index("```text", text.index(command))
    shown = blocks(text[text.rfind("\n", 0, fence) + 1 :], "text")[0]
    assert result.stdout == shown, (
        f"the example prints\n{result.stdout}\ndocs/usage.md shows\n{shown}"
    )


def test_fmi3_example_runs_the_cores_constant_acceleration(fmu_dir, tmp_path):
    """The example's run through FMPy and the FMI 3.0 inputs equals the core's own run of the
    same crank law (the packager's --simulate --accel, from rest, the same design speed) to
    1e-9 of each output's peak."""
    example = load_example()
    result = example.run(fmu_dir / "FlexibleSliderCrank-fmi3.fmu")
    end_speed = example.SPEED + example.ACCELERATION * example.STOP
    scene = (ROOT / "scenes" / "benchmark.toml").read_text()
    assert "crank_speed = 150.0" in scene and "[crank]\n" in scene
    scene = scene.replace("crank_speed = 150.0", f"crank_speed = {example.SPEED!r}")
    scene = scene.replace("[crank]\n", f"[crank]\ndesign_speed = {end_speed!r}\n")
    path = tmp_path / "from_rest.toml"
    path.write_text(scene)
    core = reference(tmp_path / "core.csv", accel=example.ACCELERATION, scene=path)
    assert len(result) == len(core["time"]) == round(example.STOP / example.STEP) + 1
    np.testing.assert_allclose(result["time"], core["time"], rtol=0, atol=1e-12)
    for name in ["rod.deflection_rel", "pinB.force_x", "pinB.force_y"]:
        assert_close(result[name], core[name], rtol=1e-9, what=name)
    shape = result["rod.shape"]
    assert shape.shape == (len(result), 11)
    # The shape's midpoint is rod.deflection_rel times the rod's length (0.3048 m).
    np.testing.assert_allclose(shape[:, 5], result["rod.deflection_rel"] * 0.3048, atol=1e-12)
