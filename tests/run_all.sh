#!/usr/bin/env bash
# The whole test suite: Rust unit and integration tests, then the packaged FMU through FMPy,
# libcosim and a C master, and the sweep tool on Dask.
#
# Python: creates .venv with python3 (3.11 or newer) on first use and installs into it fmpy,
# pytest, numpy, libcosimpy, dask[distributed], tqdm, matplotlib, setuptools (the build
# backend of python/) and ruff (the Python linter and formatter .ci/run calls) from PyPI, and
# the sweep tool python/ editable, every package (transitive ones included) at its version in
# tests/python/constraints.txt. It installs again whenever
# constraints.txt, python/pyproject.toml or the list below change (their hash is kept in
# .venv/flexrod-install.sha256). The C master of tests/c_master is compiled with gcc by the
# Python tests.
#
# Exudyn is not installed: no test imports it. The Exudyn reference script
# tests/data/automotive_reference.py (whose results are committed as CSV under tests/data/) is
# run by hand; its header says how (exudyn from PyPI).
set -euo pipefail
cd "$(dirname "$0")/.."

constraints=tests/python/constraints.txt
packages=(fmpy pytest numpy libcosimpy "dask[distributed]" tqdm matplotlib setuptools ruff)
imports="import fmpy, pytest, numpy, libcosimpy, dask.distributed, tqdm, matplotlib, ruff, flexrod_sweep"

if ! python3 -c 'import sys; sys.exit(sys.version_info < (3, 11))'; then
    echo "tests/run_all.sh: python3 is $(python3 --version 2>&1); the Python tests need 3.11 or newer" >&2
    exit 1
fi
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
stamp=.venv/flexrod-install.sha256
want=$( { printf '%s\n' "${packages[@]}"; cat "$constraints" python/pyproject.toml; } | sha256sum | cut -d' ' -f1)
if [ "$(cat "$stamp" 2>/dev/null)" != "$want" ] || ! .venv/bin/python -c "$imports" 2>/dev/null; then
    rm -f "$stamp"
    .venv/bin/python -m pip install --quiet --disable-pip-version-check -c "$constraints" --upgrade pip
    .venv/bin/python -m pip install --quiet --disable-pip-version-check -c "$constraints" \
        --build-constraint "$constraints" "${packages[@]}" -e python
    echo "$want" > "$stamp"
fi

cargo test --release --workspace
cargo run --release -p fmu
.venv/bin/python -m pytest tests/python -q
