"""Per-run overhead of the sweep machinery on a dask.distributed scheduler with two workers.

    cargo run --release -p fmu
    .venv/bin/python python/specs/overhead.py [--runs-per-chunk N]

Starts a scheduler and two single-thread workers (separate processes, 127.0.0.1), runs
python/specs/overhead.toml (1,000 cheap runs) through `run_sweep(..., scheduler=ADDRESS)` into a
temporary folder, and prints, over the runs,

    overhead per run = (wall time x workers - sum of the runs' simulation times) / runs

where the wall time is that of run_sweep's sweep (client connection, FMU scatter, chunks, result
rows appended to results.csv; not the start of the scheduler and workers, which a cluster does
once for many sweeps) and a run's simulation time is its `wall_time` column (measured in the
worker around the run: reset, set-up, initialization, the steps and the metrics)."""

import os
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
BIN = Path(sys.executable).parent


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def main():
    from dask.distributed import Client
    from flexrod_sweep import run_sweep

    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = {**os.environ, "DASK_DISTRIBUTED__WORKER__DAEMON": "False"}
    quiet = dict(stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
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
            **quiet,
        )
    ]
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
                        "--host",
                        "127.0.0.1",
                        "--no-dashboard",
                        "--name",
                        f"w{i}",
                    ],
                    **quiet,
                )
            )
        with Client(address, timeout=30) as c:
            c.wait_for_workers(2, timeout=60)
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            df = run_sweep(
                HERE / "overhead.toml",
                Path(tmp) / "out",
                scheduler=address,
                progress=False,
                plots=False,
            )
            wall = time.perf_counter() - t0
        n, workers = len(df), df.attrs["workers"]
        sim = float(df["wall_time"].sum())
        sweep = df.attrs["elapsed"]
        print(f"{n} runs on {workers} workers: status {df['status'].value_counts().to_dict()}")
        print(
            f"run_sweep {wall:.2f} s (of which the sweep {sweep:.2f} s, client and FMU scatter "
            f"{df.attrs['startup']:.2f} s); simulation {sim:.2f} s in all, "
            f"{1e3 * sim / n:.3f} ms a run"
        )
        print(
            f"overhead per run: (sweep x workers - simulation) / runs = "
            f"{1e3 * (sweep * workers - sim) / n:.3f} ms; with run_sweep's whole wall time "
            f"(validation, parquet): {1e3 * (wall * workers - sim) / n:.3f} ms"
        )
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()


if __name__ == "__main__":
    main()
