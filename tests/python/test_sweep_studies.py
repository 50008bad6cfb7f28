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
    return build_fmu(
        tmp_path_factory.mktemp("automotive_fmu"), ROOT / "scenes" / "automotive_rod.toml"
    )


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


def stale(study, fmu, tmp_path, spec=None):
    """What differs between the committed study in folder `study` and a rerun of a handful of
    its rows with `fmu`: a list of lines (empty: the study is current)."""
    from fmpy import read_model_description

    meta = json.loads((study / "sweep.json").read_text())
    guid = read_model_description(str(fmu)).guid
    if guid != meta["fmu_guid"]:
        return [
            f"made by an FMU with GUID {meta['fmu_guid']}; the current FMU's is {guid} "
            "(another model description)"
        ]
    with open(study / "results.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    chosen = pick(rows)
    assert {r["status"] for r in rows} == {r["status"] for r in chosen}
    spec = spec or (study / meta["spec"]).resolve()
    df = run_sweep(
        spec,
        tmp_path / "out",
        fmu=fmu,
        only=[r["run"] for r in chosen],
        workers=0,
        progress=False,
        plots=False,
    )
    now = df.set_index("run")
    fixed = ("run", "index", "status", "message", "wall_time")
    numeric = [
        c for c in meta["columns"] if c not in fixed and ("(" in c or c.startswith("rod.frequency"))
    ]
    scale = {
        c: max((abs(float(r[c])) for r in rows if math.isfinite(float(r[c]))), default=0.0)
        for c in numeric
    }
    problems = []
    for r in chosen:
        got = now.loc[r["run"]]
        where = f"run {r['run']} (index {r['index']})"
        if got["status"] != r["status"]:
            problems.append(
                f"{where}: status {got['status']} ({got['message']}), committed {r['status']}"
            )
            continue
        for c in numeric:
            a, b = float(got[c]), float(r[c])
            if math.isnan(a) and math.isnan(b):
                continue
            if not (abs(a - b) <= RTOL * scale[c]):
                problems.append(f"{where}: {c} = {a!r}, committed {b!r}")
    return problems


def fmu_of(meta, default_fmu, automotive_fmu):
    return {"FlexibleSliderCrank": default_fmu, "AutomotiveRod": automotive_fmu}[meta["model"]]


@pytest.mark.parametrize("name", NAMES)
def test_committed_study_matches_the_current_fmu(name, default_fmu, automotive_fmu, tmp_path):
    study = STUDIES / name
    meta = json.loads((study / "sweep.json").read_text())
    regen = (
        f"cargo run --release -p fmu && .venv/bin/flexrod-sweep regenerate docs/sweeps/{name}"
        " (then update docs/sweeps.md from the new results)"
    )
    problems = stale(study, fmu_of(meta, default_fmu, automotive_fmu), tmp_path)
    assert not problems, (
        f"docs/sweeps/{name} no longer matches the current FMU (tolerance {RTOL:g} of each column's "
        "largest value):\n  " + "\n  ".join(problems[:10]) + f"\nRegenerate: {regen}"
    )


def test_a_changed_result_is_caught(default_fmu, tmp_path):
    """The check itself: a copy of the stability study with one metric changed by 0.1 % and one
    status changed is reported stale, naming both rows."""
    import shutil

    study = tmp_path / "study"
    shutil.copytree(STUDIES / "stability_map", study)
    with open(study / "results.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    chosen = pick(rows)
    ok = next(r for r in chosen if r["status"] == "ok")
    warn = next(r for r in chosen if r["status"] == "warning")
    for r in rows:
        if r["run"] == ok["run"]:
            r["max_abs(rod.deflection_rel)"] = repr(float(r["max_abs(rod.deflection_rel)"]) * 1.001)
        if r["run"] == warn["run"]:
            r["status"] = "timeout"  # a status of its own: picked for the rerun
    with open(study / "results.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    spec = ROOT / "python" / "specs" / "stability_map.toml"
    problems = stale(study, default_fmu, tmp_path, spec=spec)
    assert any(ok["run"] in p and "max_abs(rod.deflection_rel)" in p for p in problems), problems
    assert any(
        warn["run"] in p and "status warning" in p and "committed timeout" in p for p in problems
    ), problems


def test_regenerate_makes_a_study_anew(default_fmu, tmp_path):
    """`flexrod-sweep regenerate DIR` reruns every study under DIR from the spec its sweep.json
    names: the same rows, the FMU's GUID recorded, the charts drawn again."""
    import subprocess
    import sys

    spec = tmp_path / "spec.toml"
    spec.write_text(f"""
name = "tiny"
[fmu]
path = "{default_fmu}"
[parameters]
"crank.speed" = [120.0, 180.0]
[drive]
transient_revolutions = 1
measure_revolutions = 1
[metrics]
list = ["max_abs(rod.deflection_rel)"]
[plots]
resonance = {{ x = "crank.speed", metric = "max_abs(rod.deflection_rel)" }}
""")
    study = tmp_path / "studies" / "tiny"
    first = run_sweep(spec, study, workers=0, progress=False)
    (study / "resonance.svg").unlink()
    (study / "results.csv").write_text("stale\n")
    res = subprocess.run(
        [
            sys.executable,
            "-m",
            "flexrod_sweep",
            "regenerate",
            str(tmp_path / "studies"),
            "--workers",
            "0",
            "--no-progress",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert res.returncode == 0, res.stderr
    assert "2 runs: 2 ran" in res.stdout, res.stdout
    meta = json.loads((study / "sweep.json").read_text())
    from fmpy import read_model_description

    assert meta["fmu_guid"] == read_model_description(str(default_fmu)).guid
    assert (study / meta["spec"]).resolve() == spec.resolve()
    assert (study / "resonance.svg").exists()
    with open(study / "results.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [r["max_abs(rod.deflection_rel)"] for r in rows] == [
        repr(x) for x in first["max_abs(rod.deflection_rel)"]
    ]
