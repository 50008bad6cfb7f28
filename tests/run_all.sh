#!/usr/bin/env bash
# The whole test suite: Rust unit and integration tests, then the packaged FMU through FMPy,
# libcosim and a C master, and the sweep tool on Dask.
# Creates .venv (fmpy, pytest, numpy, libcosimpy, dask[distributed], tqdm, matplotlib from PyPI;
# the sweep tool python/ installed editable) on first use; the C master of tests/c_master is
# compiled with gcc by the Python tests.
set -euo pipefail
cd "$(dirname "$0")/.."

if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
if ! .venv/bin/python -c "import fmpy, pytest, numpy, libcosimpy, dask.distributed, tqdm, matplotlib, exudyn, flexrod_sweep" 2>/dev/null; then
    .venv/bin/python -m pip install --quiet --upgrade pip
    .venv/bin/python -m pip install --quiet fmpy pytest numpy libcosimpy "dask[distributed]" tqdm matplotlib exudyn -e python
fi

cargo test --release --workspace
cargo run --release -p fmu
.venv/bin/python -m pytest tests/python -q
