"""The README's Python quick start runs as written.

Every ```python block of README.md is executed, in order and in one namespace (like a reader
pasting them into one interpreter), in a temporary directory where `target/fmu/` is the checkout's
(the FMU built by `cargo run --release -p fmu`), with matplotlib's Agg backend. A block followed
(after one line of prose) by a ```text block must print exactly that text; files a block says it
wrote ("wrote NAME") must exist and not be empty.
"""

import contextlib
import io
import os
import re

import matplotlib
import pytest
from helpers import ROOT, cargo

matplotlib.use("Agg")

FMU = ROOT / "target" / "fmu" / "FlexibleSliderCrank.fmu"

FENCE = re.compile(r"^```(\w*)[^\n]*\n(.*?)^```[ \t]*$", re.M | re.S)


def readme_blocks(text):
    """[(code, expected output or None)] of the ```python blocks of `text`, in order. The
    expected output is the ```text block that follows a python block with at most one
    paragraph of prose between them and no other block."""
    fences = [(m.group(1), m.group(2), m.start(), m.end()) for m in FENCE.finditer(text)]
    blocks = []
    for k, (lang, body, _, end) in enumerate(fences):
        if lang != "python":
            continue
        expected = None
        if k + 1 < len(fences) and fences[k + 1][0] == "text":
            between = text[end : fences[k + 1][2]]
            if len(between.strip().splitlines()) <= 1:
                expected = fences[k + 1][1]
        blocks.append((body, expected))
    return blocks


def test_the_parser_pairs_blocks_with_their_output():
    text = (
        "intro\n```python\nprint(1)\n```\n\nprints\n\n```text\n1\n```\n"
        "```sh\nls\n```\n```python\nx = 2\n```\n\nSome prose.\n\nMore prose.\n\n```text\nno\n```\n"
    )
    assert readme_blocks(text) == [("print(1)\n", "1\n"), ("x = 2\n", None)]


@pytest.fixture(scope="module")
def fmu():
    if not FMU.exists():
        cargo("run", "--release", "-q", "-p", "fmu")
    assert FMU.exists(), f"{FMU} was not built"
    return FMU


def test_readme_python_blocks_run_and_print_what_the_readme_says(fmu, tmp_path, monkeypatch):
    blocks = readme_blocks((ROOT / "README.md").read_text())
    assert blocks, "README.md has no ```python block"
    assert any(expected for _, expected in blocks), "no block states its output"
    (tmp_path / "target").mkdir()
    os.symlink(fmu.parent, tmp_path / "target" / "fmu")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    namespace = {"__name__": "__readme__"}
    for k, (code, expected) in enumerate(blocks, start=1):
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            exec(compile(code, f"README.md python block {k}", "exec"), namespace)
        printed = out.getvalue()
        print(f"--- block {k} printed:\n{printed}")
        if expected is not None:
            assert printed == expected, (
                f"README.md python block {k} printed\n{printed}\ninstead of\n{expected}"
            )
        for name in re.findall(r"^wrote (\S+)$", printed, re.M):
            path = tmp_path / name
            assert path.is_file() and path.stat().st_size > 0, f"block {k}: {name} not written"
