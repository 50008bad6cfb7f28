"""flexrod-sweep SPEC.toml --out DIR [--scheduler ADDRESS] [--workers N]
flexrod-sweep regenerate DIR [--workers N]

The console script `flexrod-sweep` (installed with the package) and `python -m flexrod_sweep`
are the same command. Exit codes: 0 done, 2 a bad command line or spec (nothing run), 130
interrupted (Ctrl-C: the finished runs are kept; the same command resumes)."""

import argparse
import sys

from .spec import SpecError
from .sweep import regenerate, run_sweep


def main(argv=None):
    """Run the command with `argv` (default: sys.argv[1:]); returns the exit code."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] == "regenerate":
        return _regenerate(argv[1:])
    p = argparse.ArgumentParser(
        prog="flexrod-sweep",
        description="Parameter sweep of the flexrod FMU on Dask; writes DIR/results.csv, "
        "DIR/results.parquet and charts. Rerunning with the same DIR skips the runs already in "
        "results.csv (and reruns those of status `exception`). "
        "`flexrod-sweep regenerate DIR` makes the committed studies in DIR anew.",
    )
    p.add_argument("spec", help="sweep spec (TOML)")
    p.add_argument(
        "--out", required=True, help="output directory (results.csv, results.parquet, charts)"
    )
    p.add_argument(
        "--scheduler",
        help="address of a dask.distributed scheduler (tcp://host:port); "
        "default: a LocalCluster on this machine",
    )
    p.add_argument(
        "--workers",
        type=int,
        default=None,
        help="LocalCluster worker processes (default: CPU count); 0 = run in this process without Dask",
    )
    p.add_argument(
        "--chunks-per-worker",
        type=int,
        default=4,
        help="chunks per worker (each chunk is one Dask task; the FMU loads once per worker)",
    )
    p.add_argument(
        "--retry-failed", action="store_true", help="rerun rows whose status is not ok/warning"
    )
    p.add_argument(
        "--series",
        action="append",
        default=[],
        metavar="RUN",
        help="write the time series of run id RUN to DIR/series/RUN.parquet (repeatable)",
    )
    p.add_argument("--no-progress", action="store_true")
    p.add_argument("--no-plots", action="store_true")
    a = p.parse_args(argv)
    if a.workers is not None and a.workers < 0:
        p.error("--workers must be >= 0")
    try:
        df = run_sweep(
            a.spec,
            a.out,
            scheduler=a.scheduler,
            workers=a.workers,
            chunks_per_worker=a.chunks_per_worker,
            progress=not a.no_progress,
            plots=not a.no_plots,
            retry_failed=a.retry_failed,
            series=a.series or None,
        )
    except SpecError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return _interrupted(a.out)
    _summary(df, a.out)
    return 0


def _interrupted(out):
    import pathlib

    from .sweep import read_results

    n = len(read_results(pathlib.Path(out) / "results.csv"))
    print(
        f"\ninterrupted: {n} finished runs kept in {out}/results.csv and results.parquet; "
        "the same command resumes the sweep",
        file=sys.stderr,
    )
    return 130


def _summary(df, out):
    info = df.attrs
    counts = df["status"].value_counts().to_dict()
    rate = info["ran"] / info["elapsed"] if info["ran"] and info["elapsed"] > 0 else float("nan")
    print(
        f"{info['runs']} runs: {info['ran']} ran, {info['skipped']} already done; "
        f"{info['elapsed']:.2f} s ({rate:.3g} runs/s); status {counts}"
    )
    if "startup" in info and info["ran"]:
        net = info["elapsed"] - info["startup"]
        print(
            f"Dask: {info.get('workers')} workers, start-up {info['startup']:.2f} s, runs {net:.2f} s "
            f"({info['ran'] / net:.3g} runs/s after start-up)"
        )
    print(
        f"wrote {out}/results.csv, {out}/results.parquet"
        + "".join(f", {p}" for p in info.get("plots", []))
        + "".join(f", {p}" for p in info.get("series", {}).values())
    )


def _regenerate(argv):
    p = argparse.ArgumentParser(
        prog="flexrod-sweep regenerate",
        description="Make the committed studies anew with the current FMU: DIR is a study "
        "(a folder with sweep.json) or a folder of studies (docs/sweeps); each is rerun from the "
        "spec its sweep.json names, after `cargo run --release -p fmu`.",
    )
    p.add_argument("dir")
    p.add_argument("--workers", type=int, default=None)
    p.add_argument("--scheduler")
    p.add_argument("--no-progress", action="store_true")
    a = p.parse_args(argv)
    try:
        for study, df in regenerate(
            a.dir, workers=a.workers, scheduler=a.scheduler, progress=not a.no_progress
        ):
            _summary(df, study)
    except SpecError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("\ninterrupted: rerun the same command to regenerate anew", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
