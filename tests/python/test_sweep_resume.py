"""Resume after a killed worker: a dask.distributed scheduler that gives a task no second try
(allowed-failures = 0) and two workers, one of them killed (SIGKILL) in the middle of a sweep.
The chunk it was running becomes rows of status `exception`; a plain rerun of the same command
runs exactly those again, and the results hold every run once."""

import csv
import os
import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

from test_sweep import free_port

BIN = Path(sys.executable).parent


def rows_of(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_rerun_after_a_killed_worker_runs_its_chunk_again(default_fmu, tmp_path):
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = {
        **os.environ,
        "DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES": "0",
        "DASK_DISTRIBUTED__WORKER__DAEMON": "False",
    }
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
    spec = tmp_path / "spec.toml"
    spec.write_text(f"""
name = "killed worker"
[fmu]
path = "{default_fmu}"
[parameters]
"crank.speed" = {{ linspace = [30, 69, 40] }}
"rod.deflection_policy" = 1
[drive]
transient_revolutions = 1
measure_revolutions = 2
""")
    out = tmp_path / "out"
    try:
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
                        "--no-nanny",
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
        from dask.distributed import Client

        with Client(address, timeout=30) as c:
            c.wait_for_workers(2, timeout=60)
        sweep = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "flexrod_sweep",
                str(spec),
                "--out",
                str(out),
                "--scheduler",
                address,
                "--no-progress",
                "--no-plots",
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        deadline = time.time() + 120
        while time.time() < deadline:
            p = out / "results.csv"
            if p.exists() and len(p.read_text().splitlines()) >= 2:
                break
            time.sleep(0.02)
        procs[1].send_signal(signal.SIGKILL)  # worker w1 dies in the middle of a chunk
        stdout, stderr = sweep.communicate(timeout=180)
        assert sweep.returncode == 0, (stdout, stderr)
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
        for f in logs:
            f.close()
    first = rows_of(out / "results.csv")
    assert len(first) == 40 and len({r["run"] for r in first}) == 40
    lost = {r["run"] for r in first if r["status"] == "exception"}
    assert lost, f"no chunk was lost: {Counter(r['status'] for r in first)}\n{stdout}\n{stderr}"
    assert all("chunk failed" in r["message"] for r in first if r["run"] in lost)
    # A plain rerun (no option): the infrastructure's failures run again, nothing else.
    res = subprocess.run(
        [
            sys.executable,
            "-m",
            "flexrod_sweep",
            str(spec),
            "--out",
            str(out),
            "--workers",
            "0",
            "--no-progress",
            "--no-plots",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert res.returncode == 0, res.stderr
    assert f"40 runs: {len(lost)} ran, {40 - len(lost)} already done" in res.stdout, res.stdout
    second = rows_of(out / "results.csv")
    ids = [r["run"] for r in second]
    assert len(ids) == 40 and len(set(ids)) == 40, Counter(ids).most_common(3)
    assert {r["status"] for r in second} <= {"ok", "warning"}
    assert [r["index"] for r in second] == [str(i) for i in range(40)]
    kept = {r["run"]: r for r in first if r["run"] not in lost}
    for r in second:
        if r["run"] in kept:
            assert r == kept[r["run"]]
