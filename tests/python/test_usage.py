"""docs/usage.md's shell and Python snippets run as written.

- The C master (```sh block that compiles tests/c_master/master.c): run with bash in a scratch
  working directory that sees the checkout's `tests/` and `target/fmu/` (the FMU built by
  `cargo run --release -p fmu`), with TMPDIR in a scratch folder; it writes nothing but the
  temporary folder it makes, and the CSV it writes there has the outputs at every
  communication point.
"""

import os
import re
import subprocess

import numpy as np
import pytest
from helpers import ROOT, cargo

FMU_DIR = ROOT / "target" / "fmu"
USAGE = ROOT / "docs" / "usage.md"

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
