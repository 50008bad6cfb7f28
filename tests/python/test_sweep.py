"""The sweep tool (python/flexrod_sweep): bad specs rejected before any run, failed runs
kept as rows, resumable results, and the same metrics, bit for bit, in this process and on a
dask.distributed cluster (scheduler and two workers as separate processes, loopback only); the
installed console script `flexrod-sweep`."""

import csv
import os
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
from flexrod_sweep import SpecError, load, run_sweep

BIN = Path(sys.executable).parent

SMALL = """
name = "small"
[fmu]
path = "{fmu}"
[parameters]
"crank.speed" = {{ linspace = [150, 450, 4] }}
"rod.model" = ["ffr", "segments"]
"rod.damping_ratio" = 0.02
[drive]
start_time = 0.01
transient_revolutions = 1
measure_revolutions = 1
step = 1e-4
[metrics]
list = ["max_abs(rod.deflection_rel)", "mean(crank.torque)", "range(pinB.force_x)", "mean(rod.axial_force)"]
abort = {{ "rod.deflection_rel" = 0.5 }}
"""


def write_spec(tmp_path, text, name="spec.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def cli(*args, check=True):
    res = subprocess.run(
        [sys.executable, "-m", "flexrod_sweep", *map(str, args), "--no-progress"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    if check and res.returncode != 0:
        raise AssertionError(f"flexrod_sweep failed:\n{res.stdout}\n{res.stderr}")
    return res


@pytest.mark.parametrize(
    "edit, message",
    [
        (
            ('"rod.damping_ratio" = 0.02', '"rod.dampingratio" = 0.02'),
            "unknown variable 'rod.dampingratio'",
        ),
        (
            ('"rod.damping_ratio" = 0.02', '"rod.damping_ratio" = [0.02, -0.01]'),
            "outside its range",
        ),
        (
            ('"rod.damping_ratio" = 0.02', '"rod.elements" = [8, 5000]'),
            "outside its range [2.0, 128.0]",
        ),
        (('["ffr", "segments"]', '["ffr", "beam"]'), "not an item of RodModel"),
        (("{ linspace = [150, 450, 4] }", "[]"), "empty grid"),
        (("{ linspace = [150, 450, 4] }", "{ linspace = [150, 450, 0] }"), "empty grid"),
        (("max_abs(rod.deflection_rel)", "max_abs(rod.bending)"), "not an output of the FMU"),
        (
            ('"rod.damping_ratio" = 0.02', '"rod.frequency[1]" = 100.0'),
            "only parameters and inputs",
        ),
    ],
)
def test_bad_spec_is_rejected_before_any_run(default_fmu, tmp_path, edit, message):
    text = SMALL.format(fmu=default_fmu).replace(*edit)
    spec = write_spec(tmp_path, text)
    with pytest.raises(SpecError) as err:
        run_sweep(spec, tmp_path / "out", workers=0, progress=False, plots=False)
    assert message in str(err.value)
    assert not (tmp_path / "out" / "results.csv").exists()
    res = cli(spec, "--out", tmp_path / "out_cli", "--workers", "0", check=False)
    assert res.returncode == 2 and message in res.stderr, res.stderr
    assert not (tmp_path / "out_cli" / "results.csv").exists()


def test_console_script_help_and_bad_spec(tmp_path):
    """The `flexrod-sweep` console script of the installed package: --help exits 0, a bad spec
    exits 2 with the spec's error on stderr and writes nothing."""
    script = BIN / "flexrod-sweep"
    assert script.is_file(), f"{script}: not installed (pip install -e python)"
    res = subprocess.run([str(script), "--help"], capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert res.stdout.startswith("usage: flexrod-sweep") and "--out" in res.stdout, res.stdout
    spec = write_spec(tmp_path, 'name = "bad"\n[fmu]\npath = "x.fmu"\n[parmeters]\n')
    res = subprocess.run(
        [str(script), str(spec), "--out", str(tmp_path / "out"), "--workers", "0", "--no-progress"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert res.returncode == 2, (res.stdout, res.stderr)
    assert "unknown table(s) ['parmeters']" in res.stderr, res.stderr
    assert not (tmp_path / "out").exists()
    res = subprocess.run([str(script), str(spec)], capture_output=True, text=True, timeout=120)
    assert res.returncode == 2 and "--out" in res.stderr, res.stderr


def test_latin_hypercube_expansion(default_fmu, tmp_path):
    text = SMALL.format(fmu=default_fmu).replace(
        '"rod.damping_ratio" = 0.02', '"slider.mass" = { range = [0.0, 0.5] }'
    )
    text += "[sampling]\nsamples = 5\nseed = 3\n"
    spec = load(write_spec(tmp_path, text))
    runs = spec.runs()
    assert len(runs) == 4 * 2 * 5
    masses = sorted(r["slider.mass"] for r in runs[:5])
    # one sample in each fifth of the range
    assert [int(m / 0.1) for m in masses] == [0, 1, 2, 3, 4]
    assert spec.runs() == runs  # deterministic


def test_failed_runs_are_rows_and_sweep_resumes(default_fmu, tmp_path):
    # crank.length >= rod.length: fmi2Error at initialization; 600 rad/s FFR: past the rod's
    # deflection limit (0.05 L), refused by the default policy (discard) before the abort limit.
    text = SMALL.format(fmu=default_fmu).replace(
        '"rod.damping_ratio" = 0.02', '"rod.damping_ratio" = 0.02\n"crank.length" = [0.1524, 0.4]'
    )
    text = text.replace("[150, 450, 4]", "[150, 600, 2]").replace('["ffr", "segments"]', '["ffr"]')
    spec = write_spec(tmp_path, text)
    out = tmp_path / "out"
    df = run_sweep(spec, out, workers=0, progress=False, plots=False)
    assert df.attrs["ran"] == 4
    rows = read_rows(out / "results.csv")
    by = {(r["crank.speed"], r["crank.length"]): r for r in rows}
    # The benchmark rod at 150 rad/s: done, with the error estimate's warning (it passes the
    # default tolerance at this load).
    good = by[("150.0", "0.1524")]
    assert good["status"] == "warning" and "rod.error_estimate" in good["message"], good
    bad = by[("150.0", "0.4")]
    assert bad["status"] == "error" and "crank.length" in bad["message"], bad
    assert bad["max_abs(rod.deflection_rel)"] == "nan"
    div = by[("600.0", "0.1524")]
    assert div["status"] == "discard" and "rod.deflection_limit" in div["message"], div
    # Rerun: everything is finished, nothing runs.
    df2 = run_sweep(spec, out, workers=0, progress=False, plots=False)
    assert df2.attrs["ran"] == 0 and df2.attrs["skipped"] == 4
    assert read_rows(out / "results.csv") == rows
    # Lose two rows (an interrupted sweep): only those run again, with the same results.
    lines = (out / "results.csv").read_text().splitlines(keepends=True)
    (out / "results.csv").write_text("".join(lines[:3]))
    df3 = run_sweep(spec, out, workers=0, progress=False, plots=False)
    assert df3.attrs["ran"] == 2

    def strip(rs):
        return [{k: v for k, v in r.items() if k != "wall_time"} for r in rs]

    assert strip(read_rows(out / "results.csv")) == strip(rows)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def dask_cluster(tmp_path):
    """A dask.distributed scheduler and two single-thread workers, separate processes on
    127.0.0.1."""
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = {**os.environ, "DASK_DISTRIBUTED__WORKER__DAEMON": "False"}
    logs = [open(tmp_path / f"dask{i}.log", "w") for i in range(3)]
    procs = [
        subprocess.Popen(
            [
                str(BIN / "dask"),
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                str(port),
                "--no-dashboard",
            ],
            stdout=logs[0],
            stderr=subprocess.STDOUT,
            env=env,
        )
    ]
    time.sleep(1.0)
    for i in (1, 2):
        procs.append(
            subprocess.Popen(
                [
                    str(BIN / "dask"),
                    "worker",
                    address,
                    "--nthreads",
                    "1",
                    "--nworkers",
                    "1",
                    "--host",
                    "127.0.0.1",
                    "--no-dashboard",
                    "--name",
                    f"w{i}",
                ],
                stdout=logs[i],
                stderr=subprocess.STDOUT,
                env=env,
            )
        )
    try:
        from dask.distributed import Client

        with Client(address, timeout=30) as c:
            c.wait_for_workers(2, timeout=60)
        yield address
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
        for f in logs:
            f.close()


def test_distributed_equals_in_process(default_fmu, tmp_path, dask_cluster):
    spec = write_spec(tmp_path, SMALL.format(fmu=default_fmu))
    res = cli(spec, "--out", tmp_path / "dist", "--scheduler", dask_cluster, "--no-plots")
    assert "8 runs: 8 ran" in res.stdout, res.stdout
    cli(spec, "--out", tmp_path / "serial", "--workers", "0", "--no-plots")
    dist = read_rows(tmp_path / "dist" / "results.csv")
    serial = read_rows(tmp_path / "serial" / "results.csv")
    assert len(dist) == len(serial) == 8
    for d, s in zip(dist, serial):
        d.pop("wall_time"), s.pop("wall_time")
        assert d == s  # the CSV holds repr(float): equal strings are bit-identical metrics
    assert {r["status"] for r in dist} <= {"ok", "warning", "discard"}


def test_local_cluster_and_plots(default_fmu, tmp_path):
    text = (
        SMALL.format(fmu=default_fmu)
        + """
[plots]
resonance = { x = "crank.speed", metric = "max_abs(rod.deflection_rel)", normalized = true }
heatmap = { x = "crank.speed", y = "rod.model", metric = "max_abs(rod.deflection_rel)" }
"""
    )
    text = text.replace('["ffr", "segments"]', "[1, 2]")
    spec = write_spec(tmp_path, text)
    res = cli(spec, "--out", tmp_path / "out", "--workers", "2")
    assert "8 runs: 8 ran" in res.stdout, res.stdout
    assert (tmp_path / "out" / "resonance.svg").stat().st_size > 1000
    assert (tmp_path / "out" / "heatmap.svg").stat().st_size > 1000
    rows = read_rows(tmp_path / "out" / "results.csv")
    # Rows in the spec's order; run ids (digests of the parameter values) distinct.
    assert [r["index"] for r in rows] == [str(i) for i in range(8)]
    assert len({r["run"] for r in rows}) == 8
    assert all(float(r["rod.frequency[1]"]) > 100 for r in rows)
