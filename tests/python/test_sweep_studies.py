"""The studies committed under docs/sweeps/ still describe the current FMU: for each study, a
handful of its rows (covering every status it has: ok, warning, diverged, ...) run again with
the FMU built from this checkout must give the committed status and metrics (to 1e-6 of the
column's largest magnitude), and the model description's GUID must be the one the study
recorded. A failure names the command that makes the study anew."""

import csv
import json
import math

import pytest

from flexrod_sweep import run_sweep
from helpers import ROOT, build_fmu

STUDIES = ROOT / "docs" / "sweeps"
NAMES = sorted(p.parent.name for p in STUDIES.glob("*/sweep.json"))
RTOL = 1e-6


@pytest.fixture(scope="module")
def automotive_fmu(tmp_path_factory):
    return build_fmu(tmp_path_factory.mktemp("automotive_fmu"), ROOT / "scenes" / "automotive_rod.toml")


def pick(rows):
    """Rows to rerun: the first, middle and last ok row, and the first and last row of every
    other status."""
    by = {}
    for r in rows:
        by.setdefault(r["status"], []).append(r)
    chosen = []
    for status, rs in sorted(by.items()):
        idx = [0, len(rs) // 2, len(rs) - 1] if status == "ok" else [0, len(rs) - 1]
        for i in dict.fromkeys(idx):
            chosen.append(rs[i])
    return chosen


def test_every_committed_study_is_checked():
    assert {"benchmark_resonance", "stability_map", "automotive_fatigue"} <= set(NAMES), NAMES


@pytest.mark.parametrize("name", NAMES)
def test_committed_study_matches_the_current_fmu(name, default_fmu, automotive_fmu, tmp_path):
    from fmpy import read_model_description

    study = STUDIES / name
    meta = json.loads((study / "sweep.json").read_text())
    regen = (f"cargo run --release -p fmu && .venv/bin/flexrod-sweep regenerate docs/sweeps/{name}"
             " (then update docs/sweeps.md from the new results)")
    fmu = {"FlexibleSliderCrank": default_fmu, "AutomotiveRod": automotive_fmu}[meta["model"]]
    guid = read_model_description(str(fmu)).guid
    assert guid == meta["fmu_guid"], (
        f"docs/sweeps/{name} was made by an FMU with GUID {meta['fmu_guid']}; the current FMU's is "
        f"{guid} (another model description). Regenerate: {regen}")
    with open(study / "results.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    chosen = pick(rows)
    statuses = {r["status"] for r in rows}
    assert statuses == {r["status"] for r in chosen}
    spec = (study / meta["spec"]).resolve()
    df = run_sweep(spec, tmp_path / "out", fmu=fmu, only=[r["run"] for r in chosen], workers=0,
                   progress=False, plots=False)
    now = df.set_index("run")
    numeric = [c for c in meta["columns"]
               if c not in ("run", "index", "status", "message", "wall_time") and "(" in c or c.startswith("rod.frequency")]
    scale = {c: max((abs(float(r[c])) for r in rows if math.isfinite(float(r[c]))), default=0.0)
             for c in numeric}
    problems = []
    for r in chosen:
        got = now.loc[r["run"]]
        where = f"run {r['run']} (index {r['index']})"
        if got["status"] != r["status"]:
            problems.append(f"{where}: status {got['status']} ({got['message']}), committed {r['status']}")
            continue
        for c in numeric:
            a, b = float(got[c]), float(r[c])
            if math.isnan(a) and math.isnan(b):
                continue
            if not (abs(a - b) <= RTOL * scale[c]):
                problems.append(f"{where}: {c} = {a!r}, committed {b!r}")
    assert not problems, (
        f"docs/sweeps/{name} no longer matches the current FMU ({len(problems)} differences in "
        f"{len(chosen)} rerun rows, tolerance {RTOL:g} of each column's largest value):\n  "
        + "\n  ".join(problems[:10]) + f"\nRegenerate: {regen}")
