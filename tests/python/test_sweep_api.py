"""The sweep tool's Python API and run control: a dict spec gives a pandas DataFrame (numeric
parameters and metrics, text status and message, run information in .attrs) and
results.parquet; time series of chosen runs; the per-run time limit; run ids that survive a
grown grid; the con-rod metrics against their formulas; Ctrl-C (exit code 130, finished rows
kept, no traceback) and the removal of the FMU's extraction folders."""

import glob
import math
import os
import signal
import subprocess
import sys
import tempfile
import time

import numpy as np
import pandas as pd
import pytest
from flexrod_sweep import Spec, SpecError, load_series, run_id, run_sweep
from flexrod_sweep.runner import TMP_PREFIX, compute_metrics, critical_load, goodman, parse_metric


def small(fmu, speeds=(150.0, 300.0), **extra):
    spec = {
        "name": "api",
        "fmu": {"path": str(fmu)},
        "parameters": {
            "crank.speed": list(speeds),
            "rod.model": ["ffr", "segments"],
            "rod.damping_ratio": 0.02,
            "rod.deflection_policy": 1,
        },
        "drive": {"start_time": 0.01, "transient_revolutions": 1, "measure_revolutions": 1},
        "metrics": {
            "list": [
                "max_abs(rod.deflection_rel)",
                "amplitude(crank.torque)",
                "midrange(crank.torque)",
                "at(crank.torque, 90)",
                "order(crank.torque, 2)",
            ],
            "abort": {"rod.deflection_rel": 0.5},
        },
    }
    for k, v in extra.items():
        spec.setdefault(k, {}).update(v)
    return spec


def mine():
    """Extraction folders of this process."""
    return glob.glob(os.path.join(tempfile.gettempdir(), f"{TMP_PREFIX}{os.getpid()}_*"))


def test_dict_spec_gives_a_dataframe_and_parquet(default_fmu, tmp_path):
    out = tmp_path / "out"
    df = run_sweep(
        small(default_fmu),
        out,
        workers=0,
        progress=False,
        plots=False,
        series=[{"crank.speed": 150.0, "rod.model": "ffr"}],
    )
    assert isinstance(df, pd.DataFrame) and len(df) == 4
    assert list(df["index"]) == [0, 1, 2, 3]
    for c in [
        "crank.speed",
        "rod.damping_ratio",
        "max_abs(rod.deflection_rel)",
        "amplitude(crank.torque)",
        "at(crank.torque, 90)",
        "rod.frequency[1]",
        "wall_time",
    ]:
        assert df[c].dtype == np.float64, (c, df[c].dtype)
    assert df["rod.deflection_policy"].dtype == np.int64
    for c in ["run", "rod.model", "status", "message"]:
        assert pd.api.types.is_string_dtype(df[c]), (c, df[c].dtype)
    assert set(df["status"]) <= {"ok", "warning"}, df[["status", "message"]]
    assert list(df["run"]) == [
        run_id(
            {
                "crank.speed": s,
                "rod.model": m,
                "rod.damping_ratio": 0.02,
                "rod.deflection_policy": 1,
            }
        )
        for s in (150.0, 300.0)
        for m in ("ffr", "segments")
    ]
    info = df.attrs
    assert info["runs"] == 4 and info["ran"] == 4 and info["fmu_guid"].startswith("{")
    assert (
        info["units"]["crank.speed"] == "rad/s"
        and info["units"]["amplitude(crank.torque)"] == "N.m"
    )
    # Shigley's amplitude and midrange: (max - min) / 2, (max + min) / 2, both finite.
    assert (df["amplitude(crank.torque)"] > 0).all() and np.isfinite(
        df["midrange(crank.torque)"]
    ).all()
    back = pd.read_parquet(out / "results.parquet")
    pd.testing.assert_frame_equal(back, df.drop(columns=[]), check_like=False, check_dtype=False)
    assert list(back.dtypes) == list(df.dtypes)
    # The time series of the chosen run: every output from t = 0 on, transient included.
    ((rid, path),) = info["series"].items()
    assert rid == df["run"][0]
    ts = load_series(out, rid)
    assert {"time", "crank.angle", "rod.deflection_rel", "crank.torque"} <= set(ts.columns)
    assert ts["time"].iloc[0] == 0 and np.all(np.diff(ts["time"]) > 0)
    # Its measured part gives the sweep's metric exactly (the same deterministic run).
    period = 2 * math.pi / 150.0
    n = len(ts)
    n_meas = math.ceil(period / 1e-4 - 1e-9) + 1
    assert (
        ts["rod.deflection_rel"].abs().iloc[n - n_meas :].max()
        == df["max_abs(rod.deflection_rel)"][0]
    )
    assert not mine(), mine()


def test_timeout_ends_a_run_and_the_sweep_goes_on(default_fmu, tmp_path):
    # 2 rad/s: 3 revolutions of 31416 steps each, about 1 s; 150 rad/s: 1257 steps, 0.02 s.
    spec = small(default_fmu, speeds=(2.0, 150.0), run={"timeout": 0.2})
    spec["parameters"]["rod.model"] = ["ffr"]
    spec["drive"]["measure_revolutions"] = 2
    t0 = time.perf_counter()
    df = run_sweep(spec, tmp_path / "out", workers=0, progress=False, plots=False)
    assert time.perf_counter() - t0 < 20
    slow, fast = df.iloc[0], df.iloc[1]
    assert slow["status"] == "timeout", df[["status", "message"]]
    assert "time limit of 0.2 s" in slow["message"] and math.isnan(slow["amplitude(crank.torque)"])
    assert slow["wall_time"] < 0.5
    assert fast["status"] in ("ok", "warning") and fast["amplitude(crank.torque)"] > 0
    # A rerun keeps the timeout (a result, not an infrastructure failure).
    df2 = run_sweep(spec, tmp_path / "out", workers=0, progress=False, plots=False)
    assert df2.attrs["ran"] == 0


def test_grown_grid_keeps_ids_and_runs_only_new_points(default_fmu, tmp_path):
    out = tmp_path / "out"
    first = run_sweep(
        small(default_fmu, speeds=(150.0, 300.0)), out, workers=0, progress=False, plots=False
    )
    # (A Spec object this time: the third form run_sweep takes.)
    grown = run_sweep(
        Spec(small(default_fmu, speeds=(100.0, 150.0, 200.0, 300.0)), tmp_path),
        out,
        workers=0,
        progress=False,
        plots=False,
    )
    assert grown.attrs["ran"] == 4 and grown.attrs["skipped"] == 4
    assert len(grown) == 8 and grown["run"].is_unique
    assert list(grown["index"]) == list(range(8))
    old = grown.set_index("run").loc[list(first["run"])]
    assert list(old["max_abs(rod.deflection_rel)"]) == list(first["max_abs(rod.deflection_rel)"])


def test_bad_run_options_are_rejected(default_fmu, tmp_path):
    with pytest.raises(SpecError, match=r"\[run\] timeout"):
        run_sweep(
            small(default_fmu, run={"timeout": -1}), tmp_path / "a", workers=0, progress=False
        )
    spec = small(default_fmu)
    spec["metrics"]["list"] = ["goodman(rod.deflection_rel)"]
    with pytest.raises(SpecError, match=r"\[material\] needs endurance_strength"):
        run_sweep(spec, tmp_path / "b", workers=0, progress=False)
    spec["metrics"]["list"] = ["at(crank.torque)"]
    with pytest.raises(SpecError, match="at takes an output and a number"):
        run_sweep(spec, tmp_path / "c", workers=0, progress=False)
    spec["metrics"]["list"] = ["amplitude(section.stress)"]
    with pytest.raises(SpecError, match=r"section.stress needs \[section\]|the FMU lacks"):
        run_sweep(spec, tmp_path / "d", workers=0, progress=False)


def test_con_rod_metrics_follow_their_formulas():
    # One revolution sampled at 360 points: x = 5 + 3 cos(2 theta) + 1 sin(theta).
    theta = np.linspace(0, 2 * math.pi, 361)
    x = 5 + 3 * np.cos(2 * theta) + np.sin(theta)
    s = {"x": x, "crank.angle": theta, "s": np.stack([x * 1e6, -x * 1e6], axis=1)}
    props = {"material": {"endurance_strength": 2e8, "ultimate_strength": 8e8}}
    m = compute_metrics(
        [
            "order(x, 2)",
            "order(x, 1)",
            "order(x, 3)",
            "at(x, 90)",
            "amplitude(x)",
            "midrange(x)",
            "goodman(s)",
            "amplitude(s)",
        ],
        s,
        [0, 360],
        props,
    )
    assert m["order(x, 2)"] == pytest.approx(3, rel=1e-9)
    assert m["order(x, 1)"] == pytest.approx(1, rel=1e-9)
    assert m["order(x, 3)"] == pytest.approx(0, abs=1e-9)
    assert m["at(x, 90)"] == pytest.approx(5 - 3 + 1, rel=1e-9)
    hi, lo = x.max(), x.min()
    assert m["amplitude(x)"] == pytest.approx((hi - lo) / 2) and m["midrange(x)"] == pytest.approx(
        (hi + lo) / 2
    )
    # Goodman (Shigley): tension mean 1/n = sa/Se + sm/Su; compressive mean n = Se/sa; the
    # two fibres: the smaller factor.
    sa, sm = (hi - lo) / 2 * 1e6, (hi + lo) / 2 * 1e6
    assert m["goodman(s)"] == pytest.approx(min(1 / (sa / 2e8 + sm / 8e8), 2e8 / sa))
    assert goodman(1e8, -5e7, props["material"]) == pytest.approx(2.0)
    assert goodman(1e8, 4e8, props["material"]) == pytest.approx(1 / (0.5 + 0.5))
    # Buckling: Euler for a slender column, Johnson's parabola below the transition slenderness.
    col = {
        "youngs_modulus": 2e11,
        "area_moment": 1e-9,
        "area": 1e-4,
        "length": 1.0,
        "end_factor": 1.0,
    }
    euler = math.pi**2 * 2e11 * 1e-9 / 1.0
    assert critical_load({"buckling": col, "material": {"yield_strength": 6e8}}) == pytest.approx(
        euler
    )
    short = {**col, "length": 0.1}
    r = math.sqrt(1e-9 / 1e-4)
    johnson = 1e-4 * (6e8 - (6e8 * 0.1 / (2 * math.pi * r)) ** 2 / 2e11)
    assert critical_load({"buckling": short, "material": {"yield_strength": 6e8}}) == pytest.approx(
        johnson
    )
    assert johnson < math.pi**2 * 2e11 * 1e-9 / 0.01
    assert parse_metric("order(crank.torque, 0.5)") == ("order", "crank.torque", 0.5)


CTRL_C = """
import sys
from flexrod_sweep.__main__ import main
sys.exit(main(sys.argv[1:]))
"""


@pytest.mark.parametrize("workers", ["0", "2"])
def test_ctrl_c_exits_130_and_keeps_the_finished_rows(default_fmu, tmp_path, workers):
    import tomllib  # noqa: F401  (the spec below is TOML)

    spec = tmp_path / "spec.toml"
    spec.write_text(f"""
name = "interrupt"
[fmu]
path = "{default_fmu}"
[parameters]
"crank.speed" = {{ linspace = [100, 300, 600] }}
"rod.deflection_policy" = 1
[drive]
transient_revolutions = 1
measure_revolutions = 40
""")
    out = tmp_path / "out"
    before = set(glob.glob(os.path.join(tempfile.gettempdir(), TMP_PREFIX + "*")))
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "flexrod_sweep",
            str(spec),
            "--out",
            str(out),
            "--workers",
            workers,
            "--no-progress",
            "--no-plots",
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
        # A shell without job control (a CI script, `cmd &`) starts its
        # background jobs with SIGINT ignored, and a Python started so
        # ignores Ctrl-C: give the child the terminal's default.
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    try:
        deadline = time.time() + 120
        while time.time() < deadline:
            p = out / "results.csv"
            if p.exists() and len(p.read_text().splitlines()) >= 4:
                break
            time.sleep(0.05)
        else:
            raise AssertionError("no rows written in 120 s")
        os.killpg(proc.pid, signal.SIGINT)  # Ctrl-C in a terminal: the whole process group
        stdout, stderr = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert proc.returncode == 130, (stdout, stderr)
    assert "interrupted:" in stderr and "Traceback" not in stderr, stderr
    rows = pd.read_parquet(out / "results.parquet")
    # 600 runs of 41 revolutions take tens of seconds: the interrupt comes long before the end.
    assert 3 <= len(rows) < 600 and rows["run"].is_unique
    assert set(rows["status"]) <= {"ok", "warning"}
    # No extraction folder of the interrupted process or its workers is left behind (folders
    # made during the test whose process has ended).
    time.sleep(0.5)
    made = set(glob.glob(os.path.join(tempfile.gettempdir(), TMP_PREFIX + "*"))) - before
    left = [d for d in made if not os.path.exists(f"/proc/{d.split(TMP_PREFIX)[1].split('_')[0]}")]
    assert not left, left


def test_charts_have_units_and_a_map_for_two_continuous_parameters(default_fmu, tmp_path):
    """A resonance chart over a Latin hypercube in speed x slider mass becomes one contour map
    (not a series per mass); every axis names its unit; failed runs are in the legend."""
    spec = small(default_fmu, speeds=(100.0, 150.0, 200.0, 250.0, 300.0, 600.0))
    spec["parameters"]["rod.model"] = "ffr"
    spec["parameters"]["rod.deflection_policy"] = 2  # 600 rad/s: refused (discard)
    spec["parameters"]["slider.mass"] = {"range": [0.0, 0.5]}
    spec["sampling"] = {"samples": 8, "seed": 1}
    spec["plots"] = {
        "resonance": {"x": "crank.speed", "metric": "max_abs(rod.deflection_rel)"},
        "heatmap": {
            "x": "crank.speed",
            "y": "slider.mass",
            "metric": "amplitude(crank.torque)",
            "contour": 20.0,
            "file": "map.svg",
        },
    }
    df = run_sweep(spec, tmp_path / "out", workers=0, progress=False)
    assert len(df) == 48 and (df["status"] == "discard").any()
    for name in ("resonance.svg", "map.svg"):
        svg = (tmp_path / "out" / name).read_text()
        for label in ("crank.speed (rad/s)", "slider.mass (kg)", "discard ("):
            assert label in svg, (name, label)
    assert "amplitude(crank.torque) (N.m)" in (tmp_path / "out" / "map.svg").read_text()
    assert "contour: amplitude(crank.torque) = 20" in (tmp_path / "out" / "map.svg").read_text()
