"""flexrod-sweep SPEC.toml --out DIR [--scheduler ADDRESS] [--workers N]

The console script `flexrod-sweep` (installed with the package) and `python -m flexrod_sweep`
are the same command. Exit codes: 0 done, 2 a bad command line or spec (nothing run)."""

import argparse
import sys

from .spec import SpecError
from .sweep import run_sweep


def main(argv=None):
    """Run the command with `argv` (default: sys.argv[1:]); returns the exit code."""
    p = argparse.ArgumentParser(
        prog="flexrod-sweep",
        description="Parameter sweep of the flexrod FMU on Dask; writes DIR/results.csv and charts. "
        "Rerunning with the same DIR skips the runs already in results.csv.",
    )
    p.add_argument("spec", help="sweep spec (TOML)")
    p.add_argument("--out", required=True, help="output directory (results.csv, charts)")
    p.add_argument("--scheduler", help="address of a dask.distributed scheduler (tcp://host:port); "
                   "default: a LocalCluster on this machine")
    p.add_argument("--workers", type=int, default=None,
                   help="LocalCluster worker processes (default: CPU count); 0 = run in this process without Dask")
    p.add_argument("--chunks-per-worker", type=int, default=4,
                   help="chunks per worker (each chunk is one Dask task; the FMU loads once per worker)")
    p.add_argument("--retry-failed", action="store_true", help="rerun rows whose status is not ok/warning")
    p.add_argument("--no-progress", action="store_true")
    p.add_argument("--no-plots", action="store_true")
    a = p.parse_args(argv)
    if a.workers is not None and a.workers < 0:
        p.error("--workers must be >= 0")
    try:
        rows, info = run_sweep(a.spec, a.out, scheduler=a.scheduler, workers=a.workers,
                               chunks_per_worker=a.chunks_per_worker, progress=not a.no_progress,
                               plots=not a.no_plots, retry_failed=a.retry_failed)
    except SpecError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    counts = {}
    for r in rows:
        counts[r["status"]] = counts.get(r["status"], 0) + 1
    rate = info["ran"] / info["elapsed"] if info["ran"] and info["elapsed"] > 0 else float("nan")
    print(f"{info['runs']} runs: {info['ran']} ran, {info['skipped']} already done; "
          f"{info['elapsed']:.2f} s ({rate:.3g} runs/s); status {counts}")
    if "startup" in info and info["ran"]:
        net = info["elapsed"] - info["startup"]
        print(f"Dask: {info.get('workers')} workers, start-up {info['startup']:.2f} s, runs {net:.2f} s "
              f"({info['ran'] / net:.3g} runs/s after start-up)")
    print(f"wrote {a.out}/results.csv" + "".join(f", {p}" for p in info.get("plots", [])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
